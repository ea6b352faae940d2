// Built-in convex scenes, all oriented counter-clockwise seen from outside.
#include <panelrad/geometry/builtin_scenes.hpp>

#include <array>
#include <charconv>
#include <cmath>
#include <map>
#include <numbers>
#include <system_error>
#include <utility>
#include <vector>

namespace panelrad::geometry {

TriangleMesh make_cube() {
  TriangleMesh mesh;
  mesh.source = "builtin:cube";
  // Vertex i has coordinates (bit 0, bit 1, bit 2) of i.
  for (int i = 0; i < 8; ++i) mesh.vertices.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  // The six squares, corners counter-clockwise seen from outside: x=0, x=1, y=0, y=1, z=0, z=1.
  const int squares[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                             {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  const auto odd = [](int i) { return ((i & 1) + ((i >> 1) & 1) + ((i >> 2) & 1)) % 2 == 1; };
  for (Index f = 0; f < 6; ++f) {
    const int* c = squares[f];
    // Split along the diagonal joining the two corners with odd x+y+z (section 3, example (31)):
    // the diagonals are then the edges of the tetrahedron (1,0,0),(0,1,0),(0,0,1),(1,1,1).
    const int s = odd(c[0]) ? 0 : 1;
    const Index a = c[s], b = c[s + 1], d = c[(s + 2) % 4], e = c[(s + 3) % 4];
    mesh.triangles.push_back({a, b, d});
    mesh.triangles.push_back({a, d, e});
    mesh.facet_of_triangle.push_back(f);
    mesh.facet_of_triangle.push_back(f);
  }
  mesh.num_facets = 6;
  return mesh;
}

TriangleMesh make_prism(int k, double circumradius, double height) {
  if (k < 3) throw MeshError("prism: needs k >= 3 sides, got " + std::to_string(k));
  if (k > 1000000) throw MeshError("prism: k = " + std::to_string(k) + " is too large (at most 1000000)");
  if (!(circumradius > 0) || !std::isfinite(circumradius) || !(height > 0) || !std::isfinite(height))
    throw MeshError("prism: circumradius and height must be positive and finite");
  TriangleMesh mesh;
  mesh.source = "builtin:prism:" + std::to_string(k);
  // Bottom ring 0..k-1 at z = 0, top ring k..2k-1 at z = height; top vertex = bottom + (0,0,h)
  // with identical x, y, so every side rectangle is exactly planar.
  for (int ring = 0; ring < 2; ++ring)
    for (int j = 0; j < k; ++j) {
      const double phi = 2.0 * std::numbers::pi * j / k;
      mesh.vertices.emplace_back(circumradius * std::cos(phi), circumradius * std::sin(phi),
                                 ring == 0 ? 0.0 : height);
    }
  const auto bottom = [](int j) { return static_cast<Index>(j); };
  const auto top = [k](int j) { return static_cast<Index>(k + j); };
  for (int j = 0; j < k; ++j) {  // side j: b_j, b_j+1, t_j+1, t_j (outward normal radial)
    const int n = (j + 1) % k;
    mesh.triangles.push_back({bottom(j), bottom(n), top(n)});
    mesh.triangles.push_back({bottom(j), top(n), top(j)});
    mesh.facet_of_triangle.push_back(j);
    mesh.facet_of_triangle.push_back(j);
  }
  for (int j = 1; j + 1 < k; ++j) {  // bottom cap, normal -z: clockwise seen from above
    mesh.triangles.push_back({bottom(0), bottom(j + 1), bottom(j)});
    mesh.facet_of_triangle.push_back(k);
  }
  for (int j = 1; j + 1 < k; ++j) {  // top cap, normal +z
    mesh.triangles.push_back({top(0), top(j), top(j + 1)});
    mesh.facet_of_triangle.push_back(k + 1);
  }
  mesh.num_facets = k + 2;
  return mesh;
}

TriangleMesh make_tetrahedron() {
  TriangleMesh mesh;
  mesh.source = "builtin:tetrahedron";
  mesh.vertices = {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(1, 1, 1)};
  mesh.triangles = {{{0, 2, 1}}, {{0, 1, 3}}, {{1, 2, 3}}, {{0, 3, 2}}};
  mesh.facet_of_triangle = {0, 1, 2, 3};
  mesh.num_facets = 4;
  return mesh;
}

TriangleMesh make_octahedron() {
  TriangleMesh mesh;
  mesh.source = "builtin:octahedron";
  // 0:+x 1:-x 2:+y 3:-y 4:+z 5:-z
  mesh.vertices = {Vec3(1, 0, 0), Vec3(-1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1), Vec3(0, 0, -1)};
  const Index xs[2] = {0, 1}, ys[2] = {2, 3}, zs[2] = {4, 5};
  for (int sx = 0; sx < 2; ++sx)
    for (int sy = 0; sy < 2; ++sy)
      for (int sz = 0; sz < 2; ++sz) {
        // Octant (±x, ±y, ±z): (x, y, z) is counter-clockwise from outside when the sign product is +.
        const bool positive = (sx + sy + sz) % 2 == 0;
        if (positive)
          mesh.triangles.push_back({xs[sx], ys[sy], zs[sz]});
        else
          mesh.triangles.push_back({xs[sx], zs[sz], ys[sy]});
        mesh.facet_of_triangle.push_back(static_cast<Index>(mesh.triangles.size() - 1));
      }
  mesh.num_facets = 8;
  return mesh;
}

TriangleMesh make_icosphere(int subdivisions) {
  if (subdivisions < 0 || subdivisions > 8)
    throw MeshError("icosphere: subdivisions must be in [0, 8], got " + std::to_string(subdivisions));
  const double t = (1 + std::sqrt(5.0)) / 2;
  TriangleMesh m;
  m.source = "builtin:icosphere:" + std::to_string(subdivisions);
  for (const Vec3& p : {Vec3(-1, t, 0), Vec3(1, t, 0), Vec3(-1, -t, 0), Vec3(1, -t, 0), Vec3(0, -1, t),
                        Vec3(0, 1, t), Vec3(0, -1, -t), Vec3(0, 1, -t), Vec3(t, 0, -1), Vec3(t, 0, 1),
                        Vec3(-t, 0, -1), Vec3(-t, 0, 1)})
    m.vertices.push_back(p.normalized());
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                 {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                 {3, 8, 9},  {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (int k = 0; k < subdivisions; ++k) {
    std::map<std::pair<Index, Index>, Index> midpoint;  // one new vertex per edge
    const auto mid = [&](Index a, Index b) {
      const auto [it, added] = midpoint.try_emplace(std::minmax(a, b), static_cast<Index>(m.vertices.size()));
      if (added)
        m.vertices.push_back(
            (m.vertices[static_cast<std::size_t>(a)] + m.vertices[static_cast<std::size_t>(b)]).normalized());
      return it->second;
    };
    std::vector<std::array<Index, 3>> finer;
    finer.reserve(4 * m.triangles.size());
    for (const auto& [a, b, c] : m.triangles) {
      const Index ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      finer.insert(finer.end(), {{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}});
    }
    m.triangles = std::move(finer);
  }
  m.num_facets = static_cast<Index>(m.triangles.size());
  for (Index f = 0; f < m.num_facets; ++f) m.facet_of_triangle.push_back(f);
  return m;
}

TriangleMesh make_builtin(const std::string& spec) {
  if (spec == "cube") return make_cube();
  if (spec == "tetrahedron") return make_tetrahedron();
  if (spec == "octahedron") return make_octahedron();
  if (spec.rfind("prism:", 0) == 0) {
    const std::string ks = spec.substr(6);
    int k = 0;
    const auto [ptr, ec] = std::from_chars(ks.data(), ks.data() + ks.size(), k);
    if (ks.empty() || ec != std::errc() || ptr != ks.data() + ks.size() || k < 3 || k > 1000000)
      throw MeshError("built-in scene '" + spec + "': K must be an integer in [3, 1000000]");
    return make_prism(k);
  }
  throw MeshError("unknown built-in scene '" + spec +
                  "' (known: cube, prism:K with K >= 3, tetrahedron, octahedron)");
}

}  // namespace panelrad::geometry

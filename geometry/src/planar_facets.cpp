// Maximal planar facets (planar_facets.hpp): triangles joined across shared edges whose four
// vertices are coplanar, exactly or within the rounding of the input (bound(t, v)).
#include "validation_internal.hpp"

#include <panelrad/geometry/planar_facets.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace panelrad::geometry {

using namespace validation_detail;

// Per triangle, the first triangle of its maximal planar facet (count_planar_facets' classes).
std::vector<Index> validation_detail::planar_facet_classes(const TriangleMesh& mesh) {
  const Sz nt = mesh.triangles.size();
  const Sz nv = mesh.vertices.size();
  for (const Tri& tr : mesh.triangles)
    for (Index v : tr)
      if (v < 0 || at(v) >= nv) throw MeshError("count_planar_facets: vertex index out of range");
  for (const Vec3& p : mesh.vertices)
    if (!p.allFinite()) throw MeshError("count_planar_facets: non-finite vertex coordinate");
  std::vector<Point> pts;
  pts.reserve(nv);
  for (const Vec3& p : mesh.vertices) pts.emplace_back(p.x(), p.y(), p.z());
  std::vector<Index> parent(nt);
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](Index x) {
    while (parent[at(x)] != x) x = parent[at(x)] = parent[at(parent[at(x)])];
    return x;
  };
  std::vector<std::array<Index, 4>> edges;  // lo, hi, triangle, opposite vertex
  edges.reserve(3 * nt);
  for (Sz t = 0; t < nt; ++t)
    for (int s = 0; s < 3; ++s) {
      const Tri& tr = mesh.triangles[t];
      const Index a = tr[at(s)], b = tr[at((s + 1) % 3)], c = tr[at((s + 2) % 3)];
      edges.push_back({std::min(a, b), std::max(a, b), static_cast<Index>(t), c});
    }
  std::sort(edges.begin(), edges.end());
  std::optional<InputRounding> rounding;  // computed on the first pair that is not exactly coplanar
  double diam = 0;
  for (Sz i = 0; i < edges.size();) {
    Sz j = i;
    while (j < edges.size() && edges[j][0] == edges[i][0] && edges[j][1] == edges[i][1]) ++j;
    if (j - i == 2) {
      const auto& e = edges[i];
      const auto& f = edges[i + 1];
      const Point &p = pts[at(e[0])], &q = pts[at(e[1])], &r = pts[at(e[3])], &s = pts[at(f[3])];
      if (CGAL::collinear(p, q, r) || CGAL::collinear(p, q, s)) {
        i = j;
        continue;
      }
      bool join = CGAL::orientation(p, q, r, s) == CGAL::COPLANAR;
      if (!join) {
        if (!rounding) rounding = input_rounding(mesh), diam = diameter(mesh);
        // Within the rounding: each far vertex within bound(t, v) of the other triangle's plane.
        const auto& V = mesh.vertices;
        const Vec3 &vp = V[at(e[0])], &vq = V[at(e[1])], &vr = V[at(e[3])], &vs = V[at(f[3])];
        const double eta = rounding->per_coordinate;
        const double ds = std::abs(plane_distance(vp, vq, vr, vs)), dr = std::abs(plane_distance(vp, vq, vs, vr));
        const double bs = rounding_bound(vp, vq, vr, vs, eta), br = rounding_bound(vp, vq, vs, vr, eta);
        join = bs >= 0 && br >= 0 && ds <= bs && dr <= br && std::max(ds, dr) <= kMaxRoundingViolation * diam;
      }
      if (join) parent[at(find(e[2]))] = find(f[2]);
    }
    i = j;
  }
  // Each class named by its smallest triangle.
  std::vector<Index> smallest(nt, -1), cls(nt);
  for (Sz t = 0; t < nt; ++t) {
    Index& s = smallest[at(find(static_cast<Index>(t)))];
    if (s < 0) s = static_cast<Index>(t);
    cls[t] = s;
  }
  return cls;
}

std::size_t count_planar_facets(const TriangleMesh& mesh) {
  const std::vector<Index> cls = planar_facet_classes(mesh);
  Sz count = 0;
  for (Sz t = 0; t < cls.size(); ++t) count += cls[t] == static_cast<Index>(t);
  return count;
}

}  // namespace panelrad::geometry

// Built-in scenes: the paper's cube with its diagonal rule, prisms, tetrahedron, octahedron.
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/validation.hpp>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>
#include <set>
#include <utility>

namespace pg = panelrad::geometry;

namespace {

pg::Vec3 normal(const pg::TriangleMesh& m, std::size_t t) {
  const auto& tr = m.triangles[t];
  const pg::Vec3& a = m.vertices[static_cast<std::size_t>(tr[0])];
  return (m.vertices[static_cast<std::size_t>(tr[1])] - a).cross(m.vertices[static_cast<std::size_t>(tr[2])] - a);
}

pg::Vec3 centroid(const pg::TriangleMesh& m, std::size_t t) {
  pg::Vec3 c = pg::Vec3::Zero();
  for (auto v : m.triangles[t]) c += m.vertices[static_cast<std::size_t>(v)];
  return c / 3.0;
}

pg::Vec3 vertex_mean(const pg::TriangleMesh& m) {
  pg::Vec3 c = pg::Vec3::Zero();
  for (const auto& v : m.vertices) c += v;
  return c / static_cast<double>(m.vertices.size());
}

/// Every triangle counter-clockwise from outside: its normal points away from the vertex mean
/// (an interior point of these convex solids).
void expect_outward(const pg::TriangleMesh& m) {
  const pg::Vec3 inside = vertex_mean(m);
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    EXPECT_GT(normal(m, t).dot(centroid(m, t) - inside), 0.0) << m.source << " triangle " << t;
}

/// Valid, no flips, no re-triangulation: the built-ins are already in the validated form.
void expect_valid_as_built(pg::TriangleMesh m) {
  const auto before = m.triangles;
  const pg::ValidationReport r = pg::validate_closed_convex(m);
  EXPECT_TRUE(r.valid) << r.message;
  EXPECT_EQ(r.flipped_faces, 0u);
  EXPECT_FALSE(r.retriangulated_from_hull);
  EXPECT_EQ(m.triangles, before);
}

}  // namespace

TEST(BuiltinScenes, CubeCountsAreaAndOrientation) {
  const pg::TriangleMesh cube = pg::make_cube();
  EXPECT_EQ(cube.vertices.size(), 8u);
  EXPECT_EQ(cube.triangles.size(), 12u);
  EXPECT_EQ(cube.num_facets, 6);
  EXPECT_DOUBLE_EQ(pg::surface_area(cube), 6.0);  // 12 right triangles of area 1/2, exact
  expect_outward(cube);
  expect_valid_as_built(cube);
  EXPECT_EQ(pg::count_planar_facets(cube), 6u);
  for (std::size_t t = 0; t < 12; ++t) {
    // Each facet is a square of the unit cube: axis-aligned unit-area-doubled normal.
    const pg::Vec3 n = normal(cube, t);
    EXPECT_DOUBLE_EQ(n.cwiseAbs().maxCoeff(), 1.0);
    EXPECT_DOUBLE_EQ(n.cwiseAbs().sum(), 1.0);
  }
}

// Section 3, example (31): each square is split along the diagonal joining its two vertices with
// odd x+y+z, so the six diagonals are the edges of the tetrahedron (1,0,0),(0,1,0),(0,0,1),(1,1,1).
TEST(BuiltinScenes, CubeDiagonalsJoinTheOddVertices) {
  const pg::TriangleMesh cube = pg::make_cube();
  const auto key = [&](pg::Index v) {
    const pg::Vec3& p = cube.vertices[static_cast<std::size_t>(v)];
    return std::array<int, 3>{static_cast<int>(p.x()), static_cast<int>(p.y()), static_cast<int>(p.z())};
  };
  std::set<std::pair<std::array<int, 3>, std::array<int, 3>>> diagonals;
  for (pg::Index f = 0; f < 6; ++f) {
    std::vector<std::array<pg::Index, 3>> tris;
    for (std::size_t t = 0; t < 12; ++t)
      if (cube.facet_of_triangle[t] == f) tris.push_back(cube.triangles[t]);
    ASSERT_EQ(tris.size(), 2u);
    std::vector<pg::Index> shared;
    for (pg::Index a : tris[0])
      for (pg::Index b : tris[1])
        if (a == b) shared.push_back(a);
    ASSERT_EQ(shared.size(), 2u);
    auto p = key(shared[0]), q = key(shared[1]);
    EXPECT_EQ((p[0] + p[1] + p[2]) % 2, 1);
    EXPECT_EQ((q[0] + q[1] + q[2]) % 2, 1);
    if (q < p) std::swap(p, q);
    diagonals.insert({p, q});
  }
  const std::array<int, 3> t[4] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
  std::set<std::pair<std::array<int, 3>, std::array<int, 3>>> tetra_edges;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) tetra_edges.insert({std::min(t[i], t[j]), std::max(t[i], t[j])});
  EXPECT_EQ(diagonals, tetra_edges);
}

TEST(BuiltinScenes, PrismCountsFacetsAndAnalyticArea) {
  for (int k : {3, 4, 5, 6, 7, 12, 100}) {
    for (auto [r, h] : {std::pair{1.0, 1.0}, std::pair{2.5, 0.25}, std::pair{1e-3, 1e3}}) {
      SCOPED_TRACE("k=" + std::to_string(k) + " r=" + std::to_string(r) + " h=" + std::to_string(h));
      const pg::TriangleMesh p = pg::make_prism(k, r, h);
      EXPECT_EQ(p.vertices.size(), static_cast<std::size_t>(2 * k));
      EXPECT_EQ(p.triangles.size(), static_cast<std::size_t>(4 * k - 4));
      EXPECT_EQ(p.num_facets, k + 2);
      // Facets: k sides (2 triangles each), then bottom and top caps (k-2 each).
      std::vector<int> per_facet(static_cast<std::size_t>(k + 2), 0);
      for (pg::Index f : p.facet_of_triangle) ++per_facet[static_cast<std::size_t>(f)];
      for (int j = 0; j < k; ++j) EXPECT_EQ(per_facet[static_cast<std::size_t>(j)], 2);
      EXPECT_EQ(per_facet[static_cast<std::size_t>(k)], k - 2);
      EXPECT_EQ(per_facet[static_cast<std::size_t>(k + 1)], k - 2);
      // Two caps of area (k/2) r^2 sin(2 pi/k), k rectangles of side 2 r sin(pi/k) by h.
      const double area = k * r * r * std::sin(2 * std::numbers::pi / k) + k * 2 * r * std::sin(std::numbers::pi / k) * h;
      // Relative 1e-13: the vertices are rounded cos/sin values (1e-16 relative each) summed
      // over at most 4k triangles.
      EXPECT_NEAR(pg::surface_area(p), area, 1e-13 * area);
      EXPECT_EQ(pg::count_planar_facets(p), static_cast<std::size_t>(k + 2));
      expect_outward(p);
      expect_valid_as_built(p);
    }
  }
}

TEST(BuiltinScenes, TetrahedronAndOctahedron) {
  const pg::TriangleMesh t = pg::make_tetrahedron();
  EXPECT_EQ(t.triangles.size(), 4u);
  EXPECT_NEAR(pg::surface_area(t), 2 * std::sqrt(3.0), 1e-14);  // 4 equilateral, edge sqrt 2
  expect_outward(t);
  expect_valid_as_built(t);
  const pg::TriangleMesh o = pg::make_octahedron();
  EXPECT_EQ(o.triangles.size(), 8u);
  EXPECT_EQ(o.num_facets, 8);
  EXPECT_NEAR(pg::surface_area(o), 4 * std::sqrt(3.0), 1e-14);  // 8 equilateral, edge sqrt 2
  expect_outward(o);
  expect_valid_as_built(o);
}

// The icosphere: 20 4^S triangles on the unit sphere, a closed convex surface counter-clockwise
// from outside (validate_closed_convex flips nothing), its area below the sphere's 4 pi and
// approaching it (the inscribed polyhedron's area grows with S).
TEST(BuiltinScenes, IcosphereCountsAndConvexity) {
  double previous = 0;
  for (int s = 0; s <= 3; ++s) {
    pg::TriangleMesh m = pg::make_icosphere(s);
    ASSERT_EQ(m.triangles.size(), static_cast<std::size_t>(20) << (2 * s));
    EXPECT_EQ(m.num_facets, static_cast<pg::Index>(m.triangles.size()));
    EXPECT_EQ(m.vertices.size(), 10 * (std::size_t{1} << (2 * s)) + 2);  // Euler: V = F / 2 + 2
    for (const pg::Vec3& v : m.vertices) EXPECT_NEAR(v.norm(), 1.0, 1e-15);
    const double area = pg::surface_area(m);
    EXPECT_LT(area, 4 * std::numbers::pi);
    EXPECT_GT(area, previous);
    previous = area;
    const pg::ValidationReport r = pg::validate_closed_convex(m);
    ASSERT_TRUE(r.valid) << r.message;
    EXPECT_EQ(r.flipped_faces, 0u);
  }
  EXPECT_THROW(pg::make_icosphere(-1), pg::MeshError);
  EXPECT_THROW(pg::make_icosphere(9), pg::MeshError);
}

TEST(BuiltinScenes, ByNameAndBadNames) {
  EXPECT_EQ(pg::make_builtin("cube").triangles.size(), 12u);
  EXPECT_EQ(pg::make_builtin("prism:6").triangles.size(), 20u);
  EXPECT_EQ(pg::make_builtin("prism:6").source, "builtin:prism:6");
  EXPECT_EQ(pg::make_builtin("tetrahedron").triangles.size(), 4u);
  EXPECT_EQ(pg::make_builtin("octahedron").triangles.size(), 8u);
  for (const char* bad : {"prism:2", "prism:", "prism:x", "prism:6x", "prism:-3", "sphere", "", "Cube"})
    EXPECT_THROW(pg::make_builtin(bad), pg::MeshError) << bad;
  EXPECT_THROW(pg::make_prism(2), pg::MeshError);
  EXPECT_THROW(pg::make_prism(6, -1.0, 1.0), pg::MeshError);
  EXPECT_THROW(pg::make_prism(6, 1.0, std::nan("")), pg::MeshError);
}

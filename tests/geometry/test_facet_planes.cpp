// Supporting planes of the facets (facet_planes in planar_facets.hpp): facets in one plane share
// an id whether or not they touch, exactly or within the rounding of the input; distinct planes
// never do. The cluster tree gives every cluster its root's plane.
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/cluster_tree.hpp>
#include <panelrad/geometry/planar_facets.hpp>
#include <panelrad/geometry/scene_validation.hpp>
#include <panelrad/geometry/validation.hpp>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <set>
#include <string>
#include <vector>

namespace {

namespace pg = panelrad::geometry;
using pg::Index;
using pg::Vec3;

const std::string kScenes = std::string(PANELRAD_SOURCE_DIR) + "/examples/scenes/";

// Appends triangle (a, b, c) as one new facet.
void add_facet(pg::TriangleMesh& m, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Index v = static_cast<Index>(m.vertices.size());
  m.vertices.insert(m.vertices.end(), {a, b, c});
  m.triangles.push_back({v, v + 1, v + 2});
  m.facet_of_triangle.push_back(m.num_facets++);
}

// The independent truth in double precision: each corner of g's first triangle within `tol` of the
// plane of f's first triangle (a unit normal from the cross product, long double).
bool near_plane(const pg::TriangleMesh& m, Index f, Index g, double tol) {
  const auto first = [&](Index facet) {
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
      if (m.facet_of_triangle[t] == facet) return t;
    return m.triangles.size();
  };
  const auto& tf = m.triangles[first(f)];
  const auto& tg = m.triangles[first(g)];
  const Vec3& a = m.vertices[static_cast<std::size_t>(tf[0])];
  const Vec3 n = (m.vertices[static_cast<std::size_t>(tf[1])] - a).cross(m.vertices[static_cast<std::size_t>(tf[2])] - a).normalized();
  for (Index v : tg)
    if (std::abs(n.dot(m.vertices[static_cast<std::size_t>(v)] - a)) > tol) return false;
  return true;
}

TEST(FacetPlanes, CoplanarFacetsShareAPlaneWhetherOrNotTheyTouch) {
  pg::TriangleMesh m;
  add_facet(m, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});      // z = 0
  add_facet(m, {0, 0, 1e-3}, {1, 0, 1e-3}, {0, 1, 1e-3});  // z = 1e-3: parallel, distinct
  add_facet(m, {5, 5, 0}, {6, 5, 0}, {5, 7, 0});      // z = 0 again, far from the first
  add_facet(m, {0, 0, 0}, {0, 1, 0}, {0, 0, 1});      // x = 0: shares an edge with the first
  add_facet(m, {9, 9, 0}, {9, 8, 0}, {8, 9, 0});      // z = 0, the other orientation
  const std::vector<Index> plane = pg::facet_planes(m);
  EXPECT_EQ(plane, (std::vector<Index>{0, 1, 0, 2, 0}));
}

TEST(FacetPlanes, InvariantUnderPowerOfTwoScalingAndTranslation) {
  pg::TriangleMesh cube = pg::make_cube();
  // Every triangle its own facet: 12 facets in 6 planes.
  for (std::size_t t = 0; t < cube.triangles.size(); ++t) cube.facet_of_triangle[t] = static_cast<Index>(t);
  cube.num_facets = 12;
  const std::vector<Index> reference = pg::facet_planes(cube);
  EXPECT_EQ(std::set<Index>(reference.begin(), reference.end()).size(), 6u);
  for (std::size_t t = 0; t < 12; ++t)
    for (std::size_t u = 0; u < 12; ++u)
      EXPECT_EQ(reference[t] == reference[u], near_plane(cube, static_cast<Index>(t), static_cast<Index>(u), 1e-12))
          << t << " " << u;
  for (int e : {-250, -60, 0, 60, 250})
    for (const Vec3& offset : {Vec3(0, 0, 0), Vec3(3.25, -7.5, 1e3)}) {
      pg::TriangleMesh m = cube;
      for (Vec3& v : m.vertices) v = std::ldexp(1.0, e) * (v + offset);
      EXPECT_EQ(pg::facet_planes(m), reference) << "2^" << e;
    }
}

// The measured Cornell box: 17 facets (walls, floor, ceiling pieces around the light, the light,
// the blocks' faces). Plane ids agree with the double-precision check for every pair of facets
// (its coordinates have one decimal: coplanar facets are so to the rounding of 0.1, ~1e-13 here,
// and distinct planes are millimetres apart), and the light lies in the ceiling's plane.
TEST(FacetPlanes, CornellBoxLightInTheCeilingPlane) {
  const pg::TriangleMesh m = pg::load_scene_mesh(kScenes + "cornell_box.obj").mesh();
  const std::vector<Index> plane = pg::facet_planes(m);
  ASSERT_EQ(plane.size(), static_cast<std::size_t>(m.num_facets));
  // The blocks' bottoms (faces 22 and 23) lie against the floor's back and leave the scene: no
  // triangle, no plane to compare.
  std::vector<bool> present(static_cast<std::size_t>(m.num_facets), false);
  for (Index f : m.facet_of_triangle) present[static_cast<std::size_t>(f)] = true;
  std::size_t together = 0;
  for (Index f = 0; f < m.num_facets; ++f)
    for (Index g = 0; g < m.num_facets; ++g) {
      if (!present[static_cast<std::size_t>(f)] || !present[static_cast<std::size_t>(g)]) continue;
      const bool same = plane[static_cast<std::size_t>(f)] == plane[static_cast<std::size_t>(g)];
      EXPECT_EQ(same, near_plane(m, f, g, 1e-9 * 560)) << f << " " << g;
      together += f != g && same;
    }
  EXPECT_GT(together, 0u);  // the light and the ceiling (and any other coplanar facets)
  // The light (facet 7, front down, y = 548.8) and a facet of the ceiling: the highest facet
  // facing down other than the light.
  const auto y_of = [&](Index f) {
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
      if (m.facet_of_triangle[t] == f) return m.vertices[static_cast<std::size_t>(m.triangles[t][0])].y();
    return 0.0;
  };
  std::size_t same_height = 0;
  for (Index g = 0; g < m.num_facets; ++g)
    if (g != 7 && present[static_cast<std::size_t>(g)] && near_plane(m, 7, g, 1e-9)) {
      ++same_height;
      EXPECT_EQ(plane[7], plane[static_cast<std::size_t>(g)]);
      EXPECT_DOUBLE_EQ(y_of(g), y_of(7));
    }
  EXPECT_GT(same_height, 0u);
}

// Faces of opposite orientation across a positive gap are never in one plane, however small the
// gap relative to the rounding of the input; exactly coplanar ones are, whichever way they face.
// Same-facing faces within the rounding share a plane only with PlaneGrouping::within_rounding.
TEST(FacetPlanes, OppositeFacesAcrossAGapAreNeverOnePlane) {
  for (const double offset : {0.0, 1e8})
    for (const double gap : {1e-15, 1e-12, 1e-9, 1e-6, 1e-3}) {
      if (offset + gap == offset) continue;  // not representable at that magnitude
      pg::TriangleMesh m;
      add_facet(m, {offset, 0, 0}, {offset + 1, 0, 0}, {offset, 1, 0});              // z = 0, normal +z
      add_facet(m, {offset, 0, gap}, {offset, 1, gap}, {offset + 1, 0, gap});        // z = gap, normal -z
      add_facet(m, {offset + 2, 0, gap}, {offset + 3, 0, gap}, {offset + 2, 1, gap});  // z = gap, normal +z
      add_facet(m, {offset + 5, 0, 0}, {offset + 5, 1, 0}, {offset + 6, 0, 0});      // z = 0, normal -z
      for (const pg::PlaneGrouping grouping : {pg::PlaneGrouping::exact, pg::PlaneGrouping::within_rounding}) {
        const std::vector<Index> plane = pg::facet_planes(m, grouping);
        SCOPED_TRACE("offset " + std::to_string(offset) + " gap " + std::to_string(gap));
        EXPECT_NE(plane[0], plane[1]);
        EXPECT_NE(plane[3], plane[1]);
        EXPECT_EQ(plane[0], plane[3]);  // exactly coplanar, facing the other way
        // Facet 2 is exactly in facet 1's plane, and faces the way facet 0 does across the gap:
        // exactly grouped with facet 1; within the rounding it may go with facet 0 instead.
        if (grouping == pg::PlaneGrouping::exact) {
          EXPECT_EQ(plane[1], plane[2]);
          EXPECT_NE(plane[0], plane[2]);
        }
      }
    }
}

// The shipped Cornell box has its coplanar facets exactly coplanar: exact grouping (used for
// general scenes) finds the planes that grouping within the rounding found, so its solution is
// the same bit for bit.
TEST(FacetPlanes, CornellBoxPlanesAreExact) {
  const pg::TriangleMesh m = pg::load_scene_mesh(kScenes + "cornell_box.obj").mesh();
  EXPECT_EQ(pg::facet_planes(m, pg::PlaneGrouping::exact), pg::facet_planes(m, pg::PlaneGrouping::within_rounding));
}

// A flat closed box (1 x 1 x 1e-5, convex): its floor and ceiling face each other and stay apart.
TEST(FacetPlanes, FlatBoxFloorAndCeilingStayApart) {
  pg::TriangleMesh flat = pg::make_cube();
  for (pg::Vec3& v : flat.vertices) v.z() *= 1e-5;
  const pg::ValidationReport r = pg::validate_closed_convex(flat);
  ASSERT_TRUE(r.valid) << r.message;
  const std::vector<Index> plane = pg::facet_planes(flat);
  EXPECT_EQ(std::set<Index>(plane.begin(), plane.end()).size(), 6u);
}

// Every cluster carries its root's plane; the roots of one facet share it.
TEST(FacetPlanes, ClusterTreePlanes) {
  pg::TriangleMesh cube = pg::make_cube();
  const std::vector<Index> facet_plane = pg::facet_planes(cube);
  const pg::ClusterTree tree(cube, 2);
  EXPECT_EQ(tree.num_planes(), 6);
  for (int l = 0; l <= 2; ++l)
    for (Index k = 0; k < tree.level_size(l); ++k)
      EXPECT_EQ(tree.plane(l, k), facet_plane[static_cast<std::size_t>(tree.cluster(l, k).facet)]);
}

}  // namespace

// triangle_planes: a quad facet bent by 1e-7 (its fourth corner off the plane of the first three)
// keeps one plane within the rounding, but its second triangle gets a plane of its own when only
// exact coplanarity counts (a general scene: G between the halves is not zero); a flat quad keeps
// one plane either way, and an unbent second facet in that plane shares it.
TEST(TrianglePlanes, ABentFaceSplitsOnlyWhenExact) {
  pg::TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 1e-7}, {0, 1, 0},   // bent quad
                {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1},      // flat quad
                {2, 0, 1}, {3, 0, 1}, {3, 1, 1}};                // a triangle in the flat quad's plane
  m.triangles = {{0, 1, 3}, {1, 2, 3}, {4, 5, 7}, {5, 6, 7}, {8, 9, 10}};
  m.facet_of_triangle = {0, 0, 1, 1, 2};
  m.num_facets = 3;
  const std::vector<Index> exact = pg::triangle_planes(m, pg::PlaneGrouping::exact);
  ASSERT_EQ(exact.size(), 5u);
  EXPECT_NE(exact[0], exact[1]);
  EXPECT_EQ(exact[2], exact[3]);
  EXPECT_EQ(exact[2], exact[4]);
  EXPECT_EQ(std::set<Index>(exact.begin(), exact.end()).size(), 3u);
  const std::vector<Index> facets = pg::facet_planes(m, pg::PlaneGrouping::exact);
  EXPECT_EQ(exact[0], facets[0]);  // a facet's first triangle keeps the facet's plane
  const std::vector<Index> rounded = pg::triangle_planes(m, pg::PlaneGrouping::within_rounding);
  const std::vector<Index> rounded_facets = pg::facet_planes(m, pg::PlaneGrouping::within_rounding);
  for (std::size_t t = 0; t < 5; ++t) EXPECT_EQ(rounded[t], rounded_facets[static_cast<std::size_t>(m.facet_of_triangle[t])]);
}

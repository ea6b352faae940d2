// Cross-check of ClusterTree's uniform 4-way midpoint subdivision against an independent
// implementation: CGAL's primal triangle quadrisection (PTQ) with a midpoint mask
// (subdivide_with_cgal). Both compute an edge midpoint as (p + q) * 0.5 in double, so the two
// triangle soups must agree bit for bit, with the same facet ids and areas per facet.
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/oracles/cgal_subdivision.hpp>
#include <panelrad/geometry/cluster_tree.hpp>
#include <panelrad/geometry/validation.hpp>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace panelrad::geometry;

/// A triangle as its three corners sorted lexicographically, flattened, with its facet id.
using Key = std::array<double, 9>;
using Soup = std::vector<std::pair<Key, Index>>;

Key sorted_key(std::array<Vec3, 3> c) {
  std::sort(c.begin(), c.end(), [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  Key k{};
  for (std::size_t i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) k[3 * i + static_cast<std::size_t>(j)] = c[i][j];
  return k;
}

Soup sorted_soup(const std::vector<std::array<Vec3, 3>>& triangles, const std::vector<Index>& facets) {
  Soup s;
  for (std::size_t i = 0; i < triangles.size(); ++i) s.emplace_back(sorted_key(triangles[i]), facets[i]);
  std::sort(s.begin(), s.end());
  return s;
}

Soup tree_soup(const ClusterTree& tree) {
  std::vector<std::array<Vec3, 3>> t;
  std::vector<Index> f;
  for (const Cluster& c : tree.elements()) {
    t.push_back(c.vertex);
    f.push_back(c.facet);
  }
  return sorted_soup(t, f);
}

/// max over corners of a of the distance (max norm) to the nearest corner of b.
double corner_distance(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b) {
  double d = 0;
  for (const Vec3& p : a) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Vec3& q : b) nearest = std::min(nearest, (p - q).cwiseAbs().maxCoeff());
    d = std::max(d, nearest);
  }
  return d;
}

/// Largest distance of a CGAL triangle to its nearest tree triangle (corner_distance), by
/// exhaustive O(n^2) search: only computed when the soups differ, to measure by how much.
double hausdorff(const ClusterTree& tree, const SubdividedTriangles& cgal) {
  double worst = 0;
  for (const auto& t : cgal.triangle) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Cluster& c : tree.elements()) nearest = std::min(nearest, corner_distance(t, c.vertex));
    worst = std::max(worst, nearest);
  }
  return worst;
}

double triangle_area(const std::array<Vec3, 3>& c) { return 0.5 * (c[1] - c[0]).cross(c[2] - c[0]).norm(); }

/// First disagreement between the tree's leaves and the CGAL triangles, empty when they agree:
/// count, corners (exact equality), facet ids, area per facet (1e-14 relative).
/// max_coordinate_difference receives 0 when the corners agree exactly, else hausdorff().
std::string compare(const ClusterTree& tree, const SubdividedTriangles& cgal, double& max_coordinate_difference) {
  std::ostringstream msg;
  msg.precision(17);
  max_coordinate_difference = 0;
  if (cgal.triangle.size() != cgal.facet.size()) return "CGAL result: triangle and facet counts differ";
  if (static_cast<std::size_t>(tree.num_elements()) != cgal.triangle.size()) {
    msg << "count: tree " << tree.num_elements() << ", CGAL " << cgal.triangle.size();
    return msg.str();
  }
  const Soup a = tree_soup(tree), b = sorted_soup(cgal.triangle, cgal.facet);
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].first != b[i].first) {
      max_coordinate_difference = hausdorff(tree, cgal);
      msg << "sorted triangle " << i << ": corners differ (largest distance of a CGAL triangle to its nearest "
          << "tree triangle: " << max_coordinate_difference << ")";
      return msg.str();
    }
    if (a[i].second != b[i].second) {
      msg << "sorted triangle " << i << ": facet " << a[i].second << " in the tree, " << b[i].second << " from CGAL";
      return msg.str();
    }
  }
  // Area per facet: the tree's exact subdivision areas (root area / 4^L) against the areas of
  // CGAL's rounded corners.
  std::vector<double> tree_area(static_cast<std::size_t>(tree.num_facets()), 0.0), cgal_area = tree_area;
  for (const Cluster& c : tree.elements()) tree_area[static_cast<std::size_t>(c.facet)] += c.area;
  for (std::size_t i = 0; i < cgal.triangle.size(); ++i) {
    const Index f = cgal.facet[i];
    if (f < 0 || f >= tree.num_facets()) {
      msg << "CGAL triangle " << i << ": facet " << f << " out of range";
      return msg.str();
    }
    cgal_area[static_cast<std::size_t>(f)] += triangle_area(cgal.triangle[i]);
  }
  for (std::size_t f = 0; f < tree_area.size(); ++f)
    if (!(std::abs(tree_area[f] - cgal_area[f]) <= 1e-14 * tree_area[f])) {
      msg << "facet " << f << ": area " << tree_area[f] << " in the tree, " << cgal_area[f] << " from CGAL";
      return msg.str();
    }
  return {};
}

TriangleMesh validated(TriangleMesh mesh) {
  const ValidationReport report = validate_closed_convex(mesh);
  EXPECT_TRUE(report.valid) << report.message;
  return mesh;
}

std::vector<std::pair<std::string, TriangleMesh>> meshes() {
  std::vector<std::pair<std::string, TriangleMesh>> m;
  m.emplace_back("cube", validated(make_cube()));
  m.emplace_back("prism:6", validated(make_prism(6)));
  m.emplace_back("tetrahedron", validated(make_tetrahedron()));
  m.emplace_back("dodecahedron", load_closed_convex(PANELRAD_SOURCE_DIR "/examples/meshes/dodecahedron.off"));
  return m;
}

TEST(CgalSubdivision, AgreesWithClusterTreeBitForBit) {
  for (const auto& [name, mesh] : meshes()) {
    const std::size_t n0 = mesh.triangles.size();
    for (int level = 0; level <= 3; ++level) {
      SCOPED_TRACE(name + " level " + std::to_string(level));
      const ClusterTree tree(mesh, level);
      const SubdividedTriangles cgal = subdivide_with_cgal(mesh, level);
      EXPECT_EQ(cgal.triangle.size(), n0 << (2 * level));
      double max_difference = -1;
      EXPECT_EQ(compare(tree, cgal, max_difference), "");
      EXPECT_EQ(max_difference, 0.0);
    }
  }
}

TEST(CgalSubdivision, DodecahedronFacetsAreRetriangulatedPentagons) {
  // The shipped dodecahedron is re-triangulated from the exact hull: 12 facets, 36 triangles whose
  // three per facet are not exactly coplanar, so facet ids must come from the root triangle.
  const TriangleMesh mesh = load_closed_convex(PANELRAD_SOURCE_DIR "/examples/meshes/dodecahedron.off");
  EXPECT_EQ(mesh.num_facets, 12);
  EXPECT_EQ(mesh.triangles.size(), 36u);
  const SubdividedTriangles cgal = subdivide_with_cgal(mesh, 2);
  std::vector<int> per_facet(12, 0);
  for (Index f : cgal.facet) ++per_facet[static_cast<std::size_t>(f)];
  for (int count : per_facet) EXPECT_EQ(count, 3 * 16);
}

// The comparison must be able to fail: negative controls.
TEST(CgalSubdivision, ComparisonDetectsPerturbations) {
  const TriangleMesh mesh = validated(make_prism(6));
  const ClusterTree tree(mesh, 2);
  const SubdividedTriangles cgal = subdivide_with_cgal(mesh, 2);
  double diff = 0;
  ASSERT_EQ(compare(tree, cgal, diff), "");

  // Wrong level: count mismatch.
  EXPECT_NE(compare(tree, subdivide_with_cgal(mesh, 1), diff), "");
  EXPECT_NE(compare(ClusterTree(mesh, 3), cgal, diff), "");

  // One coordinate moved by one ulp: corner mismatch, measured as exactly that ulp.
  SubdividedTriangles moved = cgal;
  double& x = moved.triangle[5][1][0];
  const double before = x;
  x = std::nextafter(x, 10.0);
  EXPECT_NE(compare(tree, moved, diff), "");
  EXPECT_EQ(diff, x - before);

  // One facet id changed.
  SubdividedTriangles relabelled = cgal;
  relabelled.facet[7] = (relabelled.facet[7] + 1) % mesh.num_facets;
  EXPECT_NE(compare(tree, relabelled, diff), "");

  // Two corners swapped between triangles of different root triangles keep the count and the
  // corner multiset, but not the triangles.
  SubdividedTriangles swapped = cgal;
  std::size_t other = 0;
  while (other < swapped.triangle.size() && swapped.facet[other] == swapped.facet[0]) ++other;
  ASSERT_LT(other, swapped.triangle.size());
  std::swap(swapped.triangle[0][0], swapped.triangle[other][0]);
  EXPECT_NE(compare(tree, swapped, diff), "");
}

TEST(CgalSubdivision, RejectsBadInput) {
  const TriangleMesh cube = validated(make_cube());
  EXPECT_THROW(subdivide_with_cgal(cube, -1), MeshError);
  EXPECT_THROW(subdivide_with_cgal(cube, 16), MeshError);  // 12 * 4^16 > 2^31 - 1
  TriangleMesh open = cube;
  open.triangles.pop_back();
  open.facet_of_triangle.pop_back();
  EXPECT_THROW(subdivide_with_cgal(open, 1), MeshError);
  TriangleMesh bad_index = cube;
  bad_index.triangles[0][0] = 99;
  EXPECT_THROW(subdivide_with_cgal(bad_index, 1), MeshError);
}

}  // namespace

// The cluster tree (39)-(40): uniform 4-way midpoint subdivision, element numbering, inner normals,
// areas, collocation points (22), circumcircles (41), memory refusal, transform invariance.
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/support/byte_size.hpp>
#include <panelrad/geometry/cluster_tree.hpp>
#include <panelrad/support/resources.hpp>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace panelrad::geometry;

constexpr double u = 0x1p-53;  // unit roundoff

/// Triangulated convex polyhedron from polygon faces (one facet each); every triangle oriented
/// counter-clockwise seen from outside (outward normal points away from an interior point).
/// `split` gives the triangles of face f as corner positions in the face's corner list.
TriangleMesh make_mesh(std::vector<Vec3> vertices, const std::vector<std::vector<Index>>& faces,
                       const std::vector<std::vector<std::array<int, 3>>>& split, const std::string& name) {
  TriangleMesh mesh;
  mesh.vertices = std::move(vertices);
  mesh.source = name;
  Vec3 interior = Vec3::Zero();
  for (const Vec3& v : mesh.vertices) interior += v;
  interior /= static_cast<double>(mesh.vertices.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    for (const auto& t : split[f]) {
      std::array<Index, 3> tri{faces[f][t[0]], faces[f][t[1]], faces[f][t[2]]};
      const Vec3 &a = mesh.vertices[tri[0]], &b = mesh.vertices[tri[1]], &c = mesh.vertices[tri[2]];
      if ((b - a).cross(c - a).dot(a - interior) < 0) std::swap(tri[1], tri[2]);
      mesh.triangles.push_back(tri);
      mesh.facet_of_triangle.push_back(static_cast<Index>(f));
    }
  }
  mesh.num_facets = static_cast<Index>(faces.size());
  return mesh;
}

/// The paper's unit cube: each square split along the diagonal joining its two corners with odd
/// coordinate sum x+y+z (builtin_scenes.hpp).
TriangleMesh local_cube() {
  std::vector<Vec3> v;
  for (int i = 0; i < 8; ++i) v.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  std::vector<std::vector<Index>> faces;
  std::vector<std::vector<std::array<int, 3>>> split;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      std::vector<Index> odd, even;
      for (Index i = 0; i < 8; ++i)
        if (static_cast<int>(v[i][axis]) == side) {
          const int sum = static_cast<int>(v[i].sum());
          (sum % 2 ? odd : even).push_back(i);
        }
      faces.push_back({odd[0], odd[1], even[0], even[1]});
      split.push_back({{0, 1, 2}, {0, 1, 3}});  // both triangles contain the odd diagonal
    }
  return make_mesh(v, faces, split, "local cube");
}

/// Right prism over a regular k-gon (circumradius r, height h): non-dyadic coordinates.
TriangleMesh local_prism(int k, double r, double h) {
  std::vector<Vec3> v;
  const double pi = std::acos(-1.0);
  for (int z = 0; z < 2; ++z)
    for (int i = 0; i < k; ++i) v.emplace_back(r * std::cos(2 * pi * i / k), r * std::sin(2 * pi * i / k), z * h);
  std::vector<std::vector<Index>> faces;
  std::vector<std::vector<std::array<int, 3>>> split;
  for (int i = 0; i < k; ++i) {
    faces.push_back({i, (i + 1) % k, k + (i + 1) % k, k + i});
    split.push_back({{0, 1, 2}, {0, 2, 3}});
  }
  for (int z = 0; z < 2; ++z) {
    std::vector<Index> cap;
    std::vector<std::array<int, 3>> fan;
    for (int i = 0; i < k; ++i) cap.push_back(z * k + i);
    for (int i = 1; i + 1 < k; ++i) fan.push_back({0, i, i + 1});
    faces.push_back(cap);
    split.push_back(fan);
  }
  return make_mesh(v, faces, split, "local prism");
}

/// An irregular tetrahedron (obtuse faces: circumcentres outside their triangles).
TriangleMesh local_tetrahedron() {
  std::vector<Vec3> v{{0.1, 0.05, 0.0}, {3.3, 0.2, 0.1}, {0.7, 0.9, 0.05}, {1.1, 0.4, 1.7}};
  return make_mesh(v, {{0, 1, 2}, {0, 1, 3}, {1, 2, 3}, {0, 2, 3}}, {{{0, 1, 2}}, {{0, 1, 2}}, {{0, 1, 2}}, {{0, 1, 2}}},
                   "local tetrahedron");
}

TriangleMesh transformed(TriangleMesh mesh, double scale, const Vec3& shift) {
  for (Vec3& v : mesh.vertices) v = v * scale + shift;
  return mesh;
}

Vec3 interior_point(const TriangleMesh& mesh) {
  Vec3 g = Vec3::Zero();
  for (const Vec3& v : mesh.vertices) g += v;
  return g / static_cast<double>(mesh.vertices.size());
}

double geometric_area(const Cluster& c) {
  return 0.5 * (c.vertex[1] - c.vertex[0]).cross(c.vertex[2] - c.vertex[0]).norm();
}

/// Barycentric coordinates of X (projected onto the triangle's plane) in long double.
std::array<long double, 3> barycentric(const Cluster& c, const Vec3& X) {
  using V = Eigen::Matrix<long double, 3, 1>;
  const V a = c.vertex[0].cast<long double>(), b = c.vertex[1].cast<long double>(),
          d = c.vertex[2].cast<long double>(), x = X.cast<long double>();
  const V n = (b - a).cross(d - a);
  const long double total = n.squaredNorm();
  return {(d - b).cross(x - b).dot(n) / total, (a - d).cross(x - d).dot(n) / total, (b - a).cross(x - a).dot(n) / total};
}

struct Scene {
  std::string name;
  TriangleMesh mesh;
  int level;
};

std::vector<Scene> scenes() {
  return {{"cube", local_cube(), 4}, {"prism6", local_prism(6, 1.0, 1.0), 3}, {"tetrahedron", local_tetrahedron(), 3}};
}

TEST(ClusterTree, LocalCubeFollowsTheDiagonalRule) {
  const TriangleMesh cube = local_cube();
  ASSERT_EQ(cube.triangles.size(), 12u);
  for (const auto& t : cube.triangles) {
    int odd = 0;
    for (Index i : t) odd += static_cast<int>(cube.vertices[i].sum()) % 2;
    EXPECT_EQ(odd, 2);  // each triangle holds the odd diagonal
  }
}

TEST(ClusterTree, BuiltinScenesGiveConsistentTrees) {
  // The built-in scenes (builtin_scenes.cpp): counter-clockwise from outside, so inner normals
  // point into the solid on every level; level areas sum to the surface area.
  for (const std::string spec : {"cube", "prism:6", "prism:3", "tetrahedron", "octahedron"}) {
    SCOPED_TRACE(spec);
    const TriangleMesh mesh = make_builtin(spec);
    const ClusterTree tree(mesh, 2);
    const Vec3 inside = interior_point(mesh);
    const double surface = surface_area(mesh);
    for (int l = 0; l <= 2; ++l) {
      long double sum = 0;
      for (const Cluster& c : tree.level(l)) {
        sum += c.area;
        EXPECT_GT(c.normal.dot(inside - (c.vertex[0] + c.vertex[1] + c.vertex[2]) / 3.0), 0.0);
      }
      EXPECT_NEAR(static_cast<double>(sum), surface, 1e-14 * surface);  // bound as in AreasSumToTheSurfaceArea
    }
  }
  // The paper's cube: the same triangles (as corner sets, facet by facet) as the local cube.
  const TriangleMesh builtin = make_cube(), local = local_cube();
  ASSERT_EQ(builtin.triangles.size(), 12u);
  std::multiset<std::vector<double>> a, b;
  auto key = [](const TriangleMesh& m, std::size_t t) {
    std::vector<std::array<double, 3>> corners;
    for (Index i : m.triangles[t]) corners.push_back({m.vertices[i].x(), m.vertices[i].y(), m.vertices[i].z()});
    std::sort(corners.begin(), corners.end());
    std::vector<double> flat;
    for (const auto& c : corners) flat.insert(flat.end(), c.begin(), c.end());
    return flat;
  };
  for (std::size_t t = 0; t < 12; ++t) {
    a.insert(key(builtin, t));
    b.insert(key(local, t));
  }
  EXPECT_EQ(a, b);
}

TEST(ClusterTree, LevelSizesAndContiguousRanges) {
  for (const Scene& s : scenes()) {
    SCOPED_TRACE(s.name);
    const ClusterTree tree(s.mesh, s.level);
    const Index n0 = static_cast<Index>(s.mesh.triangles.size());
    ASSERT_EQ(tree.num_roots(), n0);
    ASSERT_EQ(tree.finest_level(), s.level);
    ASSERT_EQ(tree.num_elements(), n0 << (2 * s.level));
    ASSERT_EQ(tree.elements().size(), static_cast<std::size_t>(tree.num_elements()));
    ASSERT_EQ(tree.collocation_points().size(), static_cast<std::size_t>(tree.num_elements()));
    ASSERT_EQ(tree.num_facets(), s.mesh.num_facets);
    for (int l = 0; l <= s.level; ++l) {
      ASSERT_EQ(tree.level(l).size(), static_cast<std::size_t>(n0) << (2 * l));
      ASSERT_EQ(tree.level_size(l), static_cast<Index>(tree.level(l).size()));
      // Each level partitions [0, n) into consecutive ranges, nested in the parent's range.
      Index expected_first = 0;
      for (Index k = 0; k < tree.level_size(l); ++k) {
        ASSERT_EQ(tree.first_element(l, k), expected_first);
        ASSERT_GT(tree.end_element(l, k), tree.first_element(l, k));
        expected_first = tree.end_element(l, k);
        if (l > 0) {
          ASSERT_GE(tree.first_element(l, k), tree.first_element(l - 1, k / 4));
          ASSERT_LE(tree.end_element(l, k), tree.end_element(l - 1, k / 4));
          EXPECT_EQ(tree.cluster(l, k).facet, tree.cluster(l - 1, k / 4).facet);
        }
        // Geometry agrees with the numbering: every element of the range lies in the cluster.
        const Cluster& c = tree.cluster(l, k);
        for (Index e = tree.first_element(l, k); e < tree.end_element(l, k); ++e) {
          for (long double beta : barycentric(c, tree.collocation_point(e))) ASSERT_GT(beta, 0.0L);
        }
      }
      ASSERT_EQ(expected_first, tree.num_elements());
    }
    for (Index k = 0; k < n0; ++k) {
      EXPECT_EQ(tree.cluster(0, k).facet, s.mesh.facet_of_triangle[k]);
      for (int i = 0; i < 3; ++i) EXPECT_EQ(tree.cluster(0, k).vertex[i], s.mesh.vertices[s.mesh.triangles[k][i]]);
    }
  }
}

TEST(ClusterTree, ChildrenAreTheMidpointSubtrianglesInOrder) {
  const ClusterTree tree(local_prism(5, 1.3, 0.7), 2);
  for (int l = 0; l < 2; ++l)
    for (Index k = 0; k < tree.level_size(l); ++k) {
      const auto& p = tree.cluster(l, k).vertex;
      const Vec3 ab = (p[0] + p[1]) * 0.5, bc = (p[1] + p[2]) * 0.5, ca = (p[2] + p[0]) * 0.5;
      const std::array<std::array<Vec3, 3>, 4> expected{{{p[0], ab, ca}, {ab, p[1], bc}, {ca, bc, p[2]}, {ab, bc, ca}}};
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 3; ++i) EXPECT_EQ(tree.cluster(l + 1, 4 * k + j).vertex[i], expected[j][i]);
    }
}

TEST(ClusterTree, AreasSumToTheSurfaceAreaOnEveryLevel) {
  for (const Scene& s : scenes()) {
    SCOPED_TRACE(s.name);
    const ClusterTree tree(s.mesh, s.level);
    const double surface = surface_area(s.mesh);
    for (int l = 0; l <= s.level; ++l) {
      long double sum = 0;
      for (const Cluster& c : tree.level(l)) {
        sum += c.area;
        // Stored area (root area / 4^l) against the area of the stored (rounded) corners: the
        // corners are the exact midpoints up to (l+1) roundings of u |x| each, i.e. a relative
        // perturbation below (l+1) u |x| / h_l; with |x| <= 3.4, h_l >= 0.09 / 2^l here and the
        // cross product's own few u, 1e-12 bounds it with a wide margin.
        EXPECT_NEAR(geometric_area(c), c.area, 1e-12 * c.area);
      }
      // Each root area is rounded once (relative u) and the level-0 surface_area sum has
      // relative error <= n0 u; scaling by 4^-l is exact: 1e-14 covers n0 <= 20 here.
      EXPECT_NEAR(static_cast<double>(sum), surface, 1e-14 * surface) << "level " << l;
      for (Index k = 0; l > 0 && k < tree.level_size(l - 1); ++k) {
        double children = 0;
        for (Index j = 0; j < 4; ++j) children += tree.cluster(l, 4 * k + j).area;
        EXPECT_NEAR(children, tree.cluster(l - 1, k).area, 4 * u * tree.cluster(l - 1, k).area);
      }
    }
  }
}

TEST(ClusterTree, CollocationPointsAreCentroidsInsideTheirElements) {
  for (const Scene& s : scenes()) {
    SCOPED_TRACE(s.name);
    const ClusterTree tree(s.mesh, s.level);
    for (Index e = 0; e < tree.num_elements(); ++e) {
      const Cluster& c = tree.elements()[e];
      const Vec3& P = tree.collocation_point(e);
      for (long double beta : barycentric(c, P)) {
        EXPECT_GT(beta, 0.0L);
        EXPECT_NEAR(static_cast<double>(beta), 1.0 / 3.0, 1e-12);  // the centroid (22)
      }
      // Exact (a+b+c)/3 rounded once: within u |P| per component; the double sum within 3u|x|.
      const Vec3 g = (c.vertex[0] + c.vertex[1] + c.vertex[2]) / 3.0;
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(P[i], g[i], 8 * u * (std::abs(g[i]) + 1e-300));
    }
  }
}

TEST(ClusterTree, CircumcircleIsExactThenRoundedOnce) {
  for (const Scene& s : scenes()) {
    SCOPED_TRACE(s.name);
    const ClusterTree tree(s.mesh, s.level);
    for (int l = 0; l <= s.level; ++l)
      for (const Cluster& c : tree.level(l)) {
        const Vec3& A = c.centre;
        const double R = c.radius;
        // A is the exact centre rounded once: |A - A_exact| <= u |A|_2 (componentwise u|A_i|),
        // and the distances to the corners are computed with a few more u |A - v|. Relative to R:
        const double bound = (4 * u * (A.norm() + c.vertex[0].norm()) + 8 * u * R) / R;
        for (int i = 0; i < 3; ++i) EXPECT_NEAR((A - c.vertex[i]).norm() / R, 1.0, bound);
        // In the triangle's plane (same error budget, measured along the unit normal).
        const Vec3 w = (c.vertex[1] - c.vertex[0]).cross(c.vertex[2] - c.vertex[0]).normalized();
        EXPECT_LE(std::abs((A - c.vertex[0]).dot(w)) / R, bound);
        // R against abc / (4 area) evaluated in double from the corners: each length and the area
        // carry a few u relative error (these triangles are far from degenerate): 1e-13.
        const double a = (c.vertex[1] - c.vertex[2]).norm(), b = (c.vertex[2] - c.vertex[0]).norm(),
                     cc = (c.vertex[0] - c.vertex[1]).norm();
        EXPECT_NEAR(R, a * b * cc / (4 * geometric_area(c)), 1e-13 * R);
      }
  }
}

TEST(ClusterTree, CubeCircumcentresAreHypotenuseMidpointsExactly) {
  // Every cube cluster is a right isosceles triangle with dyadic corners: A is the midpoint of
  // the hypotenuse and R half its length, both exact in double, so "rounded once" means equal.
  const ClusterTree tree(local_cube(), 3);
  for (int l = 0; l <= 3; ++l)
    for (const Cluster& c : tree.level(l)) {
      int hyp = 0;
      double longest = 0;
      for (int i = 0; i < 3; ++i) {
        const double len = (c.vertex[(i + 1) % 3] - c.vertex[(i + 2) % 3]).squaredNorm();
        if (len > longest) longest = len, hyp = i;
      }
      const Vec3 mid = (c.vertex[(hyp + 1) % 3] + c.vertex[(hyp + 2) % 3]) * 0.5;
      EXPECT_EQ(c.centre, mid);
      EXPECT_EQ(c.radius, std::sqrt(longest) * 0.5);  // sqrt(2) / 2^(l+1): sqrt correctly rounded
    }
}

TEST(ClusterTree, InnerNormalsPointIntoTheSolid) {
  for (const Scene& s : scenes()) {
    SCOPED_TRACE(s.name);
    const ClusterTree tree(s.mesh, s.level);
    const Vec3 inside = interior_point(s.mesh);
    for (int l = 0; l <= s.level; ++l)
      for (Index k = 0; k < tree.level_size(l); ++k) {
        const Cluster& c = tree.cluster(l, k);
        const Vec3 g = (c.vertex[0] + c.vertex[1] + c.vertex[2]) / 3.0;
        EXPECT_GT(c.normal.dot(inside - g), 0.0);
        EXPECT_NEAR(c.normal.norm(), 1.0, 4 * u);
        for (int i = 0; i < 3; ++i)  // perpendicular to the edges, up to the midpoints' rounding
          EXPECT_LE(std::abs(c.normal.dot(c.vertex[(i + 1) % 3] - c.vertex[i])), 1e-13);
        if (l > 0) {
          EXPECT_EQ(c.normal, tree.cluster(l - 1, k / 4).normal);  // the root's, bit for bit
        }
      }
  }
}

TEST(ClusterTree, MeshSizeAndDiameter) {
  const ClusterTree tree(local_cube(), 4);
  EXPECT_DOUBLE_EQ(tree.mesh_size(), std::sqrt(2.0) / 16);  // hypotenuse at level 4
  EXPECT_DOUBLE_EQ(tree.diameter(), std::sqrt(3.0));
  const ClusterTree prism(local_prism(6, 2.0, 0.5), 0);
  EXPECT_NEAR(prism.mesh_size(), 4.0, 4 * u * 4);  // the cap's long diagonal, 2r
}

/// Compares tree b with tree a mapped by x -> scale x + shift, with absolute tolerances.
void expect_same_tree_up_to(const ClusterTree& a, const ClusterTree& b, double scale, const Vec3& shift,
                            double pos_tol, double rel_tol) {
  ASSERT_EQ(a.num_elements(), b.num_elements());
  for (int l = 0; l <= a.finest_level(); ++l)
    for (Index k = 0; k < a.level_size(l); ++k) {
      const Cluster &x = a.cluster(l, k), &y = b.cluster(l, k);
      for (int i = 0; i < 3; ++i) ASSERT_LE((x.vertex[i] * scale + shift - y.vertex[i]).norm(), pos_tol);
      ASSERT_LE((x.centre * scale + shift - y.centre).norm(), pos_tol);
      ASSERT_NEAR(x.radius * scale, y.radius, pos_tol);
      ASSERT_NEAR(x.area * scale * scale, y.area, rel_tol * y.area);
      ASSERT_LE((x.normal - y.normal).norm(), rel_tol);
      ASSERT_EQ(x.facet, y.facet);
    }
  for (Index e = 0; e < a.num_elements(); ++e)
    ASSERT_LE((a.collocation_point(e) * scale + shift - b.collocation_point(e)).norm(), pos_tol);
  EXPECT_NEAR(a.mesh_size() * scale, b.mesh_size(), pos_tol);
  EXPECT_NEAR(a.diameter() * scale, b.diameter(), rel_tol * b.diameter());
}

TEST(ClusterTree, TranslationBy1e6AndScalingBy1em6GiveTheSameTree) {
  for (const Scene& s : scenes()) {
    SCOPED_TRACE(s.name);
    const int L = s.level;
    const ClusterTree tree(s.mesh, L);
    {
      // Translation: every stored vertex is the exact one up to one rounding per level plus the
      // shift's rounding, each <= ulp(2e6)/2 = 2^-32 (coordinates < 2^21): (L+2) 2^-32 per
      // component; A and R are Lipschitz in the corners with a constant ~ 1/sin(smallest angle)
      // (< 10 here) and the unshifted tree's own roundings are far smaller: 16 (L+2) 2^-32.
      // Normals and areas come from root triangles whose shifted corners are rounded once
      // (relative 2^-32 / 0.1 of the root size): 1e-8.
      const Vec3 shift(1e6, -1e6, 1e6);
      const ClusterTree moved(transformed(s.mesh, 1.0, shift), L);
      expect_same_tree_up_to(tree, moved, 1.0, shift, 16.0 * (L + 2) * 0x1p-32, 1e-8);
    }
    {
      // Scaling by 1e-6 (not a power of two): every coordinate and every rounding is relative
      // u |x| with |x| <= 3.4e-6; same reasoning without the shift: 16 (L+2) u 3.4e-6 absolute,
      // normals and areas a few u relative to the root triangles' shape: 1e-13.
      const double scale = 1e-6;
      const ClusterTree small(transformed(s.mesh, scale, Vec3::Zero()), L);
      expect_same_tree_up_to(tree, small, scale, Vec3::Zero(), 16.0 * (L + 2) * u * 3.4e-6, 1e-13);
    }
  }
}

TEST(ClusterTree, PowerOfTwoScalingIsExact) {
  // Scaling by 2^k is exact in double, and so is rounding an exact value to nearest: the tree of
  // 2^k x must be the tree of x times 2^k bit for bit (areas 4^k), far outside the range where
  // the intermediate squares (degree 10 in the coordinates) fit a double.
  for (const Scene& s : scenes()) {
    const ClusterTree tree(s.mesh, 2);
    for (int k : {-500, -60, 60, 300}) {
      SCOPED_TRACE(s.name + " 2^" + std::to_string(k));
      const double f = std::ldexp(1.0, k);
      const ClusterTree scaled(transformed(s.mesh, f, Vec3::Zero()), 2);
      for (int l = 0; l <= 2; ++l)
        for (Index c = 0; c < tree.level_size(l); ++c) {
          const Cluster &x = tree.cluster(l, c), &y = scaled.cluster(l, c);
          for (int i = 0; i < 3; ++i) ASSERT_EQ(x.vertex[i] * f, y.vertex[i]);
          ASSERT_EQ(x.centre * f, y.centre);
          ASSERT_EQ(x.radius * f, y.radius);
          ASSERT_EQ(x.area * f * f, y.area);
          ASSERT_EQ(x.normal, y.normal);
        }
      for (Index e = 0; e < tree.num_elements(); ++e) ASSERT_EQ(tree.collocation_point(e) * f, scaled.collocation_point(e));
      EXPECT_EQ(tree.mesh_size() * f, scaled.mesh_size());
      EXPECT_EQ(tree.diameter() * f, scaled.diameter());
    }
  }
}

TEST(ClusterTree, IndependentOfTheThreadCount) {
  const TriangleMesh mesh = local_prism(7, 1.0, 2.0);
  panelrad::set_threads(1);
  const ClusterTree one(mesh, 3);
  panelrad::set_threads(2);
  const ClusterTree two(mesh, 3);
  panelrad::set_threads(0);
  for (int l = 0; l <= 3; ++l)
    for (Index k = 0; k < one.level_size(l); ++k) {
      const Cluster &x = one.cluster(l, k), &y = two.cluster(l, k);
      ASSERT_EQ(x.centre, y.centre);
      ASSERT_EQ(x.radius, y.radius);
      ASSERT_EQ(x.normal, y.normal);
      ASSERT_EQ(x.area, y.area);
      for (int i = 0; i < 3; ++i) ASSERT_EQ(x.vertex[i], y.vertex[i]);
    }
  for (Index e = 0; e < one.num_elements(); ++e) ASSERT_EQ(one.collocation_point(e), two.collocation_point(e));
  EXPECT_EQ(one.mesh_size(), two.mesh_size());
}

TEST(ClusterTree, BytesMatchTheEstimate) {
  const ClusterTree tree(local_cube(), 4);
  const std::size_t estimate = ClusterTree::estimate_bytes(12, 4);
  std::size_t payload = tree.num_elements() * sizeof(Vec3);
  for (int l = 0; l <= 4; ++l) payload += tree.level(l).size() * sizeof(Cluster);
  EXPECT_GE(tree.bytes(), payload);
  EXPECT_GE(estimate, payload);
  EXPECT_LE(tree.bytes(), estimate + estimate / 100);
  EXPECT_NEAR(tree.bytes_per_element(), static_cast<double>(tree.bytes()) / tree.num_elements(), 1e-9);
  // About (4/3) sizeof(Cluster) + sizeof(Vec3) per element.
  EXPECT_NEAR(tree.bytes_per_element(), 4.0 / 3.0 * sizeof(Cluster) + sizeof(Vec3), 0.01 * tree.bytes_per_element());
  EXPECT_EQ(ClusterTree::estimate_bytes(12, 40), std::numeric_limits<std::size_t>::max());  // saturates
}

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const MeshError& e) {
    return e.what();
  }
  return "(no MeshError)";
}

TEST(ClusterTree, RefusesTreesThatDoNotFitBeforeAllocating) {
  const TriangleMesh cube = local_cube();
  // Level 5 needs about 12 * 4^5 * 216 B = 2.7 MB: refused under a 1 MB limit, estimate shown.
  const std::string msg = error_of([&] { ClusterTree(cube, 5, std::size_t{1} << 20); });
  const std::string shown = panelrad::format_bytes(static_cast<double>(ClusterTree::estimate_bytes(12, 5)));  // "2.7 MB"
  EXPECT_GT(ClusterTree::estimate_bytes(12, 5), std::size_t{2} << 20);
  EXPECT_NE(msg.find("level 5"), std::string::npos) << msg;
  EXPECT_NE(msg.find("needs an estimated " + shown), std::string::npos) << msg << " lacks " << shown;
  EXPECT_NE(msg.find("more than the 1.0 MB of memory available"), std::string::npos) << msg;  // 2^20 B
  EXPECT_NO_THROW(ClusterTree(cube, 5, std::size_t{4} << 20));
  // Against the machine's memory: level 13 (n = 805,306,368) needs ~174 GB.
  const std::size_t estimate = ClusterTree::estimate_bytes(12, 13);
  ASSERT_GT(ClusterTree::default_memory_limit(), 0u);
  if (estimate <= ClusterTree::default_memory_limit()) GTEST_SKIP() << "this machine could hold level 13";
  const std::string big = error_of([&] { ClusterTree(cube, 13); });
  EXPECT_NE(big.find(" GB"), std::string::npos) << big;
  EXPECT_NE(big.find("805306368"), std::string::npos) << big;
}

TEST(ClusterTree, RejectsBadLevelsAndBadMeshes) {
  const TriangleMesh cube = local_cube();
  EXPECT_NE(error_of([&] { ClusterTree(cube, -1); }).find("negative"), std::string::npos);
  EXPECT_NE(error_of([&] { ClusterTree(cube, 16); }).find("32-bit"), std::string::npos);
  EXPECT_NE(error_of([&] { ClusterTree(cube, 15); }).find("32-bit"), std::string::npos);  // 12 * 4^15 > 2^31
  EXPECT_NE(error_of([&] { ClusterTree(cube, 100); }).find("32-bit"), std::string::npos);
  EXPECT_NE(error_of([&] { ClusterTree(TriangleMesh{}, 0); }).find("no triangles"), std::string::npos);
  {
    TriangleMesh bad = cube;
    bad.triangles[3][1] = 8;
    EXPECT_NE(error_of([&] { ClusterTree(bad, 1); }).find("triangle 3 uses vertex 8"), std::string::npos);
  }
  {
    TriangleMesh bad = cube;
    bad.vertices[5].y() = std::numeric_limits<double>::quiet_NaN();
    EXPECT_NE(error_of([&] { ClusterTree(bad, 1); }).find("not finite"), std::string::npos);
  }
  {
    TriangleMesh bad = cube;
    bad.facet_of_triangle[7] = 6;
    EXPECT_NE(error_of([&] { ClusterTree(bad, 1); }).find("triangle 7 has facet id 6"), std::string::npos);
    bad.facet_of_triangle.pop_back();
    EXPECT_NE(error_of([&] { ClusterTree(bad, 1); }).find("facet ids"), std::string::npos);
  }
  {
    TriangleMesh bad = cube;  // triangle 2 collapsed onto a line
    const auto t = bad.triangles[2];
    bad.vertices.push_back((bad.vertices[t[0]] + bad.vertices[t[1]]) * 0.5);
    bad.triangles[2][2] = static_cast<Index>(bad.vertices.size() - 1);
    EXPECT_NE(error_of([&] { ClusterTree(bad, 1); }).find("triangle 2 has zero area"), std::string::npos);
  }
}

}  // namespace

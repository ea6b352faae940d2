// The element moments (48) of the fast operator, held by shape (two sets per root triangle: every
// element of uniform midpoint subdivision is its root scaled by +-2^-L), and the moments of the
// elements of the next-to-finest level's clusters about their centres, against the closed form
// of each element's own stored corners (triangle_moments).
//
// Tolerance. The shapes' moments are exact scalings of the root's; an element's corners are
// midpoints rounded to double, off the exact shape by 2^-53 of the coordinates (the unit's scale,
// ~1), i.e. by 2^(L-53) of the element's size R. A degree-k moment ~ R^(k+2) then moves by about
// (k+2) 2^(L-53) R^(k+2), and triangle_moments' own rounding of local coordinates is of the same
// order. At L <= 4 and k <= 12 that is below 3e-14 R^(k+2): 1e-12 R^(k+2) leaves a wide margin,
// and a wrong sign or scale (a mistaken parity, a missing 2^-L) is off by O(1) R^(k+2).
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/operator/far_field.hpp>
#include <panelrad/operator/detail/fast_operator_testing.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/scene/scene.hpp>

#include "test_scenes.hpp"
#include "validated_meshes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace panelrad;

// The fast operator (eta 0.5, M = degree) of a built-in scene at a level, with the far field's unit.
struct Setup {
  Setup(const std::string& builtin, int level, int degree)
      : scene(panelrad::testing::validated_builtin(builtin)),
        col(scene, level),
        op(col, options(degree)),
        unit(detail::far_field_unit(col.tree())) {}
  static FastOptions options(int degree) {
    FastOptions o;
    o.eta = 0.5;
    o.degree = degree;
    return o;
  }
  Scene scene;
  Collocation col;
  FastOperator op;
  double unit;
};

void expect_moments_of_the_elements(const std::string& builtin, int level, int degree) {
  const Setup setup(builtin, level, degree);
  const Collocation& col = setup.col;
  const FastOperator& op = setup.op;
  const geometry::ClusterTree& tree = col.tree();
  const double unit = setup.unit;
  const int T = num_taylor_terms(degree);
  std::vector<double> exact(static_cast<std::size_t>(T));
  for (Index e = 0; e < col.size(); ++e) {
    const geometry::Cluster& c = tree.elements()[static_cast<std::size_t>(e)];
    const PlaneFrame frame = make_plane_frame(unit * c.centre, c.normal);
    triangle_moments(frame, unit * c.vertex[0], unit * c.vertex[1], unit * c.vertex[2], degree, exact.data());
    const auto held = detail::element_moments(op, e);
    ASSERT_EQ(held.size(), static_cast<std::size_t>(T));
    const double R = unit * c.radius;
    for (int k = 0; k <= degree; ++k)
      for (int q = 0; q <= k; ++q) {
        const std::size_t t = static_cast<std::size_t>(taylor_index(k - q, q));
        ASSERT_NEAR(held[t], exact[t], 1e-12 * std::pow(R, k + 2))
            << builtin << " level " << level << " element " << e << " x^" << k - q << " y^" << q;
      }
  }
}

// The centres A(tau) the far field expands about: held for the clusters above the finest level
// (the circumcentre, exactly), formed for the elements from the centroid and the shape,
// unit C(e) + s (A(root) - C(root)). Against each element's circumcentre from the tree (exact
// construction rounded once): both are within a few roundings of the coordinates (the unit's
// scale, ~1, at most 2^-50 each at these levels), so 1e-13 leaves a wide margin, while a wrong
// sign or scale of the shift is off by |A - C| of an element (right triangles of the cube, the
// prism's fans and rectangles: above 1e-3 in the unit at level 3).
void expect_expansion_centres(const std::string& builtin, int level) {
  const Setup setup(builtin, level, 4);
  const geometry::ClusterTree& tree = setup.col.tree();
  for (int l = 0; l <= level; ++l)
    for (Index k = 0; k < tree.level_size(l); ++k) {
      const Vec3 exact = setup.unit * tree.cluster(l, k).centre;
      const Vec3 used = detail::expansion_centre(setup.op, detail::cluster_id(setup.op, l, k));
      if (l < level) {
        ASSERT_EQ(used, exact) << builtin << " level " << l << " cluster " << k;
      } else {
        ASSERT_LE((used - exact).norm(), 1e-13) << builtin << " level " << l << " element " << k;
      }
    }
  EXPECT_THROW((void)detail::expansion_centre(setup.op, detail::cluster_id(setup.op, level, tree.level_size(level))),
               std::out_of_range);
}

TEST(ElementMoments, ExpansionCentresOfElementsFromTheirCentroids) {
  for (const int level : {0, 1, 3}) expect_expansion_centres("cube", level);
  expect_expansion_centres("prism:5", 2);
}

// Level >= 1 holds both shapes of every root: child 3 of each triangle is point-reflected.
TEST(ElementMoments, CubeElementsAreScaledCopiesOfTheirRoots) {
  for (const int level : {0, 1, 3}) expect_moments_of_the_elements("cube", level, 6);
}

TEST(ElementMoments, PrismElementsUpToDegreeTwelve) {
  // Triangles of several shapes (the caps' fans and the sides' rectangles), odd and even degrees.
  for (const int degree : {1, 7, 12}) expect_moments_of_the_elements("prism:5", 2, degree);
  expect_moments_of_the_elements("tetrahedron", 4, 5);
}

// The moments of the four elements of each cluster of level L - 1 about that cluster's A(tau)
// (child_shape_moments: the element moments shifted once per placement class), against the closed
// form of each element's stored corners in the cluster's own frame. Tolerance as above, with R
// the cluster's radius: the class's offsets differ from a cluster's own by the rounding of the
// centres, 2^-53 of the coordinates, i.e. 2^(L-54) R; at L <= 7, k <= 12 that is below 3e-13
// R^(k+2). A wrong class (the labels of the corners turned, a wrong sign) is off by O(1) R^(k+2).
void expect_moments_of_the_children(const std::string& builtin, int level, int degree) {
  const Setup setup(builtin, level, degree);
  const geometry::ClusterTree& tree = setup.col.tree();
  const double unit = setup.unit;
  std::vector<double> exact(static_cast<std::size_t>(num_taylor_terms(degree)));
  const std::size_t T = exact.size();
  for (Index k = 0; k < tree.level_size(level - 1); ++k) {
    const geometry::Cluster& parent = tree.cluster(level - 1, k);
    const PlaneFrame frame = make_plane_frame(unit * parent.centre, parent.normal);
    const auto held = detail::child_shape_moments(setup.op, k);
    ASSERT_EQ(held.size(), 4 * T);
    const double R = unit * parent.radius;
    for (Index c = 0; c < 4; ++c) {
      const geometry::Cluster& e = tree.elements()[static_cast<std::size_t>(4 * k + c)];
      triangle_moments(frame, unit * e.vertex[0], unit * e.vertex[1], unit * e.vertex[2], degree, exact.data());
      for (int d = 0; d <= degree; ++d)
        for (int q = 0; q <= d; ++q) {
          const std::size_t t = static_cast<std::size_t>(taylor_index(d - q, q));
          ASSERT_NEAR(held[static_cast<std::size_t>(c) * T + t], exact[t],
                      1e-12 * std::pow(R, d + 2))
              << builtin << " level " << level << " cluster " << k << " child " << c << " x^" << d - q << " y^" << q;
        }
    }
  }
}

// Paths below the root with 0..6 digits 3: every placement class, and the wrap of six.
TEST(ElementMoments, ChildrenOfTheNextToFinestLevelByPlacementClass) {
  for (const int level : {1, 2, 4}) expect_moments_of_the_children("cube", level, 6);
  expect_moments_of_the_children("tetrahedron", 7, 8);
  for (const int degree : {1, 12}) expect_moments_of_the_children("prism:5", 3, degree);
}

TEST(ElementMoments, ChildMomentsOutsideTheNextToFinestLevelAreRefused) {
  const Scene scene(panelrad::testing::validated_builtin("cube"));
  const Collocation col(scene, 2);
  const FastOperator op(col, FastOptions{});
  EXPECT_THROW(static_cast<void>(detail::child_shape_moments(op, -1)), std::out_of_range);
  EXPECT_THROW(static_cast<void>(detail::child_shape_moments(op, col.tree().level_size(1))), std::out_of_range);
  const Collocation roots(scene, 0);
  const FastOperator at_roots(roots, FastOptions{});
  EXPECT_THROW(static_cast<void>(detail::child_shape_moments(at_roots, 0)), std::out_of_range);
}

TEST(ElementMoments, ElementOutsideTheSurfaceIsRefused) {
  const Scene scene(panelrad::testing::validated_builtin("cube"));
  const Collocation col(scene, 1);
  const FastOperator op(col, FastOptions{});
  EXPECT_THROW(static_cast<void>(detail::element_moments(op, -1)), std::out_of_range);
  EXPECT_THROW(static_cast<void>(detail::element_moments(op, col.size())), std::out_of_range);
}

}  // namespace

// A product reads an element's moments as v_e times those of its shape (they are never stored):
// with v the indicator of element e, (K_fast v)_i is the entry K(i, e), near or far, against the
// dense operator's exact integral. Far, it is the Taylor series (44)-(47) of degree M of one
// element (as a leaf of P_i's covering) or of an ancestor holding it; its remainder (46) is
// O((R/|P - A|)^(M+1)), R/|P - A| <= eta, relative to the entry: the tolerance is eta^(M+1)
// of the column's largest entry (1.2e-4 at eta 0.5, 2.4e-2 at eta 0.75, where level 0 has far
// pairs), and the errors measured are 2.4 to 960 times below it. A wrong root, scale or sign of
// the odd degrees moves an entry by O(eta) or more of itself (a flipped parity: 0.04 to 0.9 of
// the largest entry). Every storage of the coefficients (stored: every element's column;
// recomputed per product: every fifth), the columns from one block product (the elements'
// moments formed for several columns), single products of every 37th giving the same bits; on
// level 0 (every cluster an element, one shape per root) and above.
void expect_entries_of_the_elements(const std::string& builtin, int level, double eta) {
  constexpr int kDegree = 12;
  const double tolerance = std::pow(eta, kDegree + 1);
  const Scene scene = panelrad::testing::reflecting_builtin(builtin);  // rho 0.5: every row computed
  const Collocation col(scene, level);
  const Index n = col.size();
  const DenseOperator dense(col, NearFieldOptions{});
  struct Mode {
    const char* name;
    std::size_t limit;
    bool single;
    Index stride;  // the columns checked: every stride-th element's, and the last
  };
  // The recomputed coefficients are formed anew for every block of columns: a fifth of the
  // columns there (the element moments are the same code in all modes).
  for (const Mode mode : {Mode{"recomputed", 1, false, 5}, Mode{"stored double", SIZE_MAX, false, 1},
                          Mode{"stored single", SIZE_MAX, true, 1}}) {
    FastOptions o;
    o.eta = eta;
    o.degree = kDegree;
    o.far_storage_limit = mode.limit;
    o.single_precision_coefficients = mode.single;
    const FastOperator op(col, o);
    ASSERT_GT(op.statistics().far_pairs, 0u) << builtin << " level " << level;
    ASSERT_EQ(op.statistics().far_stored, mode.limit != 1);
    // The columns at once (a block product of columns of the identity), against the dense
    // operator's; single products of some columns give the same bits as the block's.
    std::vector<Index> element;
    for (Index e = 0; e < n; ++e)
      if (e % mode.stride == 0 || e == n - 1) element.push_back(e);
    const auto m = static_cast<Index>(element.size());
    Eigen::MatrixXd V = Eigen::MatrixXd::Zero(n, m), Y, exact;
    for (Index c = 0; c < m; ++c) V(element[static_cast<std::size_t>(c)], c) = 1.0;
    op.apply_block(V, Y);
    dense.apply_block(V, exact);
    double worst = 0;
    for (Index c = 0; c < m; ++c) {
      const double scale = exact.col(c).cwiseAbs().maxCoeff();
      ASSERT_GT(scale, 0.0);
      worst = std::max(worst, (Y.col(c) - exact.col(c)).cwiseAbs().maxCoeff() / scale);
      if (c % 37 != m % 37 && c != m - 1) continue;
      Eigen::VectorXd y;
      op.apply(V.col(c), y);
      for (Index i = 0; i < n; ++i) ASSERT_EQ(Y(i, c), y[i]) << "element " << element[static_cast<std::size_t>(c)] << ", row " << i;
    }
    EXPECT_LE(worst, tolerance) << builtin << " level " << level << ", " << mode.name;
    std::printf("%s level %d eta %.2f %s: max error %.3e of the column's largest entry\n", builtin.c_str(), level, eta,
                mode.name, worst);
  }
}

TEST(ElementMoments, ProductsFormThemForFarElements) {
  expect_entries_of_the_elements("cube", 0, 0.75);
  expect_entries_of_the_elements("prism:5", 0, 0.75);
  expect_entries_of_the_elements("cube", 1, 0.5);
  expect_entries_of_the_elements("cube", 2, 0.5);
  expect_entries_of_the_elements("prism:5", 2, 0.5);
  expect_entries_of_the_elements("tetrahedron", 3, 0.5);
}

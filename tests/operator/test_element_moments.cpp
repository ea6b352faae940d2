// The element moments (48) of the fast operator, held by shape (two sets per root triangle: every
// element of uniform midpoint subdivision is its root scaled by +-2^-L), against the closed form
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
#include <panelrad/operator/far_field.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/scene/scene.hpp>

#include "validated_meshes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace panelrad;

void expect_moments_of_the_elements(const std::string& builtin, int level, int degree) {
  const Scene scene(panelrad::testing::validated_builtin(builtin));
  const Collocation col(scene, level);
  FastOptions o;
  o.eta = 0.5;
  o.degree = degree;
  const FastOperator op(col, o);
  const geometry::ClusterTree& tree = col.tree();
  const double unit = FastOperator::far_field_unit(tree);
  const int T = num_taylor_terms(degree);
  std::vector<double> exact(static_cast<std::size_t>(T));
  for (Index e = 0; e < col.size(); ++e) {
    const geometry::Cluster& c = tree.elements()[static_cast<std::size_t>(e)];
    const PlaneFrame frame = make_plane_frame(unit * c.centre, c.normal);
    triangle_moments(frame, unit * c.vertex[0], unit * c.vertex[1], unit * c.vertex[2], degree, exact.data());
    const auto held = op.element_moments(e);
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

// Level >= 1 holds both shapes of every root: child 3 of each triangle is point-reflected.
TEST(ElementMoments, CubeElementsAreScaledCopiesOfTheirRoots) {
  for (const int level : {0, 1, 3}) expect_moments_of_the_elements("cube", level, 6);
}

TEST(ElementMoments, PrismElementsUpToDegreeTwelve) {
  // Triangles of several shapes (the caps' fans and the sides' rectangles), odd and even degrees.
  for (const int degree : {1, 7, 12}) expect_moments_of_the_elements("prism:5", 2, degree);
  expect_moments_of_the_elements("tetrahedron", 4, 5);
}

TEST(ElementMoments, ElementOutsideTheSurfaceIsRefused) {
  const Scene scene(panelrad::testing::validated_builtin("cube"));
  const Collocation col(scene, 1);
  const FastOperator op(col, FastOptions{});
  EXPECT_THROW(static_cast<void>(op.element_moments(-1)), std::out_of_range);
  EXPECT_THROW(static_cast<void>(op.element_moments(col.size())), std::out_of_range);
}

}  // namespace

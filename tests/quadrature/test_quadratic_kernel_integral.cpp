// The closed-form radial rule for quadratic f (integrate_kernel_times_quadratic and its facet
// form): (1/pi) Int f G dS to 1e-11 relative also when P is within 1e-8 of the triangle's edge,
// against independent truths: the closed-form form factor (f = 1) and the general adaptive rule
// integrate_kernel_times at its tighter tolerance 1e-12 (hierarchical collapsed Gauss and polar
// Gauss-Kronrod, no closed form in common with the rule under test).
#include <panelrad/quadrature/exact_integrals.hpp>
#include <panelrad/quadrature/singular_integration.hpp>

#include "edge_configurations.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

using namespace panelrad::quadrature;
using panelrad::geometry::Index;

namespace {

using namespace panelrad::testing::edge_triangle;  // the triangle (a, b, c), inner normal nQ = +z

std::array<double, 6> nodal_values(const std::function<double(const Vec3&)>& f, const Vec3& A,
                                   const Vec3& B, const Vec3& C) {
  return {f(A), f(B), f(C), f(Vec3(0.5 * (A + B))), f(Vec3(0.5 * (B + C))), f(Vec3(0.5 * (C + A)))};
}

double u_paper(const Vec3& q) { return q.squaredNorm(); }  // (31)
double quadratic_mixed(const Vec3& q) {                     // all six monomials of the plane
  return 1 + 2 * q.x() - q.y() + 3 * q.x() * q.y() - q.z() * q.z() + 0.5 * q.x() * q.x() +
         0.25 * q.y() * q.y() + 0.7 * q.x() * q.z();
}

}  // namespace

// f = 1 equals the closed-form form factor to 1e-11 relative (the requested tolerance; the
// closed form itself is exact to rounding, ~1e-15), at distances 1e-1 .. 1e-8 from the shared
// edge, dihedral angles 90, 60 and 150 degrees, foot of P along the edge and near its ends (a
// vertex of the triangle).
TEST(QuadraticKernelIntegral, ConstantMatchesFormFactorNearSharedEdge) {
  const auto one = [](const Vec3&) { return 1.0; };
  const std::array<double, 6> values = nodal_values(one, a, b, c);
  for (double alpha : {90.0, 60.0, 150.0})
    for (double x : {0.3, 0.999, 1e-6})
      for (double dist = 1e-1; dist >= 0.99e-8; dist /= 10) {
        const Neighbour nb = neighbour_point(alpha, x, dist);
        const double ff = form_factor(nb.P, nb.nP, a, b, c, nQ);
        const SingularIntegralResult r =
            integrate_kernel_times_quadratic(values, nb.P, nb.nP, a, b, c, nQ, 1e-11);
        ASSERT_GT(ff, 0);
        EXPECT_NEAR(r.value, ff, 1e-11 * ff) << "alpha " << alpha << " x " << x << " dist " << dist;
        EXPECT_LE(r.error_estimate, 1e-11 * ff);
        EXPECT_GT(r.evaluations, 0);
      }
}

// The foot of P beyond the edge's ends (outside the triangle): the signed parts cancel as h
// shrinks; the rule either meets the tolerance against the closed form or says it cannot
// (std::runtime_error), never a silent wrong value.
TEST(QuadraticKernelIntegral, FootOutsideIsAccurateOrAClearError) {
  const auto one = [](const Vec3&) { return 1.0; };
  const std::array<double, 6> values = nodal_values(one, a, b, c);
  int errors = 0, values_checked = 0;
  for (double alpha : {90.0, 60.0, 150.0})
    for (double x : {-0.01, 1.2})
      for (double dist = 1e-1; dist >= 0.99e-8; dist /= 10) {
        const Neighbour nb = neighbour_point(alpha, x, dist);
        const double ff = form_factor(nb.P, nb.nP, a, b, c, nQ);
        try {
          const SingularIntegralResult r =
              integrate_kernel_times_quadratic(values, nb.P, nb.nP, a, b, c, nQ, 1e-11);
          EXPECT_NEAR(r.value, ff, 1e-11 * ff) << "alpha " << alpha << " x " << x << " dist " << dist;
          ++values_checked;
        } catch (const std::runtime_error& e) {
          EXPECT_NE(std::string(e.what()).find("cancel"), std::string::npos) << e.what();
          ++errors;
        }
      }
  EXPECT_GT(values_checked, 0);  // at the larger distances the parts do not cancel
  EXPECT_GT(errors, 0);          // at the smallest they do (1e-8: 1e6 against the value)
}

// P hanging over the interior (foot inside, at 1e-1 .. 1e-8 of the size above the plane), over
// an edge and over a vertex, with tilted normals nP: f = 1 against the closed form, 1e-11.
TEST(QuadraticKernelIntegral, ConstantMatchesFormFactorOverTheTriangle) {
  const auto one = [](const Vec3&) { return 1.0; };
  const std::array<double, 6> values = nodal_values(one, a, b, c);
  for (const Vec3& foot : {Vec3(0.3, 0.3, 0), Vec3(0.5, 0, 0), Vec3(0, 0, 0), Vec3(0.5, 0.5, 0)})
    for (const Vec3& nP : {Vec3(0, 0, -1), Vec3(0.3, -0.2, -1).normalized()})
      for (double h = 1e-1; h >= 0.99e-8; h /= 10) {
        const Vec3 P = foot + Vec3(0, 0, h);
        const double ff = form_factor(P, nP, a, b, c, nQ);
        const SingularIntegralResult r =
            integrate_kernel_times_quadratic(values, P, nP, a, b, c, nQ, 1e-11);
        EXPECT_NEAR(r.value, ff, 1e-11 * std::abs(ff)) << "foot " << foot.transpose() << " h " << h;
      }
}

// Quadratic f (the paper's u and one with all six monomials) on 90, 60 and 150 degree
// neighbours at distances 1e-1 .. 1e-8 from the edge, against the general rule at 1e-12: both
// meet their tolerances, so they agree to 1e-11 + 1e-12 relative.
TEST(QuadraticKernelIntegral, QuadraticAgainstGeneralRuleAtTighterTolerance) {
  for (auto f : {&u_paper, &quadratic_mixed}) {
    const std::array<double, 6> values = nodal_values(f, a, b, c);
    for (double alpha : {90.0, 60.0, 150.0})
      for (double x : {0.4, 0.97})
        for (double dist = 1e-1; dist >= 0.99e-8; dist /= 100) {
          const Neighbour nb = neighbour_point(alpha, x, dist);
          const double ref = integrate_kernel_times(f, nb.P, nb.nP, a, b, c, nQ, 1e-12).value;
          const SingularIntegralResult r =
              integrate_kernel_times_quadratic(values, nb.P, nb.nP, a, b, c, nQ, 1e-11);
          EXPECT_NEAR(r.value, ref, 1.1e-11 * std::abs(ref))
              << "alpha " << alpha << " x " << x << " dist " << dist;
        }
  }
}

// Far P: agreement with the general rule as well (smooth integrand, both rules well inside
// their tolerances), and 0 exactly in the plane.
TEST(QuadraticKernelIntegral, FarAndCoplanar) {
  const std::array<double, 6> values = nodal_values(&quadratic_mixed, a, b, c);
  for (const Vec3& P : {Vec3(0.4, 0.3, 3.0), Vec3(0.2, 0.2, 0.8), Vec3(-0.5, 0.4, 0.6), Vec3(5, 4, 3)}) {
    const Vec3 nP = (Vec3(0.3, 0.3, 0) - P).normalized();
    const double ref = integrate_kernel_times(&quadratic_mixed, P, nP, a, b, c, nQ, 1e-12).value;
    const SingularIntegralResult r = integrate_kernel_times_quadratic(values, P, nP, a, b, c, nQ);
    EXPECT_NEAR(r.value, ref, 1.1e-11 * std::abs(ref)) << "P " << P.transpose();
  }
  const SingularIntegralResult r =
      integrate_kernel_times_quadratic(values, Vec3(2, 3, 0), Vec3(0, 1, 0), a, b, c, nQ);
  EXPECT_EQ(r.value, 0.0);
  EXPECT_EQ(r.evaluations, 0);
}

TEST(QuadraticKernelIntegral, BadInputIsAClearError) {
  const std::array<double, 6> ones = {1, 1, 1, 1, 1, 1};
  const Vec3 P(0.2, 0.2, 0.5), nP(0, 0, -1);
  EXPECT_THROW(integrate_kernel_times_quadratic(ones, P, nP, a, b, c, nQ, 0.0), std::invalid_argument);
  EXPECT_THROW(integrate_kernel_times_quadratic(ones, Vec3(NAN, 0, 1), nP, a, b, c, nQ),
               std::invalid_argument);
  EXPECT_THROW(integrate_kernel_times_quadratic(ones, P, nP, a, b, Vec3(2, 0, 0), nQ),
               std::invalid_argument);
  std::array<double, 6> bad = ones;
  bad[4] = INFINITY;
  try {
    integrate_kernel_times_quadratic(bad, P, nP, a, b, c, nQ);
    FAIL() << "no error for a non-finite value";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("non-finite value"), std::string::npos) << e.what();
  }
}

namespace {

// The unit cube's face z = 0 as two triangles (inner normal +z), its neighbour y = 0 carrying
// P, and the opposite face z = 1 (inner normal -z).
const std::vector<Vec3> kVertices = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0),
                                     Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)};
const std::vector<std::array<Index, 3>> kBottom = {{0, 2, 1}, {0, 3, 2}};  // either orientation
const std::vector<std::array<Index, 3>> kTop = {{4, 5, 6}, {4, 6, 7}};

double sum_over_triangles(const std::function<double(const Vec3&)>& f, const Vec3& P,
                          const Vec3& nP, const std::vector<std::array<Index, 3>>& tris,
                          const Vec3& n) {
  double s = 0;
  for (const auto& t : tris)
    s += integrate_kernel_times(f, P, nP, kVertices[static_cast<std::size_t>(t[0])],
                                kVertices[static_cast<std::size_t>(t[1])],
                                kVertices[static_cast<std::size_t>(t[2])], n, 1e-12)
             .value;
  return s;
}

}  // namespace

// A facet of two triangles (the cube's face z = 0) seen from its 90-degree neighbour y = 0 at
// distances 1e-1 .. 1e-8 from the shared edge, along the edge and near the cube's corners (the
// foot of P at 1e-6 from a vertex), and the opposite face z = 1: the facet rule equals the sum
// of the general rule over the triangles at 1e-12 (to 1e-11 + 1e-12 relative).
TEST(QuadraticKernelIntegral, CubeFacetAgainstGeneralRuleOverTriangles) {
  const Vec3 nP(0, 1, 0);  // inner normal of y = 0
  for (auto f : {&u_paper, &quadratic_mixed})
    for (double x : {0.5, 0.13, 1e-6, 1 - 1e-6})
      for (double dist = 1e-1; dist >= 0.99e-8; dist /= 10) {
        const Vec3 P(x, 0, dist);
        const auto r = integrate_kernel_times_quadratic_facet(f, P, nP, kVertices, kBottom, nQ, 1e-11);
        ASSERT_TRUE(r.has_value()) << "x " << x << " dist " << dist;
        const double ref = sum_over_triangles(f, P, nP, kBottom, nQ);
        EXPECT_NEAR(r->value, ref, 1.1e-11 * std::abs(ref)) << "x " << x << " dist " << dist;
        EXPECT_LE(r->error_estimate, 1e-11 * std::abs(r->value));
        const auto top = integrate_kernel_times_quadratic_facet(f, P, nP, kVertices, kTop, -nQ, 1e-11);
        ASSERT_TRUE(top.has_value());
        const double ref_top = sum_over_triangles(f, P, nP, kTop, -nQ);
        EXPECT_NEAR(top->value, ref_top, 1.1e-11 * std::abs(ref_top)) << "x " << x << " dist " << dist;
      }
}

// The facet rule declines (std::nullopt, for the caller's triangle-by-triangle integration)
// where it does not apply: f cubic (x^3: the bubble part shows at the check points) or not
// polynomial, (Q - P).nP changing sign on the facet, P in the facet's plane, a facet whose
// triangles overlap (an edge twice in one direction); and takes f quadratic in any
// coordinates (a rotated quadratic).
TEST(QuadraticKernelIntegral, CubeFacetDeclinesWhereTheRuleDoesNotApply) {
  const Vec3 P(0.5, 0, 0.2), nP(0, 1, 0);
  const auto cubic = [](const Vec3& q) { return q.x() * q.x() * q.x() + 1; };
  const auto smooth = [](const Vec3& q) { return std::exp(q.x()); };
  EXPECT_FALSE(integrate_kernel_times_quadratic_facet(cubic, P, nP, kVertices, kBottom, nQ));
  EXPECT_FALSE(integrate_kernel_times_quadratic_facet(smooth, P, nP, kVertices, kBottom, nQ));
  // nP tilted so that (Q - P).nP changes sign over the face z = 0
  EXPECT_FALSE(integrate_kernel_times_quadratic_facet(&u_paper, P, Vec3(1, 1, 0).normalized(),
                                                      kVertices, kBottom, nQ));
  EXPECT_FALSE(integrate_kernel_times_quadratic_facet(&u_paper, Vec3(0.5, 0.5, 0), Vec3(0, 0, 1),
                                                      kVertices, kBottom, nQ));
  const std::vector<std::array<Index, 3>> twice = {{0, 1, 2}, {0, 1, 2}};
  EXPECT_FALSE(integrate_kernel_times_quadratic_facet(&u_paper, P, nP, kVertices, twice, nQ));
  const auto rotated = [](const Vec3& q) {
    const Vec3 r = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()) * q;
    return r.x() * r.y() + r.z() * r.z();
  };
  const auto r = integrate_kernel_times_quadratic_facet(rotated, P, nP, kVertices, kBottom, nQ);
  ASSERT_TRUE(r.has_value());
  EXPECT_NEAR(r->value, sum_over_triangles(rotated, P, nP, kBottom, nQ),
              1.1e-11 * std::abs(r->value));
}

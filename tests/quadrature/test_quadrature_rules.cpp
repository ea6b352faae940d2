// Triangle rules, the composite scheme of section 4.2, composite_levels and
// distance_point_triangle.
#include <panelrad/quadrature/exact_integrals.hpp>
#include <panelrad/quadrature/triangle_rules.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

using namespace panelrad::quadrature;

namespace {

// A generic triangle in the positive octant: every monomial is positive on it, so relative
// errors are meaningful (no cancellation to a tiny value).
const Vec3 A(0.2, 0.1, 0.3), B(1.1, 0.4, 0.5), C(0.5, 1.3, 0.9);

double rule_monomial(const TriangleRule& rule, int i, int j, int k) {
  return integrate(rule, A, B, C, [&](const Vec3& q) {
    return std::pow(q.x(), i) * std::pow(q.y(), j) * std::pow(q.z(), k);
  });
}

// Largest relative error of `rule` over all monomials x^i y^j z^k with i+j+k == degree.
double worst_error_at_degree(const TriangleRule& rule, int degree) {
  double worst = 0;
  for (int i = 0; i <= degree; ++i)
    for (int j = 0; i + j <= degree; ++j) {
      const int k = degree - i - j;
      const double exact = monomial_integral(A, B, C, i, j, k);
      worst = std::max(worst, std::abs(rule_monomial(rule, i, j, k) - exact) / exact);
    }
  return worst;
}

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

// Largest relative error over the barycentric monomials l1^p l2^q l3^r, p+q+r == degree, on the
// reference triangle: Int l1^p l2^q l3^r / area = 2 p! q! r! / (degree + 2)!.
double worst_barycentric_error(const TriangleRule& rule, int degree) {
  double worst = 0;
  for (int p = 0; p <= degree; ++p)
    for (int q = 0; p + q <= degree; ++q) {
      const int r = degree - p - q;
      double sum = 0;
      for (std::size_t i = 0; i < rule.size(); ++i) {
        const auto& l = rule.barycentric[i];
        sum += rule.weight[i] * std::pow(l[0], p) * std::pow(l[1], q) * std::pow(l[2], r);
      }
      const double exact = 2 * factorial(p) * factorial(q) * factorial(r) / factorial(degree + 2);
      worst = std::max(worst, std::abs(sum - exact) / exact);
    }
  return worst;
}

std::vector<const TriangleRule*> all_rules() {
  std::vector<const TriangleRule*> rules = {&centroid_rule(), &three_point_rule(), &stroud_t2_5_1()};
  for (int d = 1; d <= 20; ++d) rules.push_back(&rule_of_degree(d));
  for (int n = 1; n <= kMaxCollapsedGaussPoints; ++n) rules.push_back(&collapsed_gauss_rule(n));
  return rules;
}

}  // namespace

TEST(TriangleRules, WeightsPositiveSumToOnePointsInside) {
  for (const TriangleRule* r : all_rules()) {
    ASSERT_EQ(r->barycentric.size(), r->weight.size()) << r->name;
    double sum = 0;
    for (std::size_t i = 0; i < r->size(); ++i) {
      EXPECT_GT(r->weight[i], 0) << r->name;
      const auto& l = r->barycentric[i];
      EXPECT_GE(l[0], 0) << r->name;
      EXPECT_GE(l[1], 0) << r->name;
      EXPECT_GE(l[2], 0) << r->name;
      EXPECT_NEAR(l[0] + l[1] + l[2], 1.0, 1e-15) << r->name;
      sum += r->weight[i];
    }
    EXPECT_NEAR(sum, 1.0, 1e-14) << r->name;  // a few ulps of rounding over <= 256 weights
  }
}

TEST(TriangleRules, SizesAndNames) {
  EXPECT_EQ(centroid_rule().size(), 1u);
  EXPECT_EQ(three_point_rule().size(), 3u);
  EXPECT_EQ(stroud_t2_5_1().size(), 7u);
  EXPECT_EQ(stroud_t2_5_1().degree, 5);
  EXPECT_EQ(&rule_by_name("centroid"), &centroid_rule());
  EXPECT_EQ(&rule_by_name("three_point"), &three_point_rule());
  EXPECT_EQ(&rule_by_name("stroud7"), &stroud_t2_5_1());
  EXPECT_GE(rule_by_name("degree12").degree, 12);
  EXPECT_THROW(rule_by_name("degree21"), std::invalid_argument);
  EXPECT_THROW(rule_by_name("degreeX"), std::invalid_argument);
  EXPECT_THROW(rule_by_name("gauss"), std::invalid_argument);
  EXPECT_THROW(rule_of_degree(21), std::invalid_argument);
  EXPECT_THROW(rule_of_degree(-1), std::invalid_argument);
  EXPECT_THROW(collapsed_gauss_rule(0), std::invalid_argument);
  for (int d = 1; d <= 20; ++d) EXPECT_GE(rule_of_degree(d).degree, d);
}

TEST(TriangleRules, ThreePointRuleIsThePapersEdgeMidpointRule) {
  // Section 5.1: (1/6)[f(0,1/2) + f(1/2,0) + f(1/2,1/2)] on sigma (area 1/2).
  const TriangleRule& r = three_point_rule();
  int midpoints = 0;
  for (const auto& l : r.barycentric) {
    int halves = 0, zeros = 0;
    for (double x : l) {
      halves += x == 0.5;
      zeros += x == 0.0;
    }
    midpoints += halves == 2 && zeros == 1;
  }
  EXPECT_EQ(midpoints, 3);
  for (double w : r.weight) EXPECT_DOUBLE_EQ(w, 1.0 / 3.0);
}

// Degree of precision: exact (1e-14 relative, rounding of <= 121 positive terms of O(1)) for all
// monomials up to the claimed degree, and some monomial of degree+1 is off by far more.
TEST(TriangleRules, IntegrateAllMonomialsUpToDegreeExactly) {
  for (const TriangleRule* r : all_rules()) {
    for (int d = 0; d <= r->degree; ++d)
      EXPECT_LT(worst_error_at_degree(*r, d), 1e-14) << r->name << " degree " << d;
    // The error at degree+1 must stand clearly above the 1e-14 exactness bound (checked for the
    // rules rule_of_degree hands out, degree <= 20; beyond, it falls to rounding level).
    if (r->degree <= 20) {
      EXPECT_GT(worst_barycentric_error(*r, r->degree + 1), 1e-12)
          << r->name << " claims degree " << r->degree << " but is exact at degree "
          << r->degree + 1;
    }
  }
}

TEST(TriangleRules, StroudConstants) {
  // Radon's 7-point rule: centroid weight 9/40, orbits at a = (6 -+ sqrt 15)/21.
  const TriangleRule& r = stroud_t2_5_1();
  EXPECT_DOUBLE_EQ(r.weight[0], 9.0 / 40.0);
  EXPECT_NEAR(r.barycentric[1][0], 0.101286507323456338800987361915123, 1e-16);
  EXPECT_NEAR(r.barycentric[4][0], 0.470142064105115089770441209513447, 1e-16);
  EXPECT_NEAR(r.weight[1], 0.125939180544827152595683945500181, 1e-16);
  EXPECT_NEAR(r.weight[4], 0.132394152788506180737649387833152, 1e-16);
}

TEST(CompositeLevels, PapersRule) {
  const double h = 0.1;
  // Section 4.2: mu for 0 < dist <= h, mu-1 for h < dist <= 2h, ..., 0 beyond.
  EXPECT_EQ(composite_levels(0.05, h, 3), 3);
  EXPECT_EQ(composite_levels(0.1, h, 3), 3);
  EXPECT_EQ(composite_levels(0.1000001, h, 3), 2);
  EXPECT_EQ(composite_levels(0.2, h, 3), 2);
  EXPECT_EQ(composite_levels(0.25, h, 3), 1);
  EXPECT_EQ(composite_levels(0.3, h, 3), 1);
  EXPECT_EQ(composite_levels(0.31, h, 3), 0);
  EXPECT_EQ(composite_levels(5.0, h, 3), 0);
  EXPECT_EQ(composite_levels(0.05, h, 0), 0);
  EXPECT_EQ(composite_levels(0.05, h, 2), 2);
  EXPECT_EQ(composite_levels(0.15, h, 2), 1);
  EXPECT_EQ(composite_levels(0.25, h, 2), 0);
}

TEST(DistancePointTriangle, AgainstDenseSampling) {
  const Vec3 points[] = {{0.6, 0.6, 0.6}, {-1, -1, 0}, {2, 0.2, 0.4}, {0.5, 0.5, 5},
                         {0.3, 0.3, 0.45}, {1.1, 0.4, 0.5}, {0.7, 2.0, -0.3}, {0.0, 0.9, 0.9}};
  const int N = 400;  // grid spacing ~ 1.5/400: sampled minimum within ~4e-3 above the true one
  for (const Vec3& P : points) {
    double best = 1e300;
    for (int i = 0; i <= N; ++i)
      for (int j = 0; i + j <= N; ++j) {
        const double s = double(i) / N, t = double(j) / N;
        best = std::min(best, (P - (A + s * (B - A) + t * (C - A))).norm());
      }
    const double d = distance_point_triangle(P, A, B, C);
    EXPECT_LE(d, best + 1e-14);
    EXPECT_GT(d, best - 5e-3);
  }
  EXPECT_EQ(distance_point_triangle(B, A, B, C), 0.0);
  // Foot inside the face: distance along the normal.
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_DOUBLE_EQ(distance_point_triangle(Vec3(0.2, 0.3, -0.7), a, b, c), 0.7);
  EXPECT_DOUBLE_EQ(distance_point_triangle(Vec3(0.5, -2, 0), a, b, c), 2.0);
}

TEST(IntegrateComposite, ExactForPolynomialsAndConvergesAtOrderSix) {
  auto poly = [](const Vec3& q) { return 1 + q.x() * q.y() * q.y() * q.z() * q.x() - 3 * q.z(); };
  const double exact = monomial_integral(A, B, C, 0, 0, 0) + monomial_integral(A, B, C, 2, 2, 1) -
                       3 * monomial_integral(A, B, C, 0, 0, 1);
  for (int levels = 0; levels <= 3; ++levels)
    EXPECT_NEAR(integrate_composite(stroud_t2_5_1(), A, B, C, levels, poly), exact,
                1e-14 * std::abs(exact));
  // A smooth non-polynomial: the degree-5 rule's error falls by ~2^6 = 64 per level.
  auto g = [](const Vec3& q) { return std::exp(2 * q.x() - q.y()) * std::cos(3 * q.z()); };
  const double ref = integrate_composite(rule_of_degree(20), A, B, C, 3, g);
  double previous = 0;
  for (int levels = 0; levels <= 4; ++levels) {
    const double err = std::abs(integrate_composite(stroud_t2_5_1(), A, B, C, levels, g) - ref);
    if (levels > 0) {
      EXPECT_GT(previous / err, 40.0) << "levels " << levels;
    }
    previous = err;
  }
  // The composite three-point rule converges at order 3 or better (error ratio >= 2^3 roughly).
  const double e2 = std::abs(integrate_composite(three_point_rule(), A, B, C, 2, g) - ref);
  const double e3 = std::abs(integrate_composite(three_point_rule(), A, B, C, 3, g) - ref);
  EXPECT_GT(e2 / e3, 7.0);
}

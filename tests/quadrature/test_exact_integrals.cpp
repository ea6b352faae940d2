// Exact monomial integrals over triangles (3-D and 2-D) and the graded 2-D moments.
#include <panelrad/quadrature/exact_integrals.hpp>
#include <panelrad/quadrature/triangle_rules.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace panelrad::quadrature;

namespace {
double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }
}  // namespace

// Unit right triangle: Int x^p y^q dA = p! q! / (p+q+2)! (independent closed form).
TEST(ExactIntegrals, UnitRightTriangleClosedForm) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const std::array<double, 2> a2{0, 0}, b2{1, 0}, c2{0, 1};
  for (int p = 0; p <= 12; ++p)
    for (int q = 0; p + q <= 12; ++q) {
      const double exact = factorial(p) * factorial(q) / factorial(p + q + 2);
      // 1e-14: a few roundings in a sum of positive terms
      EXPECT_NEAR(monomial_integral(a, b, c, p, q, 0), exact, 1e-14 * exact) << p << "," << q;
      EXPECT_NEAR(monomial_integral_2d(a2, b2, c2, p, q), exact, 1e-14 * exact) << p << "," << q;
      EXPECT_NEAR(monomial_integral_2d(c2, a2, b2, p, q), exact, 1e-14 * exact);  // orientation
    }
  // A z power on the plane z = 2 multiplies by 2^k.
  const Vec3 az(0, 0, 2), bz(1, 0, 2), cz(0, 1, 2);
  EXPECT_NEAR(monomial_integral(az, bz, cz, 2, 1, 3), 8.0 * 2.0 / factorial(5), 1e-15);
}

// Against an independent computation: the degree-20 collapsed Gauss rule on a generic 3-D
// triangle, for every monomial up to total degree 20.
TEST(ExactIntegrals, GenericTriangleAgainstHighDegreeRule) {
  const Vec3 a(0.3, -0.2, 0.7), b(1.4, 0.5, 0.1), c(-0.4, 1.1, 1.2);
  const TriangleRule& rule = rule_of_degree(20);
  for (int d = 0; d <= 20; ++d)
    for (int i = 0; i <= d; ++i)
      for (int j = 0; i + j <= d; ++j) {
        const int k = d - i - j;
        const double exact = monomial_integral(a, b, c, i, j, k);
        double scale = 0;  // Int |x^i y^j z^k|: the size of the terms that may cancel
        const double q = integrate(rule, a, b, c, [&](const Vec3& p) {
          const double v = std::pow(p.x(), i) * std::pow(p.y(), j) * std::pow(p.z(), k);
          scale += std::abs(v);
          return v;
        });
        scale *= 0.5 * (b - a).cross(c - a).norm() / double(rule.size());
        EXPECT_NEAR(exact, q, 1e-13 * std::max(std::abs(exact), scale)) << i << j << k;
      }
}

TEST(ExactIntegrals, TwoDimensionalMatchesThreeDimensionalEmbedding) {
  const std::array<double, 2> a{0.1, -0.3}, b{2.0, 0.4}, c{0.7, 1.5};
  const Vec3 a3(a[0], a[1], 0), b3(b[0], b[1], 0), c3(c[0], c[1], 0);
  for (int p = 0; p <= 9; ++p)
    for (int q = 0; p + q <= 9; ++q) {
      const double v3 = monomial_integral(a3, b3, c3, p, q, 0);
      EXPECT_NEAR(monomial_integral_2d(a, b, c, p, q), v3, 1e-13 * std::max(1.0, std::abs(v3)));
    }
}

TEST(ExactIntegrals, MomentsInGradedOrder) {
  const std::array<double, 2> a{-0.2, 0.1}, b{0.9, -0.4}, c{0.3, 0.8};
  for (int M = 0; M <= 12; ++M) {
    const std::vector<double> m = monomial_moments_2d(a, b, c, M);
    ASSERT_EQ(m.size(), static_cast<std::size_t>((M + 1) * (M + 2) / 2));
    std::size_t idx = 0;
    for (int d = 0; d <= M; ++d)
      for (int p = d; p >= 0; --p) {  // (0,0),(1,0),(0,1),(2,0),(1,1),(0,2),...
        const double exact = monomial_integral_2d(a, b, c, p, d - p);
        EXPECT_NEAR(m[idx], exact, 1e-15) << "M " << M << " (" << p << "," << d - p << ")";
        ++idx;
      }
  }
  // Large M falls back on the closed form.
  const std::vector<double> big = monomial_moments_2d(a, b, c, 32);
  EXPECT_NEAR(big[1], monomial_integral_2d(a, b, c, 1, 0), 1e-16);
}

TEST(ExactIntegrals, BadInput) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_THROW(monomial_integral(a, b, c, -1, 0, 0), std::invalid_argument);
  EXPECT_THROW(monomial_integral(a, b, c, 100, 100, 0), std::invalid_argument);
  EXPECT_THROW(monomial_moments_2d({0, 0}, {1, 0}, {0, 1}, -2), std::invalid_argument);
  EXPECT_THROW(monomial_integral_2d({0, 0}, {1, 0}, {0, 1}, 0, -3), std::invalid_argument);
}

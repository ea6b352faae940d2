// Gauss-Legendre rules on [0, 1] (gauss_legendre.hpp) against independent truths: exactness on the
// monomials x^p, p <= 2n - 1 (Int_0^1 x^p = 1 / (p + 1)), the known error on x^(2n) that only the
// n-point Gauss rule has, the closed forms for n = 2 and 3, Boost's separately tabulated nodes for
// n = 7, 10, 15, 20, 25, 30, and the symmetry about 1/2.
#include <panelrad/quadrature/gauss_legendre.hpp>

#include <boost/math/quadrature/gauss.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace {

using panelrad::quadrature::gauss_legendre_01;
using panelrad::quadrature::GaussLegendreRule;
using panelrad::quadrature::kMaxGaussLegendrePoints;

constexpr double u = 0x1p-53;  // unit roundoff

/// sum_i w_i x_i^p, accumulated in long double so that only the rounding of the rule's nodes and
/// weights to double is measured.
long double moment(const GaussLegendreRule& r, int p) {
  long double s = 0;
  for (std::size_t i = 0; i < r.node.size(); ++i)
    s += static_cast<long double>(r.weight[i]) * std::pow(static_cast<long double>(r.node[i]), p);
  return s;
}

TEST(GaussLegendre, NodesInsideIncreasingWeightsPositive) {
  for (int n = 1; n <= kMaxGaussLegendrePoints; ++n) {
    const GaussLegendreRule& r = gauss_legendre_01(n);
    ASSERT_EQ(r.node.size(), static_cast<std::size_t>(n));
    ASSERT_EQ(r.weight.size(), static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i);
      EXPECT_GT(r.node[k], 0.0) << "n " << n;
      EXPECT_LT(r.node[k], 1.0) << "n " << n;
      EXPECT_GT(r.weight[k], 0.0) << "n " << n;
      if (i > 0) {
        EXPECT_LT(r.node[k - 1], r.node[k]) << "n " << n << " i " << i;
      }
    }
  }
}

// Weights sum to 1 = Int_0^1 1 and x^p, p = 1 .. 2n-1, is integrated exactly. Each node and weight
// is within an ulp (relative <= 2u) of the exact value (long double zeros rounded once to double),
// so each positive term w x^p is off by at most (2p + 2) u relatively, and so is their sum; the
// long double accumulation adds far less: bound 2 (p + 2) u of 1/(p+1).
TEST(GaussLegendre, ExactForDegreeUpTo2nMinus1) {
  for (int n = 1; n <= kMaxGaussLegendrePoints; ++n) {
    const GaussLegendreRule& r = gauss_legendre_01(n);
    for (int p = 0; p <= 2 * n - 1; ++p) {
      const double exact = 1.0 / (p + 1);
      EXPECT_NEAR(static_cast<double>(moment(r, p)), exact, 2 * (p + 2) * u * exact) << "n " << n << " p " << p;
    }
  }
}

// Int_0^1 x^(2n) - Q_n(x^(2n)) = Int_0^1 pi_n(x)^2 dx = (n!)^4 / ((2n + 1) ((2n)!)^2), pi_n the monic
// Legendre polynomial on [0, 1] (the Gauss error term with f^(2n) / (2n)! = 1). Checked where it
// exceeds the rounding bound of the test above a hundredfold (n <= 11), so that the rule is the
// n-point Gauss rule and not merely some rule exact for degree 2n - 1.
TEST(GaussLegendre, ErrorOnDegree2nIsTheGaussRemainder) {
  for (int n = 1; n <= kMaxGaussLegendrePoints; ++n) {
    const int p = 2 * n;
    const double exact = 1.0 / (p + 1);
    const double remainder = std::exp(4 * std::lgamma(n + 1.0) - 2 * std::lgamma(2 * n + 1.0) - std::log(2 * n + 1.0));
    const double rounding = 2 * (p + 2) * u * exact;
    if (remainder < 100 * rounding) continue;
    EXPECT_NEAR(exact - static_cast<double>(moment(gauss_legendre_01(n), p)), remainder,
                rounding + 1e-12 * remainder)  // lgamma / exp: a few ulps of the remainder
        << "n " << n;
  }
  EXPECT_NEAR(1.0 / 3 - static_cast<double>(moment(gauss_legendre_01(1), 2)), 1.0 / 12, 1e-16);  // 1/3 - 1/4
}

TEST(GaussLegendre, ClosedFormsForTwoAndThreePoints) {
  const GaussLegendreRule& r2 = gauss_legendre_01(2);  // 1/2 -+ 1/(2 sqrt 3), weights 1/2
  EXPECT_NEAR(r2.node[0], 0.5 - 0.5 / std::sqrt(3.0), 2 * u);
  EXPECT_NEAR(r2.node[1], 0.5 + 0.5 / std::sqrt(3.0), 2 * u);
  EXPECT_NEAR(r2.weight[0], 0.5, u);
  EXPECT_NEAR(r2.weight[1], 0.5, u);
  const GaussLegendreRule& r3 = gauss_legendre_01(3);  // 1/2 -+ sqrt(15)/10, 1/2; 5/18, 8/18, 5/18
  EXPECT_NEAR(r3.node[0], 0.5 - std::sqrt(15.0) / 10, 2 * u);
  EXPECT_EQ(r3.node[1], 0.5);
  EXPECT_NEAR(r3.node[2], 0.5 + std::sqrt(15.0) / 10, 2 * u);
  EXPECT_NEAR(r3.weight[0], 5.0 / 18, u);
  EXPECT_NEAR(r3.weight[1], 8.0 / 18, u);
  EXPECT_NEAR(r3.weight[2], 5.0 / 18, u);
}

// Boost's fixed-size rules carry tabulated (not computed) nodes on [-1, 1] for these N, correctly
// rounded doubles: mapped to [0, 1] in double they agree with ours to an ulp of 1 (the mapping
// (1 - z) / 2 rounds once more, our node is rounded once: together <= 1.5 u, bound 2 u).
template <unsigned N>
void expect_matches_boost_table() {
  using Table = boost::math::quadrature::gauss<double, N>;
  const auto& z = Table::abscissa();  // non-negative zeros, increasing (0 first when N is odd)
  const auto& w = Table::weights();
  const GaussLegendreRule& r = gauss_legendre_01(static_cast<int>(N));
  for (std::size_t j = 0; j < z.size(); ++j) {
    const std::size_t lo = (N - 1) / 2 - j, hi = N - 1 - lo;
    EXPECT_NEAR(r.node[lo], (1 - z[j]) / 2, 2 * u) << "N " << N << " j " << j;
    EXPECT_NEAR(r.node[hi], (1 + z[j]) / 2, 2 * u) << "N " << N << " j " << j;
    EXPECT_NEAR(r.weight[lo], w[j] / 2, 2 * u * w[j]) << "N " << N << " j " << j;
  }
}

TEST(GaussLegendre, MatchesBoostTabulatedRules) {
  expect_matches_boost_table<7>();
  expect_matches_boost_table<10>();
  expect_matches_boost_table<15>();
  expect_matches_boost_table<20>();
  expect_matches_boost_table<25>();
  expect_matches_boost_table<30>();
}

// x_i + x_{n-1-i} = 1 to within rounding: each node is within an ulp (<= u below 1) of the exact
// one, and the double sum rounds once more (<= u/2 near 1): bound 2 u. Weights exactly equal
// (computed once per pair of zeros +-z).
TEST(GaussLegendre, SymmetricAboutOneHalf) {
  for (int n = 1; n <= kMaxGaussLegendrePoints; ++n) {
    const GaussLegendreRule& r = gauss_legendre_01(n);
    for (int i = 0; i < n; ++i) {
      const auto k = static_cast<std::size_t>(i), m = static_cast<std::size_t>(n - 1 - i);
      EXPECT_NEAR(r.node[k] + r.node[m], 1.0, 2 * u) << "n " << n << " i " << i;
      EXPECT_EQ(r.weight[k], r.weight[m]) << "n " << n << " i " << i;
    }
  }
}

TEST(GaussLegendre, RefusesPointCountsOutsideTheTable) {
  EXPECT_THROW(gauss_legendre_01(0), std::invalid_argument);
  EXPECT_THROW(gauss_legendre_01(-3), std::invalid_argument);
  EXPECT_THROW(gauss_legendre_01(kMaxGaussLegendrePoints + 1), std::invalid_argument);
  EXPECT_NO_THROW(gauss_legendre_01(kMaxGaussLegendrePoints));
}

}  // namespace

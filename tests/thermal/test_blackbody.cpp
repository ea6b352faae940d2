// The blackbody fraction F(0 -> lambda T) against Planck's law integrated numerically (Boost.Math's
// adaptive Gauss-Kronrod quadrature, an independent computation), its limits and its sum over bands.
#include <panelrad/thermal/blackbody.hpp>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace panelrad {
namespace {

/// (15 / pi^4) Int_x^inf t^3 / (e^t - 1) dt by quadrature: F(0 -> lambda T) with x = c2 / (lambda T).
double fraction_by_quadrature(double x) {
  const auto planck = [](double t) { return t * t * t / std::expm1(t); };
  const double tail = boost::math::quadrature::gauss_kronrod<double, 61>::integrate(planck, x, x + 200, 15, 1e-15);
  const double pi = std::numbers::pi;
  return 15 / (pi * pi * pi * pi) * tail;
}

TEST(Blackbody, FractionAgreesWithPlancksLawIntegrated) {
  // lambda T from 300 um K (x = 48) to 1 m K (x = 0.0144), across the switch of series at x = 1.
  for (double lambda_T : {3e-4, 1e-3, 2e-3, 2.8977e-3, 5e-3, 1e-2, 1.4e-2, 1.45e-2, 2e-2, 5e-2, 0.2, 1.0}) {
    const double x = kSecondRadiationConstant / lambda_T;
    EXPECT_NEAR(blackbody_fraction(lambda_T), fraction_by_quadrature(x), 2e-15) << "lambda T = " << lambda_T;
  }
  // The textbook value at Wien's peak lambda T = 2897.77 um K: 0.25005 (Siegel & Howell, table A.5).
  EXPECT_NEAR(blackbody_fraction(2.89777e-3), 0.25005, 5e-5);
}

TEST(Blackbody, FractionLimitsAndMonotonicity) {
  EXPECT_EQ(blackbody_fraction(0), 0);
  EXPECT_EQ(blackbody_fraction(INFINITY), 1);
  EXPECT_THROW(blackbody_fraction(-1), std::invalid_argument);
  double last = 0;
  for (double lambda_T = 1e-4; lambda_T < 10; lambda_T *= 1.1) {
    const double F = blackbody_fraction(lambda_T);
    EXPECT_GE(F, last);
    EXPECT_LE(F, 1);
    last = F;
  }
}

TEST(Blackbody, BandFractionsSumToOne) {
  const std::vector<double> edges = {0.5, 2.5, 4.0, 12.0};
  for (double T : {300.0, 1000.0, 5800.0}) {
    const std::vector<double> f = band_fractions(edges, T);
    ASSERT_EQ(f.size(), 5u);
    double sum = 0;
    for (double x : f) {
      EXPECT_GE(x, 0);
      sum += x;
    }
    EXPECT_NEAR(sum, 1, 1e-15);
    EXPECT_NEAR(f[2], blackbody_fraction(4.0e-6 * T) - blackbody_fraction(2.5e-6 * T), 1e-16);
  }
}

}  // namespace
}  // namespace panelrad

// The admissibility predicate (41) R <= eta |P - A|: exact on the double inputs, double fast path
// with an error bound, exact fallback counted.
#include <panelrad/geometry/admissibility.hpp>

#include <gmp.h>  // GMP rationals as the independent exact reference (not CGAL)
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

namespace {

using panelrad::geometry::admissibility_exact_fallbacks;
using panelrad::geometry::is_admissible;
using panelrad::geometry::Vec3;

/// R^2 <= eta^2 |P - A|^2 in exact rational arithmetic (every double converts exactly).
bool reference_admissible(const Vec3& P, const Vec3& A, double R, double eta) {
  mpq_t s, d, t, lhs, rhs;
  mpq_inits(s, d, t, lhs, rhs, nullptr);
  for (int i = 0; i < 3; ++i) {
    mpq_set_d(d, P[i]);
    mpq_set_d(t, A[i]);
    mpq_sub(d, d, t);
    mpq_mul(d, d, d);
    mpq_add(s, s, d);
  }
  mpq_set_d(t, eta);
  mpq_mul(rhs, t, t);
  mpq_mul(rhs, rhs, s);
  mpq_set_d(lhs, R);
  mpq_mul(lhs, lhs, lhs);
  const bool result = mpq_cmp(lhs, rhs) <= 0;
  mpq_clears(s, d, t, lhs, rhs, nullptr);
  return result;
}

TEST(Admissibility, ExactlyOnTheBoundaryIsAdmissibleAndUsesTheExactPath) {
  // P - A = (3, 4, 0) exactly (dyadic coordinates), |P - A| = 5, eta = 0.5: eta |P - A| = 2.5.
  const Vec3 A(0.25, -1.5, 2.0);
  const Vec3 P = A + Vec3(3, 4, 0);
  ASSERT_EQ(P - A, Vec3(3, 4, 0));
  const double eta = 0.5;
  const unsigned long long before = admissibility_exact_fallbacks();
  EXPECT_TRUE(is_admissible(P, A, 2.5, eta));
  EXPECT_EQ(admissibility_exact_fallbacks(), before + 1);
  EXPECT_FALSE(is_admissible(P, A, std::nextafter(2.5, 3.0), eta));
  EXPECT_EQ(admissibility_exact_fallbacks(), before + 2);
  EXPECT_TRUE(is_admissible(P, A, std::nextafter(2.5, 2.0), eta));
  EXPECT_EQ(admissibility_exact_fallbacks(), before + 3);
}

TEST(Admissibility, ClearCasesStayOnTheFastPath) {
  const Vec3 A(0.1, 0.2, 0.3), P(1.7, -0.4, 2.9);
  const double dist = (P - A).norm();
  const unsigned long long before = admissibility_exact_fallbacks();
  EXPECT_TRUE(is_admissible(P, A, 0.2 * 0.99 * dist, 0.2));
  EXPECT_FALSE(is_admissible(P, A, 0.2 * 1.01 * dist, 0.2));
  EXPECT_EQ(admissibility_exact_fallbacks(), before);
}

TEST(Admissibility, BoundaryDecidedAtExtremeMagnitudes) {
  // The same boundary case scaled by 2^k (exact): underflow (k << 0) and overflow (k >> 0) of the
  // squares send the decision to the exact path, which must still be right.
  for (int k : {-1000, -600, -480, -200, 0, 200, 480, 600, 1000}) {
    const double s = std::ldexp(1.0, k);
    const Vec3 A = Vec3(0.25, -1.5, 2.0) * s;
    const Vec3 P = Vec3(3.25, 2.5, 2.0) * s;
    SCOPED_TRACE(k);
    EXPECT_TRUE(is_admissible(P, A, 2.5 * s, 0.5));
    EXPECT_FALSE(is_admissible(P, A, std::nextafter(2.5 * s, 3.0 * s), 0.5));
    EXPECT_TRUE(is_admissible(P, A, 0.5 * s, 0.5));
    EXPECT_FALSE(is_admissible(P, A, 4.0 * s, 0.5));
  }
}

TEST(Admissibility, RandomCasesAgreeWithExactRationals) {
  std::mt19937_64 rng(20240601);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), eta_dist(0.05, 0.95);
  std::uniform_int_distribution<int> exponent(-30, 30), ulps(-4, 4);
  unsigned long long near_boundary_fallbacks = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    const double scale = std::ldexp(1.0, exponent(rng));
    const Vec3 offset = Vec3(unit(rng), unit(rng), unit(rng)) * std::ldexp(1.0, exponent(rng));
    const Vec3 A = offset + Vec3(unit(rng), unit(rng), unit(rng)) * scale;
    const Vec3 P = offset + Vec3(unit(rng), unit(rng), unit(rng)) * scale;
    const double eta = eta_dist(rng);
    const double dist = (P - A).norm();
    const bool clear = trial % 2 == 0;
    double R;
    if (clear) {
      R = std::abs(unit(rng)) * 2 * eta * dist;  // away from the boundary but for rare draws
    } else {
      // Within a few ulps of the boundary: the double evaluation alone cannot decide these.
      R = eta * dist;
      for (int step = ulps(rng); step != 0; step += step > 0 ? -1 : 1) R = std::nextafter(R, step > 0 ? 2 * R + 1 : 0.0);
    }
    const unsigned long long before = admissibility_exact_fallbacks();
    ASSERT_EQ(is_admissible(P, A, R, eta), reference_admissible(P, A, R, eta))
        << "trial " << trial << " P=" << P.transpose() << " A=" << A.transpose() << " R=" << R << " eta=" << eta;
    const unsigned long long used = admissibility_exact_fallbacks() - before;
    const double ratio = R / (eta * dist);
    if (clear && dist > 0 && R > 0 && std::abs(ratio - 1) > 1e-10) {
      ASSERT_EQ(used, 0u) << "a clear case fell back: trial " << trial << ", R / (eta |P - A|) = " << ratio;
    }
    if (!clear) near_boundary_fallbacks += used;
  }
  EXPECT_GT(near_boundary_fallbacks, 50000u);  // most of the 100000 near-boundary cases
}

TEST(Admissibility, InvalidInputIsRejected) {
  const Vec3 A(0, 0, 0), P(1, 0, 0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(is_admissible(P, A, -0.1, 0.5), std::invalid_argument);
  EXPECT_THROW(is_admissible(P, A, 0.1, -0.5), std::invalid_argument);
  EXPECT_THROW(is_admissible(P, A, nan, 0.5), std::invalid_argument);
  EXPECT_THROW(is_admissible(P, A, 0.1, nan), std::invalid_argument);
  EXPECT_THROW(is_admissible(Vec3(nan, 0, 0), A, 0.1, 0.5), std::invalid_argument);
  EXPECT_THROW(is_admissible(P, Vec3(0, inf, 0), 0.1, 0.5), std::invalid_argument);
  EXPECT_THROW(is_admissible(P, A, inf, 0.5), std::invalid_argument);
}

TEST(Admissibility, DegenerateZeroCases) {
  const Vec3 A(0.5, 0.5, 0.5);
  EXPECT_TRUE(is_admissible(A, A, 0.0, 0.5));    // 0 <= 0
  EXPECT_FALSE(is_admissible(A, A, 1e-300, 0.5));  // R > 0 = eta |P - A|
  EXPECT_TRUE(is_admissible(Vec3(1, 0.5, 0.5), A, 0.0, 0.0));
  EXPECT_FALSE(is_admissible(Vec3(1, 0.5, 0.5), A, 1e-300, 0.0));
}

}  // namespace

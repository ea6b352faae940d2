// The bounding-box diameter |hi - lo| of a point set: equal, bit for bit, to the plain Euclidean
// norm of the box diagonal wherever that norm neither overflows nor underflows (the formula it
// replaces), and exactly scale-covariant by powers of two far outside that range.
#include <panelrad/geometry/bounding_box.hpp>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <ranges>
#include <vector>

namespace {

using namespace panelrad::geometry;

/// n points with coordinates uniform in [-1, 1) times 2^k, plus a translation of 3 * 2^k.
std::vector<Vec3> random_points(std::mt19937_64& rng, int n, int k) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<Vec3> p(static_cast<std::size_t>(n));
  for (Vec3& v : p) v = Vec3(std::ldexp(unit(rng), k), std::ldexp(unit(rng) + 3, k), std::ldexp(unit(rng), k));
  return p;
}

/// The diagonal of Eigen's bounding box, norm() without scaling: the independent reference.
double plain_diagonal(const std::vector<Vec3>& p) {
  Eigen::AlignedBox3d box;
  for (const Vec3& v : p) box.extend(v);
  return box.diagonal().norm();
}

TEST(BoundingBox, EqualsThePlainNormOfTheDiagonalBitForBit) {
  // Scales 2^-400 .. 2^400: every nonzero component of the diagonal is in [2^-511, 2^511) and
  // within 2^510 of the largest (the points fill the box), where bounding_box.hpp states equality.
  std::mt19937_64 rng(20261201);
  for (int k = -400; k <= 400; k += 8)
    for (int trial = 0; trial < 20; ++trial) {
      const std::vector<Vec3> p = random_points(rng, 1 + trial * 7, k);
      ASSERT_EQ(bounding_box_diameter(p), plain_diagonal(p)) << "scale 2^" << k << ", trial " << trial;
    }
}

TEST(BoundingBox, ScalesExactlyWherePlainSquaresWouldOverflowOrUnderflow) {
  std::mt19937_64 rng(7);
  const std::vector<Vec3> p = random_points(rng, 50, 0);
  const double d = bounding_box_diameter(p);
  for (int k : {-1000, -700, 600, 1000}) {
    std::vector<Vec3> q = p;
    for (Vec3& v : q) v = Vec3(std::ldexp(v.x(), k), std::ldexp(v.y(), k), std::ldexp(v.z(), k));
    // Power-of-two scaling of the points is exact, so is that of lo, hi, hi - lo and their length.
    EXPECT_EQ(bounding_box_diameter(q), std::ldexp(d, k)) << "scale 2^" << k;
  }
  // The plain norm loses the same diagonal at 2^1000 (squares overflow) and 2^-1000 (they underflow).
  std::vector<Vec3> big = p, small = p;
  for (Vec3& v : big) v *= 0x1p1000;
  for (Vec3& v : small) v *= 0x1p-1000;
  EXPECT_EQ(plain_diagonal(big), std::numeric_limits<double>::infinity());
  EXPECT_NE(plain_diagonal(small), std::ldexp(d, -1000));
}

TEST(BoundingBox, EmptySinglePointAndTriangleCorners) {
  EXPECT_EQ(bounding_box_diameter(std::vector<Vec3>{}), 0.0);
  EXPECT_EQ(bounding_box_diameter(std::vector<Vec3>{Vec3(1, -2, 3)}), 0.0);
  // A unit cube's corners as triangle corner triples (a joined view) and as a flat list: sqrt(3).
  const std::vector<std::array<Vec3, 3>> corners{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
                                                 {Vec3(1, 1, 1), Vec3(0, 0, 1), Vec3(1, 1, 0)}};
  EXPECT_EQ(bounding_box_diameter(corners | std::views::join), std::sqrt(3.0));
  EXPECT_EQ(overflow_free_length(Vec3(0, 0, 0)), 0.0);
  // 3-4-5 at 2^1000, where the plain squares overflow: every step is exact.
  EXPECT_EQ(overflow_free_length(Vec3(0x3p1000, 0x4p1000, 0)), 0x5p1000);
  EXPECT_TRUE(std::isnan(overflow_free_length(Vec3(std::nan(""), 1, 0))));
}

}  // namespace

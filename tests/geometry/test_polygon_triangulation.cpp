// Triangulation of one polygonal face (geometry/src/polygon_triangulation.hpp, private to the
// geometry library): triangles on the polygon's own corners, of its area and orientation, the fan
// kept where it is a triangulation, and the refusals (repeated corner, zero area, not planar,
// crossing or touching itself) with the corner or sides at fault.
#include "../../geometry/src/polygon_triangulation.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace {

namespace pg = panelrad::geometry;
using pg::Index;
using pg::Vec3;
using pg::polygon_detail::triangulate_polygon;
using Tris = std::vector<std::array<Index, 3>>;

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << "message: " << (haystack)

/// Twice the vector area (Newell), on coordinates relative to the first corner.
Vec3 newell(const std::vector<Vec3>& p) {
  Vec3 n = Vec3::Zero();
  for (std::size_t k = 1; k + 1 < p.size(); ++k) n += (p[k] - p[0]).cross(p[k + 1] - p[0]);
  return n;
}

Tris fan(std::size_t n) {
  Tris t;
  for (std::size_t k = 1; k + 1 < n; ++k) t.push_back({0, static_cast<Index>(k), static_cast<Index>(k + 1)});
  return t;
}

/// The triangles cover the polygon once with its orientation: n - 2 of them, every corner used,
/// each of positive area facing the Newell normal, their area vectors summing to the polygon's.
void expect_triangulation(const Tris& tris, const std::vector<Vec3>& p, double tolerance = 1e-12) {
  ASSERT_EQ(tris.size(), p.size() - 2);
  const Vec3 n = newell(p);
  Vec3 sum = Vec3::Zero();
  std::vector<int> used(p.size(), 0);
  for (const auto& t : tris) {
    for (Index c : t) {
      ASSERT_TRUE(c >= 0 && static_cast<std::size_t>(c) < p.size());
      used[static_cast<std::size_t>(c)] = 1;
    }
    const Vec3 area = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
    EXPECT_GT(area.dot(n), 0) << "triangle " << t[0] << " " << t[1] << " " << t[2];
    sum += area;
  }
  EXPECT_EQ(std::count(used.begin(), used.end(), 1), static_cast<long>(p.size()));
  EXPECT_LE((sum - n).norm(), tolerance * n.norm()) << sum.transpose() << " vs " << n.transpose();
}

/// 2-D outline -> 3-D polygon: rotated by `rot`, shifted by `at`, reversed when asked.
std::vector<Vec3> embed(const std::vector<std::array<double, 2>>& outline, const Eigen::Matrix3d& rot, const Vec3& at,
                        bool reversed) {
  std::vector<Vec3> p;
  for (const auto& q : outline) p.push_back(at + rot * Vec3(q[0], q[1], 0));
  if (reversed) std::reverse(p.begin(), p.end());
  return p;
}

const std::vector<std::array<double, 2>> kComb = {{0, 0}, {5, 0}, {5, 3}, {4, 3}, {4, 1}, {3, 1}, {3, 3},
                                                  {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};

}  // namespace

TEST(PolygonTriangulation, TriangleIsKeptAsWritten) {
  const auto r = triangulate_polygon({Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(1, 0, 0)}, 0);
  EXPECT_TRUE(r.refusal.empty());
  EXPECT_EQ(r.triangles, (Tris{{0, 1, 2}}));
}

// A convex polygon (regular octagon on a tilted plane, either direction) keeps the fan from its
// first corner, as the reader wrote it before; so does a non-convex one that is star-shaped from
// its first corner, and one with corners on a straight side not touching the fan's apex.
TEST(PolygonTriangulation, FanIsKeptWhereItIsATriangulation) {
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  std::vector<std::array<double, 2>> octagon;
  for (int k = 0; k < 8; ++k) octagon.push_back({std::cos(k * std::numbers::pi / 4), std::sin(k * std::numbers::pi / 4)});
  for (bool reversed : {false, true}) {
    const auto p = embed(octagon, rot, Vec3(3, -1, 2), reversed);
    const auto r = triangulate_polygon(p, 0);
    ASSERT_TRUE(r.refusal.empty()) << r.refusal;
    EXPECT_EQ(r.triangles, fan(8));
    expect_triangulation(r.triangles, p);
  }
  const std::vector<Vec3> l_from_corner = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  EXPECT_EQ(triangulate_polygon(l_from_corner, 0).triangles, fan(6));
  const std::vector<Vec3> straight_side = {{0, 0, 0}, {3, 0, 0}, {3, 1, 0}, {2, 1, 0}, {1, 1, 0}, {0, 1, 0}};
  EXPECT_EQ(triangulate_polygon(straight_side, 0).triangles, fan(6));
}

// Non-convex outlines (L, U, a comb) from every starting corner, in both directions, on planes
// where each coordinate axis in turn is the projection axis: the triangles cover the polygon once
// with its orientation.
TEST(PolygonTriangulation, NonConvexPolygonsCoverTheirAreaWithTheirOrientation) {
  const std::vector<std::vector<std::array<double, 2>>> outlines = {
      {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}},
      {{0, 0}, {3, 0}, {3, 2}, {2, 2}, {2, 1}, {1, 1}, {1, 2}, {0, 2}},
      kComb};
  const std::vector<Eigen::Matrix3d> planes = {
      Eigen::Matrix3d::Identity(),                                                      // z dropped
      Eigen::AngleAxisd(std::numbers::pi / 2, Vec3::UnitY()).toRotationMatrix(),       // x dropped
      Eigen::AngleAxisd(-std::numbers::pi / 2, Vec3::UnitX()).toRotationMatrix(),      // y dropped
      Eigen::AngleAxisd(1.1, Vec3(3, -1, 2).normalized()).toRotationMatrix()};          // oblique
  int fans = 0, constrained = 0;
  for (const auto& outline : outlines)
    for (const auto& rot : planes)
      for (std::size_t shift = 0; shift < outline.size(); ++shift)
        for (bool reversed : {false, true}) {
          std::vector<std::array<double, 2>> shifted(outline.begin() + static_cast<long>(shift), outline.end());
          shifted.insert(shifted.end(), outline.begin(), outline.begin() + static_cast<long>(shift));
          const auto p = embed(shifted, rot, Vec3(-2, 5, 1), reversed);
          SCOPED_TRACE(std::to_string(outline.size()) + " corners, shift " + std::to_string(shift) +
                       (reversed ? " reversed" : ""));
          const auto r = triangulate_polygon(p, 0);
          ASSERT_TRUE(r.refusal.empty()) << r.refusal;
          expect_triangulation(r.triangles, p);
          (r.triangles == fan(p.size()) ? fans : constrained) += 1;
        }
  EXPECT_GT(constrained, 0);
  EXPECT_GT(fans, 0);
}

// Random star-shaped polygons around a point that is not a corner (up to 40 corners, radii from
// 0.05 to 1, some corners on straight sides) on random planes far from the origin.
TEST(PolygonTriangulation, RandomStarShapedPolygons) {
  std::mt19937 rng(2024);
  std::uniform_real_distribution<double> unit(0, 1);
  int tested = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 4 + static_cast<int>(rng() % 37);
    std::vector<double> angle(static_cast<std::size_t>(n));
    for (double& a : angle) a = 2 * std::numbers::pi * unit(rng);
    std::sort(angle.begin(), angle.end());
    // The centre inside: every angular gap between consecutive corners below a half turn.
    double gap = angle.front() + 2 * std::numbers::pi - angle.back();
    for (std::size_t k = 1; k < angle.size(); ++k) gap = std::max(gap, angle[k] - angle[k - 1]);
    if (!(gap < 0.9 * std::numbers::pi)) continue;
    std::vector<std::array<double, 2>> outline;
    for (double a : angle) {
      const double radius = 0.05 + 0.95 * unit(rng);
      outline.push_back({radius * std::cos(a), radius * std::sin(a)});
    }
    const Vec3 axis = Vec3(unit(rng) - 0.5, unit(rng) - 0.5, unit(rng) - 0.5).normalized();
    const Eigen::Matrix3d rot = Eigen::AngleAxisd(7 * unit(rng), axis).toRotationMatrix();
    const auto p = embed(outline, rot, Vec3(100, -50, 30), trial % 2 == 1);
    SCOPED_TRACE("trial " + std::to_string(trial));
    const auto r = triangulate_polygon(p, 0);
    ASSERT_TRUE(r.refusal.empty()) << r.refusal;
    expect_triangulation(r.triangles, p, 1e-9);
    ++tested;
  }
  EXPECT_GT(tested, 150);
}

// Every corner turns to the same side and every fan triangle has the same orientation, but the
// corners wind 2.5 times around the first one: the fan would cover the centre more than once. The
// polygon crosses itself and is refused.
TEST(PolygonTriangulation, SpiralWindingMoreThanOnceIsRefused) {
  std::vector<Vec3> p = {Vec3(0, 0, 0)};
  const int steps = 50;
  for (int k = 0; k < steps; ++k) {
    const double a = 2.5 * 2 * std::numbers::pi * k / (steps - 1), radius = 1 + 0.2 * k;
    p.emplace_back(radius * std::cos(a), radius * std::sin(a), 0);
  }
  for (std::size_t k = 1; k + 1 < p.size(); ++k)
    ASSERT_GT(p[k].cross(p[k + 1]).z(), 1e-3) << "fan triangle " << k << " must be counter-clockwise";
  const auto r = triangulate_polygon(p, 0);
  EXPECT_TRUE(r.triangles.empty());
  EXPECT_CONTAINS(r.refusal, "crosses or touches itself: its side from its ");
}

TEST(PolygonTriangulation, DefectsAreRefusedNamingTheCornersOrSides) {
  // A corner on another side.
  const std::vector<Vec3> touching = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {3, 4, 0}, {2, 0, 0}, {1, 4, 0}, {0, 4, 0}};
  EXPECT_CONTAINS(triangulate_polygon(touching, 0).refusal,
                  "crosses or touches itself: its side from its 1st vertex (0, 0, 0) to its 2nd vertex (4, 0, 0) meets "
                  "its side from its 4th vertex (3, 4, 0) to its 5th vertex (2, 0, 0)");
  // A spike: the path goes back along its own side.
  const std::vector<Vec3> spike = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {2, 1, 0}, {0, 2, 0}};
  EXPECT_CONTAINS(triangulate_polygon(spike, 0).refusal, "crosses or touches itself");
  // Two sides crossing.
  const std::vector<Vec3> crossing = {{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {1, -1, 0}, {0, 2, 0}};
  EXPECT_CONTAINS(triangulate_polygon(crossing, 0).refusal,
                  "its side from its 1st vertex (0, 0, 0) to its 2nd vertex (2, 0, 0) meets its side from its 3rd "
                  "vertex (2, 2, 0) to its 4th vertex (1, -1, 0)");
  // A symmetric bow-tie: zero vector area.
  const std::vector<Vec3> bow_tie = {{0, 0, 0}, {1, 1, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_CONTAINS(triangulate_polygon(bow_tie, 0).refusal, "has no plane: its vector area");
  const std::vector<Vec3> repeated = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 0, 0}, {0, 1, 0}};
  EXPECT_CONTAINS(triangulate_polygon(repeated, 0).refusal,
                  "lists one vertex twice: its 1st and 4th vertices are both (0, 0, 0)");
  const std::vector<Vec3> line = {{0, 0, 0}, {1, 2, 3}, {3, 6, 9}, {2, 4, 6}};
  EXPECT_CONTAINS(triangulate_polygon(line, 0).refusal, "has zero area: its 4 vertices lie on one straight line");
}

// The flatness tolerance max(1e-9 s, 4 eta): a unit square with a corner lifted by h has its
// corners h / 4 from the Newell plane. Beyond it, up to 1e-4 of the size (the diagonal sqrt(2)),
// the polygon is triangulated with a note; beyond that, refused.
TEST(PolygonTriangulation, FlatnessToleranceIsTheLargerOfSizeAndRounding) {
  const auto lifted = [](double h) { return std::vector<Vec3>{{0, 0, 0}, {1, 0, 0}, {1, 1, h}, {0, 1, 0}}; };
  // Exact data (eta = 0): 1e-9 of the diagonal sqrt(2).
  EXPECT_TRUE(triangulate_polygon(lifted(5e-9), 0).note.empty());    // 1.25e-9 < 1.41e-9
  EXPECT_CONTAINS(triangulate_polygon(lifted(6e-9), 0).note, "is not exactly planar: its ");  // 1.5e-9
  EXPECT_TRUE(triangulate_polygon(lifted(6e-9), 0).refusal.empty());
  // eta = 5e-6 (6 digits of magnitude 1): 4 eta = 2e-5.
  EXPECT_TRUE(triangulate_polygon(lifted(7.9e-5), 5e-6).note.empty());  // 1.975e-5
  const auto noted = triangulate_polygon(lifted(8.1e-5), 5e-6);          // 2.025e-5
  EXPECT_TRUE(noted.refusal.empty());
  EXPECT_EQ(noted.triangles.size(), 2u);
  EXPECT_CONTAINS(noted.note, " lies 2.02e-05 from the plane");
  EXPECT_CONTAINS(noted.note, "more than the tolerance 2.00e-05 = max(1e-09 x its size 1.41e+00, 4 x the rounding 5.00e-06");
  // 1e-4 of the size is 1.41e-4: lifted by 5.6e-4 (1.4e-4 away) noted, by 5.7e-4 refused.
  EXPECT_TRUE(triangulate_polygon(lifted(5.6e-4), 5e-6).refusal.empty());
  const std::string why = triangulate_polygon(lifted(5.7e-4), 5e-6).refusal;
  EXPECT_CONTAINS(why, "is not planar: its ");  // the four corners are equally far
  EXPECT_CONTAINS(why, "and more than 1e-04 of its size");
  EXPECT_CONTAINS(why, "split it into planar polygons or triangles");
  EXPECT_CONTAINS(triangulate_polygon(lifted(1e-2), 5e-6).refusal, "lies 2.50e-03 from the plane");
}

// A polygon refused as not planar by no more than its coordinates' printing could bend it (a
// millimetre-sized quad written with 6 decimals: 3 significant digits) is told so, and asked for
// more digits; one written with short numbers meant as written (a place coarser than 1e-2 of its
// size), or bent by more than 4 printed places, is not.
TEST(PolygonTriangulation, RefusalWithinThePrintingAsksForMoreDigits) {
  const std::vector<Vec3> printed = {{0.000100, 0.000200, 0.000000}, {0.000600, 0.000200, 0.000000},
                                     {0.000600, 0.000700, 0.000001}, {0.000100, 0.000700, 0.000000}};
  const std::string why = triangulate_polygon(printed, 0).refusal;
  EXPECT_CONTAINS(why, "is not planar");
  EXPECT_CONTAINS(why, "The coordinates are printed to 1e-06 (a rounding of 5.00e-07");
  EXPECT_CONTAINS(why, "write the coordinates with more digits");
  const std::vector<Vec3> meant = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.3}, {0, 1, 0}};
  EXPECT_CONTAINS(triangulate_polygon(meant, 0).refusal, "is not planar");
  EXPECT_EQ(triangulate_polygon(meant, 0).refusal.find("more digits"), std::string::npos);
  const std::vector<Vec3> bent = {{0.000100, 0.000200, 0.000000}, {0.000600, 0.000200, 0.000000},
                                  {0.000600, 0.000700, 0.000009}, {0.000100, 0.000700, 0.000000}};
  EXPECT_EQ(triangulate_polygon(bent, 0).refusal.find("more digits"), std::string::npos);
}

// Coordinates near the ends of the double range (exact binary scalings of an L): the plane is
// computed on coordinates scaled by a power of two, the rest by exact predicates.
TEST(PolygonTriangulation, ExtremeCoordinateScales) {
  for (double scale : {0x1p900, 0x1p-900}) {
    std::vector<Vec3> p = {{2, 0, 0}, {2, 1, 1}, {1, 1, 1}, {1, 2, 2}, {0, 2, 2}, {0, 0, 0}};
    for (Vec3& v : p) v *= scale;
    const auto r = triangulate_polygon(p, 0);
    ASSERT_TRUE(r.refusal.empty()) << scale << ": " << r.refusal;
    ASSERT_EQ(r.triangles.size(), 4u);
    std::vector<Vec3> unscaled = p;
    for (Vec3& v : unscaled) v /= scale;
    expect_triangulation(r.triangles, unscaled);
  }
}

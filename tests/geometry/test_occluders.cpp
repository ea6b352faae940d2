// The line-of-sight function V(P, Q) of the radiosity equation (1) on general scenes (Occluders):
// the visible part of a triangle seen from a point against independent truths (CGAL's exact
// Boolean operations on polygons, Monte Carlo with the ray test, a closed-form shadow), touching
// faces that do not occlude, the consistency of the shaft classes with the visible parts and across
// the midpoint subdivision, and the ray test on simple cases.
#include <panelrad/geometry/occluders.hpp>
#include <panelrad/support/parallel_for.hpp>

#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>
#include <CGAL/Polygon_set_2.h>
#include <CGAL/Polygon_with_holes_2.h>

#include <Eigen/Geometry>
#include "../common/occluded_scenes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

namespace {

using namespace panelrad::geometry;
using Tri = std::array<Vec3, 3>;
using panelrad::parallel_for;

TriangleMesh mesh_of(const std::vector<Tri>& tris) {
  return panelrad::testing::triangle_soup(tris, "occluder test scene");
}

/// The two triangles of the axis-aligned rectangle [x0, x1] x [y0, y1] at height z, split along
/// the diagonal from (x0, y0) to (x1, y1) or, with `other_diagonal`, along the other one.
std::vector<Tri> horizontal_rectangle(double x0, double x1, double y0, double y1, double z, bool other_diagonal = false) {
  const Vec3 a(x0, y0, z), b(x1, y0, z), c(x1, y1, z), d(x0, y1, z);
  if (other_diagonal) return {Tri{a, b, d}, Tri{b, c, d}};
  return {Tri{a, b, c}, Tri{a, c, d}};
}

double area(const Tri& t) { return 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).norm(); }

std::array<Tri, 4> midpoint_children(const Tri& t) {
  const Vec3 m01 = (t[0] + t[1]) / 2, m12 = (t[1] + t[2]) / 2, m20 = (t[2] + t[0]) / 2;
  return {Tri{t[0], m01, m20}, Tri{m01, t[1], m12}, Tri{m20, m12, t[2]}, Tri{m01, m12, m20}};
}

std::vector<Index> all_indices(const Occluders& occ) {
  std::vector<Index> v(static_cast<std::size_t>(occ.size()));
  std::iota(v.begin(), v.end(), 0);
  return v;
}

// ---- The exact oracle: tau minus the shadows, in the plane z = 0, by CGAL's Boolean operations ----

using EK = CGAL::Exact_predicates_exact_constructions_kernel;
using EPolygon = CGAL::Polygon_2<EK>;

EPolygon polygon_xy(const std::vector<Vec3>& pts) {
  EPolygon p;
  for (const Vec3& v : pts) p.push_back(EK::Point_2(v.x(), v.y()));
  if (p.is_clockwise_oriented()) p.reverse_orientation();
  return p;
}

/// Area of tau \ (union of the shadows), all in the plane z = 0.
double oracle_visible_area(const Tri& tau, const std::vector<std::vector<Vec3>>& shadows) {
  CGAL::Polygon_set_2<EK> set(polygon_xy({tau.begin(), tau.end()}));
  for (const auto& s : shadows) set.difference(polygon_xy(s));
  std::vector<CGAL::Polygon_with_holes_2<EK>> parts;
  set.polygons_with_holes(std::back_inserter(parts));
  EK::FT a = 0;
  for (const auto& p : parts) {
    a += p.outer_boundary().area();
    for (auto h = p.holes_begin(); h != p.holes_end(); ++h) a -= CGAL::abs(h->area());
  }
  return CGAL::to_double(a);
}

/// The shadow on z = 0 of a triangle lying strictly between z = 0 and P's height, cast from P:
/// the triangle of its projected corners (central projection is then defined on all of it).
std::vector<Vec3> projected_to_floor(const Vec3& P, const Tri& t) {
  std::vector<Vec3> s;
  for (const Vec3& x : t) s.push_back(P + (x - P) * (P.z() / (P.z() - x.z())));
  return s;
}

/// Checks the structure of a visible part: convex pieces, counter-clockwise about nQ, in tau's
/// plane and inside tau, with `area` their total area. Corners are reconstructed from tau's frame:
/// tolerances of 1e-12 times tau's size cover the rounding of that frame (~1e-16 relative). When
/// they come from the frame of a larger triangle containing tau (frame_size its size), each corner
/// carries a rounding of ~1e-16 frame_size: the area recomputed from them moves by at most the
/// pieces' perimeters (a few times tau's size) times that, covered by 1e-14 frame_size size.
void expect_well_formed(const VisiblePart& part, const Tri& tau, const Vec3& nQ, double frame_size = 0) {
  const Vec3 n = (tau[1] - tau[0]).cross(tau[2] - tau[0]).normalized() * ((tau[1] - tau[0]).cross(tau[2] - tau[0]).dot(nQ) > 0 ? 1 : -1);
  const double size = std::max({(tau[1] - tau[0]).norm(), (tau[2] - tau[1]).norm(), (tau[0] - tau[2]).norm()});
  double total = 0;
  std::uint32_t begin = 0;
  for (const std::uint32_t end : part.piece_end) {
    ASSERT_GE(end, begin + 3);
    double a = 0;
    for (std::uint32_t i = begin; i < end; ++i) {
      const Vec3& p = part.points[i];
      const Vec3& q = part.points[i + 1 < end ? i + 1 : begin];
      const Vec3& r = part.points[i + 2 < end ? i + 2 : begin + (i + 2 - end)];
      EXPECT_NEAR((p - tau[0]).dot(n), 0, 1e-12 * size);
      // Inside tau: on the inner side of each of its edges (oriented about n).
      for (int e = 0; e < 3; ++e) {
        const Vec3 inward = n.cross(tau[(e + 1) % 3] - tau[e]) * ((tau[1] - tau[0]).cross(tau[2] - tau[0]).dot(n) > 0 ? 1 : -1);
        EXPECT_GE((p - tau[e]).dot(inward.normalized()), -1e-12 * size);
      }
      EXPECT_GE((q - p).cross(r - q).dot(n), -1e-12 * size * size) << "piece not convex counter-clockwise";
      a += (p - part.points[begin]).cross(q - part.points[begin]).dot(n) / 2;
    }
    EXPECT_GT(a, 0);
    total += a;
    begin = end;
  }
  EXPECT_EQ(begin, part.points.size());
  EXPECT_NEAR(total, part.area, 1e-12 * area(tau) + 1e-14 * frame_size * size);
}

struct RandomConfig {
  Vec3 P, nP;
  Tri tau;
  std::vector<Tri> blockers;
};

/// P on a ceiling facing down at height H in [1, 2], tau a random floor triangle facing up, and 1-3
/// blockers strictly between the floor and the ceiling, placed around segments from P to tau.
RandomConfig random_config(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u01(0, 1);
  RandomConfig c;
  const double H = 1 + u01(rng);
  c.P = Vec3(2 * u01(rng) - 0.5, 2 * u01(rng) - 0.5, H);
  c.nP = Vec3(0, 0, -1);
  for (Vec3& v : c.tau) v = Vec3(u01(rng), u01(rng), 0);
  if ((c.tau[1] - c.tau[0]).cross(c.tau[2] - c.tau[0]).z() < 0) std::swap(c.tau[1], c.tau[2]);
  const int nb = 1 + static_cast<int>(u01(rng) * 3);
  for (int b = 0; b < nb; ++b) {
    const double t = 0.15 + 0.7 * u01(rng);  // fraction of the way from P down to the floor
    const Vec3 Q(1.4 * u01(rng) - 0.2, 1.4 * u01(rng) - 0.2, 0);
    const Vec3 centre = c.P + t * (Q - c.P);
    const double scale = (0.1 + 0.8 * u01(rng)) * t;
    Tri tri;
    for (Vec3& v : tri) {
      v = centre + scale * Vec3(2 * u01(rng) - 1, 2 * u01(rng) - 1, 0.3 * (2 * u01(rng) - 1));
      v.z() = std::clamp(v.z(), 0.05 * H, 0.95 * H);
    }
    c.blockers.push_back(tri);
  }
  return c;
}

// ---- 1. Visible area against CGAL's exact Boolean operations, and against Monte Carlo rays ----

TEST(Occluders, VisibleAreaEqualsTheExactPolygonDifferenceOnRandomScenes) {
  std::mt19937_64 rng(20261201);
  const Vec3 nQ(0, 0, 1);
  int cut = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const RandomConfig c = random_config(rng);
    std::vector<Tri> tris = {c.tau};
    tris.insert(tris.end(), c.blockers.begin(), c.blockers.end());
    const Occluders occ(mesh_of(tris));
    std::vector<std::vector<Vec3>> shadows;
    for (const Tri& b : c.blockers) shadows.push_back(projected_to_floor(c.P, b));
    const double expected = oracle_visible_area(c.tau, shadows);

    std::vector<Index> among;
    occ.candidates(c.P, c.nP, c.tau, nQ, among);
    EXPECT_TRUE(std::is_sorted(among.begin(), among.end()));
    EXPECT_TRUE(std::find(among.begin(), among.end(), 0) == among.end()) << "tau's own face is no occluder of it";
    VisiblePart part, part_all;
    occ.visible_part(c.P, c.nP, c.tau, nQ, among, part);
    occ.visible_part(c.P, c.nP, c.tau, nQ, all_indices(occ), part_all);
    // The oracle's shadows come from corners projected in double precision (relative error ~1e-16,
    // magnified at most H / (H - z) <= 20 by the projection): 1e-12 of tau's area bounds the area
    // difference this and the rounding policy's margin make.
    EXPECT_NEAR(part.area, expected, 1e-12 * area(c.tau)) << "trial " << trial;
    EXPECT_EQ(part.area, part_all.area) << "the candidates miss an occluder, trial " << trial;
    expect_well_formed(part, c.tau, nQ);
    if (expected > 0 && expected < area(c.tau) * (1 - 1e-9)) ++cut;
  }
  EXPECT_GT(cut, 100) << "the random scenes should mostly cut tau";
}

/// Total area of the covered pieces of `part` (about nQ = +z).
double covered_area(const VisiblePart& part) {
  double total = 0;
  std::uint32_t begin = 0;
  for (const std::uint32_t end : part.covered_end) {
    for (std::uint32_t i = begin + 1; i + 1 < end; ++i)
      total += (part.covered_points[i] - part.covered_points[begin])
                   .cross(part.covered_points[i + 1] - part.covered_points[begin])
                   .z() / 2;
    begin = end;
  }
  return total;
}

// The covered pieces (the parts of tau inside the shadows) are the complement of the visible
// pieces in tau, the exact hidden area up to the same 1e-12 area(tau) as the visible area above
// (plus the pieces below a thousandth of the area margin that the visible part drops: at most a
// few dozen of 1e-15 area(tau)); for tau's sub-triangles classified in the root's plane as well
// (the frame of the root: 1e-12 of the root's area).
TEST(Occluders, CoveredPiecesAreTheRestOfTau) {
  std::mt19937_64 rng(20261206);
  const Vec3 nQ(0, 0, 1);
  int partial = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const RandomConfig c = random_config(rng);
    std::vector<Tri> tris = {c.tau};
    tris.insert(tris.end(), c.blockers.begin(), c.blockers.end());
    const Occluders occ(mesh_of(tris));
    ShadowPlane plane;
    VisiblePart part;
    const ShaftClass cls = occ.classify(c.P, c.nP, c.tau, nQ, all_indices(occ), plane, &part);
    if (cls != ShaftClass::partial) continue;
    ++partial;
    std::vector<std::vector<Vec3>> shadows;
    for (const Tri& b : c.blockers) shadows.push_back(projected_to_floor(c.P, b));
    const double a = area(c.tau);
    EXPECT_TRUE(part.whole_front) << "tau lies in front of P's plane, trial " << trial;
    EXPECT_NEAR(part.area + covered_area(part), a, 1e-12 * a) << "trial " << trial;
    EXPECT_NEAR(covered_area(part), a - oracle_visible_area(c.tau, shadows), 1e-12 * a) << "trial " << trial;
    std::vector<Index> shadow_indices(plane.shadows.size()), meeting;
    for (std::size_t k = 0; k < shadow_indices.size(); ++k) shadow_indices[k] = static_cast<Index>(k);
    for (const Tri& sub : midpoint_children(c.tau)) {
      VisiblePart sub_part;
      if (occ.classify_within(plane, sub, shadow_indices, meeting, &sub_part) != ShaftClass::partial) continue;
      EXPECT_TRUE(sub_part.whole_front);
      EXPECT_NEAR(sub_part.area + covered_area(sub_part), area(sub), 1e-12 * a) << "trial " << trial;
      EXPECT_NEAR(covered_area(sub_part), area(sub) - oracle_visible_area(sub, shadows), 1e-12 * a)
          << "trial " << trial;
    }
  }
  EXPECT_GT(partial, 50) << "the random scenes should mostly cut tau";
}

TEST(Occluders, VisibleAreaAgreesWithTheFractionOfUnblockedRays) {
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> u01(0, 1);
  const Vec3 nQ(0, 0, 1);
  constexpr int kRays = 2000;
  for (int trial = 0; trial < 20; ++trial) {
    const RandomConfig c = random_config(rng);
    std::vector<Tri> tris = {c.tau};
    tris.insert(tris.end(), c.blockers.begin(), c.blockers.end());
    const Occluders occ(mesh_of(tris));
    std::vector<Index> among;
    occ.candidates(c.P, c.nP, c.tau, nQ, among);
    VisiblePart part;
    occ.visible_part(c.P, c.nP, c.tau, nQ, among, part);
    int seen = 0;
    for (int r = 0; r < kRays; ++r) {
      double s = u01(rng), t = u01(rng);
      if (s + t > 1) s = 1 - s, t = 1 - t;  // uniform in tau
      const Vec3 Q = c.tau[0] + s * (c.tau[1] - c.tau[0]) + t * (c.tau[2] - c.tau[0]);
      seen += occ.visible(c.P, Q) ? 1 : 0;
    }
    // The count of unblocked rays is binomial(kRays, p), p the visible fraction: 5 standard
    // deviations (plus one ray) fail a correct implementation with probability < 1e-6 per trial.
    const double p = part.area / area(c.tau);
    const double tol = 5 * std::sqrt(p * (1 - p) / kRays) + 1.0 / kRays;
    EXPECT_NEAR(static_cast<double>(seen) / kRays, p, tol) << "trial " << trial;
  }
}

// ---- 2. The closed-form shadow of a square blocker on a square emitter ----

TEST(Occluders, SquareBlockerCastsTheCentralProjectionOfItselfOnTheEmitter) {
  const std::vector<Tri> emitter = horizontal_rectangle(-0.5, 0.5, -0.5, 0.5, 1);
  // The blocker is split along the other diagonal: its two shadows together cover what neither does.
  const std::vector<Tri> blocker = horizontal_rectangle(-0.25, 0.25, -0.25, 0.25, 0.5, true);
  const std::vector<Tri> floor = horizontal_rectangle(-2, 2, -2, 2, 0);
  std::vector<Tri> tris = emitter;
  tris.insert(tris.end(), blocker.begin(), blocker.end());
  tris.insert(tris.end(), floor.begin(), floor.end());
  const Occluders occ(mesh_of(tris));
  const Vec3 nP(0, 0, 1), nQ(0, 0, -1);
  const std::vector<std::array<double, 2>> positions = {{0.3, -0.2}, {0.6, 0.1}, {-0.05, 0.45}, {0.999, 0.5},
                                                        {1.2, 0.1}, {0, 0}, {0.25, 0.25}};
  for (const auto& [px, py] : positions) {
    const Vec3 P(px, py, 0);
    // The blocker at half the height projects with factor 2: [-0.5 - px, 0.5 - px] x [-0.5 - py, 0.5 - py].
    const double expected = 1 - std::max(0.0, 1 - std::abs(px)) * std::max(0.0, 1 - std::abs(py));
    double total = 0;
    for (const Tri& tau : emitter) {
      std::vector<Index> among, meeting;
      occ.candidates(P, nP, tau, nQ, among);
      VisiblePart part, classified;
      occ.visible_part(P, nP, tau, nQ, among, part);
      const ShaftClass cls = occ.classify(P, nP, tau, nQ, among, meeting, &classified);
      expect_well_formed(part, tau, nQ);
      total += part.area;
      if (cls == ShaftClass::partial) {
        EXPECT_EQ(classified.area, part.area);
      } else if (cls == ShaftClass::full) {
        EXPECT_NEAR(part.area, area(tau), 1e-15);
      } else {
        EXPECT_EQ(part.area, 0);
      }
      for (const Vec3& q : part.points) {
        // In the emitter, and not inside the shadow's interior (1e-12: the rounding of tau's frame).
        EXPECT_LE(std::abs(q.x()), 0.5 + 1e-12);
        EXPECT_LE(std::abs(q.y()), 0.5 + 1e-12);
        EXPECT_NEAR(q.z(), 1, 1e-12);
        EXPECT_FALSE(std::abs(q.x() + px) < 0.5 - 1e-12 && std::abs(q.y() + py) < 0.5 - 1e-12)
            << "corner (" << q.x() << ", " << q.y() << ") in the shadow, P = (" << px << ", " << py << ")";
      }
      // Each convex piece has its centroid outside the shadow (else it would overlap the shadow).
      std::uint32_t begin = 0;
      for (const std::uint32_t end : part.piece_end) {
        Vec3 g = Vec3::Zero();
        for (std::uint32_t i = begin; i < end; ++i) g += part.points[i];
        g /= end - begin;
        EXPECT_FALSE(std::abs(g.x() + px) < 0.5 && std::abs(g.y() + py) < 0.5);
        begin = end;
      }
    }
    // 1e-13: the areas are sums of a few products of coordinates of size 1, rounded.
    EXPECT_NEAR(total, expected, 1e-13) << "P = (" << px << ", " << py << ")";
    if (px == 0 && py == 0) {
      // The shadow is exactly the emitter: both halves hidden, by the two blocker triangles together.
      for (const Tri& tau : emitter) {
        std::vector<Index> among, meeting;
        occ.candidates(P, nP, tau, nQ, among);
        EXPECT_EQ(occ.classify(P, nP, tau, nQ, among, meeting), ShaftClass::hidden);
        EXPECT_EQ(meeting.size(), 2u);
      }
    }
  }
}

TEST(Occluders, BoxSeenThroughTwoOfItsFacesHidesATriangleAtTheCoarsestLevel) {
  // The box [-0.3, 0.3]^2 x [0.4, 0.6]; from P = (0.6, 0, 0) the rays to tau enter through the
  // bottom face (tau's corners with x < -0.15) or through the side x = 0.3 (the others).
  std::vector<Tri> tris;
  const double x0 = -0.3, x1 = 0.3, z0 = 0.4, z1 = 0.6;
  for (const double z : {z0, z1}) {
    const auto r = horizontal_rectangle(x0, x1, x0, x1, z);
    tris.insert(tris.end(), r.begin(), r.end());
  }
  for (const double x : {x0, x1}) {
    tris.push_back({Vec3(x, x0, z0), Vec3(x, x1, z0), Vec3(x, x1, z1)});
    tris.push_back({Vec3(x, x0, z0), Vec3(x, x1, z1), Vec3(x, x0, z1)});
  }
  for (const double y : {x0, x1}) {
    tris.push_back({Vec3(x0, y, z0), Vec3(x1, y, z0), Vec3(x1, y, z1)});
    tris.push_back({Vec3(x0, y, z0), Vec3(x1, y, z1), Vec3(x0, y, z1)});
  }
  const Tri tau = {Vec3(-0.2, -0.1, 1), Vec3(0.1, -0.1, 1), Vec3(-0.05, 0.1, 1)};
  tris.push_back(tau);
  const Occluders occ(mesh_of(tris));
  const Vec3 P(0.6, 0, 0), nP(0, 0, 1), nQ(0, 0, -1);
  std::vector<Index> among, meeting;
  occ.candidates(P, nP, tau, nQ, among);
  EXPECT_EQ(occ.classify(P, nP, tau, nQ, among, meeting), ShaftClass::hidden);
  // Neither the bottom (faces 0, 1) nor the side x = 0.3 (faces 6, 7) alone hides tau.
  const std::vector<Index> bottom = {0, 1}, side = {6, 7};
  EXPECT_EQ(occ.classify(P, nP, tau, nQ, bottom, meeting), ShaftClass::partial);
  EXPECT_EQ(occ.classify(P, nP, tau, nQ, side, meeting), ShaftClass::partial);
  // Independently: no ray from P to a point inside tau passes (the corner tau[1] sees the box's
  // edge x = 0.3, z = 0.6 exactly: a touching ray, not tested).
  for (int i = 1; i < 20; ++i)
    for (int j = 1; i + j < 20; ++j) {
      const Vec3 Q = tau[0] + (i / 20.0) * (tau[1] - tau[0]) + (j / 20.0) * (tau[2] - tau[0]);
      EXPECT_FALSE(occ.visible(P, Q)) << i << " " << j;
    }
}

// ---- 3. Touching is not occluding ----

/// The floor [0, 2]^2 split at x = 1 (faces 0-1 left, 2-3 right, facing up), and a wall x = 1,
/// 0 <= y <= 2, 0 <= z <= 1 standing on it (faces 4-5, facing -x).
std::vector<Tri> floor_and_wall() {
  std::vector<Tri> tris = horizontal_rectangle(0, 1, 0, 2, 0);
  const auto right = horizontal_rectangle(1, 2, 0, 2, 0);
  tris.insert(tris.end(), right.begin(), right.end());
  tris.push_back({Vec3(1, 0, 0), Vec3(1, 2, 1), Vec3(1, 2, 0)});
  tris.push_back({Vec3(1, 0, 0), Vec3(1, 0, 1), Vec3(1, 2, 1)});
  return tris;
}

TEST(Occluders, AWallStandingOnTheFloorHidesOnlyWhatIsBehindIt) {
  const std::vector<Tri> tris = floor_and_wall();
  const Occluders occ(mesh_of(tris));
  const Vec3 up(0, 0, 1);
  std::vector<Index> among, meeting;
  // P on the floor, tau on the floor: P on tau's plane, nothing seen whatever the wall.
  const Vec3 P_floor(0.5, 1, 0);
  for (const Index t : {1, 2}) {
    EXPECT_EQ(occ.classify(P_floor, up, tris[t], up, all_indices(occ), meeting), ShaftClass::hidden);
    EXPECT_TRUE(meeting.empty());
  }
  EXPECT_TRUE(occ.visible(P_floor, Vec3(0.2, 0.3, 0)));  // along the floor, the wall not in between
  // P above the floor, facing down: the left floor touches the wall's foot and is fully seen; the
  // right floor is behind the wall (P's height 0.5 < the wall's 1).
  const Vec3 P(0.5, 1, 0.5), down(0, 0, -1);
  for (const Index t : {0, 1}) {
    occ.candidates(P, down, tris[t], up, among);
    EXPECT_TRUE(among.empty()) << "face " << t;
    EXPECT_EQ(occ.classify(P, down, tris[t], up, all_indices(occ), meeting), ShaftClass::full) << "face " << t;
    EXPECT_TRUE(meeting.empty());
  }
  for (const Index t : {2, 3}) {
    // The rays from P to the right floor cross the wall's plane below its diagonal z = y / 2, in
    // face 4; face 5 touches the shaft along that diagonal only.
    occ.candidates(P, down, tris[t], up, among);
    EXPECT_EQ(among, (std::vector<Index>{4})) << "face " << t;
    EXPECT_EQ(occ.classify(P, down, tris[t], up, among, meeting), ShaftClass::hidden) << "face " << t;
  }
  EXPECT_TRUE(occ.visible(P, Vec3(0.99, 1.5, 0)));
  EXPECT_FALSE(occ.visible(P, Vec3(1.01, 1.5, 0)));
}

// A point a gap 1e-11 above the edge of a box's top, the side of the box below that edge: P's
// distance from the side's plane (y = 0.6) is below the visibility margin, and its exact side
// decides. One double above 0.6 (1.1e-16 in front) it sees the side, whose factor is that
// distance over twice the gap (5.6e-6, what the top misses of its half); on the plane or behind
// it, nothing. The box's top, through the shaft's edge only, is no occluder of it.
TEST(Occluders, APointWithinTheMarginInFrontOfAPlaneSeesItsFace) {
  const double top = 1 - 1e-11;
  const Tri side_a = {Vec3(0.35, 0.6, 0.6), Vec3(0.65, 0.6, 0.6), Vec3(0.65, 0.6, top)};
  const Tri side_b = {Vec3(0.35, 0.6, 0.6), Vec3(0.65, 0.6, top), Vec3(0.35, 0.6, top)};
  const Tri top_a = {Vec3(0.35, 0.3, top), Vec3(0.65, 0.3, top), Vec3(0.65, 0.6, top)};
  const Tri top_b = {Vec3(0.35, 0.3, top), Vec3(0.65, 0.6, top), Vec3(0.35, 0.6, top)};
  const std::vector<Tri> tris = {side_a, side_b, top_a, top_b};
  const Occluders occ(mesh_of(tris));
  const Vec3 down(0, 0, -1), out(0, 1, 0);
  std::vector<Index> among, meeting;
  for (const double y : {std::nextafter(0.6, 1.0), 0.6, std::nextafter(0.6, 0.0)}) {
    const Vec3 P(0.64166666666666661, y, 1);
    const ShaftClass expected = y > 0.6 ? ShaftClass::full : ShaftClass::hidden;
    for (const Index t : {0, 1}) {
      occ.candidates(P, down, tris[t], out, among);
      EXPECT_TRUE(among.empty()) << "y " << y << ", face " << t;
      EXPECT_EQ(occ.classify(P, down, tris[t], out, all_indices(occ), meeting), expected)
          << "y " << y << ", face " << t;
      EXPECT_TRUE(meeting.empty());
      ShadowPlane plane;
      EXPECT_EQ(occ.classify(P, down, tris[t], out, all_indices(occ), plane), expected);
      EXPECT_EQ(plane.seen, y > 0.6);
      EXPECT_TRUE(plane.shadows.empty());
    }
  }
}

TEST(Occluders, TheWallIsSeenFullyFromTheFloorItStandsOn) {
  const std::vector<Tri> tris = floor_and_wall();
  const Occluders occ(mesh_of(tris));
  const Vec3 P(0.5, 1, 0), up(0, 0, 1), towards_P(-1, 0, 0);
  std::vector<Index> among, meeting;
  for (const Index t : {4, 5}) {
    occ.candidates(P, up, tris[t], towards_P, among);
    EXPECT_TRUE(among.empty()) << "the floor (through P) and the wall (tau's plane) are no candidates";
    EXPECT_EQ(occ.classify(P, up, tris[t], towards_P, all_indices(occ), meeting), ShaftClass::full);
    VisiblePart part;
    occ.visible_part(P, up, tris[t], towards_P, all_indices(occ), part);
    EXPECT_NEAR(part.area, area(tris[t]), 1e-15);
  }
}

TEST(Occluders, AFaceIsNoOccluderOfItsSubTriangles) {
  const std::vector<Tri> tris = floor_and_wall();
  const Occluders occ(mesh_of(tris));
  const Vec3 P(0.5, 1, 0.5), down(0, 0, -1), up(0, 0, 1);
  std::vector<Index> among, meeting;
  for (const Tri& child : midpoint_children(tris[0])) {
    // The candidates are a superset (the wall, touching the middle child at a corner, may be one);
    // the face containing the child never is, and nothing meets the shaft.
    occ.candidates(P, down, child, up, among);
    EXPECT_TRUE(std::find(among.begin(), among.end(), 0) == among.end());
    EXPECT_EQ(occ.classify(P, down, child, up, all_indices(occ), meeting), ShaftClass::full);
    EXPECT_TRUE(meeting.empty());
  }
}

TEST(Occluders, AFaceThroughPSeenEdgeOnCastsNoShadow) {
  const Tri floor = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 2, 0)};
  const Vec3 P(0.5, 1, 0.5), down(0, 0, -1), up(0, 0, 1);
  for (const double y : {1.0, 1.05}) {
    // In the plane y = 1 through P (edge-on), or moved off it (then it does cast a shadow).
    const Tri blade = {Vec3(0.3, y, 0.1), Vec3(0.7, y, 0.1), Vec3(0.5, y, 0.3)};
    const Occluders occ(mesh_of({floor, blade}));
    std::vector<Index> among, meeting;
    occ.candidates(P, down, floor, up, among);
    const ShaftClass cls = occ.classify(P, down, floor, up, all_indices(occ), meeting);
    if (y == 1.0) {
      EXPECT_TRUE(among.empty());
      EXPECT_EQ(cls, ShaftClass::full);
      EXPECT_TRUE(meeting.empty());
    } else {
      EXPECT_EQ(among, (std::vector<Index>{1}));
      EXPECT_EQ(cls, ShaftClass::partial);
      EXPECT_EQ(meeting, (std::vector<Index>{1}));
    }
  }
}

TEST(Occluders, TauStraddlingPsPlaneIsPartialAndCutToItsFront) {
  // P on the floor facing up; tau a vertical triangle crossing the floor's plane: the part above
  // z = 0 is seen (a quarter of tau: the part above the midline of a triangle with its apex up).
  const Tri tau = {Vec3(1, -1, -1), Vec3(1, 1, -1), Vec3(1, 0, 1)};
  const Occluders occ(mesh_of({tau}));
  const Vec3 P(0, 0, 0), up(0, 0, 1), towards_P(-1, 0, 0);
  std::vector<Index> meeting;
  VisiblePart part;
  EXPECT_EQ(occ.classify(P, up, tau, towards_P, {}, meeting, &part), ShaftClass::partial);
  EXPECT_NEAR(part.area, 0.25 * area(tau), 1e-15);
  for (const Vec3& q : part.points) EXPECT_GE(q.z(), -1e-15);
  expect_well_formed(part, tau, towards_P);
}

// ---- 4. The classes agree with the visible parts, and across the midpoint subdivision ----

double class_area(const Occluders& occ, const RandomConfig& c, const Tri& tau, std::span<const Index> among,
                  int depth, int& checked) {
  const Vec3 nQ(0, 0, 1);
  std::vector<Index> meeting;
  VisiblePart part, direct;
  const ShaftClass cls = occ.classify(c.P, c.nP, tau, nQ, among, meeting, &part);
  occ.visible_part(c.P, c.nP, tau, nQ, among, direct);
  for (const Index t : meeting) EXPECT_TRUE(std::find(among.begin(), among.end(), t) != among.end());
  EXPECT_TRUE(std::is_sorted(meeting.begin(), meeting.end()));
  if (cls == ShaftClass::full) {
    EXPECT_TRUE(part.points.empty());
    EXPECT_NEAR(direct.area, area(tau), 1e-12 * area(tau));
    return area(tau);
  }
  if (cls == ShaftClass::hidden) {
    EXPECT_EQ(direct.area, 0);
    return 0;
  }
  EXPECT_EQ(part.area, direct.area);
  EXPECT_EQ(part.points, direct.points);
  EXPECT_GT(part.area, 0);
  if (depth > 0) {
    double sum = 0;
    for (const Tri& child : midpoint_children(tau)) sum += class_area(occ, c, child, meeting, depth - 1, checked);
    // Each child declared hidden may drop a visible area up to kShadowMargin * area(child) (the
    // rounding policy), 4 children at most kShadowMargin * area(tau); the rest is rounding.
    EXPECT_NEAR(sum, part.area, 2e-12 * area(tau));
    ++checked;
  }
  return part.area;
}

TEST(Occluders, ClassesAgreeWithVisiblePartsAndWithTheChildrensClasses) {
  std::mt19937_64 rng(4242);
  int checked = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const RandomConfig c = random_config(rng);
    std::vector<Tri> tris = {c.tau};
    tris.insert(tris.end(), c.blockers.begin(), c.blockers.end());
    const Occluders occ(mesh_of(tris));
    std::vector<Index> among;
    occ.candidates(c.P, c.nP, c.tau, Vec3(0, 0, 1), among);
    class_area(occ, c, c.tau, among, 3, checked);
  }
  EXPECT_GT(checked, 200) << "partial parents refined";
}

TEST(Occluders, TreeCandidatesOfALargeSceneContainEveryMeetingFace) {
  // 800 random small triangles between a ceiling point and the floor: more than a linear scan's
  // worth, so the candidates come from the AABB tree.
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> u01(0, 1);
  std::vector<Tri> tris;
  const Tri tau = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  tris.push_back(tau);
  for (int i = 0; i < 800; ++i) {
    const Vec3 centre(3 * u01(rng) - 1, 3 * u01(rng) - 1, 0.1 + 0.8 * u01(rng));
    Tri t;
    for (Vec3& v : t) v = centre + 0.1 * Vec3(2 * u01(rng) - 1, 2 * u01(rng) - 1, 2 * u01(rng) - 1);
    tris.push_back(t);
  }
  const Occluders occ(mesh_of(tris));
  const Vec3 down(0, 0, -1), up(0, 0, 1);
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3 P(2 * u01(rng) - 0.5, 2 * u01(rng) - 0.5, 1);
    std::vector<Index> among, meeting_all, meeting;
    occ.candidates(P, down, tau, up, among);
    EXPECT_TRUE(std::is_sorted(among.begin(), among.end()));
    EXPECT_LT(among.size(), tris.size() / 2) << "the candidates should prune";
    const ShaftClass cls_all = occ.classify(P, down, tau, up, all_indices(occ), meeting_all);
    const ShaftClass cls = occ.classify(P, down, tau, up, among, meeting);
    EXPECT_EQ(cls, cls_all);
    EXPECT_EQ(meeting, meeting_all);
    for (const Index t : meeting_all) EXPECT_TRUE(std::binary_search(among.begin(), among.end(), t));
    // Each candidate's box meets the shaft's box, and it has a corner strictly below P (in front of
    // P's plane) and one strictly above the floor (in front of tau's plane).
    const Eigen::AlignedBox3d shaft_box = Eigen::AlignedBox3d(P).extend(tau[0]).extend(tau[1]).extend(tau[2]);
    for (const Index t : among) {
      const Tri& f = tris[static_cast<std::size_t>(t)];
      Eigen::AlignedBox3d box(f[0]);
      box.extend(f[1]).extend(f[2]);
      EXPECT_TRUE(box.intersects(shaft_box)) << "face " << t;
      EXPECT_LT(box.min().z(), P.z());
      EXPECT_GT(box.max().z(), 0);
    }
  }
}

TEST(Occluders, ConcurrentQueriesGiveTheSerialResults) {
  // The queries are const with per-thread scratch: run them from OpenMP threads, one index per
  // chunk so that the threads interleave, and compare with a serial run bit for bit.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u01(0, 1);
  std::vector<Tri> tris = horizontal_rectangle(0, 1, 0, 1, 0);
  for (int i = 0; i < 700; ++i) {
    const Vec3 centre(1.4 * u01(rng) - 0.2, 1.4 * u01(rng) - 0.2, 0.1 + 0.8 * u01(rng));
    Tri t;
    for (Vec3& v : t) v = centre + 0.08 * Vec3(2 * u01(rng) - 1, 2 * u01(rng) - 1, 2 * u01(rng) - 1);
    tris.push_back(t);
  }
  const Occluders occ(mesh_of(tris));
  struct Query {
    Vec3 P;
    Tri tau;
  };
  std::vector<Query> queries;
  for (int q = 0; q < 400; ++q) {
    const Tri& face = tris[static_cast<std::size_t>(q % 2)];
    const double s = 0.8 * u01(rng), t = 0.8 * u01(rng) * (1 - s);
    const Vec3 corner = face[0] + s * (face[1] - face[0]) + t * (face[2] - face[0]);
    const Vec3 e1 = 0.2 * (face[1] - face[0]), e2 = 0.2 * (face[2] - face[0]);
    queries.push_back({Vec3(u01(rng), u01(rng), 1), Tri{corner, corner + e1, corner + e2}});
  }
  struct Result {
    ShaftClass cls = ShaftClass::hidden;
    std::vector<Index> meeting;
    VisiblePart part;
    bool ray = false;
  };
  const Vec3 down(0, 0, -1), up(0, 0, 1);
  const auto run = [&](const Query& q, Result& r) {
    std::vector<Index> among;
    occ.candidates(q.P, down, q.tau, up, among);
    r.cls = occ.classify(q.P, down, q.tau, up, among, r.meeting, &r.part);
    r.ray = occ.visible(q.P, (q.tau[0] + q.tau[1] + q.tau[2]) / 3);
  };
  std::vector<Result> serial(queries.size()), parallel(queries.size());
  for (std::size_t k = 0; k < queries.size(); ++k) run(queries[k], serial[k]);
  panelrad::parallel_for(queries.size(), [&](std::size_t k) { run(queries[k], parallel[k]); }, 1);
  int partial = 0;
  for (std::size_t k = 0; k < queries.size(); ++k) {
    EXPECT_EQ(parallel[k].cls, serial[k].cls) << k;
    EXPECT_EQ(parallel[k].meeting, serial[k].meeting) << k;
    EXPECT_EQ(parallel[k].part.points, serial[k].part.points) << k;
    EXPECT_EQ(parallel[k].part.area, serial[k].part.area) << k;
    EXPECT_EQ(parallel[k].ray, serial[k].ray) << k;
    partial += serial[k].cls == ShaftClass::partial ? 1 : 0;
  }
  EXPECT_GT(partial, 50);
}

// ---- 5. Sub-triangles classified in 2-D against the shadows on their root's plane ----

struct WithinStats {
  int compared = 0, partial = 0, hidden = 0, full = 0, straddling = 0;
};

/// Walks the midpoint subdivision of the root of `plane` down `depth` levels as the fast operator
/// does (partial sub-triangles refined, the shadows meeting them their children's candidates) and
/// compares classify_within with classify on the same faces, and the visible area with the exact
/// oracle when `oracle_shadows` is given.
void walk_within(const Occluders& occ, const RandomConfig& c, const ShadowPlane& plane, const Tri& sub,
                 std::span<const Index> among, int depth, const std::vector<std::vector<Vec3>>* oracle_shadows,
                 double root_area, double root_size, WithinStats& stats) {
  const Vec3 nQ(0, 0, 1);
  std::vector<Index> meeting;
  VisiblePart part;
  const ShaftClass cls = occ.classify_within(plane, sub, among, meeting, &part);
  // Without the visible part (the subtraction may stop early), the same class and meeting shadows.
  std::vector<Index> meeting_class_only;
  EXPECT_EQ(occ.classify_within(plane, sub, among, meeting_class_only), cls);
  EXPECT_EQ(meeting_class_only, meeting);
  std::vector<Index> faces, ref_meeting;
  for (const Index k : among) faces.push_back(plane.faces[static_cast<std::size_t>(k)]);
  VisiblePart ref;
  const ShaftClass ref_cls = occ.classify(c.P, c.nP, sub, nQ, faces, ref_meeting, &ref);
  ++stats.compared;
  // Random scenes put no decision within the margins: the classes agree.
  ASSERT_EQ(cls, ref_cls) << "sub-triangle at depth " << depth;
  const double a = area(sub);
  double visible = 0;
  if (cls == ShaftClass::full) {
    ++stats.full;
    EXPECT_TRUE(part.points.empty());
    visible = a;
  } else if (cls == ShaftClass::hidden) {
    ++stats.hidden;
    EXPECT_TRUE(meeting.empty());
  } else {
    ++stats.partial;
    // The same polygon differences computed in T's frame instead of sub's: rounding of the
    // corners at 1e-16 of the scene's size, far below the area margin 1e-12 area(sub) of the
    // rounding policy, which bounds what a decision within the margins may move.
    EXPECT_NEAR(part.area, ref.area, 1e-12 * a);
    expect_well_formed(part, sub, nQ, root_size);
    visible = part.area;
  }
  if (cls != ShaftClass::hidden) {
    std::vector<Index> meeting_faces;
    for (const Index k : meeting) meeting_faces.push_back(plane.faces[static_cast<std::size_t>(k)]);
    EXPECT_EQ(meeting_faces, ref_meeting) << "the shadows that meet sub are those of the faces that meet its shaft";
  }
  if (oracle_shadows) {
    // As in the oracle test above: 1e-12 of the root's area bounds the oracle's rounding.
    EXPECT_NEAR(visible, oracle_visible_area(sub, *oracle_shadows), 1e-12 * root_area);
  }
  if (cls != ShaftClass::partial || depth == 0) return;
  for (const Tri& child : midpoint_children(sub))
    walk_within(occ, c, plane, child, meeting, depth - 1, oracle_shadows, root_area, root_size, stats);
}

TEST(Occluders, SubTrianglesClassifiedInTheRootsPlaneAgreeWithTheirShafts) {
  std::mt19937_64 rng(31337);
  std::uniform_real_distribution<double> u01(0, 1);
  const Vec3 nQ(0, 0, 1);
  WithinStats stats;
  for (int trial = 0; trial < 80; ++trial) {
    RandomConfig c = random_config(rng);
    // Every other scene tilts P's plane so that it cuts the floor through tau (straddling roots
    // and sub-triangles); the oracle's floor shadows then no longer apply.
    const bool tilted = trial % 2 == 1;
    if (tilted) {
      // P's plane through P and an interior point X of tau, containing the horizontal direction
      // normal to X - P; its front side chosen at random.
      const double w0 = 0.2 + 0.6 * u01(rng), w1 = 0.2 + 0.6 * u01(rng), w2 = 0.2 + 0.6 * u01(rng);
      const Vec3 X = (w0 * c.tau[0] + w1 * c.tau[1] + w2 * c.tau[2]) / (w0 + w1 + w2);
      const Vec3 e = X - c.P;
      c.nP = e.cross(Vec3(-e.y(), e.x(), 0)).normalized() * (u01(rng) < 0.5 ? 1 : -1);
    }
    std::vector<Tri> tris = {c.tau};
    tris.insert(tris.end(), c.blockers.begin(), c.blockers.end());
    const Occluders occ(mesh_of(tris));
    std::vector<std::vector<Vec3>> shadows;
    for (const Tri& b : c.blockers) shadows.push_back(projected_to_floor(c.P, b));

    std::vector<Index> among, meeting;
    occ.candidates(c.P, c.nP, c.tau, nQ, among);
    ShadowPlane plane;
    VisiblePart part, ref;
    const ShaftClass cls = occ.classify(c.P, c.nP, c.tau, nQ, among, plane, &part);
    // The root's class, shadows and visible part are classify's, bit for bit.
    ASSERT_EQ(cls, occ.classify(c.P, c.nP, c.tau, nQ, among, meeting, &ref));
    EXPECT_EQ(plane.faces, meeting);
    EXPECT_EQ(part.points, ref.points);
    EXPECT_EQ(part.area, ref.area);
    if (cls != ShaftClass::partial) continue;
    std::vector<Index> all(plane.shadows.size());
    std::iota(all.begin(), all.end(), 0);
    const double tP_lo = std::min({(c.tau[0] - c.P).dot(c.nP), (c.tau[1] - c.P).dot(c.nP), (c.tau[2] - c.P).dot(c.nP)});
    stats.straddling += tP_lo < 0 ? 1 : 0;
    for (Tri child : midpoint_children(c.tau)) {
      if (trial % 4 == 2) std::swap(child[1], child[2]);  // either orientation of a sub-triangle
      const double root_size =
          std::max({(c.tau[1] - c.tau[0]).norm(), (c.tau[2] - c.tau[1]).norm(), (c.tau[0] - c.tau[2]).norm()});
      walk_within(occ, c, plane, child, all, 3, tilted ? nullptr : &shadows, area(c.tau), root_size, stats);
    }
  }
  EXPECT_GT(stats.partial, 400);
  EXPECT_GT(stats.hidden, 100);
  EXPECT_GT(stats.full, 100);
  EXPECT_GT(stats.straddling, 10) << "P's plane should cut some roots";
}

TEST(Occluders, SubTrianglesOfAHiddenOrFullRootAndBadShadowIndices) {
  // A floor triangle under a square blocker: P above the blocker's middle.
  const Tri tau = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  std::vector<Tri> tris = {tau};
  for (const Tri& t : horizontal_rectangle(0.2, 0.4, 0.2, 0.4, 0.5)) tris.push_back(t);
  const Occluders occ(mesh_of(tris));
  const Vec3 P(0.3, 0.3, 1), down(0, 0, -1), up(0, 0, 1);
  ShadowPlane plane;
  std::vector<Index> among, meeting;
  occ.candidates(P, down, tau, up, among);
  ASSERT_EQ(occ.classify(P, down, tau, up, among, plane), ShaftClass::partial);
  ASSERT_EQ(plane.shadows.size(), 2u);
  const std::vector<Index> both = {0, 1};
  // The blocker's shadow is the square [0.1, 0.5]^2 (magnification 2 about (0.3, 0.3)).
  const Tri inside = {Vec3(0.15, 0.15, 0), Vec3(0.45, 0.15, 0), Vec3(0.15, 0.45, 0)};
  const Tri outside = {Vec3(0.6, 0.05, 0), Vec3(0.9, 0.05, 0), Vec3(0.6, 0.3, 0)};
  const Tri across = {Vec3(0.3, 0.3, 0), Vec3(0.7, 0.3, 0), Vec3(0.3, 0.6, 0)};
  EXPECT_EQ(occ.classify_within(plane, inside, both, meeting), ShaftClass::hidden);
  EXPECT_TRUE(meeting.empty());
  EXPECT_EQ(occ.classify_within(plane, outside, both, meeting), ShaftClass::full);
  EXPECT_TRUE(meeting.empty());
  VisiblePart part;
  EXPECT_EQ(occ.classify_within(plane, across, both, meeting, &part), ShaftClass::partial);
  // across = right triangle with legs 0.4 and 0.3 at (0.3, 0.3); the shadow covers its part in
  // [0.3, 0.5]^2, which lies below the hypotenuse x/0.4 + y/0.3 = 1 (shifted) except the corner
  // region beyond it: by the exact oracle.
  EXPECT_NEAR(part.area, oracle_visible_area(across, {projected_to_floor(P, tris[1]), projected_to_floor(P, tris[2])}),
              1e-14);
  expect_well_formed(part, across, up);
  const std::vector<Index> bad = {2};
  EXPECT_THROW(occ.classify_within(plane, across, bad, meeting), std::invalid_argument);
  // Seen from below the floor, the root is hidden by the plane tests, and so is every sub-triangle.
  ShadowPlane below;
  EXPECT_EQ(occ.classify(Vec3(0.3, 0.3, -1), up, tau, up, among, below), ShaftClass::hidden);
  EXPECT_FALSE(below.seen);
  EXPECT_EQ(occ.classify_within(below, inside, {}, meeting), ShaftClass::hidden);
}

TEST(Occluders, ConcurrentSubTriangleClassificationsGiveTheSerialResults) {
  std::mt19937_64 rng(8);
  std::vector<RandomConfig> configs;
  for (int i = 0; i < 64; ++i) configs.push_back(random_config(rng));
  const Vec3 nQ(0, 0, 1);
  const auto run = [&](const RandomConfig& c, std::vector<double>& out) {
    std::vector<Tri> tris = {c.tau};
    tris.insert(tris.end(), c.blockers.begin(), c.blockers.end());
    const Occluders occ(mesh_of(tris));
    std::vector<Index> among, meeting;
    occ.candidates(c.P, c.nP, c.tau, nQ, among);
    ShadowPlane plane;
    occ.classify(c.P, c.nP, c.tau, nQ, among, plane);
    std::vector<Index> all(plane.shadows.size());
    std::iota(all.begin(), all.end(), 0);
    std::vector<Tri> level = {c.tau};
    for (int d = 0; d < 3; ++d) {
      std::vector<Tri> next;
      for (const Tri& t : level)
        for (const Tri& child : midpoint_children(t)) next.push_back(child);
      level = next;
    }
    VisiblePart part;
    for (const Tri& t : level) {
      const ShaftClass cls = occ.classify_within(plane, t, all, meeting, &part);
      out.push_back(static_cast<double>(cls));
      out.push_back(part.area);
      out.push_back(static_cast<double>(meeting.size()));
    }
  };
  std::vector<std::vector<double>> serial(configs.size()), parallel(configs.size());
  for (std::size_t k = 0; k < configs.size(); ++k) run(configs[k], serial[k]);
  panelrad::parallel_for(configs.size(), [&](std::size_t k) { run(configs[k], parallel[k]); }, 1);
  for (std::size_t k = 0; k < configs.size(); ++k) EXPECT_EQ(parallel[k], serial[k]) << k;
}

// ---- 6. The ray test ----

TEST(Occluders, RayIsBlockedOnlyByACrossingOfAFacesInterior) {
  const Occluders occ(mesh_of({Tri{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)},
                               Tri{Vec3(5, 5, 5), Vec3(6, 5, 5), Vec3(5, 6, 5)}}));
  EXPECT_FALSE(occ.visible(Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, -1)));       // through the interior
  EXPECT_FALSE(occ.visible(Vec3(0.5, 1e-6, 1), Vec3(0.5, 1e-6, -1)));     // just inside an edge
  EXPECT_FALSE(occ.visible(Vec3(0.2, 0.2, -1), Vec3(0.3, 0.1, 1)));       // either direction, oblique
  EXPECT_TRUE(occ.visible(Vec3(2, 2, 1), Vec3(2, 2, -1)));                // beside the face
  EXPECT_TRUE(occ.visible(Vec3(0.5, -1e-6, 1), Vec3(0.5, -1e-6, -1)));    // just outside an edge
  EXPECT_TRUE(occ.visible(Vec3(0.5, 0, 1), Vec3(0.5, 0, -1)));            // grazing an edge
  EXPECT_TRUE(occ.visible(Vec3(0, 0, 1), Vec3(0, 0, -1)));                // through a corner
  EXPECT_TRUE(occ.visible(Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, 0)));         // ending on the face
  EXPECT_TRUE(occ.visible(Vec3(0.2, 0.2, 0), Vec3(0.7, 0.3, 2)));         // starting on the face
  EXPECT_TRUE(occ.visible(Vec3(-1, 0.2, 0), Vec3(2, 0.2, 0)));            // in the face's plane
  EXPECT_TRUE(occ.visible(Vec3(0.2, 0.2, 1), Vec3(0.2, 0.2, 0.5)));       // stopping short of it
  EXPECT_FALSE(occ.visible(Vec3(5.2, 5.2, 6), Vec3(5.2, 5.2, -1)));       // the other face blocks it
}

TEST(Occluders, RefusesTrianglesWithoutAPlane) {
  TriangleMesh m = mesh_of({Tri{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)}});
  EXPECT_THROW(Occluders{m}, MeshError);
  m = mesh_of({Tri{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, std::nan(""), 0)}});
  EXPECT_THROW(Occluders{m}, MeshError);
}

}  // namespace

// Two faces of a box meeting along an edge that points almost exactly at P (seen end-on) cast
// shadows whose far corner projects a rounding's length (2.5e-11) from the near one, nearly in line
// with the next corner: the projected polygon may turn the wrong way there by rounding. Its
// convex hull is the shadow; otherwise the half-planes of its edges leave out a sliver wedge of
// tau (here 4e-7 wide at its base) that the faces hide. Coordinates from a rotated room with a box
// in a corner, written with 6 decimals: every visible piece must be seen from P through its
// interior (the ray test, an independent algorithm), and no piece is a sliver between the two
// shadows.
TEST(Occluders, AnEdgeSeenEndOnHidesAllItsFacesCover) {
  const Vec3 A(-0.13682996053524843, 1.0213188944129947, 0.76958090490811659),
      B(0.13426578456298155, 0.81337184965790854, 0.88475492853750914),
      C(0.055998272459508128, 1.0724378010244449, 0.75529859106401054),
      D(0.15857920995599728, 0.59603219933947604, 0.43511917282930362),
      E(0.42350793731654079, 0.89005024539153266, 0.86333142982046884);
  const Tri tau{A, B, C};
  const Occluders occ(mesh_of({tau, Tri{C, B, D}, Tri{E, D, B}}));
  const Vec3 P(0.78303100183371666, 0.18326865027495298, 0.85373738275524014);
  const Vec3 nP(-0.26089040718959883, 0.86355388993949378, -0.43152158069650925);
  const Vec3 nQ = -(B - A).cross(C - A).normalized();
  std::vector<Index> among;
  occ.candidates(P, nP, tau, nQ, among);
  VisiblePart part;
  occ.visible_part(P, nP, tau, nQ, among, part);
  ASSERT_EQ(part.piece_end.size(), 1u) << "one wedge between the shadow's edge and tau's edge AB is seen";
  Vec3 centre = Vec3::Zero();
  for (const Vec3& p : part.points) centre += p;
  centre /= static_cast<double>(part.points.size());
  EXPECT_TRUE(occ.visible(P, centre));
  EXPECT_GT(part.area, 0);
  EXPECT_LT(part.area, 1e-5 * area(tau)) << "a wedge about 3e-7 wide at A";
}

// Cluster to cluster: a triangle sigma on the ceiling and tau on the floor with blockers between
// (random_config's). Full must mean that every point of sigma sees all of tau: no sampled segment
// between them is blocked (the ray test, an independent algorithm) and the point shafts of sampled
// points of sigma are full. Hidden must mean hidden from each point. Both full and undecided occur.
TEST(Occluders, ClusterPairsFullOnlyWhenEverySegmentIsClear) {
  std::mt19937_64 rng(20261207);
  std::uniform_real_distribution<double> u01(0, 1);
  const Vec3 nS(0, 0, -1), nT(0, 0, 1);
  const auto point_in = [&](const Tri& t) {
    double a = u01(rng), b = u01(rng);
    if (a + b > 1) {
      a = 1 - a;
      b = 1 - b;
    }
    return Vec3(t[0] + a * (t[1] - t[0]) + b * (t[2] - t[0]));
  };
  int full = 0, undecided = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const RandomConfig c = random_config(rng);
    const double size = 0.02 + 0.4 * u01(rng);
    Tri sigma;
    for (Vec3& v : sigma) v = c.P + size * Vec3(2 * u01(rng) - 1, 2 * u01(rng) - 1, 0);
    if ((sigma[1] - sigma[0]).cross(sigma[2] - sigma[0]).z() > 0) std::swap(sigma[1], sigma[2]);  // faces down
    std::vector<Tri> tris = {c.tau, sigma};
    tris.insert(tris.end(), c.blockers.begin(), c.blockers.end());
    const Occluders occ(mesh_of(tris));
    const ShaftClass cls = occ.classify_clusters(sigma, nS, c.tau, nT);
    ASSERT_NE(cls, ShaftClass::hidden) << "trial " << trial << ": they face each other";
    if (cls == ShaftClass::partial) {
      ++undecided;
      continue;
    }
    ++full;
    for (int k = 0; k < 400; ++k) {
      const Vec3 P = point_in(sigma), Q = point_in(c.tau);
      ASSERT_TRUE(occ.visible(P, Q)) << "trial " << trial << ", segment " << k;
    }
    for (int k = 0; k < 5; ++k) {
      const Vec3 P = point_in(sigma);
      std::vector<Index> among, meeting;
      occ.candidates(P, nS, c.tau, nT, among);
      EXPECT_EQ(occ.classify(P, nS, c.tau, nT, among, meeting), ShaftClass::full) << "trial " << trial;
    }
  }
  EXPECT_GT(full, 30);
  EXPECT_GT(undecided, 30);
  // Hidden by the planes: tau behind sigma's plane, or sigma behind tau's.
  const Tri floor{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  const Tri above{Vec3(0, 0, 1), Vec3(0, 1, 1), Vec3(1, 0, 1)};
  const Occluders occ(mesh_of({floor, above}));
  EXPECT_EQ(occ.classify_clusters(above, Vec3(0, 0, 1), floor, nT), ShaftClass::hidden);  // sigma faces away
  EXPECT_EQ(occ.classify_clusters(above, nS, floor, Vec3(0, 0, -1)), ShaftClass::hidden);  // tau faces away
  EXPECT_EQ(occ.classify_clusters(above, nS, floor, nT), ShaftClass::full);
  // tau crossing sigma's plane: undecided (cut for the points, not for the pair).
  const Tri upright{Vec3(0.2, 0.5, 0.5), Vec3(0.8, 0.5, 0.5), Vec3(0.5, 0.5, 1.5)};
  EXPECT_EQ(occ.classify_clusters(above, nS, upright, Vec3(0, -1, 0)), ShaftClass::partial);
}

// The closed-form point-to-rectangle configuration factors of tests/common/
// configuration_factors.hpp (with and without the blocker of the shadow scene) against the
// contour-integral form factor (1/pi) Int G dS of paper (2) and against numerical quadrature; and
// the scene builders of tests/common/occluded_scenes.hpp for which these truths are stated.
#include "configuration_factors.hpp"
#include "occluded_scenes.hpp"

#include <panelrad/quadrature/exact_integrals.hpp>

#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

using panelrad::geometry::Index;
using panelrad::geometry::TriangleMesh;
using panelrad::geometry::Vec3;
using namespace panelrad::testing;

namespace {

constexpr double kPi = 3.14159265358979323846;

/// The point-to-rectangle kernel (1/pi) cos cos / r^2 = c^2 / (pi (x^2 + y^2 + c^2)^2) for the
/// in-plane offset (x, y) from the element's foot, height c.
double parallel_kernel(double x, double y, double c) {
  const double d = x * x + y * y + c * c;
  return c * c / (kPi * d * d);
}

/// (1/pi) Int_r c^2 / (x^2 + y^2 + c^2)^2 by nested adaptive Gauss-Kronrod (Boost.Math), relative
/// tolerance 1e-14 per level.
double adaptive_rectangle_factor(double px, double py, const AxisRectangle& r, double c) {
  using boost::math::quadrature::gauss_kronrod;
  auto inner = [&](double x) {
    return gauss_kronrod<double, 31>::integrate(
        [&](double y) { return parallel_kernel(x - px, y - py, c); }, r.y0, r.y1, 15, 1e-14);
  };
  return gauss_kronrod<double, 31>::integrate(inner, r.x0, r.x1, 15, 1e-14);
}

/// The contour-integral form factor of the rectangle r at height c, as the two triangles of its
/// diagonal, seen from (px, py, 0) with normal +z; the rectangle's front normal faces P (-z).
double contour_rectangle_factor(double px, double py, const AxisRectangle& r, double c) {
  const Vec3 P(px, py, 0), nP(0, 0, 1), nQ(0, 0, -1);
  const Vec3 a(r.x0, r.y0, c), b(r.x1, r.y0, c), cc(r.x1, r.y1, c), d(r.x0, r.y1, c);
  return panelrad::quadrature::form_factor(P, nP, a, b, cc, nQ) +
         panelrad::quadrature::form_factor(P, nP, a, cc, d, nQ);
}

/// The form factor of every triangle of `facet` in `mesh`, its front normal (b - a) x (c - a)
/// (the builders' triangles run counter-clockwise seen from their front side).
double contour_facet_factor(const TriangleMesh& mesh, Index facet, const Vec3& P, const Vec3& nP) {
  double sum = 0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (mesh.facet_of_triangle[t] != facet) continue;
    const Vec3& a = mesh.vertices[mesh.triangles[t][0]];
    const Vec3& b = mesh.vertices[mesh.triangles[t][1]];
    const Vec3& c = mesh.vertices[mesh.triangles[t][2]];
    sum += panelrad::quadrature::form_factor(P, nP, a, b, c, (b - a).cross(c - a).normalized());
  }
  return sum;
}

/// Floor points of the shadow scene: a 9 x 9 grid over [-0.95, 0.95]^2 (through the centre, where
/// the shadow covers the emitter exactly) plus a few off-grid points.
std::vector<std::pair<double, double>> floor_points() {
  std::vector<std::pair<double, double>> pts;
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j) pts.emplace_back(0.2375 * (i - 4), 0.2375 * (j - 4));
  pts.emplace_back(0.013, -0.41);
  pts.emplace_back(0.5, 0.5);  // a shadow corner on the emitter's corner
  pts.emplace_back(-0.999, 0.731);
  return pts;
}

}  // namespace

// The classical value for a unit square at unit height above its corner: A = B = 1, F = (1/2pi)
// 2 atan(1/sqrt 2)/sqrt 2 = 0.13853 (tabulated as 0.1385 in the catalogues: 4 digits, tolerance
// half a unit of the last). Against an independent Gauss-Legendre tensor rule (Boost.Math, 30
// points per direction; the integrand is analytic on a neighbourhood of [0,1]^2, its nearest
// singularity at distance ~1 in the complex plane, so the rule is exact to rounding: 1e-14).
TEST(ConfigurationFactors, UnitSquareAboveItsCorner) {
  const double F = parallel_corner_factor(1, 1, 1);
  EXPECT_NEAR(F, 0.1385, 5e-5);
  EXPECT_NEAR(F, std::atan(1 / std::sqrt(2.0)) / (kPi * std::sqrt(2.0)), 1e-16);
  using boost::math::quadrature::gauss;
  const double quad = gauss<double, 30>::integrate(
      [](double x) {
        return gauss<double, 30>::integrate([x](double y) { return parallel_kernel(x, y, 1); }, 0, 1);
      },
      0, 1);
  EXPECT_NEAR(F, quad, 1e-14);
}

// Signed superposition of corners for rectangles around, beside and far from the foot, at several
// heights, against nested adaptive Gauss-Kronrod (relative tolerance 1e-14 per level; the factors
// are O(0.01 .. 1), the corner formula is accurate to a few ulps of its O(0.25) terms): 1e-12.
TEST(ConfigurationFactors, RectangleFactorAgainstAdaptiveQuadrature) {
  const AxisRectangle rects[] = {{-0.5, 0.5, -0.5, 0.5}, {0.2, 1.1, -0.3, 0.4},
                                 {-2.0, -1.5, 0.5, 3.0}, {-0.1, 0.0, -0.7, 0.9}};
  const double heights[] = {0.3, 1.0, 2.5};
  const std::pair<double, double> feet[] = {{0, 0}, {0.25, -0.1}, {-1.3, 0.8}, {0.5, 0.5}};
  int n = 0;
  for (const auto& r : rects) {
    for (const double c : heights)
      for (const auto& [px, py] : feet) {
        const double closed = parallel_rectangle_factor(px, py, r, c);
        const double quad = adaptive_rectangle_factor(px, py, r, c);
        EXPECT_GT(closed, 0);
        EXPECT_NEAR(closed, quad, 1e-12) << "rect " << n << " c " << c << " P " << px << " " << py;
      }
    ++n;
  }
  // An empty rectangle has no factor; an infinite plane above has factor 1 (the whole hemisphere).
  EXPECT_EQ(parallel_rectangle_factor(0, 0, {0.5, 0.5, -1, 1}, 1), 0.0);
  EXPECT_NEAR(parallel_rectangle_factor(0.3, -0.2, {-1e9, 1e9, -1e9, 1e9}, 1), 1.0, 1e-8);
}

// The closed form against the project's contour-integral form factor (paper (2), two triangles per
// rectangle) at many points: two independent closed forms, each a sum of a few O(1) terms accurate
// to an ulp or two (measured: <= 4.5e-16 apart): 1e-14 absolute on factors of O(0.001 .. 1).
TEST(ConfigurationFactors, RectangleFactorAgainstContourFormFactor) {
  const AxisRectangle rects[] = {{-0.5, 0.5, -0.5, 0.5}, {0.2, 1.1, -0.3, 0.4},
                                 {-0.25, 0.25, -0.25, 0.25}, {-3.0, -0.2, 0.1, 0.6}};
  const double heights[] = {0.05, 0.5, 1.0, 4.0};
  int checked = 0;
  for (const auto& r : rects)
    for (const double c : heights)
      for (const auto& [px, py] : floor_points()) {
        const double closed = parallel_rectangle_factor(px, py, r, c);
        const double contour = contour_rectangle_factor(px, py, r, c);
        ASSERT_NEAR(closed, contour, 1e-14) << "P " << px << " " << py << " c " << c;
        ++checked;
      }
  EXPECT_EQ(checked, 4 * 4 * 84);
}

// F_vis(P) = F(emitter) - F(emitter n shadow) against an independent integration of V(P, Q) G:
// the emitter is cut along the shadow's edges into at most 3 x 3 cells, and on each cell a 20 x 20
// Gauss-Legendre rule (Boost.Math) integrates the kernel times the visibility found by intersecting
// the segment PQ with the blocker's square at every node. Were the shadow wrong, a cell would hold
// a jump of V and the rule would be off by O(1e-3); with the right shadow each cell's integrand is
// analytic and the rule exact to ~1e-15 (c = 1 >= the cells' size): 1e-13.
TEST(ConfigurationFactors, ShadowSceneAgainstRayVisibilityQuadrature) {
  using boost::math::quadrature::gauss;
  const AxisRectangle emitter = shadow_scene_emitter();
  for (const auto& [px, py] : floor_points()) {
    const AxisRectangle s = shadow_scene_shadow(px, py);
    auto cuts = [](double lo, double hi, double a, double b) {
      std::vector<double> v = {lo, hi};
      for (const double t : {a, b})
        if (t > lo && t < hi) v.push_back(t);
      std::sort(v.begin(), v.end());
      return v;
    };
    const std::vector<double> xs = cuts(emitter.x0, emitter.x1, s.x0, s.x1);
    const std::vector<double> ys = cuts(emitter.y0, emitter.y1, s.y0, s.y1);
    const Vec3 P(px, py, 0);
    auto visible = [&](double qx, double qy) {
      // The segment P -> Q = (qx, qy, 1) meets z = 0.5 at its midpoint.
      const Vec3 M = P + (kShadowBlockerHeight / kShadowEmitterHeight) * (Vec3(qx, qy, 1) - P);
      return !(std::abs(M.x()) < kShadowBlockerHalfWidth && std::abs(M.y()) < kShadowBlockerHalfWidth);
    };
    double quad = 0;
    for (std::size_t i = 0; i + 1 < xs.size(); ++i)
      for (std::size_t j = 0; j + 1 < ys.size(); ++j)
        quad += gauss<double, 20>::integrate(
            [&](double x) {
              return gauss<double, 20>::integrate(
                  [&](double y) { return visible(x, y) ? parallel_kernel(x - px, y - py, 1) : 0.0; },
                  ys[j], ys[j + 1]);
            },
            xs[i], xs[i + 1]);
    EXPECT_NEAR(shadow_scene_visible_factor(px, py), quad, 1e-13) << "P " << px << " " << py;
  }
}

// F_vis against the contour form factor on the meshes of shadow_scene(): the emitter's facet
// (facet 0, its triangles' front normal -z) minus the hidden rectangle; 1e-14 as above.
// At the centre the shadow is the emitter (F_vis = 0); elsewhere the emitter is partly visible;
// the truth has the scene's symmetries.
TEST(ConfigurationFactors, ShadowSceneAgainstContourFormFactor) {
  const TriangleMesh scene = shadow_scene();
  const Vec3 nP(0, 0, 1);
  for (const auto& [px, py] : floor_points()) {
    const Vec3 P(px, py, 0);
    const double emitter = contour_facet_factor(scene, 0, P, nP);
    EXPECT_NEAR(emitter, parallel_rectangle_factor(px, py, shadow_scene_emitter(), 1), 1e-14);
    const AxisRectangle hidden = intersection(shadow_scene_emitter(), shadow_scene_shadow(px, py));
    const double contour =
        emitter - (hidden.empty() ? 0.0 : contour_rectangle_factor(px, py, hidden, 1));
    const double truth = shadow_scene_visible_factor(px, py);
    EXPECT_NEAR(truth, contour, 1e-14) << "P " << px << " " << py;
    EXPECT_LE(truth, emitter);
    EXPECT_NEAR(truth, shadow_scene_visible_factor(-px, py), 1e-15);
    EXPECT_NEAR(truth, shadow_scene_visible_factor(py, px), 1e-15);
    if (px != 0 || py != 0) {
      EXPECT_GT(truth, 0) << "P " << px << " " << py;
    }
  }
  EXPECT_EQ(shadow_scene_visible_factor(0, 0), 0.0);
  // The blocker's own factor seen from the centre: a square of half-width 0.25 at height 0.5,
  // the same solid angle as the emitter (half-width 0.5 at height 1): all of it is hidden.
  const Vec3 O(0, 0, 0);
  EXPECT_NEAR(contour_facet_factor(scene, 1, O, nP), contour_facet_factor(scene, 0, O, nP), 1e-14);
}

// ------------------------------------------------------------------------------------------------
// The scene builders: counts, facets, orientation (each polygon counter-clockwise seen from its
// front side) and closedness, checked by exact edge bookkeeping and by the divergence theorem:
// Int_S x . n dS / 3 = sum over triangles of a . (b x c) / 6 is the enclosed volume for an outward
// closed surface and its negative seen from inside.

namespace {

double signed_volume(const TriangleMesh& m) {
  double v = 0;
  for (const auto& t : m.triangles)
    v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6;
  return v;
}

/// Directed edge counts: a consistently oriented closed surface has every directed edge once and
/// its reverse once. Returns the number of edges without a reversed partner (boundary edges).
int unmatched_edges(const TriangleMesh& m, bool* consistent) {
  std::map<std::pair<Index, Index>, int> directed;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  int unmatched = 0;
  *consistent = true;
  for (const auto& [e, n] : directed) {
    if (n != 1) *consistent = false;
    const auto r = directed.find({e.second, e.first});
    if (r == directed.end()) ++unmatched;
  }
  return unmatched;
}

Vec3 facet_normal_sum(const TriangleMesh& m, Index facet) {
  Vec3 n = Vec3::Zero();
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    if (m.facet_of_triangle[t] == facet) {
      const auto& tri = m.triangles[t];
      n += (m.vertices[tri[1]] - m.vertices[tri[0]]).cross(m.vertices[tri[2]] - m.vertices[tri[0]]) / 2;
    }
  return n;  // area times the front normal
}

void expect_well_formed(const TriangleMesh& m, std::size_t triangles, Index facets) {
  EXPECT_EQ(m.triangles.size(), triangles) << m.source;
  EXPECT_EQ(m.facet_of_triangle.size(), triangles) << m.source;
  EXPECT_EQ(m.num_facets, facets) << m.source;
  for (const Index f : m.facet_of_triangle) EXPECT_TRUE(f >= 0 && f < m.num_facets) << m.source;
  for (const auto& t : m.triangles) {
    for (const Index v : t) EXPECT_TRUE(v >= 0 && static_cast<std::size_t>(v) < m.vertices.size());
    const Vec3 n = (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]);
    EXPECT_GT(n.norm(), 0) << m.source << ": zero-area triangle";
  }
}

}  // namespace

// Volumes and areas are sums of O(1) products of the coordinates: exact for the integer box, to a
// few ulps for the decimal ones: 1e-14.
TEST(OccludedScenes, BoxesAndRoomsAreClosedAndOriented) {
  bool consistent = false;
  const TriangleMesh box = axis_box(Vec3(0, 0, 0), Vec3(1, 2, 3));
  expect_well_formed(box, 12, 6);
  EXPECT_EQ(box.vertices.size(), 8u);
  EXPECT_EQ(unmatched_edges(box, &consistent), 0);
  EXPECT_TRUE(consistent);
  EXPECT_NEAR(signed_volume(box), 6.0, 1e-14);
  EXPECT_NEAR(signed_volume(axis_box(Vec3(0, 0, 0), Vec3(1, 2, 3), BoxFront::inside)), -6.0, 1e-14);
  EXPECT_NEAR(signed_volume(reversed(box)), -6.0, 1e-14);
  // Facet order x = lo, x = hi, y = lo, ...: the front normals of an outward box.
  const Vec3 outward[6] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
  for (Index f = 0; f < 6; ++f)
    EXPECT_GT(facet_normal_sum(box, f).normalized().dot(outward[f]), 1 - 1e-14) << f;

  const TriangleMesh rb = room_with_box();
  expect_well_formed(rb, 24, 12);
  EXPECT_EQ(unmatched_edges(rb, &consistent), 0);
  EXPECT_TRUE(consistent);
  EXPECT_NEAR(signed_volume(rb), -1.0 + 0.3 * 0.35 * 0.35, 1e-14);

  const TriangleMesh L = l_shaped_room();
  expect_well_formed(L, 20, 8);
  EXPECT_EQ(L.vertices.size(), 12u);
  EXPECT_EQ(unmatched_edges(L, &consistent), 0);  // no T-junction: every edge has its partner
  EXPECT_TRUE(consistent);
  EXPECT_NEAR(signed_volume(L), -3.0, 1e-14);
  EXPECT_NEAR(facet_normal_sum(L, 0).z(), 3.0, 1e-14);   // floor: area 3, facing up
  EXPECT_NEAR(facet_normal_sum(L, 1).z(), -3.0, 1e-14);  // ceiling: facing down

  const TriangleMesh fb = room_with_floating_boxes();
  expect_well_formed(fb, 48, 24);
  EXPECT_EQ(unmatched_edges(fb, &consistent), 0);
  EXPECT_TRUE(consistent);
  EXPECT_NEAR(signed_volume(fb), -1.0 + 0.2 * 0.2 * 0.3 + 0.3 * 0.2 * 0.3 + 0.3 * 0.3 * 0.3, 1e-14);
}

TEST(OccludedScenes, OpenScenesFaceTheirDocumentedSides) {
  bool consistent = false;
  const TriangleMesh s = shadow_scene();
  expect_well_formed(s, 6, 3);
  EXPECT_NEAR(facet_normal_sum(s, 0).z(), -1.0, 1e-14);   // emitter: area 1, facing down
  EXPECT_NEAR(facet_normal_sum(s, 1).z(), -0.25, 1e-14);  // blocker: area 0.25, facing down
  EXPECT_NEAR(facet_normal_sum(s, 2).z(), 4.0, 1e-14);    // floor: area 4, facing up

  const TriangleMesh b = block_on_floor();
  expect_well_formed(b, 12, 6);
  // The floor's 4 edges and the block's 4 bottom edges are boundary edges; the block's faces are
  // consistently oriented (its 8 other edges matched), the floor is not cut (no shared vertex).
  EXPECT_EQ(unmatched_edges(b, &consistent), 8);
  EXPECT_TRUE(consistent);
  EXPECT_EQ(b.vertices.size(), 12u);
  EXPECT_NEAR(facet_normal_sum(b, 0).z(), 4.0, 1e-14);
  const Vec3 outward[5] = {{0, 0, 1}, {-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}};
  for (Index f = 1; f <= 5; ++f)
    EXPECT_GT(facet_normal_sum(b, f).normalized().dot(outward[f - 1]), 1 - 1e-14) << f;

  const TriangleMesh q = quad(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0));
  expect_well_formed(q, 2, 1);
  const TriangleMesh two = append(q, shadow_scene());
  expect_well_formed(two, 8, 4);
  EXPECT_EQ(two.vertices.size(), q.vertices.size() + s.vertices.size());  // nothing shared
  EXPECT_EQ(two.facet_of_triangle.back(), 3);
  EXPECT_EQ(two.triangles.back()[0], s.triangles.back()[0] + 4);
}

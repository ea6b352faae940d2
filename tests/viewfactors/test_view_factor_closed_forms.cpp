// View factors of open scenes against closed forms with rigorous tolerances:
//  - coaxial parallel discs (Howell's catalog C-41), approximated by regular N-gons: the exchange
//    area A_1 F_12 = (1/pi) Int_1 Int_2 cos cos / r^2 grows with either surface (its integrand is
//    positive between facing parallel planes), and an N-gon inscribed in the circle of radius r
//    contains the disc of radius r cos(pi/N), so the polygons' value lies between the discs' at
//    r cos(pi/N) and at r;
//  - the sky view factor of the ground beside a long wall: in two dimensions 1 - F_wall =
//    (1 + cos beta) / 2 with beta = atan(H / x) the wall's elevation seen from the ground point at
//    distance x; a wall of length 2L misses at most x H^2 / (3 pi (L - |y|)^3) of it (the
//    integrand x z / (x^2 + y^2 + z^2)^2 <= x z / y^4 beyond |y| = L), and the element's sky is the
//    point value at its centroid (collocation), so the finite wall is held to that bound plus the
//    fast operator's product error;
//  - the blocked pair of the shadow scene, per floor element, by superposition of rectangle
//    factors;
//  - per element, the factors to chosen groups and the sky sum to 1 - (the factor to the other
//    groups), and their area-weighted means are the group factors.
#include "configuration_factors.hpp"
#include "occluded_scenes.hpp"

#include <panelrad/io/view_factor_output.hpp>
#include <panelrad/viewfactors/view_factors.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace panelrad {
namespace {

using geometry::Index;
using geometry::Vec3;

/// F_12 from a disc of radius r1 to a coaxial parallel disc of radius r2 at distance h (C-41).
double coaxial_discs(double r1, double r2, double h) {
  const double R1 = r1 / h, R2 = r2 / h, X = 1 + (1 + R2 * R2) / (R1 * R1);
  return 0.5 * (X - std::sqrt(X * X - 4 * (R2 / R1) * (R2 / R1)));
}

/// A regular N-gon of circumradius r in the plane z, centred on the axis, fanned from its centre,
/// facing +z (up) or -z.
void add_disc(geometry::TriangleMesh& mesh, double r, double z, int N, bool up) {
  std::vector<Vec3> corners;
  for (int k = 0; k < N; ++k) {
    const double t = 2 * std::numbers::pi * k / N;
    corners.emplace_back(r * std::cos(t), r * std::sin(t), z);
  }
  if (!up) std::reverse(corners.begin(), corners.end());
  testing::add_polygon(mesh, corners);
}

TEST(ViewFactorClosedForms, CoaxialDiscsLieBetweenTheInscribedAndCircumscribedDiscs) {
  const int N = 16;
  const double r1 = 0.5, r2 = 1.0, h = 0.75;
  geometry::TriangleMesh mesh;
  mesh.source = "coaxial discs";
  add_disc(mesh, r1, 0, N, true);
  add_disc(mesh, r2, h, N, false);
  const Scene scene(std::move(mesh));
  ASSERT_FALSE(scene.enclosed());
  ViewFactorOptions o;
  o.solve.level = 3;
  const ViewFactors v = compute_view_factors(scene, groups_by_facet(scene), o);
  const double shrink = std::cos(std::numbers::pi / N);
  const auto exchange = [&](double a, double b) { return std::numbers::pi * a * a * coaxial_discs(a, b, h); };
  const double low = exchange(r1 * shrink, r2 * shrink), high = exchange(r1, r2);
  ASSERT_GT(high - low, 0.02 * high);  // the bracket is about 5 % wide, the estimate 2 % of that
  // Both directions, through reciprocity: A_1 F_12 and A_2 F_21, each with its error estimate.
  const double a12 = v.area[0] * v.F(0, 1), a21 = v.area[1] * v.F(1, 0);
  const double e12 = v.area[0] * v.error(0, 1), e21 = v.area[1] * v.error(1, 0);
  EXPECT_LT(e12, 0.5 * (high - low));
  for (const auto& [value, estimate] : {std::pair{a12, e12}, std::pair{a21, e21}}) {
    EXPECT_GT(value, low - estimate);
    EXPECT_LT(value, high + estimate);
  }
  EXPECT_DOUBLE_EQ(v.F(0, 0), 0.0);  // a plane does not see itself
  EXPECT_NEAR(v.uncovered[0], 1 - v.F(0, 1), 1e-15);
}

TEST(ViewFactorClosedForms, GroundBesideALongWallSeesTheTwoDimensionalSky) {
  // The wall x = 0, |y| <= L, 0 <= z <= H facing +x, and the ground 0 <= x <= 2H beside it facing
  // up, both cut into H x H squares along y so that the elements stay near-equilateral.
  const double H = 1.0, L = 10.0;
  geometry::TriangleMesh mesh;
  mesh.source = "long wall";
  for (double y = -L; y < L; y += H) {
    testing::add_polygon(mesh, {Vec3(0, y, 0), Vec3(0, y + H, 0), Vec3(0, y + H, H), Vec3(0, y, H)});  // +x
    for (double x = 0; x < 2 * H; x += H)
      testing::add_polygon(mesh, {Vec3(x, y, 0), Vec3(x + H, y, 0), Vec3(x + H, y + H, 0), Vec3(x, y + H, 0)});  // up
  }
  const Scene scene(std::move(mesh));
  ASSERT_FALSE(scene.enclosed());
  ViewFactorOptions o;
  o.solve.level = 2;
  o.estimate_error = false;
  o.elements = true;
  SurfaceGroups g;
  g.names = {"wall", "ground"};
  for (Index f = 0; f < scene.num_facets(); ++f) g.of_facet.push_back(f % 3 == 0 ? 0 : 1);
  const ViewFactors v = compute_view_factors(scene, g, o);
  const ElementSky& e = v.elements;
  const double product_error = std::max(v.self_check_error, 0.0) + 1e-12;
  int checked = 0;
  double worst = 0;
  for (Index i = 0; i < e.sky.size(); ++i) {
    const Vec3& P = e.centroid[static_cast<std::size_t>(i)];
    if (e.group[static_cast<std::size_t>(i)] != 1 || std::abs(P.y()) > L / 2) continue;
    const double x = P.x(), beta = std::atan(H / x);
    const double two_d = 0.5 * (1 + std::cos(beta));
    const double missing = x * H * H / (3 * std::numbers::pi * std::pow(L - std::abs(P.y()), 3));
    // The finite wall covers less of the hemisphere than the infinite one: the sky is larger, by
    // at most `missing`.
    EXPECT_GT(e.sky[i], two_d - product_error) << "x " << x << " y " << P.y();
    EXPECT_LT(e.sky[i], two_d + missing + product_error) << "x " << x << " y " << P.y();
    worst = std::max(worst, std::abs(e.sky[i] - two_d));
    ++checked;
  }
  EXPECT_GT(checked, 100);
  EXPECT_GT(worst, 0);  // the sky varies with x, and it is the computed one
}

// The blocked pair of the shadow scene (occluded_scenes.hpp): the floor sees the emitter past the
// blocker. Each floor element's factor to the emitter is its centroid's point value, which
// superposition gives in closed form: the emitter's rectangle factor minus that of its part in the
// blocker's shadow (configuration_factors.hpp). The dense operator (exact integrals over the
// visible parts) to rounding; the fast one within 10 times its self-check (measured on other
// vectors than this indicator); the floor's group factor is their area-weighted mean.
void expect_blocked_pair(int level, OperatorMethod method) {
  const Scene scene(testing::shadow_scene());
  ViewFactorOptions o;
  o.solve.level = level;
  o.solve.op.method = method;
  if (method == OperatorMethod::fast) {
    o.solve.op.eta = 0.5;
    o.solve.op.degree = 6;
  }
  o.estimate_error = false;
  const SurfaceGroups g = groups_by_facet(scene);  // emitter, blocker, floor
  o.element_targets = {"facet 0"};
  const ViewFactors v = compute_view_factors(scene, g, o);
  ASSERT_EQ(v.self_check_error >= 0, method == OperatorMethod::fast);
  const ElementSky& e = v.elements;
  const double tolerance = 10 * std::max(v.self_check_error, 0.0) + 1e-12;
  double weighted = 0, worst = 0;
  int shadowed = 0;
  for (Index i = 0; i < e.sky.size(); ++i) {
    if (e.group[static_cast<std::size_t>(i)] != 2) continue;
    const Vec3& P = e.centroid[static_cast<std::size_t>(i)];
    const double exact = testing::shadow_scene_visible_factor(P.x(), P.y());
    worst = std::max(worst, std::abs(e.to(i, 0) - exact));
    weighted += e.area[i] * exact;
    if (!testing::intersection(testing::shadow_scene_emitter(), testing::shadow_scene_shadow(P.x(), P.y())).empty())
      ++shadowed;
  }
  EXPECT_LT(worst, tolerance);
  EXPECT_GT(shadowed, 100);  // most of the floor has part of the emitter hidden
  EXPECT_NEAR(v.F(2, 0), weighted / v.area[2], tolerance);
}

TEST(ViewFactorClosedForms, ShadowScenesBlockedPairBySuperpositionDense) { expect_blocked_pair(3, OperatorMethod::dense); }

TEST(ViewFactorClosedForms, ShadowScenesBlockedPairBySuperpositionFast) { expect_blocked_pair(4, OperatorMethod::fast); }

// The factors to chosen groups per element: with every group chosen they and the sky sum to 1 at
// every element; each one's area-weighted mean over group I is F_IJ; the VTK carries them.
TEST(ViewFactorClosedForms, ElementFactorsToChosenGroupsAddUp) {
  const Scene scene(testing::block_on_floor());
  ViewFactorOptions o;
  o.solve.level = 2;
  o.estimate_error = false;
  o.block_columns = 4;  // targets in two different blocks
  const SurfaceGroups g = groups_by_facet(scene);
  o.element_targets = g.names;
  const ViewFactors v = compute_view_factors(scene, g, o);
  const ElementSky& e = v.elements;
  ASSERT_EQ(e.to.cols(), 6);
  ASSERT_EQ(e.to.rows(), e.sky.size());
  Eigen::MatrixXd mean = Eigen::MatrixXd::Zero(6, 6);
  for (Index i = 0; i < e.sky.size(); ++i) {
    EXPECT_NEAR(e.to.row(i).sum() + e.sky[i], 1.0, 1e-13) << "element " << i;
    mean.row(e.group[static_cast<std::size_t>(i)]) += e.area[i] * e.to.row(i);
  }
  for (Index I = 0; I < 6; ++I) mean.row(I) /= v.area[I];
  EXPECT_LT((mean - v.F).cwiseAbs().maxCoeff(), 1e-14);
  const std::string vtk = element_sky_vtk(v);
  EXPECT_NE(vtk.find("SCALARS F_facet_5 double 1"), std::string::npos);
  EXPECT_NE(vtk.find("SCALARS sky double 1"), std::string::npos);
  EXPECT_NE(vtk.find("POLYGONS " + std::to_string(e.sky.size())), std::string::npos);
  const std::string csv = element_sky_csv(v);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "element,facet,group,x,y,z,area,sky,F_facet 0,F_facet 1,F_facet 2,F_facet 3,F_facet 4,F_facet 5");
  // Only the chosen ones, in the order given.
  o.element_targets = {"facet 3", "facet 0"};
  const ViewFactors w = compute_view_factors(scene, g, o);
  ASSERT_EQ(w.elements.to.cols(), 2);
  EXPECT_EQ(w.elements.to.col(0), e.to.col(3));
  EXPECT_EQ(w.elements.to.col(1), e.to.col(0));
  o.element_targets = {"roof"};
  EXPECT_THROW((void)compute_view_factors(scene, g, o), std::invalid_argument);
}

}  // namespace
}  // namespace panelrad

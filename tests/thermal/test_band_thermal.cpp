// The band (non-gray) thermal solve (thermal/thermal_solve.hpp: Bands) against exact answers:
//  - a plate alone under a sky: it sees only the sky, q = sum_k eps_k sigma (F_k(T) T^4 -
//    F_k(T_env) T_env^4), F_k the blackbody's band fractions (blackbody.hpp);
//  - a convex body with band emissivities in a black room: on the body's elements, exactly
//    q_i = sum_k eps_k (F_k(T1) sigma T1^4 - F_k(T2) sigma T2^4 (H 1)_i);
//  - bands of equal emissivity are the gray model, adiabatic walls included: the same J, H, q, T
//    (the split among the bands then cancels out);
//  - a closed room with one surface at T and the rest adiabatic, each with other band
//    emissivities: every temperature T (equilibrium), whatever the split's first guess;
//  - the fast operator against the dense one; refusals naming the group.
#include "occluded_scenes.hpp"

#include <panelrad/thermal/blackbody.hpp>
#include <panelrad/thermal/thermal_solve.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace panelrad {
namespace {

using geometry::Index;
using geometry::Vec3;
using Given = SurfaceCondition::Given;

const std::vector<double> kEdges = {3.0, 8.0};  // um: [0, 3], [3, 8], [8, inf)

SurfaceCondition at(double T, std::vector<double> eps) { return {Given::temperature, T, 1.0, std::move(eps)}; }
SurfaceCondition flux(double q, std::vector<double> eps) { return {Given::heat_flux, q, 1.0, std::move(eps)}; }

ThermalOptions options(int level, OperatorMethod method = OperatorMethod::dense) {
  ThermalOptions o;
  o.solve.level = level;
  o.solve.op.method = method;
  o.tolerance = 1e-12;
  o.band_edges_um = kEdges;
  return o;
}

/// sum_k eps_k F_k(T) sigma T^4.
double emits(const std::vector<double>& eps, double T) { return band_emission(kEdges, eps, T); }

TEST(BandThermal, APlateUnderTheSkyExchangesBandByBand) {
  const Scene scene(testing::quad(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(2, 1, 0), Vec3(0, 1, 0)));
  ThermalOptions o = options(2);
  o.environment_temperature = 250;
  const std::vector<double> eps = {0.9, 0.2, 0.6};
  const ThermalSolution s = solve_thermal(scene, groups_by_facet(scene), {at(900, eps)}, o);
  ASSERT_TRUE(s.iteration.converged());
  const double exact = emits(eps, 900) - emits(eps, 250);
  for (Index i = 0; i < s.n; ++i) EXPECT_NEAR(s.q[i], exact, 1e-12 * exact);
  EXPECT_EQ(s.band_rounds, 0);  // no flux given: nothing to settle
  // Not the gray answer at any one of the emissivities.
  for (double e : eps) EXPECT_GT(std::abs(exact - e * kStefanBoltzmann * (std::pow(900, 4) - std::pow(250, 4))), 0.01 * exact);
}

TEST(BandThermal, ABodyWithBandEmissivitiesInABlackRoom) {
  const Scene scene(testing::room_with_box());  // room facets 0-5, box 6-11
  SurfaceGroups g;
  g.names = {"room", "box"};
  for (Index f = 0; f < 12; ++f) g.of_facet.push_back(f < 6 ? 0 : 1);
  const double T1 = 800, T2 = 300;
  const std::vector<double> eps1 = {0.1, 0.7, 0.95};
  const ThermalOptions o = options(2);
  SurfaceCondition black = at(T2, {});  // gray in the band model: emissivity 1 in every band
  const ThermalSolution s = solve_thermal(scene, g, {black, at(T1, eps1)}, o);
  ASSERT_TRUE(s.iteration.converged());
  Scene plain = scene;
  plain.set_reflectivity(0.0);
  const RadiositySolver solver(plain, o.solve);
  const Eigen::VectorXd seen = solver.irradiance(Eigen::VectorXd::Ones(s.n));
  const double scale = emits(eps1, T1);
  for (Index i = 0; i < s.n; ++i) {
    if (s.group[static_cast<std::size_t>(i)] != 1) continue;
    EXPECT_NEAR(s.q[i], emits(eps1, T1) - emits(eps1, T2) * seen[i], 1e-9 * scale);
  }
}

/// The room with a box, floor at 600 K and ceiling at 300 K, the rest adiabatic: gray, and as a
/// band model with each surface's emissivity in every band.
TEST(BandThermal, EqualBandEmissivitiesAreTheGrayModel) {
  const Scene scene(testing::room_with_box());
  const SurfaceGroups g = groups_by_facet(scene);
  std::vector<SurfaceCondition> gray(12), bands(12);
  for (Index I = 0; I < 12; ++I) {
    const double e = 0.3 + 0.05 * I;
    gray[I] = {Given::heat_flux, 0.0, e, {}};
    bands[I] = flux(0, {e, e, e});
  }
  gray[4] = {Given::temperature, 600, 0.8, {}};
  gray[5] = {Given::temperature, 300, 1.0, {}};
  bands[4] = at(600, {0.8, 0.8, 0.8});
  bands[5] = at(300, {1.0, 1.0, 1.0});
  ThermalOptions o = options(2);
  o.band_edges_um.clear();
  const ThermalSolution a = solve_thermal(scene, g, gray, o);
  const ThermalSolution b = solve_thermal(scene, g, bands, options(2));
  ASSERT_TRUE(a.iteration.converged());
  ASSERT_TRUE(b.iteration.converged());
  EXPECT_GE(b.band_rounds, 1);
  const double scale = kStefanBoltzmann * std::pow(600, 4);
  EXPECT_LT((a.J - b.J).cwiseAbs().maxCoeff(), 1e-9 * scale);
  EXPECT_LT((a.q - b.q).cwiseAbs().maxCoeff(), 1e-9 * scale);
  EXPECT_LT((a.T - b.T).cwiseAbs().maxCoeff(), 1e-9 * 600);
  EXPECT_LT((a.group_Q - b.group_Q).cwiseAbs().maxCoeff(), 1e-9 * scale);
}

// One surface at 400 K, every other adiabatic with its own band emissivities, the first guess of
// the split made at 400 K: equilibrium, every temperature 400 K to the closure defect of the
// discretization (as in the gray test), and the split settled.
TEST(BandThermal, ClosedRoomWithOneSurfaceAtTAndTheRestAdiabaticIsInEquilibrium) {
  const Scene scene(testing::room_with_box());
  const SurfaceGroups g = groups_by_facet(scene);
  std::vector<SurfaceCondition> c;
  for (Index I = 0; I < 12; ++I) c.push_back(flux(0, {0.1 + 0.07 * I, 0.9 - 0.06 * I, 0.5}));
  c[0] = at(400, {0.9, 0.3, 0.05});
  const ThermalSolution s = solve_thermal(scene, g, c, options(2));
  ASSERT_TRUE(s.iteration.converged());
  EXPECT_LT(s.band_change, 1e-10);
  const double scale = kStefanBoltzmann * std::pow(400, 4);
  for (Index i = 0; i < s.n; ++i) {
    EXPECT_NEAR(s.T[i], 400, 1e-3 * 400) << "element " << i;
    EXPECT_LT(std::abs(s.q[i]), 4e-3 * scale) << "element " << i;
  }
  for (Index I = 1; I < 12; ++I) EXPECT_LT(std::abs(s.group_Q[I]), 1e-9 * scale) << s.names[I];
}

// A hot floor heating adiabatic walls whose emissivity differs by band: their temperatures depend
// on the split, which the rounds settle; the fast operator's answer is the dense one's to within
// its measured product error.
TEST(BandThermal, FastAgreesWithDense) {
  const Scene scene(testing::room_with_box());
  const SurfaceGroups g = groups_by_facet(scene);
  std::vector<SurfaceCondition> c(12, flux(0, {0.9, 0.2, 0.5}));
  c[4] = at(1000, {0.8, 0.8, 0.8});
  c[5] = at(300, {1, 1, 1});
  const ThermalSolution dense = solve_thermal(scene, g, c, options(3));
  const ThermalSolution fast = solve_thermal(scene, g, c, options(3, OperatorMethod::fast));
  ASSERT_GE(fast.self_check_error, 0);
  EXPECT_GE(dense.band_rounds, 2);
  EXPECT_LT(dense.band_change, 1e-10);
  const double scale = dense.group_Q.cwiseAbs().maxCoeff();
  EXPECT_LT((fast.group_Q - dense.group_Q).cwiseAbs().maxCoeff(), 100 * fast.self_check_error * scale);
  EXPECT_LT((fast.T - dense.T).cwiseAbs().maxCoeff(), 100 * fast.self_check_error * 1000);
  // The walls' temperatures are not those of the gray model at any one band's emissivity.
  std::vector<SurfaceCondition> gray = c;
  for (Index I = 0; I < 12; ++I) gray[I].band_emissivity.clear();
  ThermalOptions o = options(3);
  o.band_edges_um.clear();
  const ThermalSolution g1 = solve_thermal(scene, g, gray, o);
  EXPECT_GT((g1.T - dense.T).cwiseAbs().maxCoeff(), 1.0);
  std::printf("n = %d: %d rounds (last change %.2g), %d block products in all against %d products of the gray "
              "solve; fast: %d rounds; walls' T off the gray model's by up to %.1f K\n",
              static_cast<int>(dense.n), dense.band_rounds, dense.band_change, dense.band_products,
              g1.iteration.iterations, fast.band_rounds, (g1.T - dense.T).cwiseAbs().maxCoeff());
}

TEST(BandThermal, ProblemsAreRefusedNamingTheGroup) {
  const Scene room(testing::axis_box(Vec3::Zero(), Vec3(1, 1, 1), testing::BoxFront::inside, "room"));
  const SurfaceGroups g = groups_by_facet(room);
  std::vector<SurfaceCondition> c(6, flux(0, {0.5, 0.5, 0.5}));
  c[0] = at(300, {1, 1, 1});
  ThermalOptions o = options(1);
  EXPECT_EQ(thermal_problem(room, g, c, o), "");
  c[2] = flux(0, {0.5, 0.5});
  EXPECT_NE(thermal_problem(room, g, c, o).find("group 'facet 2': 2 band emissivities for 3 bands"), std::string::npos);
  c[2] = flux(0, {0.5, 1.5, 0.5});
  EXPECT_NE(thermal_problem(room, g, c, o).find("the emissivity of band 2, 1.5, is not in [0, 1]"), std::string::npos);
  c[2] = flux(0, {0, 0, 0});
  EXPECT_NE(thermal_problem(room, g, c, o).find("every band emissivity is 0"), std::string::npos);
  c[2] = flux(0, {0, 0.5, 0});  // zero in some bands: allowed
  EXPECT_EQ(thermal_problem(room, g, c, o), "");
  o.band_edges_um = {8.0, 3.0};
  EXPECT_NE(thermal_problem(room, g, c, o).find("band edges must be finite, > 0 and increasing"), std::string::npos);
  o.band_edges_um.clear();
  EXPECT_NE(thermal_problem(room, g, c, o).find("an emissivity per band, but no band edges"), std::string::npos);
}

}  // namespace
}  // namespace panelrad

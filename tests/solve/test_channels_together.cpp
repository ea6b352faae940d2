// Several channels solved together (RadiositySolver::solve_channels): each channel's answer is the
// one solve(channel) gives, bit for bit (the Neumann iteration (34) of every channel takes the
// same products, now one pass over H for all of them), with H u for the irradiance; and on an
// occluded scene the automatic setting is chosen on probes of the self-check's rows, the operator
// being built once with a setting whose check is its own.
#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/radiosity_solver.hpp>

#include "occluded_scenes.hpp"
#include "test_scenes.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace panelrad {
namespace {

// Three colour channels of different rho and E per facet on a room with a box (V computed).
Scene three_channel_room() {
  Scene scene = testing::general_scene(testing::room_with_box(), {"R", "G", "B"});
  for (std::size_t c = 0; c < 3; ++c) {
    std::vector<double> rho, E;
    for (Index f = 0; f < scene.num_facets(); ++f) {
      rho.push_back(0.15 + 0.1 * static_cast<double>((f + 2 * c) % 7));
      E.push_back(f == 5 ? 1.0 + static_cast<double>(c) : (f == 8 && c == 1 ? 0.5 : 0.0));
    }
    scene.set_reflectivity(rho, c);
    scene.set_emissivity(E, c);
  }
  return scene;
}

void expect_same(const ChannelSolve& together, const ChannelSolve& alone, const Eigen::VectorXd& irradiance) {
  EXPECT_EQ(together.status, alone.status);
  EXPECT_EQ(together.solver, alone.solver);
  EXPECT_EQ(together.iterations, alone.iterations);
  EXPECT_EQ(together.residual, alone.residual);
  EXPECT_EQ(together.error_estimate, alone.error_estimate);
  EXPECT_EQ(together.convergence_ratio, alone.convergence_ratio);
  ASSERT_EQ(together.u.size(), alone.u.size());
  EXPECT_TRUE((together.u.array() == alone.u.array()).all());
  ASSERT_EQ(together.irradiance.size(), irradiance.size());
  EXPECT_TRUE((together.irradiance.array() == irradiance.array()).all());
}

void expect_together_is_alone(const RadiositySolver& solver, const std::vector<std::size_t>& channels) {
  const std::vector<ChannelSolve> together = solver.solve_channels(channels);
  ASSERT_EQ(together.size(), channels.size());
  for (std::size_t s = 0; s < channels.size(); ++s) {
    const ChannelSolve alone = solver.solve(channels[s]);
    expect_same(together[s], alone, solver.irradiance(alone.u));
  }
}

TEST(ChannelsTogether, NeumannChannelsBitForBit) {
  const Scene scene = three_channel_room();
  SolveOptions o;
  o.level = 2;
  o.op.method = OperatorMethod::fast;
  o.op.eta = 0.4;
  o.op.degree = 4;
  o.solver.kind = SolverKind::neumann;
  const RadiositySolver solver(scene, o);
  expect_together_is_alone(solver, {0, 1, 2});
  expect_together_is_alone(solver, {2, 0});  // any order, any subset
  expect_together_is_alone(solver, {1});
  EXPECT_TRUE(solver.solve_channels({}).empty());
}

// Automatic: several channels are stepped together by Neumann, and a channel goes on with GMRES
// when its measured ratio says that costs less; one channel alone is GMRES (fewer products). Both
// answers are within their error bounds of each other.
void expect_automatic_within_bounds(const RadiositySolver& solver, const std::vector<std::size_t>& channels,
                                    const std::string& path) {
  const std::vector<ChannelSolve> together = solver.solve_channels(channels);
  ASSERT_EQ(together.size(), channels.size());
  for (std::size_t s = 0; s < channels.size(); ++s) {
    const ChannelSolve alone = solver.solve(channels[s]);
    EXPECT_EQ(together[s].status, SolveStatus::converged);
    EXPECT_EQ(alone.status, SolveStatus::converged);
    EXPECT_NE(alone.solver.find("auto: GMRES, expected"), std::string::npos) << alone.solver;
    EXPECT_NE(together[s].solver.find(path), std::string::npos) << together[s].solver;
    const double diff = (together[s].u - alone.u).lpNorm<Eigen::Infinity>();
    EXPECT_LE(diff, together[s].error_estimate + alone.error_estimate) << together[s].solver;
    // The irradiance is H u of the final u.
    EXPECT_TRUE((together[s].irradiance.array() == solver.irradiance(together[s].u).array()).all());
  }
}

TEST(ChannelsTogether, AutomaticAndGmresChannels) {
  const Scene scene = three_channel_room();
  SolveOptions o;
  o.level = 1;
  o.op.method = OperatorMethod::dense;
  const RadiositySolver automatic(scene, o);  // the room's measured ratio ~0.4: Neumann together
  expect_automatic_within_bounds(automatic, {0, 1, 2}, "channels together (block products); measured ratio");
  o.solver.kind = SolverKind::gmres;  // solved one by one
  const RadiositySolver gmres(scene, o);
  expect_together_is_alone(gmres, {0, 1, 2});
}

// A closed cube of rho 0.97 in three channels: Neumann's measured ratio is near rho, and GMRES
// continues each channel after the first steps, from Neumann's iterate, with fewer products in
// all than the channels' Neumann iterations take.
TEST(ChannelsTogether, AutomaticHandsSlowChannelsToGmres) {
  Scene scene(testing::validated_builtin("cube"), {"R", "G", "B"});
  for (std::size_t c = 0; c < 3; ++c) {
    scene.set_reflectivity(0.97 - 0.01 * static_cast<double>(c), c);
    std::vector<double> E(static_cast<std::size_t>(scene.num_facets()), 0.0);
    E[c] = 1.0;
    scene.set_emissivity(E, c);
  }
  SolveOptions o;
  o.level = 1;
  o.op.method = OperatorMethod::dense;
  const RadiositySolver automatic(scene, o);
  expect_automatic_within_bounds(automatic, {0, 1, 2}, "auto: Neumann for 3 steps, then GMRES");
  o.solver.kind = SolverKind::neumann;
  const RadiositySolver neumann(scene, o);
  const std::vector<ChannelSolve> a = automatic.solve_channels({0, 1, 2}), b = neumann.solve_channels({0, 1, 2});
  for (std::size_t c = 0; c < 3; ++c) EXPECT_LT(a[c].iterations, b[c].iterations) << a[c].solver;
}

TEST(ChannelsTogether, NotConvergedKeepsItsMessage) {
  const Scene scene = three_channel_room();
  SolveOptions o;
  o.level = 1;
  o.op.method = OperatorMethod::dense;
  o.solver.kind = SolverKind::neumann;
  o.solver.max_iterations = 3;
  const RadiositySolver solver(scene, o);
  const std::vector<ChannelSolve> together = solver.solve_channels({0, 1, 2});
  for (std::size_t c = 0; c < 3; ++c) {
    EXPECT_EQ(together[c].status, SolveStatus::not_converged);
    EXPECT_EQ(together[c].message, solver.solve(c).message);
  }
}

TEST(ChannelsTogether, FoldedReflectivityHasNoH) {
  const Scene cube = testing::reflecting_builtin("cube");
  SolveOptions o;
  o.level = 1;
  o.fold_reflectivity = true;
  const RadiositySolver solver(cube, o);
  EXPECT_THROW(solver.solve_channels({0}), std::logic_error);
}

// A loose manual setting with tightening on an occluded scene: probes choose a stricter setting
// whose check passes, and among the stricter settings none that passes costs less product work
// (far pairs x terms + near pairs on the probed rows); the built operator's own check is the
// probe's, bit for bit.
TEST(ChannelsTogether, OccludedSettingChosenOnProbes) {
  const Scene scene = three_channel_room();
  SolveOptions o;
  o.level = 3;
  o.op.method = OperatorMethod::fast;
  o.op.eta = 0.5;
  o.op.degree = 3;
  o.tighten_on_failed_check = true;
  const RadiositySolver solver(scene, o);
  const RadiositySolverInfo& info = solver.info();
  ASSERT_TRUE(info.self_check.has_value());
  EXPECT_EQ(info.tightened, 1);
  EXPECT_LE(info.self_check->relative_error, info.self_check_threshold);
  OperatorOptions first = o.op;
  first.method = OperatorMethod::fast;
  const std::vector<OperatorOptions> candidates = stricter_settings(first);
  ASSERT_NE(std::find(candidates.begin(), candidates.end(), solver.parameters()), candidates.end());
  const auto& fast = dynamic_cast<const FastOperator&>(solver.op());
  const FastSelfCheck own = fast.self_check(RadiositySolver::kSelfCheckSamples);
  EXPECT_EQ(own.relative_error, info.self_check->relative_error);
  const auto work = [&](const OperatorOptions& s) {
    FastOptions f;
    static_cast<ClusteringParameters&>(f) = s;
    f.occluders = fast.options().occluders;
    f.single_precision_coefficients = fast.options().single_precision_coefficients;
    f.probe_samples = RadiositySolver::kSelfCheckSamples;
    const Collocation rows = solver.collocation().with_row_weights(Eigen::VectorXd::Ones(solver.n()));
    const FastOperator probe(rows, f);
    return std::make_pair(probe.self_check(RadiositySolver::kSelfCheckSamples).relative_error,
                          static_cast<double>(probe.statistics().far_pairs) * num_taylor_terms(s.degree) +
                              static_cast<double>(probe.statistics().near_pairs));
  };
  const double chosen_work = work(solver.parameters()).second;
  for (const OperatorOptions& s : candidates) {
    const auto [check, w] = work(s);
    if (check <= info.self_check_threshold) {
      EXPECT_GE(w, chosen_work) << describe_parameters(s);
    }
  }
}

// When no probed setting passes, the one with the smallest check is built and a warning says that
// the stricter settings were probed (M <= 2 here, far from the accuracy asked at n = 1536).
TEST(ChannelsTogether, NoProbedSettingPassesSaysSo) {
  const Scene scene = three_channel_room();
  SolveOptions o;
  o.level = 3;
  o.op.method = OperatorMethod::fast;
  o.op.eta = 0.5;
  o.op.degree = 0;
  o.tighten_on_failed_check = true;
  const RadiositySolver solver(scene, o);
  const RadiositySolverInfo& info = solver.info();
  ASSERT_TRUE(info.self_check.has_value());
  EXPECT_GT(info.self_check->relative_error, info.self_check_threshold);
  ASSERT_EQ(info.warnings.size(), 1u);
  EXPECT_NE(info.warnings[0].find("none of the stricter settings probed passes"), std::string::npos) << info.warnings[0];
  EXPECT_LE(solver.parameters().degree, 2);
}

}  // namespace
}  // namespace panelrad

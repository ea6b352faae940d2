// The environment's radiosity (Scene::set_environment): u - K u = E + rho u_env s with
// s = 1 - H 1 the part of each hemisphere no front side covers. Checked against exact answers:
//  - equilibrium: E = (1 - rho) u_env everywhere gives u = u_env exactly, since
//    u_env - rho u_env H 1 - rho u_env (1 - H 1) = (1 - rho) u_env; this holds for the discrete
//    operator too (s is computed from the same H), so it checks the right-hand side, the
//    irradiance and the energy balance to the iteration's tolerance on an occluded open scene;
//  - a sheet alone sees only the sky: u = rho u_env, H u + u_env s = u_env;
//  - an enclosed scene never sees its environment: the same bits as without one;
//  - linearity: the solution with E and u_env is the sum of the two solutions.
#include <panelrad/geometry/validation.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/scene_solver.hpp>

#include <gtest/gtest.h>

#include "occluded_scenes.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace panelrad {
namespace {

using geometry::Vec3;

SolveOptions options(const std::string& method, int level) {
  SolveOptions o;
  o.level = level;
  o.op.method = parse_operator_method(method);
  if (o.op.method == OperatorMethod::fast) {
    o.op.eta = 0.5;
    o.op.degree = 4;
  }
  o.solver.tolerance = 1e-12;
  return o;
}

// rho differs per facet (0.2 .. 0.6), E = (1 - rho) u_env: u = u_env everywhere.
void expect_equilibrium(const std::string& method, int level) {
  Scene scene(testing::block_on_floor());
  ASSERT_FALSE(scene.enclosed());
  const double u_env = 2.0;
  std::vector<double> rho, E;
  for (geometry::Index f = 0; f < scene.num_facets(); ++f) {
    rho.push_back(0.2 + 0.08 * static_cast<double>(f));
    E.push_back((1 - rho.back()) * u_env);
  }
  scene.set_reflectivity(rho);
  scene.set_emissivity(E);
  scene.set_environment(u_env);
  const SceneSolution s = solve_scene(scene, options(method, level));
  ASSERT_TRUE(s.converged());
  const ChannelSolution& ch = s.channels[0];
  EXPECT_NEAR(ch.radiosity.maxCoeff(), u_env, 1e-9 * u_env) << method;
  EXPECT_NEAR(ch.radiosity.minCoeff(), u_env, 1e-9 * u_env) << method;
  // Everything arriving is u_env: from the surfaces (H u = u_env H 1) and from the sky.
  EXPECT_NEAR(ch.irradiance.maxCoeff(), u_env, 1e-9 * u_env) << method;
  EXPECT_NEAR(ch.irradiance.minCoeff(), u_env, 1e-9 * u_env) << method;
  // emitted + environment_in = absorbed + escaped holds term by term: (1 - rho) u_env A is both
  // emitted and absorbed, u_env s A both arrives and escapes.
  EXPECT_GT(ch.environment_in, 0.1 * ch.emitted);
  EXPECT_LT(ch.energy_mismatch, 1e-9);
  EXPECT_TRUE(s.energy_balanced);
}

TEST(Environment, EquilibriumWithTheSkyIsUniformDense) { expect_equilibrium("dense", 2); }

TEST(Environment, EquilibriumWithTheSkyIsUniformFast) { expect_equilibrium("fast", 3); }

TEST(Environment, ASheetAloneSeesOnlyTheSky) {
  Scene scene(testing::quad(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)));
  scene.set_reflectivity(0.3);
  scene.set_environment(2.0);
  const SceneSolution s = solve_scene(scene, options("dense", 2));
  const ChannelSolution& ch = s.channels[0];
  for (Eigen::Index i = 0; i < ch.radiosity.size(); ++i) {
    EXPECT_NEAR(ch.radiosity[i], 0.6, 1e-14);
    EXPECT_NEAR(ch.irradiance[i], 2.0, 1e-14);
  }
  EXPECT_DOUBLE_EQ(ch.emitted, 0.0);
  EXPECT_NEAR(ch.environment_in, 2.0, 1e-14);  // area 1, s = 1
  EXPECT_NEAR(ch.escaped, 0.3, 1e-14);         // rho of what arrives leaves again
  EXPECT_LT(ch.energy_mismatch, 1e-14);
}

TEST(Environment, AnEnclosedSceneNeverSeesIt) {
  Scene lit(testing::room_with_box()), dark(testing::room_with_box());
  for (Scene* s : {&lit, &dark}) {
    s->set_reflectivity(0.5);
    s->set_emissivity(std::vector<double>{1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
  }
  lit.set_environment(5.0);
  EXPECT_FALSE(lit.sees_environment(0));
  const SceneSolution a = solve_scene(lit, options("dense", 1)), b = solve_scene(dark, options("dense", 1));
  EXPECT_EQ(a.channels[0].radiosity, b.channels[0].radiosity);
  EXPECT_EQ(a.channels[0].irradiance, b.channels[0].irradiance);
  EXPECT_EQ(a.channels[0].environment_in, 0.0);
}

// Two channels: one with E alone, one with E and the sky; a third with the sky alone. The
// equation is linear: u(E, u_env) = u(E, 0) + u(0, u_env), to the iterations' tolerance. The
// channels differ only in the environment, so none shares another's solution.
TEST(Environment, TheSolutionIsLinearInEmissionAndEnvironment) {
  Scene scene(testing::block_on_floor(), {"E", "E+sky", "sky"});
  std::vector<double> E(static_cast<std::size_t>(scene.num_facets()), 0.0);
  E[1] = 1.0;  // the block's top
  for (std::size_t c = 0; c < 3; ++c) {
    scene.set_reflectivity(0.6, c);
    if (c < 2) scene.set_emissivity(E, c);
  }
  scene.set_environment(0.7, 1);
  scene.set_environment(0.7, 2);
  const SceneSolution s = solve_scene(scene, options("dense", 2));
  for (const ChannelSolution& ch : s.channels) EXPECT_TRUE(ch.shared_with.empty()) << ch.name;
  const Eigen::VectorXd sum = s.channels[0].radiosity + s.channels[2].radiosity;
  EXPECT_LT((s.channels[1].radiosity - sum).lpNorm<Eigen::Infinity>(), 1e-10);
  const Eigen::VectorXd arriving = s.channels[0].irradiance + s.channels[2].irradiance;
  EXPECT_LT((s.channels[1].irradiance - arriving).lpNorm<Eigen::Infinity>(), 1e-10);
  EXPECT_EQ(s.channels[0].environment_in, 0.0);
  EXPECT_DOUBLE_EQ(s.channels[1].environment_in, s.channels[2].environment_in);
}

TEST(Environment, ANegativeOrNonFiniteEnvironmentIsRefusedNamingTheChannel) {
  Scene scene(testing::block_on_floor(), {"R", "G"});
  try {
    scene.set_environment(-1.0, 1);
    FAIL() << "a negative environment was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("channel G"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("environment"), std::string::npos) << e.what();
  }
  EXPECT_THROW(scene.set_environment(std::nan(""), 0), std::invalid_argument);
  EXPECT_THROW(scene.set_environment(1.0, 2), std::out_of_range);
  EXPECT_EQ(scene.environment(1), 0.0);
}

}  // namespace
}  // namespace panelrad

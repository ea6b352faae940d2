// The solver object (radiosity_solver.hpp): one setup, many right-hand sides; the same answers as
// the one-shot solve_scene; iterations out of steps keep their iterate; the fast operator's
// self-check and the one tighten loop; the options vocabulary; the one rule for rho and E at the
// collocation points (the rule on the scene itself: tests/scene/test_scene.cpp).
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/validation.hpp>
#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/radiosity_solver.hpp>
#include <panelrad/solve/scene_solver.hpp>
#include <panelrad/scene/errors.hpp>

#include "test_support.hpp"

#include "validated_meshes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace panelrad {
namespace {

geometry::TriangleMesh valid_cube() { return testing::validated_builtin("cube"); }

// rho and E per facet of one channel, different per facet (the cube has 6 facets).
struct FacetData {
  std::vector<double> rho, E;
};
const FacetData kData[] = {
    {{0.1, 0.5, 0.3, 0.7, 0.2, 0.4}, {1.0, 0.0, 0.5, 0.0, 2.0, 0.0}},
    {{0.6, 0.6, 0.2, 0.2, 0.9, 0.0}, {0.0, 3.0, 0.0, 1.0, 0.0, 0.25}},
};

Scene scalar_scene(const FacetData& d) {
  Scene s(valid_cube());
  s.set_reflectivity(d.rho);
  s.set_emissivity(d.E);
  return s;
}

// d's values at the collocation points: by the facet of each element.
void at_points(const RadiositySolver& solver, const FacetData& d, Eigen::VectorXd& rho, Eigen::VectorXd& E) {
  const Collocation& col = solver.collocation();
  rho.resize(col.size());
  E.resize(col.size());
  for (Index i = 0; i < col.size(); ++i) {
    rho[i] = d.rho[static_cast<std::size_t>(col.facet(i))];
    E[i] = d.E[static_cast<std::size_t>(col.facet(i))];
  }
}

// One solver object, two data sets solved in turn, against a separate one-shot solve_scene per
// data set: bit-for-bit the same (the same H, the same iteration, the same tolerance).
// bit_identical: the same operator both ways (dense). The fast operator stores its far
// coefficients in single precision, or recomputes them in double, by the products its solver
// expects (far_field_costs), which depend on rho (0 for the geometry-only solver): the two
// operators may then differ by the float rounding, 2^-24 ~ 6e-8 relative per coefficient, so the
// solutions by at most about 6e-8 rho/(1 - rho) ||u|| (1e-7 ||u|| here, rho <= 0.5) beside their
// iteration errors.
void expect_reuse_matches_one_shot(const SolveOptions& options, bool bit_identical) {
  const Scene geometry_only(valid_cube());  // rho 0, E 0: only its surface is used
  const RadiositySolver solver(geometry_only, options);
  for (const FacetData& d : kData) {
    Eigen::VectorXd rho, E;
    at_points(solver, d, rho, E);
    const ChannelSolve reused = solver.solve(rho, E);
    const SceneSolution one_shot = solve_scene(scalar_scene(d), options);
    ASSERT_TRUE(reused.converged()) << reused.message;
    EXPECT_EQ(one_shot.parameters, solver.parameters());
    const Eigen::VectorXd& u = one_shot.channels[0].radiosity;
    if (bit_identical) {
      EXPECT_EQ(reused.iterations, one_shot.channels[0].iterations);
      EXPECT_TRUE((reused.u.array() == u.array()).all());
    } else {
      const double bound = 1e-7 * u.lpNorm<Eigen::Infinity>() + reused.error_estimate + one_shot.channels[0].error_estimate;
      EXPECT_LE((reused.u - u).lpNorm<Eigen::Infinity>(), bound);
    }
  }
}

}  // namespace

TEST(RadiositySolver, SeveralRightHandSidesEqualOneShotSolvesDense) {
  SolveOptions o;
  o.level = 2;  // n = 192: dense
  o.op.method = OperatorMethod::dense;
  expect_reuse_matches_one_shot(o, true);
}

TEST(RadiositySolver, SeveralRightHandSidesEqualOneShotSolvesFast) {
  SolveOptions o;
  o.level = 3;  // n = 768
  o.op.method = OperatorMethod::fast;
  o.op.eta = 0.5;
  o.op.degree = 4;
  expect_reuse_matches_one_shot(o, false);
}

TEST(RadiositySolver, ChannelSolveIsTheSceneChannel) {
  Scene scene(valid_cube(), {"R", "G", "B"});
  for (std::size_t c = 0; c < 3; ++c) {
    scene.set_reflectivity(kData[c % 2].rho, c);
    scene.set_emissivity(kData[c % 2].E, c);
  }
  scene.set_emissivity([](const Vec3& P, Index) { return 1 + P.x() * P.y(); }, 2);  // E as a function
  SolveOptions o;
  o.level = 2;
  // One iteration for both (the automatic choice differs between one channel, GMRES, and several
  // stepped together, Neumann: ChannelsTogether tests it).
  o.solver.kind = SolverKind::neumann;
  const RadiositySolver solver(scene, o);
  const SceneSolution all = solve_scene(scene, o);
  ASSERT_EQ(all.channels.size(), 3u);
  EXPECT_EQ(all.channels[2].shared_with, "");
  for (std::size_t c = 0; c < 3; ++c) {
    const ChannelSolve r = solver.solve(c);
    EXPECT_TRUE((r.u.array() == all.channels[c].radiosity.array()).all()) << "channel " << c;
    EXPECT_TRUE((solver.irradiance(r.u).array() == all.channels[c].irradiance.array()).all());
  }
  // E(P) = 1 + x y at the collocation points, as the scene evaluates it.
  const Collocation::ChannelValues b = solver.channel_values(2);
  for (Index i = 0; i < solver.n(); ++i) {
    const Vec3& P = solver.collocation().collocation_point(i);
    EXPECT_EQ(b.E[i], 1 + P.x() * P.y());
  }
  EXPECT_THROW(solver.solve(3), std::invalid_argument);
}

// rho given as a function: its maximum (the conditioning of (11), which the automatic parameters
// honour) is taken over the collocation points, and the answer is the one for that data given at
// the points.
TEST(RadiositySolver, ReflectivityAsAFunction) {
  Scene scene(valid_cube());
  scene.set_reflectivity([](const Vec3& P, Index) { return 0.3 + 0.4 * P.x() * P.z(); });
  scene.set_emissivity(kData[0].E);
  SolveOptions o;
  o.level = 2;
  const RadiositySolver solver(scene, o);
  const Eigen::VectorXd& rho = solver.collocation().reflectivity();
  double rho_max = 0;
  for (Index i = 0; i < solver.n(); ++i) {
    const Vec3& P = solver.collocation().collocation_point(i);
    EXPECT_EQ(rho[i], 0.3 + 0.4 * P.x() * P.z());
    rho_max = std::max(rho_max, rho[i]);
  }
  EXPECT_EQ(solver.info().conditioning_reflectivity, rho_max);
  EXPECT_GT(rho_max, 0.6);
  const ChannelSolve a = solver.solve(0);
  const ChannelSolve b = solver.solve(rho, solver.collocation().emissivity());
  ASSERT_TRUE(a.converged());
  EXPECT_TRUE((a.u.array() == b.u.array()).all());
}

// max_iterations too small: the iterate is kept with its status and a finite error bound, never
// reported as converged; the one-shot solve keeps it too, warns, and require_converged throws.
TEST(RadiositySolver, NotConvergedKeepsTheIterate) {
  const Scene scene = scalar_scene(kData[0]);
  SolveOptions o;
  o.level = 2;
  o.solver.kind = SolverKind::neumann;
  o.solver.tolerance = 1e-14;
  o.solver.max_iterations = 5;  // rho <= 0.7: ~90 steps to 1e-14
  const RadiositySolver solver(scene, o);
  const ChannelSolve r = solver.solve(0);
  EXPECT_EQ(r.status, SolveStatus::not_converged);
  EXPECT_FALSE(r.converged());
  EXPECT_EQ(r.iterations, 5);
  ASSERT_EQ(r.u.size(), solver.n());
  EXPECT_TRUE(r.u.allFinite());
  EXPECT_TRUE(std::isfinite(r.error_estimate));
  EXPECT_GT(r.error_estimate, o.solver.tolerance * r.u.lpNorm<Eigen::Infinity>());
  EXPECT_NE(r.message.find("did not reach the tolerance"), std::string::npos) << r.message;
  // The converged answer differs from the 5-step iterate by about the reported bound: more than
  // the tolerance, and within the bound's factor (the ratio estimate (36) is an estimate).
  SolveOptions full = o;
  full.solver.max_iterations = 1000;
  const ChannelSolve done = RadiositySolver(scene, full).solve(0);
  ASSERT_TRUE(done.converged()) << done.message;
  const double distance = (done.u - r.u).lpNorm<Eigen::Infinity>();
  EXPECT_GT(distance, 1e-6);
  EXPECT_LT(distance, 10 * r.error_estimate);

  const SceneSolution sol = solve_scene(scene, o);
  EXPECT_EQ(sol.channels[0].status, SolveStatus::not_converged);
  EXPECT_TRUE((sol.channels[0].radiosity.array() == r.u.array()).all());
  ASSERT_FALSE(sol.warnings.empty());
  EXPECT_THROW(sol.require_converged(), SolverError);
  try {
    sol.require_converged();
  } catch (const SolverError& e) {
    EXPECT_EQ(std::string(e.what()), r.message);
  }
}

// The paper's cube at n = 768 with a loose fast setting (eta 0.5, M 1: far outside 5%, see
// auto_parameters.hpp): the self-check fails and tightening rebuilds until it passes. The count
// and the final parameters agree with tighten_parameters applied that many times.
TEST(RadiositySolver, FastSelfCheckAndTightenCount) {
  const Scene cube = make_paper_cube_scene();
  SolveOptions o;
  o.level = 3;
  o.op.method = OperatorMethod::fast;
  o.op.eta = 0.5;
  o.op.degree = 1;
  o.fold_reflectivity = true;
  {
    const RadiositySolver loose(cube, o);  // manual: checked, not tightened
    ASSERT_TRUE(loose.self_check().has_value());
    EXPECT_EQ(loose.info().tightened, 0);
    EXPECT_GT(loose.self_check()->relative_error, loose.info().self_check_threshold);
    EXPECT_EQ(loose.info().warnings.size(), 1u);
    // The check is the operator's own, deterministic.
    EXPECT_EQ(loose.self_check()->relative_error,
              dynamic_cast<const FastOperator&>(loose.op()).self_check().relative_error);
  }
  o.tighten_on_failed_check = true;
  const RadiositySolver solver(cube, o);
  ASSERT_TRUE(solver.self_check().has_value());
  EXPECT_GT(solver.info().tightened, 0);
  EXPECT_LE(solver.self_check()->relative_error, solver.info().self_check_threshold);
  EXPECT_EQ(solver.info().self_check_threshold, self_check_threshold(problem_size(cube.mesh(), 3), 0.5));
  OperatorOptions expected = o.op;
  expected.method = OperatorMethod::fast;
  for (int k = 0; k < solver.info().tightened; ++k) expected = tighten_parameters(expected);
  EXPECT_EQ(solver.parameters(), expected);
  EXPECT_TRUE(solver.info().warnings.empty());

  // Automatic parameters at n = 3072 (the cube's rho_max 0.5): the rule's choice passes its check.
  SolveOptions a;
  a.level = 4;
  a.fold_reflectivity = true;
  const RadiositySolver automatic(cube, a);
  EXPECT_EQ(automatic.parameters(), choose_parameters(problem_size(cube.mesh(), 4)));
  EXPECT_EQ(automatic.info().tightened, 0);
  ASSERT_TRUE(automatic.self_check().has_value());
  EXPECT_LE(automatic.self_check()->relative_error, automatic.info().self_check_threshold);
}

// With rho folded into the operator's rows, only that rho can be solved, and there is no H.
TEST(RadiositySolver, FoldedReflectivityRefusesOtherData) {
  const Scene cube = make_paper_cube_scene();
  SolveOptions o;
  o.level = 1;
  o.fold_reflectivity = true;
  const RadiositySolver solver(cube, o);
  const Eigen::VectorXd& rho = solver.collocation().reflectivity();
  const Eigen::VectorXd E = Eigen::VectorXd::Ones(solver.n());
  EXPECT_TRUE(solver.solve(rho, E).converged());
  EXPECT_THROW(solver.solve(Eigen::VectorXd::Constant(solver.n(), 0.2), E), std::invalid_argument);
  EXPECT_THROW(solver.irradiance(E), std::logic_error);
  EXPECT_THROW(solve_scene(cube, o), std::invalid_argument);
}

TEST(RadiositySolver, OptionsCompareByValue) {
  ClusteringParameters c1, c2;
  EXPECT_EQ(c1, c2);
  c2.eta = 0.3;
  EXPECT_NE(c1, c2);
  c2 = c1;
  c2.degree = 3;
  EXPECT_NE(c1, c2);

  NearFieldOptions n1, n2;
  EXPECT_EQ(n1, n2);
  n2.mu = 3;
  EXPECT_NE(n1, n2);
  n2 = n1;
  n2.basic_rule = "three_point";
  EXPECT_NE(n1, n2);

  OperatorOptions a, b;
  EXPECT_EQ(a, b);
  b.method = OperatorMethod::fast;
  EXPECT_NE(a, b);
  b = a;
  b.eta = 0.4;  // the base's fields count
  EXPECT_NE(a, b);
  b = a;
  b.near.rule = NearRule::quadrature;
  EXPECT_NE(a, b);
  FastOptions f;
  f.degree = 6;
  EXPECT_EQ(static_cast<const ClusteringParameters&>(f), (ClusteringParameters{0.2, 6, LocalExpansionOptions{}}));

  for (OperatorMethod m : {OperatorMethod::automatic, OperatorMethod::dense, OperatorMethod::fast})
    EXPECT_EQ(parse_operator_method(to_string(m)), m);
  EXPECT_EQ(std::string(to_string(OperatorMethod::automatic)), "auto");
  try {
    parse_operator_method("Dense");
    ADD_FAILURE() << "no error";
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    for (const char* name : {"'Dense'", "auto", "dense", "fast"}) EXPECT_NE(msg.find(name), std::string::npos) << msg;
  }
  const Scene cube = make_paper_cube_scene();
  const Collocation col(cube, 0);
  OperatorOptions automatic;
  automatic.method = OperatorMethod::automatic;
  EXPECT_THROW(make_operator(col, automatic), std::invalid_argument);
  EXPECT_EQ(std::string(to_string(Visibility::unoccluded)), "unoccluded");
}

namespace {

using testing::expect_names;
using testing::refusal;

}  // namespace

// Every option is checked by SolveOptions::validate before any work (no progress line), by the
// solver object and by solve_scene alike, the message naming the option and its value.
TEST(RadiositySolver, BadOptionsAreRefusedByNameBeforeAnyWork) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  struct Bad {
    std::function<void(SolveOptions&)> set;
    std::vector<std::string> names;
  };
  const std::vector<Bad> bad = {
      {[](SolveOptions& o) { o.max_elements = 0; }, {"max_elements", "0"}},
      {[](SolveOptions& o) { o.level = -2; }, {"level", "-2"}},
      {[](SolveOptions& o) { o.accuracy = 0.01; }, {"accuracy", "0.01", "0.05"}},
      {[nan](SolveOptions& o) { o.accuracy = nan; }, {"accuracy", "nan"}},
      {[](SolveOptions& o) { o.op.method = OperatorMethod::fast; o.op.eta = 1.5; }, {"eta", "1.5"}},
      {[](SolveOptions& o) { o.op.method = OperatorMethod::fast; o.op.degree = 13; }, {"degree", "13"}},
      {[](SolveOptions& o) { o.op.method = OperatorMethod::dense; o.op.near.mu = -1; }, {"mu", "-1"}},
      {[inf](SolveOptions& o) { o.solver.tolerance = inf; }, {"tolerance", "inf"}},
      {[nan](SolveOptions& o) { o.solver.tolerance = nan; }, {"tolerance", "nan"}},
      {[](SolveOptions& o) { o.solver.tolerance = -1e-8; }, {"tolerance", "-1e-08"}},
      {[](SolveOptions& o) { o.solver.max_iterations = 0; }, {"max_iterations", "0"}},
      {[](SolveOptions& o) { o.solver.gmres_restart = 0; }, {"gmres_restart", "0"}},
  };
  const Scene scene = scalar_scene(kData[0]);
  for (const Bad& b : bad) {
    SolveOptions o;
    o.level = 1;
    int lines = 0;
    o.progress = [&lines](const std::string&) { ++lines; };
    b.set(o);
    expect_names(refusal([&] { RadiositySolver solver(scene, o); }), b.names);
    expect_names(refusal([&] { (void)solve_scene(scene, o); }), b.names);
    EXPECT_EQ(lines, 0) << b.names[0] << ": refused before any work";
  }
  SolveOptions tied;  // the defaults: tolerance 0, tied to the discretization error; level -1
  tied.max_elements = 200;
  EXPECT_NO_THROW(RadiositySolver(scene, tied));
}

// The one rule for functions where they are evaluated: at the collocation points (per-facet data:
// tests/scene/test_scene.cpp).
TEST(RadiositySolver, OneValidatorForFunctionsAtCollocationPoints) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  SolveOptions o;
  o.level = 1;
  for (const double bad : {1.0, -0.1, nan}) {
    Scene scene(valid_cube(), {"R", "G"});
    scene.set_reflectivity([bad](const Vec3&, Index f) { return f == 3 ? bad : 0.4; }, 0);
    expect_names(refusal([&] { RadiositySolver solver(scene, o); }),
                 {"reflectivity rho", "point (", "of facet 3", "channel R", reflectivity_problem(bad)});
  }
  for (const double bad : {inf, -1.0}) {
    Scene scene(valid_cube(), {"R", "G"});
    scene.set_emissivity([bad](const Vec3&, Index f) { return f == 5 ? bad : 1.0; }, 1);
    const RadiositySolver solver(scene, o);  // channel G is evaluated when solved
    expect_names(refusal([&] { solver.solve(1); }),
                 {"emission E", "point (", "of facet 5", "channel G", emission_problem(bad)});
    expect_names(refusal([&] { solve_scene(scene, o); }), {"of facet 5", "channel G"});
  }
  // Data given at the points directly passes the same reflectivity rule.
  const Scene cube(valid_cube());
  const RadiositySolver solver(cube, o);
  Eigen::VectorXd rho = Eigen::VectorXd::Constant(solver.n(), 0.3);
  rho[7] = 1.0;
  expect_names(refusal([&] { solver.solve(rho, Eigen::VectorXd::Ones(solver.n())); }),
               {"rho = 1", "collocation point 7", reflectivity_problem(1.0)});
}

}  // namespace panelrad

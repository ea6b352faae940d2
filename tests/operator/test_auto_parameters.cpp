// Automatic parameters: the rule of auto_parameters.hpp keeps the solution
// within 5% of the discretization error, is deterministic, and refuses bad input.
#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/paper/cube_example.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/validation.hpp>
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/solvers.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace panelrad;

namespace {

// Neumann to 1e-9 relative: the iteration error (<= 3e-9) is negligible against the 5% margins
// compared below (>= 5e-5 for n <= 3072).
SolverOptions tight_solver() {
  SolverOptions s;
  s.tolerance = 1e-9;
  return s;
}

Scene prism_scene() {
  geometry::TriangleMesh mesh = geometry::make_builtin("prism:6");
  EXPECT_TRUE(geometry::validate_closed_convex(mesh).valid);
  Scene scene(std::move(mesh));
  std::vector<double> rho(8, 0.5);  // six sides 0.5, bottom cap 0.3, top cap 0.4
  rho[6] = 0.3;
  rho[7] = 0.4;
  scene.set_reflectivity(std::move(rho));
  scene.set_manufactured_solution([](const Vec3& Q, Index) { return Q.squaredNorm(); });
  return scene;
}

struct Outcome {
  double reference_error = 0;  // dense, exact near field: the discretization error
  double deviation = 0;        // max_k |u_auto - u_ref|
  double error = 0;            // max_k |u - u_auto|
};

Outcome solve_both(const Scene& scene, int level, const OperatorOptions& chosen) {
  const Collocation col(scene, level);
  OperatorOptions reference;  // dense, exact
  const auto K_ref = make_operator(col, reference);
  const auto K = make_operator(col, chosen);
  const SolveResult ref = solve(*K_ref, col.emissivity(), tight_solver(), scene.max_reflectivity());
  const SolveResult got = solve(*K, col.emissivity(), tight_solver(), scene.max_reflectivity());
  return {col.max_error(ref.u), (got.u - ref.u).lpNorm<Eigen::Infinity>(), col.max_error(got.u)};
}

}  // namespace

TEST(AutoParameters, ProblemSizeMatchesTheClusterTree) {
  const Scene cube = make_paper_cube_scene();
  for (int level = 0; level <= 3; ++level) {
    const ProblemSize s = problem_size(cube.mesh(), level);
    const Collocation col(cube, level);
    EXPECT_EQ(s.n, col.size());
    EXPECT_DOUBLE_EQ(s.mesh_size, col.tree().mesh_size());
    EXPECT_DOUBLE_EQ(s.diameter, col.tree().diameter());
    // The cube's equivalent level is its level (up to rounding of sqrt and log2).
    EXPECT_NEAR(s.equivalent_level(), level, 1e-12);
  }
}

TEST(AutoParameters, DeterministicAndValid) {
  const Scene cube = make_paper_cube_scene();
  for (int level = 0; level <= 8; ++level) {
    const ProblemSize s = problem_size(cube.mesh(), level);
    const OperatorOptions a = choose_parameters(s), b = choose_parameters(s);
    EXPECT_EQ(a.method, b.method);
    EXPECT_EQ(a.near.rule, b.near.rule);
    EXPECT_EQ(a.eta, b.eta);
    EXPECT_EQ(a.degree, b.degree);
    EXPECT_TRUE(a.method == OperatorMethod::dense || a.method == OperatorMethod::fast);
    EXPECT_EQ(a.near.rule, NearRule::exact);
    if (a.method == OperatorMethod::fast) {
      EXPECT_GT(a.eta, 0.0);
      EXPECT_LT(a.eta, 1.0);
      EXPECT_GE(a.degree, 0);
      EXPECT_LE(a.degree, 12);
    }
    // A looser margin never gives a different (less safe) choice than the measured 5%.
    EXPECT_EQ(choose_parameters(s, 0.2), a);
  }
  // The smallest sizes are solved densely, the large ones with the fast method.
  EXPECT_EQ(choose_parameters(problem_size(cube.mesh(), 1)).method, OperatorMethod::dense);
  EXPECT_EQ(choose_parameters(problem_size(cube.mesh(), 6)).method, OperatorMethod::fast);
}

TEST(AutoParameters, RefusesBadInput) {
  const Scene cube = make_paper_cube_scene();
  const ProblemSize ok = problem_size(cube.mesh(), 2);
  EXPECT_THROW(choose_parameters(ok, 0.01), std::invalid_argument);  // tighter than measured
  EXPECT_THROW(choose_parameters(ok, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  ProblemSize bad = ok;
  bad.n = 0;
  EXPECT_THROW(choose_parameters(bad), std::invalid_argument);
  bad = ok;
  bad.mesh_size = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(choose_parameters(bad), std::invalid_argument);
  bad = ok;
  bad.mesh_size = -1;
  EXPECT_THROW(choose_parameters(bad), std::invalid_argument);
  bad = ok;
  bad.mesh_size = 2 * bad.diameter;
  EXPECT_THROW(choose_parameters(bad), std::invalid_argument);
  EXPECT_THROW(problem_size(cube.mesh(), -1), std::invalid_argument);
  EXPECT_THROW(problem_size(geometry::TriangleMesh{}, 1), std::invalid_argument);
}

TEST(AutoParameters, TightenIsStricterAndStops) {
  OperatorOptions o;
  o.method = OperatorMethod::fast;
  o.eta = 0.5;
  o.degree = 5;
  o = tighten_parameters(o);
  EXPECT_EQ(o.degree, 6);
  EXPECT_EQ(o.eta, 0.5);
  o = tighten_parameters(o);
  EXPECT_EQ(o.degree, 6);
  EXPECT_EQ(o.eta, 0.3);
  o.eta = 0.1;
  const OperatorOptions last = tighten_parameters(o);
  EXPECT_EQ(last.eta, 0.1);
  EXPECT_EQ(last.degree, 6);
  OperatorOptions dense;
  EXPECT_EQ(tighten_parameters(dense).method, OperatorMethod::dense);
}

// The criterion of the header, at the cube's levels 2-4 (dense at 2 and 3, fast at 4) and the
// hexagonal prism's level 3 (fast, n = 1280): the automatic solution differs from the dense
// exact one by at most 5% of the discretization error, so its error is within 5% of it.
TEST(AutoParameters, WithinFivePercentOfTheDiscretizationError) {
  const Scene cube = make_paper_cube_scene();
  bool saw_fast = false;
  for (int level = 2; level <= 4; ++level) {
    const OperatorOptions chosen = choose_parameters(problem_size(cube.mesh(), level));
    saw_fast = saw_fast || chosen.method == OperatorMethod::fast;
    const Outcome r = solve_both(cube, level, chosen);
    SCOPED_TRACE("cube level " + std::to_string(level) + ": " + describe_parameters(chosen));
    EXPECT_LE(r.deviation, 0.05 * r.reference_error);
    EXPECT_LE(r.error, 1.05 * r.reference_error);
  }
  EXPECT_TRUE(saw_fast) << "levels 2-4 should exercise the fast method at least once";
  const Scene prism = prism_scene();
  const OperatorOptions chosen = choose_parameters(problem_size(prism.mesh(), 3));
  EXPECT_EQ(chosen.method, OperatorMethod::fast);
  const Outcome r = solve_both(prism, 3, chosen);
  EXPECT_LE(r.deviation, 0.05 * r.reference_error) << describe_parameters(chosen);
}

// The same check can fail: the loosest setting of the sweep (eta 0.5, M 1) is far outside 5%.
TEST(AutoParameters, TheCriterionRejectsACheapSetting) {
  const Scene cube = make_paper_cube_scene();
  OperatorOptions cheap;
  cheap.method = OperatorMethod::fast;
  cheap.eta = 0.5;
  cheap.degree = 1;
  const Outcome r = solve_both(cube, 3, cheap);
  EXPECT_GT(r.deviation, 0.05 * r.reference_error);
}

// A setting whose self-check fails is tightened until the check passes.
TEST(AutoParameters, FailedSelfCheckTightensTheParameters) {
  panelrad::CubeRunOptions o;
  o.min_level = o.max_level = 3;
  o.op.method = OperatorMethod::fast;
  o.op.eta = 0.5;
  o.op.degree = 1;  // far outside 5% (see the header's table)
  o.tighten_on_failed_check = true;
  const auto rows = panelrad::run_paper_cube(o);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_GT(rows[0].tightened, 0);
  const panelrad::ProblemSize size = panelrad::problem_size(panelrad::make_paper_cube_scene().mesh(), 3);
  EXPECT_LE(rows[0].checked_product_error, panelrad::self_check_threshold(size));
  EXPECT_GT(rows[0].degree, 1);
}

// The conditioning (auto_parameters.hpp): at rho_max the target delta* shrinks by
// A = rho_max / (1 - rho_max), which the rule meets as the target of log2 A levels finer; at the
// cube's rho_max 0.5 (A = 1), and below it, the choice is the one for the cube.
TEST(AutoParameters, ConditioningAsksForTheTargetOfAFinerLevel) {
  const Scene cube = make_paper_cube_scene();
  for (int level = 4; level <= 6; ++level) {
    const ProblemSize s = problem_size(cube.mesh(), level);
    EXPECT_EQ(choose_parameters(s, 0.05, 0.5), choose_parameters(s));
    EXPECT_EQ(choose_parameters(s, 0.05, 0.2), choose_parameters(s));
    // rho_max 0.8: A = 4, two levels finer exactly.
    EXPECT_EQ(describe_parameters(choose_parameters(s, 0.05, 0.8)),
              describe_parameters(choose_parameters(problem_size(cube.mesh(), level + 2))));
  }
  // rho_max 0.9 at level 4 (lambda_eff 7.17) is stricter than at rho_max 0.5: a higher M at eta 0.4.
  const OperatorOptions loose = choose_parameters(problem_size(cube.mesh(), 4));
  const OperatorOptions strict = choose_parameters(problem_size(cube.mesh(), 4), 0.05, 0.9);
  EXPECT_EQ(strict.method, OperatorMethod::fast);
  EXPECT_LE(strict.eta, loose.eta);
  EXPECT_GT(strict.degree, loose.degree);
  // The cube at the sizes the README measures: n = 3072 and 12288 (0.4, 6), 49152 (0.4, 8).
  EXPECT_EQ(describe_parameters(choose_parameters(problem_size(cube.mesh(), 5))), "fast, exact near field, eta 0.4, M 6");
  EXPECT_EQ(describe_parameters(choose_parameters(problem_size(cube.mesh(), 6))), "fast, exact near field, eta 0.4, M 8");
}

// Solvers under stress: reflectivity up to 0.99 on closed boxes (the cube and a
// hexagonal prism). Neumann's step count (34) grows like 1/(1 - rho), GMRES's stays bounded, the
// automatic choice picks Neumann for rho <= 0.8 and GMRES above and says so. Known answers: with
// constant rho and E = c (1 - rho) on a closed convex surface the solution is u = c, and the
// discrete system keeps it because the exact rule gives K_n 1 = rho 1 (row-sum identity, Lemma 1).
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/validation.hpp>
#include <panelrad/support/resources.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/solvers.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <string>

namespace {

using namespace panelrad;

constexpr double kC = 2.0;  // the constant solution u = c

Scene box_scene(const std::string& builtin, double rho) {
  geometry::TriangleMesh mesh = geometry::make_builtin(builtin);
  const auto report = geometry::validate_closed_convex(mesh);
  EXPECT_TRUE(report.valid) << report.message;
  Scene scene(std::move(mesh));
  scene.set_reflectivity(rho);
  scene.set_emissivity(kC * (1 - rho));  // u = c solves u - K u = E when K 1 = rho
  return scene;
}

double max_deviation_from_constant(const Eigen::VectorXd& u) { return (u.array() - kC).abs().maxCoeff(); }

void report(const std::string& key, double value) {
  std::cout << "[stress] " << key << " = " << value << "\n";
  ::testing::Test::RecordProperty(key, std::to_string(value));
}

struct BoxCase {
  const char* builtin;
  int level;  // cube level 2: n = 192; prism:6 level 2: n = 320
};

// n is a few hundred here and Neumann needs thousands of products: one thread each (the products
// are bit-identical for any thread count, linear_operator.hpp), since a parallel region per tiny
// product costs a scheduler time slice per barrier on a loaded machine (ctest -j, CI).
class ClosedBox : public ::testing::TestWithParam<BoxCase> {
 protected:
  void SetUp() override {
    threads_ = max_threads();
    set_threads(1);
  }
  void TearDown() override { set_threads(threads_); }

 private:
  int threads_ = 1;
};

// Neumann on the constant solution: u^(k) tends to c with the ratio (36) equal to rho, so the
// stopping rule q/(1-q) ||step|| <= tol ||u|| (solvers.cpp) is met when rho^(k+1) <= tol, i.e.
// k ~ ln(1/tol) / (-ln rho). Since 1 - rho <= -ln rho <= (1 - rho)/rho, the product
// k (1 - rho) lies in [rho ln(1/tol), ln(1/tol)] up to the O(1) steps the rule needs to start
// (k >= 3) and to round: the band asserted below, [0.5, 1] ln(1/tol) widened by 2 (1 - rho) + 0.5,
// holds for every rho in [0.5, 1). The answer must be c to 1e-10 even at rho = 0.99, where the
// iteration needs thousands of products.
TEST_P(ClosedBox, NeumannStepsGrowLikeOneOverOneMinusRho) {
  const BoxCase box = GetParam();
  const double tol = 1e-12;
  const double log_inv_tol = std::log(1 / tol);
  double previous_count = 0;
  for (double rho : {0.5, 0.9, 0.99}) {
    const Scene scene = box_scene(box.builtin, rho);
    const Collocation col(scene, box.level);
    const DenseOperator K(col, NearFieldOptions{});  // exact rule: rows sum to rho (Lemma 1)
    SolverOptions opt;
    opt.kind = SolverKind::neumann;
    opt.tolerance = tol;
    opt.max_iterations = 20000;
    const SolveResult r = solve(K, col.emissivity(), opt, scene.max_reflectivity());
    ASSERT_TRUE(r.u.allFinite());
    const double err = max_deviation_from_constant(r.u);
    const double scaled = r.iterations * (1 - rho);
    report(std::string(box.builtin) + " neumann rho=" + std::to_string(rho) + " steps", r.iterations);
    report(std::string(box.builtin) + " neumann rho=" + std::to_string(rho) + " max|u-c|", err);
    EXPECT_LT(err, 1e-10 * kC) << "rho " << rho;
    // The ratio (36) of successive steps of an operator with constant row sums is rho. Read it at
    // step 3, where the steps are still ~rho^3 c (1 - rho) >> rounding: the last steps are ~tol and
    // their ratio carries the rounding of u (~1e-16 / 1e-12 relative).
    ASSERT_GE(r.ratio_history.size(), 3u);
    EXPECT_NEAR(r.ratio_history[2], rho, 1e-9) << "the ratio (36) of a constant-row-sum operator is rho";
    EXPECT_GE(scaled, 0.5 * log_inv_tol - 2 * (1 - rho)) << "rho " << rho << " steps " << r.iterations;
    EXPECT_LE(scaled, log_inv_tol + 2 * (1 - rho) + 0.5) << "rho " << rho << " steps " << r.iterations;
    EXPECT_GT(r.iterations, previous_count);
    previous_count = r.iterations;
  }
}

// GMRES on the same systems with a right-hand side that is not the Perron vector (a lamp on one
// facet: E = 1 there, 0 elsewhere), checked against dense LU. Its product count must stay bounded
// as rho -> 1 (the spectrum of I - K is 1 - rho, isolated, plus a cluster around 1): fewer than
// 40 products even at rho = 0.99 (Neumann needs ~2800 there, the test above).
TEST_P(ClosedBox, GmresStaysBoundedAsRhoNearsOne) {
  const BoxCase box = GetParam();
  for (double rho : {0.5, 0.9, 0.99}) {
    Scene scene = box_scene(box.builtin, rho);
    std::vector<double> lamp(static_cast<std::size_t>(scene.num_facets()), 0.0);
    lamp[0] = 1.0;
    scene.set_emissivity(lamp);
    const Collocation col(scene, box.level);
    const DenseOperator K(col, NearFieldOptions{});
    const SolveResult lu = solve_lu(K, col.emissivity());
    SolverOptions opt;
    opt.kind = SolverKind::gmres;
    opt.tolerance = 1e-11;
    const SolveResult r = solve(K, col.emissivity(), opt, scene.max_reflectivity());
    ASSERT_TRUE(r.u.allFinite());
    const double diff = (r.u - lu.u).lpNorm<Eigen::Infinity>() / lu.u.lpNorm<Eigen::Infinity>();
    report(std::string(box.builtin) + " gmres rho=" + std::to_string(rho) + " products", r.iterations);
    report(std::string(box.builtin) + " gmres rho=" + std::to_string(rho) + " rel diff to LU", diff);
    // The solver's bound (11) is 1e-11 relative; LU itself is backward stable (cond <= 2/(1-rho)).
    EXPECT_LT(diff, 1e-10) << "rho " << rho;
    EXPECT_LT(r.iterations, 40) << "rho " << rho;
    // The lamp's light reaches every element (unoccluded, rho > 0): u > 0 everywhere.
    EXPECT_GT(r.u.minCoeff(), 0.0);
  }
}

// The automatic solver: the iteration of fewer expected products (expected_products), and it
// does use the fewest products among Neumann and GMRES, at every rho; SolveResult says which and
// why (both expected counts); every solver answers c to 1e-10.
TEST_P(ClosedBox, AutomaticChoiceTakesTheFewestProducts) {
  const BoxCase box = GetParam();
  for (double rho : {0.1, 0.3, 0.5, 0.8, 0.9, 0.99}) {
    const Scene scene = box_scene(box.builtin, rho);
    const Collocation col(scene, box.level);
    const DenseOperator K(col, NearFieldOptions{});
    SolverOptions opt;  // kind = automatic
    // 1e-11: GMRES maps its residual to an error bound with 1/(1 - rho) = 100 at rho = 0.99, so a
    // tighter tolerance asks for residuals at the rounding floor (~1e-15 n^(1/2)) and stagnates.
    opt.tolerance = 1e-11;
    opt.max_iterations = 5000;
    const SolveResult r = solve(K, col.emissivity(), opt, scene.max_reflectivity());
    SolverOptions each = opt;
    each.kind = SolverKind::neumann;
    const SolveResult neumann = solve(K, col.emissivity(), each, scene.max_reflectivity());
    each.kind = SolverKind::gmres;
    const SolveResult gmres = solve(K, col.emissivity(), each, scene.max_reflectivity());
    const ExpectedProducts e = expected_products(rho, rho, opt.tolerance);
    EXPECT_GT(e.neumann, 0);
    EXPECT_GT(e.gmres, 0);
    EXPECT_EQ(r.solver, e.gmres < e.neumann ? "gmres" : "neumann") << "rho " << rho;
    EXPECT_EQ(choose_solver(rho, opt.tolerance), e.gmres < e.neumann ? SolverKind::gmres : SolverKind::neumann);
    EXPECT_LE(r.iterations, std::min(neumann.iterations, gmres.iterations)) << "rho " << rho << ", " << r.choice;
    EXPECT_NE(r.choice.find("expected " + std::to_string(std::min(e.neumann, e.gmres)) + " products"), std::string::npos)
        << r.choice;
    // The bounds are bounds: neither iteration needs more products than expected.
    EXPECT_LE(neumann.iterations, e.neumann) << "rho " << rho;
    EXPECT_LE(gmres.iterations, e.gmres) << "rho " << rho;
    for (const SolveResult* s : {&r, &neumann, &gmres})
      EXPECT_LT(max_deviation_from_constant(s->u), 1e-10 * kC) << "rho " << rho << ", " << s->solver;
    std::cout << "[stress] " << box.builtin << " rho " << rho << ": " << r.choice << "; products auto " << r.iterations
              << ", Neumann " << neumann.iterations << ", GMRES " << gmres.iterations << "\n";
  }
}

INSTANTIATE_TEST_SUITE_P(Stress, ClosedBox,
                         ::testing::Values(BoxCase{"cube", 2}, BoxCase{"prism:6", 2}),
                         [](const ::testing::TestParamInfo<BoxCase>& info) {
                           return std::string(info.param.builtin).substr(0, 4) + "_level" +
                                  std::to_string(info.param.level);
                         });

// rho given as a function: its maximum is unknown (NaN), so the automatic choice is GMRES, and it
// says why.
TEST(StressSolvers, AutomaticChoiceWithPointwiseReflectivityIsGmres) {
  Scene scene = box_scene("cube", 0.5);
  scene.set_reflectivity([](const Vec3&, Index) { return 0.95; });
  scene.set_emissivity(kC * (1 - 0.95));
  EXPECT_TRUE(std::isnan(scene.max_reflectivity()));
  const Collocation col(scene, 1);
  const DenseOperator K(col, NearFieldOptions{});
  SolverOptions opt;
  opt.tolerance = 1e-12;
  const SolveResult r = solve(K, col.emissivity(), opt, scene.max_reflectivity());
  EXPECT_EQ(r.solver, "gmres");
  EXPECT_NE(r.choice.find("unknown"), std::string::npos) << r.choice;
  // Without max rho the GMRES bound uses a fixed amplification (1e3 >= 1/(1 - 0.95)): still c.
  EXPECT_LT(max_deviation_from_constant(r.u), 1e-10 * kC);
}

// Neumann forced at rho = 0.99 with too few steps for the tolerance: a not-converged status and
// a clear SolverError (require_converged) that points to GMRES, never a silent answer.
TEST(StressSolvers, NeumannOutOfStepsAtRhoNearOneIsAnError) {
  const Scene scene = box_scene("cube", 0.99);
  const Collocation col(scene, 1);
  const DenseOperator K(col, NearFieldOptions{});
  SolverOptions opt;
  opt.kind = SolverKind::neumann;
  opt.tolerance = 1e-12;
  opt.max_iterations = 500;  // ~2700 needed (rho^k <= 1e-12)
  try {
    const SolveResult r = solve(K, col.emissivity(), opt, scene.max_reflectivity());
    EXPECT_EQ(r.status, SolveStatus::not_converged);
    r.require_converged();
    ADD_FAILURE() << "no SolverError";
  } catch (const SolverError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("500"), std::string::npos) << msg;
    EXPECT_NE(msg.find("GMRES"), std::string::npos) << msg;
  }
}

// The fast operator at rho = 0.99 (cube, n = 768): the automatic choice (GMRES) stays bounded, and
// the answer's distance from c is bounded by the operator's own row-sum defect d = max|K 1 - rho|:
// (I - K)(u - c) = c (K 1 - rho 1), so ||u - c|| <= c d / (1 - rho - d) (K >= 0 far from
// cancellation; ||K||_inf <= rho + d). 1 - rho = 0.01 amplifies the product error 100-fold.
TEST(StressSolvers, FastOperatorAtRhoNearOne) {
  const double rho = 0.99;
  const Scene scene = box_scene("cube", rho);
  const Collocation col(scene, 3);
  const FastOperator K(col, FastOptions{});
  Eigen::VectorXd ones = Eigen::VectorXd::Ones(col.size()), K1;
  K.apply(ones, K1);
  const double defect = (K1.array() - rho).abs().maxCoeff();
  ASSERT_LT(defect, 0.5 * (1 - rho)) << "fast row sums too far from rho for the bound";
  SolverOptions opt;
  // The operator's own error (d / (1 - rho) ~ 1e-2 here) dwarfs any iteration tolerance below
  // 1e-9, so iterating further buys nothing (the discretization-tied rule of solvers.hpp).
  opt.tolerance = 1e-9;
  const SolveResult r = solve(K, col.emissivity(), opt, scene.max_reflectivity());
  ASSERT_TRUE(r.u.allFinite());
  const double err = max_deviation_from_constant(r.u);
  const double bound = kC * defect / (1 - rho - defect);
  report("fast cube n=768 rho=0.99 row-sum defect", defect);
  report("fast cube n=768 rho=0.99 max|u-c|", err);
  report("fast cube n=768 rho=0.99 gmres products", r.iterations);
  EXPECT_EQ(r.solver, "gmres");
  EXPECT_LT(r.iterations, 40);
  EXPECT_LE(err, bound * 1.01 + 1e-10);
}

}  // namespace

// Solvers against an independent truth: Eigen's dense solve of a small synthetic system.
#include <panelrad/solve/solvers.hpp>

#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

using panelrad::RadiosityOperator;

// A matrix as an operator: y = K v.
class MatrixOperator final : public RadiosityOperator {
 public:
  explicit MatrixOperator(Eigen::MatrixXd K) : K_(std::move(K)) {}
  panelrad::Index size() const override { return static_cast<panelrad::Index>(K_.rows()); }
  void apply(const Eigen::VectorXd& v, Eigen::VectorXd& y) const override { y = K_ * v; }
  std::string name() const override { return "matrix"; }
  std::size_t bytes() const override { return static_cast<std::size_t>(K_.size()) * sizeof(double); }
  const Eigen::MatrixXd& K() const { return K_; }

 private:
  Eigen::MatrixXd K_;
};

// Nonnegative matrix with every row sum equal to r, like K_n on a closed convex surface with rho = r.
Eigen::MatrixXd row_stochastic(int n, double r, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> U(0.1, 1.0);
  Eigen::MatrixXd K(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) K(i, j) = (i == j) ? 0.0 : U(gen);
    K.row(i) *= r / K.row(i).sum();
  }
  return K;
}

TEST(Solvers, NeumannMatchesDirectSolveAndRatioIsTheRowSum) {
  const int n = 60;
  const double r = 0.4;
  const MatrixOperator K(row_stochastic(n, r, 1));
  Eigen::VectorXd E = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  const Eigen::VectorXd truth = (Eigen::MatrixXd::Identity(n, n) - K.K()).partialPivLu().solve(E);
  panelrad::SolverOptions opt;
  opt.tolerance = 1e-12;
  const auto res = panelrad::solve_neumann(K, E, opt);
  EXPECT_LT((res.u - truth).lpNorm<Eigen::Infinity>(), 1e-11 * truth.lpNorm<Eigen::Infinity>());
  // Positive matrix with constant row sums r: Perron root r with eigenvector 1, the other
  // eigenvalues are far smaller, so the ratio of successive differences (36) tends to r.
  EXPECT_NEAR(res.convergence_ratio, r, 1e-3);
  EXPECT_LT(res.residual, 1e-11);
  // Error bound of the iteration really bounds the error.
  EXPECT_LE((res.u - truth).lpNorm<Eigen::Infinity>(), res.error_estimate * 1.0001 + 1e-300);
}

TEST(Solvers, GmresMatchesDirectSolveAndStaysBoundedAsRhoNearsOne) {
  const int n = 80;
  Eigen::VectorXd E = Eigen::VectorXd::LinSpaced(n, -1.0, 3.0);
  int previous = 0;
  for (double r : {0.5, 0.9, 0.99}) {
    const MatrixOperator K(row_stochastic(n, r, 7));
    const Eigen::VectorXd truth = (Eigen::MatrixXd::Identity(n, n) - K.K()).partialPivLu().solve(E);
    panelrad::SolverOptions opt;
    opt.tolerance = 1e-10;
    const auto res = panelrad::solve_gmres(K, E, opt, r);
    EXPECT_LT((res.u - truth).lpNorm<Eigen::Infinity>(), 1e-9 * truth.lpNorm<Eigen::Infinity>()) << "rho " << r;
    EXPECT_LT(res.iterations, 60) << "rho " << r;
    previous = res.iterations;
  }
  EXPECT_GT(previous, 0);
}

// An iteration out of steps keeps its iterate and says so (status, message, error bound); it
// is never reported as converged, and require_converged turns it into the SolverError.
TEST(Solvers, NonConvergenceKeepsTheIterateAndSaysSo) {
  const int n = 30;
  const MatrixOperator K(row_stochastic(n, 0.999, 3));
  // Not the Perron vector 1 (for which one Krylov step is exact).
  Eigen::VectorXd E = Eigen::VectorXd::LinSpaced(n, -1.0, 2.0);
  panelrad::SolverOptions opt;
  opt.tolerance = 1e-12;
  opt.max_iterations = 20;
  const panelrad::SolveResult neumann = panelrad::solve_neumann(K, E, opt);
  EXPECT_EQ(neumann.status, panelrad::SolveStatus::not_converged);
  EXPECT_EQ(neumann.iterations, 20);
  EXPECT_EQ(neumann.u.size(), n);
  EXPECT_TRUE(neumann.u.allFinite());
  EXPECT_NE(neumann.message.find("20 steps"), std::string::npos) << neumann.message;
  EXPECT_THROW(neumann.require_converged(), panelrad::SolverError);
  // The kept iterate after 20 products, from u^(1) = E: sum_{k=0}^{20} K^k E (34), computed
  // independently as a partial sum of the Neumann series.
  Eigen::VectorXd partial = E, term = E, next;
  for (int k = 1; k <= 20; ++k) {
    K.apply(term, next);
    term = next;
    partial += term;
  }
  EXPECT_LE((neumann.u - partial).lpNorm<Eigen::Infinity>(), 1e-12 * partial.lpNorm<Eigen::Infinity>());
  // GMRES converges on this small system within ~n products; 3 products cannot reach 1e-12.
  opt.max_iterations = 3;
  const panelrad::SolveResult gmres = panelrad::solve_gmres(K, E, opt, 0.999);
  EXPECT_EQ(gmres.status, panelrad::SolveStatus::not_converged);
  EXPECT_TRUE(std::isfinite(gmres.error_estimate));
  EXPECT_GT(gmres.error_estimate, opt.tolerance * gmres.u.lpNorm<Eigen::Infinity>());
  EXPECT_THROW(gmres.require_converged(), panelrad::SolverError);
}

TEST(Solvers, BadRightHandSideIsRejected) {
  const MatrixOperator K(row_stochastic(5, 0.3, 2));
  Eigen::VectorXd E = Eigen::VectorXd::Ones(4);
  EXPECT_THROW(panelrad::solve_neumann(K, E, {}), std::invalid_argument);
  Eigen::VectorXd F = Eigen::VectorXd::Ones(5);
  F[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(panelrad::solve_neumann(K, F, {}), std::invalid_argument);
  EXPECT_THROW(panelrad::parse_solver("cholesky"), std::invalid_argument);
}

// The iteration's options are checked before the first product, by every entry, naming the
// option and its value: a tolerance that is not finite and positive (inf would report convergence
// at once), no iteration allowed, a GMRES restart of 0.
TEST(Solvers, BadOptionsAreRefusedByName) {
  const MatrixOperator K(row_stochastic(5, 0.3, 2));
  const Eigen::VectorXd E = Eigen::VectorXd::Ones(5);
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  struct Bad {
    panelrad::SolverOptions options;
    std::string names;
  };
  std::vector<Bad> bad;
  for (const double t : {inf, -inf, nan, 0.0, -1e-8}) {
    panelrad::SolverOptions o;
    o.tolerance = t;
    char shown[32];
    std::snprintf(shown, sizeof shown, "%g", t);
    bad.push_back({o, std::string("tolerance ") + shown});
  }
  for (const int m : {0, -3}) {
    panelrad::SolverOptions o;
    o.max_iterations = m;
    bad.push_back({o, "max_iterations " + std::to_string(m)});
  }
  {
    panelrad::SolverOptions o;
    o.gmres_restart = 0;
    bad.push_back({o, "gmres_restart 0"});
  }
  for (const Bad& b : bad) {
    for (const panelrad::SolverKind kind :
         {panelrad::SolverKind::automatic, panelrad::SolverKind::neumann, panelrad::SolverKind::gmres}) {
      panelrad::SolverOptions o = b.options;
      o.kind = kind;
      int products = 0;
      o.progress = [&products](int, double) { ++products; };
      const std::vector<std::function<void()>> entries = {
          [&] { (void)panelrad::solve(K, E, o, 0.3); },
          [&] { (void)panelrad::solve_neumann(K, E, o); },
          [&] { (void)panelrad::solve_gmres(K, E, o, 0.3); },
          [&] { (void)panelrad::NeumannIteration(E, o); },
      };
      for (std::size_t k = 0; k < entries.size(); ++k) {
        try {
          entries[k]();
          ADD_FAILURE() << b.names << " accepted by entry " << k << " (kind " << panelrad::to_string(kind) << ")";
        } catch (const std::invalid_argument& e) {
          const std::string what = e.what();
          const std::string name = b.names.substr(0, b.names.find(' '));
          const std::string value = b.names.substr(b.names.find(' ') + 1);
          EXPECT_NE(what.find(name), std::string::npos) << what;
          EXPECT_NE(what.find(value), std::string::npos) << what << " lacks " << value;
        }
      }
      EXPECT_EQ(products, 0) << b.names << ": refused before the first product";
    }
  }
  // One rule for every kind: a restart of 0 is refused by Neumann too (above); the defaults pass.
  EXPECT_NO_THROW((void)panelrad::solve_neumann(K, E, panelrad::SolverOptions{}));
}

TEST(Solvers, LuNeedsTheDenseOperator) {
  const MatrixOperator K(row_stochastic(5, 0.3, 2));
  panelrad::SolverOptions opt;
  opt.kind = panelrad::SolverKind::lu;
  EXPECT_THROW(panelrad::solve(K, Eigen::VectorXd::Ones(5), opt, 0.3), std::invalid_argument);
}

}  // namespace

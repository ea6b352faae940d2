#pragma once
// Solvers of (I - K_n) u_n = E_n, (32), over the RadiosityOperator interface: the Neumann
// iteration (34) with its convergence ratio (36), restarted GMRES, and dense LU (direct baseline).
// Every sum over the rows (inner products, 2-norms) is taken in the fixed blocks of
// BlockedReductions, so that the iterates are the same bits on one process and on any number of
// processes that share the rows (SolverOptions::communicator).
#include <panelrad/distributed/blocked_reductions.hpp>
#include <panelrad/distributed/communicator.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/scene/errors.hpp>
#include <panelrad/operator/linear_operator.hpp>

#include <Eigen/Core>

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace panelrad {

/// automatic: the solver of fewer expected products (expected_products): GMRES for one equation
/// (its residual is the least over the Krylov space that holds Neumann's iterate, and the bound
/// of its rate is below Neumann's for every rho < 1), unless Neumann's bound is no larger; with
/// several channels (RadiositySolver::solve_channels) Neumann steps them together through one block
/// product until their measured ratios (36) say GMRES costs less.
enum class SolverKind { automatic, neumann, gmres, lu };
SolverKind parse_solver(const std::string& name);  ///< "auto" | "neumann" | "gmres" | "lu"
const char* to_string(SolverKind kind);

struct SolverOptions {
  SolverKind kind = SolverKind::automatic;
  /// Stop when the estimated error ||u_n - u^(k)||_inf <= tolerance * ||u^(k)||_inf. Tie it to the
  /// discretization error: there is no point in iterating far below it.
  double tolerance = 1e-10;
  int max_iterations = 1000;
  int gmres_restart = 60;
  /// Called after every product with K_n (products so far, current error estimate; the estimate
  /// is 0 before the iteration has one), e.g. for progress on stderr. May be empty.
  std::function<void(int products, double error_estimate)> progress;
  /// The processes sharing the rows (nullptr: one process). With several, K is the operator of
  /// this process's rows (RowBlockOperator), E and the iterates hold those rows, and every
  /// process runs the same iteration: the reductions are collectives (BlockedReductions).
  const Communicator* communicator = nullptr;
  /// std::invalid_argument naming the option and its value unless tolerance is finite and > 0,
  /// max_iterations >= 1 and gmres_restart >= 1. Every solver entry below (and NeumannIteration)
  /// calls it before its first product (option_checks.cpp).
  void validate() const;
};

/// converged: the error estimate reached the tolerance. not_converged: the iteration stopped at
/// max_iterations; u is its last iterate and error_estimate its bound (+inf when the iteration has
/// none yet), and `message` says so (the text of the SolverError a caller may throw).
enum class SolveStatus { converged, not_converged };
const char* to_string(SolveStatus status);  ///< "converged" | "not converged"

/// What every solve reports, the base of each result (SolveResult, ChannelSolve, ChannelSolution):
/// whether it converged, what ran and how far it got.
struct IterationReport {
  SolveStatus status = SolveStatus::converged;
  std::string message;             ///< not_converged: what was not reached, and how far it got
  std::string solver;              ///< the solver that ran (with the automatic choice's reason where one was made)
  int iterations = 0;              ///< products with K_n
  double error_estimate = 0;       ///< bound on ||u_n - u||_inf from the iteration (+inf: none yet)
  double residual = 0;             ///< ||E - (I - K) u||_inf / ||E||_inf, one extra product
  bool converged() const { return status == SolveStatus::converged; }
  /// Throws SolverError(message) when the iteration did not converge.
  void require_converged() const;
};

/// One iteration's answer (solve_neumann, solve_gmres, solve_lu, solve).
struct SolveResult : IterationReport {
  Eigen::VectorXd u;
  std::string choice;              ///< why the solver was chosen (automatic choice), else empty
  double convergence_ratio = 0;    ///< Neumann: ratio (36), estimated by successive differences
  std::vector<double> ratio_history;
  double seconds = 0;
};

/// The solvers return their last iterate when they stop at max_iterations (status
/// not_converged); an iterate that is not finite is a SolverError; options that fail
/// SolverOptions::validate are a std::invalid_argument before any product.
/// Neumann iteration (34), u^(0) = 0: u^(k+1) = E + K u^(k).
SolveResult solve_neumann(const RadiosityOperator& K, const Eigen::VectorXd& E, const SolverOptions& options);
/// The Neumann iteration (34) as a sequence of products, so that several equations can share each
/// pass over one operator (RadiosityOperator::apply_block): next() is the vector to multiply by K,
/// take(K next()) advances. After the iteration stops (converged, or max_iterations), one more
/// product, of the final u, gives the residual; then finished(). solve_neumann is this loop with
/// K.apply, so an equation iterated here gives solve_neumann's result bit for bit.
class NeumannIteration {
 public:
  /// E finite (checked by the caller, as solve_neumann does).
  NeumannIteration(Eigen::VectorXd E, SolverOptions options);
  bool finished() const { return phase_ == Phase::finished; }
  /// The next product is the final u's, for the residual.
  bool awaiting_residual() const { return phase_ == Phase::residual; }
  /// u^(k) while iterating; the final u while the residual's product is awaited.
  const Eigen::VectorXd& next() const { return u_; }
  /// Steps taken, the latest ratio (36) and the latest step u^(k+1) - u^(k) = E - (I - K) u^(k):
  /// the residual of the previous iterate u^(k) = next() - step(), for handing the equation to
  /// another solver (solve_gmres_from) without a product.
  int steps() const { return r_.iterations; }
  double ratio() const { return ratio_; }
  const Eigen::VectorXd& step() const { return step_; }
  const Eigen::VectorXd& rhs() const { return E_; }
  /// Advances with Kv = K next(); SolverError when an iterate is not finite.
  void take(const Eigen::VectorXd& Kv);
  /// The result once finished() (seconds not set).
  const SolveResult& result() const { return r_; }
  SolveResult&& release() { return std::move(r_); }

 private:
  enum class Phase { iterating, residual, finished };
  void stop(SolveStatus status);
  Eigen::VectorXd E_, u_, step_;
  SolverOptions options_;
  BlockedReductions sums_;
  SolveResult r_;
  Phase phase_ = Phase::iterating;
  double previous_norm_ = 0, ratio_ = 0, e_norm_ = 0;
};

/// Restarted GMRES on (I - K) u = E; stops on the relative residual, mapped to an error bound
/// with ||(I-K)^-1|| <= 1/(1 - max rho) (paper (11)). From u = 0, whose residual E needs no product.
SolveResult solve_gmres(const RadiosityOperator& K, const Eigen::VectorXd& E, const SolverOptions& options,
                        double max_reflectivity);
/// The same from the iterate u whose residual E - (I - K) u is `residual` (known, so no product),
/// after `products` products already made (counted in the result's iterations and against
/// options.max_iterations).
SolveResult solve_gmres_from(const RadiosityOperator& K, const Eigen::VectorXd& E, const SolverOptions& options,
                             double max_reflectivity, Eigen::VectorXd u, Eigen::VectorXd residual, int products = 0);
/// Dense LU with partial pivoting of I - K_n (Eigen).
SolveResult solve_lu(const DenseOperator& K, const Eigen::VectorXd& E);

/// A stopping tolerance tied to the discretization error: the centroid method's error is O(h)
/// (Theorem 5, (28)), about 0.03 h/diam relative on the cube (Table 1); iterating to
/// 1e-5 h/diam keeps the iteration error near 0.03% of it. h: mesh size, diam: surface diameter.
double discretization_tolerance(double h, double diameter);

/// Products each iteration is expected to need, from the ratio q of Neumann's steps (36) (at most
/// max rho by (10); measured once Neumann has taken a few steps), max rho and the tolerance, for
/// reducing the error from `reduction` (the current ||residual|| / ||u||; 1 at the start) to the
/// tolerance, the final residual's product included (see solvers.cpp for the bounds).
/// 0 where no estimate exists (q or max rho not in [0, 1), tolerance or reduction not positive).
struct ExpectedProducts {
  int neumann = 0;
  int gmres = 0;
};
ExpectedProducts expected_products(double ratio, double max_reflectivity, double tolerance, double reduction = 1);

/// The solver `automatic` resolves to for one equation: the fewer expected_products with the
/// ratio bound max rho (NaN: unknown -> GMRES).
SolverKind choose_solver(double max_reflectivity, double tolerance);

/// Why `automatic` chose choose_solver(max_reflectivity, tolerance): the text of
/// SolveResult::choice, with both expected counts.
std::string solver_choice(double max_reflectivity, double tolerance);

/// Dispatch on options.kind; LU needs a DenseOperator (std::invalid_argument otherwise).
SolveResult solve(const RadiosityOperator& K, const Eigen::VectorXd& E, const SolverOptions& options,
                  double max_reflectivity);

}  // namespace panelrad

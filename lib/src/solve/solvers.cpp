#include <panelrad/support/resources.hpp>
#include <panelrad/solve/solvers.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace panelrad {

namespace {
double relative_residual(const RadiosityOperator& K, const Eigen::VectorXd& E, const Eigen::VectorXd& u) {
  Eigen::VectorXd Ku;
  K.apply(u, Ku);
  const double e = E.lpNorm<Eigen::Infinity>();
  const double r = (E - u + Ku).lpNorm<Eigen::Infinity>();
  return e > 0 ? r / e : r;
}

void check_sizes(const RadiosityOperator& K, const Eigen::VectorXd& E, const BlockedReductions& sums) {
  if (E.size() != K.size()) throw std::invalid_argument("solver: right-hand side size differs from n");
  if (!sums.all_finite(E)) throw std::invalid_argument("solver: right-hand side has NaN or Inf entries");
}
// One restart cycle of GMRES on (I - K) c = res: Arnoldi with modified Gram-Schmidt and Givens
// rotations, up to m products (and no more than options.max_iterations in all), stopping when the
// error bound amplification |g[j+1]| (|g[j+1]| the 2-norm residual) falls to `stop`.
class GmresCycle {
 public:
  GmresCycle(Eigen::Index n, int m, const BlockedReductions& sums)
      : m_(m), sums_(sums), V_(n, m + 1), H_(Eigen::MatrixXd::Zero(m + 1, m)), cs_(m), sn_(m), g_(m + 1) {}

  /// The correction c_j in the Krylov space of res; `products` counts the products with K.
  Eigen::VectorXd correction(const RadiosityOperator& K, const Eigen::VectorXd& res, double stop,
                             const SolverOptions& options, double amplification, int& products) {
    const double beta = sums_.norm(res);
    V_.col(0) = res / beta;
    g_.setZero();
    g_[0] = beta;
    H_.setZero();
    int j = 0;
    for (; j < m_ && products < options.max_iterations; ++j) {
      const bool done = arnoldi_step(K, j);
      ++products;
      if (options.progress) options.progress(products, amplification * std::abs(g_[j + 1]));
      // |g[j+1]| is the 2-norm residual; ||.||_inf <= ||.||_2
      if (amplification * std::abs(g_[j + 1]) <= stop) {
        ++j;
        break;
      }
      if (done) break;
    }
    // Solve the j x j upper-triangular system.
    const Eigen::VectorXd y = H_.topLeftCorner(j, j).triangularView<Eigen::Upper>().solve(g_.head(j));
    return V_.leftCols(j) * y;
  }

 private:
  // Column j of the Hessenberg matrix, rotated to triangular form; true when H(j, j) = 0 (the
  // Krylov space is exhausted).
  bool arnoldi_step(const RadiosityOperator& K, int j) {
    Eigen::VectorXd Kv;
    K.apply(V_.col(j), Kv);
    Eigen::VectorXd w = V_.col(j) - Kv;  // (I - K) v_j
    for (int i = 0; i <= j; ++i) {       // modified Gram-Schmidt
      H_(i, j) = sums_.dot(w, V_.col(i));
      w -= H_(i, j) * V_.col(i);
    }
    H_(j + 1, j) = sums_.norm(w);
    if (H_(j + 1, j) > 0) V_.col(j + 1) = w / H_(j + 1, j);
    for (int i = 0; i < j; ++i) {  // apply previous Givens rotations
      const double t = cs_[i] * H_(i, j) + sn_[i] * H_(i + 1, j);
      H_(i + 1, j) = -sn_[i] * H_(i, j) + cs_[i] * H_(i + 1, j);
      H_(i, j) = t;
    }
    const double d = std::hypot(H_(j, j), H_(j + 1, j));
    cs_[j] = d > 0 ? H_(j, j) / d : 1;
    sn_[j] = d > 0 ? H_(j + 1, j) / d : 0;
    H_(j, j) = d;
    H_(j + 1, j) = 0;
    g_[j + 1] = -sn_[j] * g_[j];
    g_[j] = cs_[j] * g_[j];
    return H_(j, j) == 0;
  }

  int m_;
  const BlockedReductions& sums_;
  Eigen::MatrixXd V_, H_;
  Eigen::VectorXd cs_, sn_, g_;
};

}  // namespace

SolverKind parse_solver(const std::string& name) {
  if (name == "auto") return SolverKind::automatic;
  if (name == "neumann") return SolverKind::neumann;
  if (name == "gmres") return SolverKind::gmres;
  if (name == "lu") return SolverKind::lu;
  throw std::invalid_argument("solver '" + name + "' is not auto, neumann, gmres or lu");
}

const char* to_string(SolveStatus status) {
  return status == SolveStatus::converged ? "converged" : "not converged";
}

void IterationReport::require_converged() const {
  if (status != SolveStatus::converged) throw SolverError(message);
}

const char* to_string(SolverKind kind) {
  switch (kind) {
    case SolverKind::automatic: return "auto";
    case SolverKind::neumann: return "neumann";
    case SolverKind::gmres: return "gmres";
    case SolverKind::lu: return "lu";
  }
  return "?";
}

NeumannIteration::NeumannIteration(Eigen::VectorXd E, SolverOptions options)
    : E_(std::move(E)), u_(E_), options_(std::move(options)), sums_(options_.communicator) {  // u^(1) = E + K 0
  options_.validate();
  r_.solver = "neumann";
  e_norm_ = sums_.inf_norm(E_);
  previous_norm_ = e_norm_;
  if (e_norm_ == 0) {
    phase_ = Phase::finished;  // u = 0 exactly, no product
    r_.u = u_;
  }
}

void NeumannIteration::stop(SolveStatus status) {
  r_.status = status;
  r_.convergence_ratio = ratio_;
  if (status == SolveStatus::not_converged) {
    std::ostringstream os;
    os << "Neumann iteration did not reach the tolerance " << options_.tolerance << " in " << options_.max_iterations
       << " steps (last ratio " << ratio_
       << "; a ratio near 1 means rho close to 1, where GMRES needs far fewer products)";
    r_.message = os.str();
  }
  phase_ = Phase::residual;
}

void NeumannIteration::take(const Eigen::VectorXd& Kv) {
  if (phase_ == Phase::finished) throw std::logic_error("NeumannIteration::take: the iteration has finished");
  if (phase_ == Phase::residual) {  // ||E - (I - K) u||_inf / ||E||_inf
    r_.residual = sums_.inf_norm(E_ - u_ + Kv) / e_norm_;
    r_.u = std::move(u_);
    phase_ = Phase::finished;
    return;
  }
  const int k = ++r_.iterations;
  Eigen::VectorXd next = E_ + Kv;
  step_ = next - u_;  // u^(k+1) - u^(k) = K (u^(k) - u^(k-1)), (35)
  const double step_norm = sums_.inf_norm(step_);
  u_ = std::move(next);
  const double q = previous_norm_ > 0 ? step_norm / previous_norm_ : 0;  // estimate of (36)
  r_.ratio_history.push_back(q);
  ratio_ = q;
  if (options_.progress) options_.progress(r_.iterations, q < 1 ? q / (1 - q) * step_norm : 0.0);
  previous_norm_ = step_norm;
  if (!sums_.all_finite(u_)) throw SolverError("Neumann iteration produced NaN/Inf at step " + std::to_string(k));
  // Error bound from (35) with contraction q < 1: ||u_n - u^(k+1)|| <= q/(1-q) ||step||;
  // none (+inf) while the ratio is not yet known to be below 1.
  r_.error_estimate = std::numeric_limits<double>::infinity();
  if (k >= 3 && q < 1) {
    const double q_safe = std::max(q, r_.ratio_history[r_.ratio_history.size() - 2]);
    if (q_safe < 1) {
      r_.error_estimate = q_safe / (1 - q_safe) * step_norm;
      if (r_.error_estimate <= options_.tolerance * sums_.inf_norm(u_)) return stop(SolveStatus::converged);
    }
  }
  if (step_norm == 0) {  // exact fixed point reached
    r_.error_estimate = 0;
    return stop(SolveStatus::converged);
  }
  if (k >= options_.max_iterations) stop(SolveStatus::not_converged);
}

SolveResult solve_neumann(const RadiosityOperator& K, const Eigen::VectorXd& E, const SolverOptions& options) {
  check_sizes(K, E, BlockedReductions(options.communicator));
  Stopwatch clock;
  NeumannIteration iteration(E, options);
  Eigen::VectorXd Kv;
  while (!iteration.finished()) {
    K.apply(iteration.next(), Kv);
    iteration.take(Kv);
  }
  SolveResult r = iteration.release();
  r.seconds = clock.seconds();
  return r;
}

SolveResult solve_gmres(const RadiosityOperator& K, const Eigen::VectorXd& E, const SolverOptions& options,
                        double max_reflectivity) {
  check_sizes(K, E, BlockedReductions(options.communicator));
  return solve_gmres_from(K, E, options, max_reflectivity, Eigen::VectorXd::Zero(E.size()), E);
}

SolveResult solve_gmres_from(const RadiosityOperator& K, const Eigen::VectorXd& E, const SolverOptions& options,
                             double max_reflectivity, Eigen::VectorXd u, Eigen::VectorXd residual, int products) {
  options.validate();
  const BlockedReductions sums(options.communicator);
  check_sizes(K, E, sums);
  if (u.size() != E.size() || residual.size() != E.size())
    throw std::invalid_argument("solve_gmres_from: the initial iterate or its residual differs in size from n");
  Stopwatch clock;
  SolveResult r;
  r.solver = "gmres";
  r.iterations = products;
  const Eigen::Index n = E.size();
  // The restart from the whole n, the same on every process.
  const int m = std::max(1, std::min<int>(options.gmres_restart, static_cast<int>(sums.total_rows(n))));
  // ||u - u_k||_inf <= ||(I-K)^-1||_inf ||res||_inf <= ||res||_inf / (1 - max rho)   (11)
  const double amplification = (max_reflectivity >= 0 && max_reflectivity < 1) ? 1.0 / (1.0 - max_reflectivity) : 1e3;
  Eigen::VectorXd Kv;
  const double e_norm2 = sums.norm(E);
  if (e_norm2 == 0) {
    r.u = Eigen::VectorXd::Zero(n);
    return r;
  }
  GmresCycle cycle(n, m, sums);
  bool residual_known = true;  // the first residual is given (u = 0: E itself, no product K 0)
  while (r.iterations < options.max_iterations) {
    Eigen::VectorXd res;
    if (residual_known) {
      res = std::move(residual);
      residual_known = false;
    } else {
      K.apply(u, Kv);
      ++r.iterations;
      res = E - u + Kv;
    }
    const double res_inf = sums.inf_norm(res);
    r.error_estimate = amplification * res_inf;
    if (options.progress) options.progress(r.iterations, r.error_estimate);
    const double u_norm = sums.inf_norm(u);
    if (r.error_estimate <= options.tolerance * std::max(u_norm, 1e-300)) break;
    const double stop = 0.5 * options.tolerance * std::max(u_norm, sums.inf_norm(E));
    u += cycle.correction(K, res, stop, options, amplification, r.iterations);
    if (!sums.all_finite(u)) throw SolverError("GMRES produced NaN/Inf");
  }
  K.apply(u, Kv);
  ++r.iterations;
  const Eigen::VectorXd res = E - u + Kv;
  const double res_inf = sums.inf_norm(res);
  r.error_estimate = amplification * res_inf;
  r.residual = res_inf / sums.inf_norm(E);
  if (r.error_estimate > options.tolerance * sums.inf_norm(u)) {
    std::ostringstream os;
    os << "GMRES did not reach the tolerance " << options.tolerance << " in " << options.max_iterations
       << " products (error bound " << r.error_estimate << ")";
    r.status = SolveStatus::not_converged;
    r.message = os.str();
  }
  r.u = std::move(u);
  r.seconds = clock.seconds();
  return r;
}

SolveResult solve_lu(const DenseOperator& K, const Eigen::VectorXd& E) {
  check_sizes(K, E, BlockedReductions());
  Stopwatch clock;
  SolveResult r;
  r.solver = "lu";
  const Eigen::Index n = K.size();
  const std::size_t need = DenseOperator::matrix_bytes(static_cast<geometry::Index>(n));
  if (need > available_memory_bytes() / 10 * 9)
    throw std::runtime_error("LU of I - K_n needs another " + format_bytes(static_cast<double>(need)) +
                             ", more than the memory available; use the Neumann or GMRES iteration");
  Eigen::MatrixXd A = -K.matrix();
  A.diagonal().array() += 1.0;
  Eigen::PartialPivLU<Eigen::Ref<Eigen::MatrixXd>> lu(A);  // in place
  r.u = lu.solve(E);
  if (!r.u.allFinite()) throw SolverError("LU produced NaN/Inf (singular system?)");
  r.residual = relative_residual(K, E, r.u);
  r.seconds = clock.seconds();
  return r;
}

double discretization_tolerance(double h, double diameter) {
  if (!(h > 0) || !(diameter > 0)) throw std::invalid_argument("discretization_tolerance: h and diameter must be positive");
  return std::clamp(1e-5 * h / diameter, 1e-14, 1e-3);
}

ExpectedProducts expected_products(double ratio, double max_reflectivity, double tolerance, double reduction) {
  ExpectedProducts e;
  if (!(ratio >= 0 && ratio < 1) || !(max_reflectivity >= 0 && max_reflectivity < 1) || !(tolerance > 0) ||
      !(reduction > 0))
    return e;  // unknown: 0 (no estimate)
  const double q = std::max(ratio, 1e-3);
  // Neumann: the bound q/(1-q) ||step|| of (35) with ||step_k|| ~ q^k ||step_0|| reaches
  // tolerance ||u|| when q^(k+1) reduction / (1 - q) <= tolerance; one more product for the residual.
  e.neumann = static_cast<int>(std::ceil(std::log(tolerance * (1 - q) / reduction) / std::log(q))) + 1;
  // GMRES: K = diag(rho) H with H similar to a symmetric matrix (reciprocity A_i F_ij = A_j F_ji of
  // the form factors, V symmetric), so the spectrum of I - K lies in [1 - q, 1 + q]; its residual
  // falls at least by the Chebyshev rate (sqrt(k) - 1)/(sqrt(k) + 1), k = (1 + q)/(1 - q), up to a
  // factor 2, to the bound tolerance (1 - max rho) ||u|| of (11); one product to check it.
  const double kappa = (1 + q) / (1 - q);
  const double rate = (std::sqrt(kappa) - 1) / (std::sqrt(kappa) + 1);
  e.gmres = static_cast<int>(std::ceil(std::log(tolerance * (1 - max_reflectivity) / (2 * reduction)) / std::log(rate))) + 1;
  e.neumann = std::max(e.neumann, 1);
  e.gmres = std::max(e.gmres, 1);
  return e;
}

SolverKind choose_solver(double max_reflectivity, double tolerance) {
  const ExpectedProducts e = expected_products(max_reflectivity, max_reflectivity, tolerance);
  if (e.neumann <= 0 || e.gmres <= 0) return SolverKind::gmres;  // no bound on the ratio
  return e.neumann <= e.gmres ? SolverKind::neumann : SolverKind::gmres;
}

std::string solver_choice(double max_reflectivity, double tolerance) {
  std::ostringstream os;
  const ExpectedProducts e = expected_products(max_reflectivity, max_reflectivity, tolerance);
  if (e.neumann <= 0 || e.gmres <= 0) {
    os << "auto: GMRES, since rho varies by point and its maximum is unknown (no bound on Neumann's ratio)";
    return os.str();
  }
  const bool neumann = choose_solver(max_reflectivity, tolerance) == SolverKind::neumann;
  os << "auto: " << (neumann ? "Neumann" : "GMRES") << ", expected " << (neumann ? e.neumann : e.gmres)
     << " products against " << (neumann ? e.gmres : e.neumann) << " for " << (neumann ? "GMRES" : "Neumann")
     << " at max rho = " << max_reflectivity << ", tolerance " << tolerance;
  return os.str();
}

SolveResult solve(const RadiosityOperator& K, const Eigen::VectorXd& E, const SolverOptions& options,
                  double max_reflectivity) {
  options.validate();
  if (options.kind == SolverKind::automatic) {
    SolverOptions chosen = options;
    chosen.kind = choose_solver(max_reflectivity, options.tolerance);
    SolveResult r = solve(K, E, chosen, max_reflectivity);
    r.choice = solver_choice(max_reflectivity, options.tolerance);
    return r;
  }
  switch (options.kind) {
    case SolverKind::automatic: break;  // handled above
    case SolverKind::neumann: return solve_neumann(K, E, options);
    case SolverKind::gmres: return solve_gmres(K, E, options, max_reflectivity);
    case SolverKind::lu: {
      const auto* dense = dynamic_cast<const DenseOperator*>(&K);
      if (!dense) throw std::invalid_argument("the LU solver needs the dense operator (33)");
      return solve_lu(*dense, E);
    }
  }
  throw std::invalid_argument("unknown solver");
}

}  // namespace panelrad

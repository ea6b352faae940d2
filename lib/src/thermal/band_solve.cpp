// The band model of a thermal solve (band_solve.hpp, thermal_solve.hpp: Bands).
#include "band_solve.hpp"

#include <panelrad/solve/solvers.hpp>
#include <panelrad/thermal/blackbody.hpp>

#include <algorithm>
#include <deque>
#include <cmath>
#include <string>
#include <vector>

namespace panelrad::thermal_detail {

using geometry::Index;

namespace {

/// J -> M J on the n B stacked band radiosities (band k the k-th block of n): with Y = H J (one
/// block product), (M J)_k = rho_k Y_k + a_k sum_j eps'_j Y_j, where eps' is eps on the rows with
/// a given flux and 0 elsewhere, and a the split of those rows' emission (0 elsewhere). GMRES then
/// solves (I - M) J = b.
class BandOperator final : public RadiosityOperator {
 public:
  BandOperator(const RadiosityOperator& H, Eigen::MatrixXd rho, Eigen::MatrixXd flux_eps, const Eigen::MatrixXd& split)
      : H_(H), rho_(std::move(rho)), flux_eps_(std::move(flux_eps)), split_(split) {}
  Index size() const override { return rho_.size(); }
  void apply(const Eigen::VectorXd& v, Eigen::VectorXd& y) const override {
    const Index n = rho_.rows(), B = rho_.cols();
    const Eigen::MatrixXd X = Eigen::Map<const Eigen::MatrixXd>(v.data(), n, B);
    Eigen::MatrixXd Y;
    H_.apply_block(X, Y);
    const Eigen::VectorXd absorbed = flux_eps_.cwiseProduct(Y).rowwise().sum();
    y.resize(n * B);
    Eigen::Map<Eigen::MatrixXd> out(y.data(), n, B);
    out = rho_.cwiseProduct(Y);
    out += (split_.array().colwise() * absorbed.array()).matrix();
  }
  std::string name() const override { return "bands of " + H_.name(); }
  std::size_t bytes() const override { return 3 * static_cast<std::size_t>(rho_.size()) * sizeof(double); }

 private:
  const RadiosityOperator& H_;
  Eigen::MatrixXd rho_, flux_eps_;
  const Eigen::MatrixXd& split_;
};

/// Anderson acceleration of depth m of a fixed point x = G(x) (Walker & Ni, SIAM J. Numer. Anal.
/// 49 (2011), without damping): from x_k and g_k = G(x_k), the next iterate is
/// g_k - sum_j gamma_j (g_j+1 - g_j) over the last m steps, gamma minimizing the 2-norm of
/// f_k - sum_j gamma_j (f_j+1 - f_j), f = g - x (least squares by Householder QR with column
/// pivoting: deterministic). Here x are the temperatures of the rows with a given flux and G one
/// round; a plain step is taken where the mixed one would leave a temperature not finite and > 0.
class AndersonMixing {
 public:
  explicit AndersonMixing(std::size_t depth) : depth_(depth) {}
  Eigen::VectorXd next(const Eigen::VectorXd& x, const Eigen::VectorXd& g) {
    const Eigen::VectorXd f = g - x;
    if (f_last_.size() == f.size()) {
      dF_.push_back(f - f_last_);
      dG_.push_back(g - g_last_);
      if (dF_.size() > depth_) {
        dF_.pop_front();
        dG_.pop_front();
      }
    }
    f_last_ = f;
    g_last_ = g;
    if (dF_.empty()) return g;
    const Eigen::Index m = static_cast<Eigen::Index>(dF_.size());
    Eigen::MatrixXd F(f.size(), m), G(f.size(), m);
    for (Eigen::Index j = 0; j < m; ++j) {
      F.col(j) = dF_[static_cast<std::size_t>(j)];
      G.col(j) = dG_[static_cast<std::size_t>(j)];
    }
    const Eigen::VectorXd gamma = F.colPivHouseholderQr().solve(f);
    Eigen::VectorXd mixed = g - G * gamma;
    if (!mixed.allFinite() || mixed.minCoeff() <= 0) return g;
    return mixed;
  }

 private:
  std::size_t depth_;
  std::deque<Eigen::VectorXd> dF_, dG_;
  Eigen::VectorXd f_last_, g_last_;
};

}  // namespace

namespace {

/// The bands' data per element: emissivities, what the given temperatures emit, the rows with a
/// given flux and the environment's emission per band.
struct BandRows {
  Index n = 0, B = 0;
  Eigen::VectorXd u_env;                      ///< F_k(T_env) sigma T_env^4
  Eigen::MatrixXd eps, rho, flux_eps, emitted;  ///< n x B; flux_eps: eps on the flux rows, else 0
  std::vector<std::vector<double>> eps_of_group;
  std::vector<Index> flux_rows;
  Eigen::VectorXd T;  ///< given, and on the flux rows the first guess
};

const SurfaceCondition& condition_of(const BandProblem& p, Index i) {
  return (*p.conditions)[static_cast<std::size_t>((*p.group)[static_cast<std::size_t>(i)])];
}

BandRows band_rows(const BandProblem& p, const std::vector<double>& edges) {
  BandRows r;
  r.n = p.solver->n();
  r.B = static_cast<Index>(edges.size()) + 1;
  const double sigma = kStefanBoltzmann;
  r.u_env = Eigen::VectorXd::Zero(r.B);
  if (p.environment_temperature > 0) {
    const double Te = p.environment_temperature;
    const std::vector<double> f = band_fractions(edges, Te);
    for (Index k = 0; k < r.B; ++k) r.u_env[k] = f[static_cast<std::size_t>(k)] * sigma * std::pow(Te, 4);
  }
  r.eps.resize(r.n, r.B);
  r.flux_eps = r.emitted = Eigen::MatrixXd::Zero(r.n, r.B);
  for (const SurfaceCondition& c : *p.conditions) {
    r.eps_of_group.emplace_back();
    for (Index k = 0; k < r.B; ++k) r.eps_of_group.back().push_back(c.emissivity_in(static_cast<std::size_t>(k)));
  }
  r.T.resize(r.n);
  double given_area = 0, given_sum = 0;
  for (Index i = 0; i < r.n; ++i) {
    const SurfaceCondition& c = condition_of(p, i);
    for (Index k = 0; k < r.B; ++k) r.eps(i, k) = c.emissivity_in(static_cast<std::size_t>(k));
    if (c.given == SurfaceCondition::Given::temperature) {
      r.T[i] = c.value;
      const std::vector<double> f = band_fractions(edges, c.value);
      for (Index k = 0; k < r.B; ++k)
        r.emitted(i, k) = r.eps(i, k) * f[static_cast<std::size_t>(k)] * sigma * std::pow(c.value, 4);
      given_area += p.area[i];
      given_sum += p.area[i] * c.value;
    } else {
      r.flux_eps.row(i) = r.eps.row(i);
      r.flux_rows.push_back(i);
    }
  }
  // The first split: at the given temperatures' mean (or the environment's).
  for (Index i : r.flux_rows) r.T[i] = given_area > 0 ? given_sum / given_area : p.environment_temperature;
  r.rho = Eigen::MatrixXd::Ones(r.n, r.B) - r.eps;
  return r;
}

/// The split a_k = eps_k F_k(T) / sum_j eps_j F_j(T) of each flux row's emission at its T.
void set_split(const BandRows& r, const std::vector<double>& edges, Eigen::MatrixXd& split) {
  for (Index i : r.flux_rows) {
    const std::vector<double> f = band_fractions(edges, r.T[i]);
    double total = 0, eps_total = 0;
    for (Index k = 0; k < r.B; ++k) {
      total += r.eps(i, k) * f[static_cast<std::size_t>(k)];
      eps_total += r.eps(i, k);
    }
    for (Index k = 0; k < r.B; ++k)
      split(i, k) = total > 0 ? r.eps(i, k) * f[static_cast<std::size_t>(k)] / total : r.eps(i, k) / eps_total;
  }
}

/// b of (I - M) J = b: eps_k F_k(T) sigma T^4 + rho_k u_env,k s where T is given, and
/// a_k (q + sum_j eps_j u_env,j s) + rho_k u_env,k s where q is.
void set_rhs(const BandRows& r, const BandProblem& p, const Eigen::MatrixXd& split, Eigen::VectorXd& b) {
  b.resize(r.n * r.B);
  Eigen::Map<Eigen::MatrixXd> rhs(b.data(), r.n, r.B);
  for (Index i = 0; i < r.n; ++i) {
    const double s = p.sky[i];
    const SurfaceCondition& c = condition_of(p, i);
    if (c.given == SurfaceCondition::Given::temperature) {
      for (Index k = 0; k < r.B; ++k) rhs(i, k) = r.emitted(i, k) + r.rho(i, k) * r.u_env[k] * s;
      continue;
    }
    double absorbed_env = 0;
    for (Index k = 0; k < r.B; ++k) absorbed_env += r.eps(i, k) * r.u_env[k] * s;
    for (Index k = 0; k < r.B; ++k) rhs(i, k) = split(i, k) * (c.value + absorbed_env) + r.rho(i, k) * r.u_env[k] * s;
  }
}

/// The temperatures of the flux rows from what they emit, e = sum_k eps_k H_k + q (NaN where
/// e <= 0): one per flux row, in parallel (each row on its own: the same for any thread count).
std::vector<double> flux_temperatures(const BandRows& r, const BandProblem& p, const std::vector<double>& edges,
                                      const Eigen::MatrixXd& Hk) {
  std::vector<double> found(r.flux_rows.size());
#pragma omp parallel for schedule(static)
  for (std::size_t m = 0; m < r.flux_rows.size(); ++m) {
    const Index i = r.flux_rows[m];
    double e = condition_of(p, i).value;
    for (Index k = 0; k < r.B; ++k) e += r.eps(i, k) * Hk(i, k);
    found[m] = band_temperature(edges, r.eps_of_group[static_cast<std::size_t>((*p.group)[static_cast<std::size_t>(i)])], e);
  }
  return found;
}

}  // namespace

BandAnswer solve_bands(const BandProblem& p, const ThermalOptions& options) {
  const RadiositySolver& solver = *p.solver;
  const std::vector<double>& edges = options.band_edges_um;
  BandRows rows = band_rows(p, edges);
  const Index n = rows.n, B = rows.B;
  Eigen::MatrixXd split = Eigen::MatrixXd::Zero(n, B);
  const BandOperator M(solver.op(), rows.rho, rows.flux_eps, split);
  SolverOptions gmres;
  gmres.kind = SolverKind::gmres;
  gmres.max_iterations = options.max_iterations;
  BandAnswer out;
  Eigen::VectorXd J = Eigen::VectorXd::Zero(n * B), b;
  Eigen::MatrixXd Hk;
  double last_change = rows.flux_rows.empty() ? 0 : 1;
  AndersonMixing mixing(3);
  for (int round = 1;; ++round) {
    set_split(rows, edges, split);
    set_rhs(rows, p, split, b);
    // Early rounds, whose split is still off, need no more accuracy than the split has: GMRES to a
    // tenth of the last change of the temperatures (the final rounds to the tolerance asked).
    gmres.tolerance = std::max(options.tolerance, std::min(1e-4, 1e-1 * last_change));
    SolveResult r;
    if (round == 1) {
      r = solve_gmres(M, b, gmres, 1.0);
    } else {
      Eigen::VectorXd MJ;
      M.apply(J, MJ);
      r = solve_gmres_from(M, b, gmres, 1.0, J, b - J + MJ, 1);
    }
    out.iteration = r;
    out.products += r.iterations + 1;  // and the block product of H J below
    J = std::move(r.u);
    // H_k = H J_k + u_env,k s: one block product.
    solver.op().apply_block(Eigen::Map<const Eigen::MatrixXd>(J.data(), n, B), Hk);
    for (Index k = 0; k < B; ++k) Hk.col(k) += rows.u_env[k] * p.sky;
    if (rows.flux_rows.empty()) break;
    out.rounds = round;
    // One round maps the temperatures x of the flux rows to g; Anderson mixing of the last rounds
    // gives the next (a row whose temperature is not defined keeps its own and its split).
    const std::vector<double> found = flux_temperatures(rows, p, edges, Hk);
    Eigen::VectorXd x(static_cast<Eigen::Index>(found.size())), g(x.size());
    double change = 0;
    for (std::size_t m = 0; m < found.size(); ++m) {
      const auto e = static_cast<Eigen::Index>(m);
      x[e] = g[e] = rows.T[rows.flux_rows[m]];
      if (std::isnan(found[m])) continue;
      g[e] = found[m];
      change = std::max(change, std::abs(found[m] - x[e]) / found[m]);
    }
    out.change = last_change = change;
    // Settled when the temperatures moved by less than 1e-10 in a round solved to the tolerance
    // asked: the last round's own temperatures are the answer.
    if (change < 1e-10 && gmres.tolerance <= options.tolerance) {
      for (std::size_t m = 0; m < found.size(); ++m) rows.T[rows.flux_rows[m]] = found[m];
      break;
    }
    const Eigen::VectorXd mixed = mixing.next(x, g);
    for (std::size_t m = 0; m < found.size(); ++m) rows.T[rows.flux_rows[m]] = mixed[static_cast<Eigen::Index>(m)];
    if (round >= options.max_band_rounds) {
      out.warnings.push_back("the band temperatures changed by " + std::to_string(change) + " (relative) in the last of " +
                             std::to_string(round) + " rounds: not settled to 1e-10");
      break;
    }
  }
  out.J = Eigen::Map<const Eigen::MatrixXd>(J.data(), n, B).rowwise().sum();
  out.H = Hk.rowwise().sum();
  out.T = std::move(rows.T);
  return out;
}

}  // namespace panelrad::thermal_detail

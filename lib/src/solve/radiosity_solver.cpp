#include <panelrad/geometry/cluster_tree.hpp>
#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/solve/radiosity_solver.hpp>
#include <panelrad/scene/errors.hpp>
#include <panelrad/support/resources.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace panelrad {

ScaledOperator::ScaledOperator(const RadiosityOperator& H, Eigen::VectorXd row_scale)
    : H_(H), scale_(std::move(row_scale)) {
  if (scale_.size() != H_.size()) throw std::invalid_argument("ScaledOperator: scale size differs from n");
}

void ScaledOperator::apply(const Eigen::VectorXd& v, Eigen::VectorXd& y) const {
  H_.apply(v, y);
  y.array() *= scale_.array();  // (K v)_i = rho_i (H v)_i, (33)
}

int level_for_max_elements(geometry::Index n0, geometry::Index max_elements) {
  if (n0 <= 0) throw std::invalid_argument("level_for_max_elements: n0 must be positive");
  if (max_elements <= 0) throw std::invalid_argument("max elements must be positive");
  int level = 0;
  std::int64_t n = n0;
  while (n * 4 <= max_elements) {
    n *= 4;
    ++level;
  }
  return level;
}

namespace {

std::string fmt(const char* format, double a, double b = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, format, a, b);
  return buf;
}

/// The scene as the refusals name it: its source, or "scene".
std::string scene_name(const Scene& scene) {
  const std::string& source = scene.mesh().source;
  return source.empty() ? std::string("scene") : source;
}

std::string number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace

RadiositySolver::RadiositySolver(const Scene& scene, const SolveOptions& options)
    : scene_(scene), options_(options) {
  try {
    setup();
  } catch (const std::bad_alloc&) {
    throw ResourceError(out_of_memory_message(stage_, static_cast<double>(info_.memory.n), stage_bytes_));
  }
}

void RadiositySolver::say(const std::string& line) const {
  if (options_.progress) options_.progress(line);
}

void RadiositySolver::setup() {
  stage_ = "reading the options";
  options_.validate();
  const Index n0 = static_cast<Index>(scene_.mesh().triangles.size());
  info_.level = options_.level >= 0 ? options_.level : level_for_max_elements(n0, options_.max_elements);
  if (const std::string problem = geometry::level_size_problem(n0, info_.level); !problem.empty())
    throw ResourceError(scene_name(scene_) + ": " + problem);
  if (options_.fold_reflectivity && scene_.num_channels() != 1)
    throw std::invalid_argument("fold_reflectivity: the operator takes one channel's rho, the scene has " +
                                std::to_string(scene_.num_channels()));
  info_.visibility = options_.visibility;
  if (info_.visibility == Visibility::automatic)
    info_.visibility = scene_.shape() == geometry::SceneShape::convex ? Visibility::unoccluded : Visibility::occluded;
  if (const std::string why = visibility_problem(info_.visibility, scene_.shape()); !why.empty())
    throw std::invalid_argument(why);
  if (options_.communicator && options_.solver.kind == SolverKind::lu)
    throw std::invalid_argument("solver: LU factors the whole matrix I - K_n on one process; with several processes "
                                "use neumann, gmres or auto");
  info_.conditioning_reflectivity = scene_.max_reflectivity();  // NaN: rho given as a function
  choose_parameters_and_plan();
  discretize();
  if (std::isnan(info_.conditioning_reflectivity)) {
    // rho given as a function: its largest value is known once evaluated at the points (22).
    double rho_max = collocation_->reflectivity().maxCoeff();
    for (std::size_t c = 1; c < scene_.num_channels(); ++c) rho_max = std::max(rho_max, channel_values(c).rho.maxCoeff());
    info_.conditioning_reflectivity = rho_max;
    choose_parameters_and_plan();
  }
  info_.tolerance = options_.solver.tolerance > 0 ? options_.solver.tolerance  // 0: tied to h
                                                  : discretization_tolerance(info_.mesh_size, info_.diameter);
  build_operator();
}

// Steps 2-3: the parameters first, so that a size that cannot fit is refused before any work.
// With rho given as a function its maximum is not known before the collocation: the plan is then
// made for rho_max 0 (the loosest automatic parameters: a lower bound) and made again after it.
void RadiositySolver::choose_parameters_and_plan() {
  const double rho_max = std::isnan(info_.conditioning_reflectivity) ? 0.0 : info_.conditioning_reflectivity;
  if (options_.op.method == OperatorMethod::automatic) {
    info_.parameters = choose_parameters(problem_size(scene_.mesh(), info_.level), options_.accuracy, rho_max,
                                          info_.visibility);
    info_.parameters.local = options_.op.local;  // target clusters on or off, as asked
  } else {
    info_.parameters = options_.op;
  }
  LevelMemoryOptions memory;
  // fold: the collocation's rho, E (and u); else also the unit-weight copy's.
  memory.collocation_vectors = options_.fold_reflectivity ? 3 : 4;
  memory.field_bytes_per_element = options_.result_bytes_per_element;
  memory.channels_together = options_.fold_reflectivity ? 1 : static_cast<int>(scene_.num_channels());
  memory.target_clusters = info_.visibility == Visibility::unoccluded;
  SolverOptions planned_solver;
  planned_solver.kind = options_.solver.kind;
  info_.memory = estimate_level_memory(scene_.mesh(), info_.level, info_.parameters, planned_solver, rho_max, memory);
  refuse_levels_that_cannot_fit({info_.memory}, scene_name(scene_) + ": ");
}

// Step 4: subdivision, collocation points (22), rho and E of channel 0 (and u) at them.
void RadiositySolver::discretize() {
  const Index n0 = static_cast<Index>(scene_.mesh().triangles.size());
  say("subdividing " + std::to_string(n0) + " triangles " + std::to_string(info_.level) + " times: n = " +
      std::to_string(static_cast<long long>(n0) << (2 * info_.level)));
  stage_ = "subdividing: the cluster tree (40) and the collocation points (22)";
  stage_bytes_ = info_.memory.tree + info_.memory.collocation / 2;
  Stopwatch clock;
  collocation_.emplace(scene_, info_.level);
  info_.n = collocation_->size();
  info_.mesh_size = collocation_->tree().mesh_size();
  info_.diameter = collocation_->tree().diameter();
  info_.subdivision_s = clock.seconds();
  say(fmt("subdivision done in %.2f s", info_.subdivision_s));
}

std::unique_ptr<RadiosityOperator> RadiositySolver::make(const Collocation& rows, const OperatorOptions& parameters,
                                                         const RowRange& held, int probe_samples) {
  stage_ = "building the operator (" + describe_parameters(parameters) + ")";
  stage_bytes_ = info_.memory.op;
  OperatorOptions op = parameters;
  {
    // The products the solves will make, by expected_products with the ratio bound max rho (an
    // upper bound): each channel's iteration and its irradiance product. The fast operator stores
    // its far coefficients only when these repay their writing.
    const double rho = info_.conditioning_reflectivity;
    const ExpectedProducts e = expected_products(rho, rho, info_.tolerance);
    const int channels = options_.fold_reflectivity ? 1 : static_cast<int>(scene_.num_channels());
    const int per_channel = solver_kind(rho) == SolverKind::neumann ? e.neumann : e.gmres;
    op.expected_products = per_channel > 0 ? channels * (per_channel + 1) : 0;
  }
  // The operator's own stages (near field, far field) are named by its progress lines.
  return make_operator(rows, op, info_.visibility, [this](const std::string& line) {
    stage_ = "building the operator: " + line;
    say(line);
  }, held, probe_samples);
}

// Occluded scenes: the coverings (42), refined along every shadow, are most of the setup, and a
// smaller eta adds fewer far pairs than on a convex surface (the shadows refine anyway), so no
// rule of thumb says which stricter setting is the cheapest. The settings are measured on probes
// instead (FastOptions::probe_samples: an operator covering only the self-check's sampled rows,
// whose check equals the whole operator's bit for bit) and the operator is built once: with the
// first setting when its check passes, else with the stricter_settings whose check passes at the
// least product work (far pairs x Taylor terms + near pairs over the probed rows; a setting whose
// work is not below the cheapest passing one's so far is not checked); when none passes, the one
// with the smallest check.
void RadiositySolver::choose_by_probes(const Collocation& rows, OperatorOptions& op) {
  FastOptions base;
  base.near = op.near;
  base.occluders = scene_occluders(rows.tree());
  base.probe_samples = kSelfCheckSamples;
  base.single_precision_coefficients = single_precision_far_field(Visibility::occluded);  // as make() will
  base.single_precision_near = single_precision_near_field(Visibility::occluded);
  struct Trial {
    OperatorOptions options;
    FastSelfCheck check;
    double work = 0;
  };
  std::optional<FastSelfCheckReference> reference;
  // The probe of setting o; its check is skipped (+inf) when its work is not below `bound`.
  const auto trial = [&](const OperatorOptions& o, double bound) {
    FastOptions f = base;
    static_cast<ClusteringParameters&>(f) = o;
    stage_ = "probing the setting " + describe_parameters(o) + " on the self-check's rows";
    const FastOperator probe(rows, f);
    const FastStatistics& stats = probe.statistics();
    Trial t{o, {}, static_cast<double>(stats.far_pairs) * num_taylor_terms(o.degree) + static_cast<double>(stats.near_pairs)};
    if (!(t.work < bound)) {
      const double rows_probed = static_cast<double>(std::max<std::size_t>(1, reference->rows.size()));
      t.check.relative_error = std::numeric_limits<double>::infinity();
      say("probe, " + describe_parameters(o) + fmt(": product work %.3g per sampled row, not below the cheapest passing "
                                                   "setting's: not checked", t.work / rows_probed));
      return t;
    }
    if (!reference) reference = probe.self_check_reference(kSelfCheckSamples);
    t.check = probe.self_check(*reference);
    const double rows_probed = static_cast<double>(std::max(1, t.check.rows));
    say("probe, " + describe_parameters(o) + fmt(": self-check %.2e, product work %.3g per sampled row", t.check.relative_error,
                                                 t.work / rows_probed));
    return t;
  };
  const double unbounded = std::numeric_limits<double>::infinity();
  const double threshold = info_.self_check_threshold;
  Trial chosen = trial(op, unbounded);
  if (!(chosen.check.relative_error <= threshold)) {
    say(fmt("self-check %.2e above %.2e: probing stricter settings", chosen.check.relative_error, threshold));
    std::optional<Trial> best_passing;
    Trial smallest = chosen;
    for (const OperatorOptions& o : stricter_settings(op)) {
      Trial t = trial(o, best_passing ? best_passing->work : unbounded);
      if (t.check.relative_error <= threshold) {
        if (!best_passing || t.work < best_passing->work) best_passing = t;
      } else if (t.check.relative_error < smallest.check.relative_error) {
        smallest = t;
      }
    }
    const Trial& next = best_passing ? *best_passing : smallest;
    if (!(next.options == chosen.options)) {
      chosen = next;
      ++info_.tightened;
    }
  }
  op = chosen.options;
  info_.self_check = std::move(chosen.check);
}

// Steps 5-6: the operator, its self-check, and (automatic parameters) the one tighten loop.
void RadiositySolver::build_operator() {
  Stopwatch clock;
  const std::optional<Collocation> unit =
      options_.fold_reflectivity ? std::nullopt
                                 : std::optional<Collocation>(collocation_->with_row_weights(Eigen::VectorXd::Ones(info_.n)));
  const Collocation& rows = unit ? *unit : *collocation_;
  OperatorOptions& op = info_.parameters;
  const bool tighten = options_.op.method == OperatorMethod::automatic || options_.tighten_on_failed_check;
  if (op.method == OperatorMethod::fast)
    info_.self_check_threshold =
        self_check_threshold(problem_size(scene_.mesh(), info_.level), info_.conditioning_reflectivity,
                             options_.op.method == OperatorMethod::automatic ? options_.accuracy : 0.05);
  std::string why = tighten ? "(nothing stricter to try)" : "(manual parameters, not tightened)";
  if (op.method == OperatorMethod::fast && tighten && info_.visibility == Visibility::occluded)
    why = "(none of the stricter settings probed passes)";
  info_.partition.begin = {0, info_.n};
  if (options_.communicator) {
    build_rows_of_this_process(rows, op, tighten);
  } else if (op.method == OperatorMethod::fast && tighten && info_.visibility == Visibility::occluded) {
    say("fast operator: probing the setting on the self-check's sampled rows");
    choose_by_probes(rows, op);
    op_ = make(rows, op);  // its self-check is the probe's (the same rows, computed alike)
  } else {
    op_ = make(rows, op);
    if (dynamic_cast<const FastOperator*>(op_.get())) {
      say("fast operator: checking the product on sampled exact rows");
      bool built = true;  // op_ is the operator of op
      check_and_tighten(op, tighten, [&](const OperatorOptions& o) {
        if (!built) {
          op_.reset();  // free the looser operator before building the stricter one
          op_ = make(rows, o);
        }
        built = false;
        return dynamic_cast<const FastOperator&>(*op_).self_check(kSelfCheckSamples);
      });
    }
  }
  if (info_.self_check && !(info_.self_check->relative_error <= info_.self_check_threshold))
    info_.warnings.push_back(fmt("the fast product's measured relative error %.2e is above the accepted %.2e ",
                                 info_.self_check->relative_error, info_.self_check_threshold) +
                             why +
                             "; the answer may be less accurate than the discretization");
  info_.operator_bytes = op_->bytes();
  info_.operator_s = clock.seconds();
  say(fmt("operator ready in %.2f s: ", info_.operator_s) + describe_parameters(op) + ", " +
      format_bytes(static_cast<double>(info_.operator_bytes)));
}

// Step 6's loop: the self-check of the operator of `op` (check(op): that operator's, or its
// probe's), and while it fails and `tighten`, the next tighten_parameters and its check.
void RadiositySolver::check_and_tighten(OperatorOptions& op, bool tighten,
                                        const std::function<FastSelfCheck(const OperatorOptions&)>& check) {
  info_.self_check = check(op);
  while (tighten && !(info_.self_check->relative_error <= info_.self_check_threshold)) {
    const OperatorOptions stricter = tighten_parameters(op);
    if (stricter == op) break;  // nothing stricter
    say(fmt("self-check %.2e above %.2e: tightening", info_.self_check->relative_error, info_.self_check_threshold));
    op = stricter;
    ++info_.tightened;
    info_.self_check = check(op);
  }
}

// Steps 5-6 on one of several processes: the parameters chosen as build_operator chooses them on
// one process, each self-check on a probe of the sampled rows (the same check, bit for bit, at the
// cost of those rows); then the operator of this process's rows.
void RadiositySolver::build_rows_of_this_process(const Collocation& rows, OperatorOptions& op, bool tighten) {
  const Communicator& comm = *options_.communicator;
  if (op.method == OperatorMethod::fast && tighten && info_.visibility == Visibility::occluded) {
    say("fast operator: probing the setting on the self-check's sampled rows");
    choose_by_probes(rows, op);
  } else if (op.method == OperatorMethod::fast) {
    say("fast operator: checking the product on sampled exact rows (a probe of those rows)");
    check_and_tighten(op, tighten, [&](const OperatorOptions& o) {
      const std::unique_ptr<RadiosityOperator> probe = make(rows, o, {}, kSelfCheckSamples);
      return dynamic_cast<const FastOperator&>(*probe).self_check(kSelfCheckSamples);
    });
  }
  // The rows cut by the fast product's measured cost per block; the dense matrix's rows cost alike.
  const bool fast = op.method == OperatorMethod::fast;
  const std::shared_ptr<const geometry::Occluders> occluders =
      fast && info_.visibility == Visibility::occluded ? scene_occluders(rows.tree()) : nullptr;
  const std::vector<double> cost =
      fast ? fast_product_block_costs(rows, op.eta, op.degree, occluders.get(), op.near)
           : std::vector<double>(static_cast<std::size_t>((info_.n + kRowBlock - 1) / kRowBlock), 1.0);
  info_.partition = partition_rows(info_.n, cost, comm.size());
  const RowRange mine = info_.partition.rows(comm.rank());
  say("rows of " + std::to_string(comm.size()) + " processes cut by measured cost; process " +
      std::to_string(comm.rank()) + " holds [" + std::to_string(mine.begin) + ", " + std::to_string(mine.end) + ")");
  op_ = std::make_unique<RowBlockOperator>(make(rows, op, fast ? mine : RowRange{}), mine, comm);
  rows_op_ = static_cast<const RowBlockOperator*>(op_.get());
}

Eigen::VectorXd RadiositySolver::held(const Eigen::VectorXd& v) const { return rows_op_ ? rows_op_->rows_of(v) : v; }

Eigen::VectorXd RadiositySolver::whole(const Eigen::VectorXd& v) const { return rows_op_ ? rows_op_->gather(v) : v; }

Collocation::ChannelValues RadiositySolver::channel_values(std::size_t channel) const {
  if (channel >= scene_.num_channels())
    throw std::invalid_argument("channel " + std::to_string(channel) + ": the scene has " +
                                std::to_string(scene_.num_channels()));
  if (channel == 0) return {collocation_->reflectivity(), collocation_->emissivity()};
  return collocation_->channel_values(scene_, channel);
}

Eigen::VectorXd RadiositySolver::irradiance(const Eigen::VectorXd& u) const {
  if (options_.fold_reflectivity)
    throw std::logic_error("irradiance: the operator holds K_n = diag(rho) H (fold_reflectivity), not H");
  if (u.size() != info_.n) throw std::invalid_argument("irradiance: vector size differs from n");
  Eigen::VectorXd Hu;
  op_->apply(held(u), Hu);
  return whole(Hu);
}

const Eigen::VectorXd& RadiositySolver::uncovered() const {
  if (!uncovered_) {
    say("uncovered part of every hemisphere: 1 - H 1");
    uncovered_ = (1 - irradiance(Eigen::VectorXd::Ones(info_.n)).array()).cwiseMax(0.0).matrix();
  }
  return *uncovered_;
}

Eigen::VectorXd RadiositySolver::sky() const {
  return scene_.enclosed() ? Eigen::VectorXd::Zero(info_.n) : uncovered();
}

Eigen::VectorXd RadiositySolver::environment_light(std::size_t channel) const {
  if (!scene_.sees_environment(channel)) return Eigen::VectorXd::Zero(info_.n);
  return scene_.environment(channel) * uncovered();
}

// E + rho u_env s: the surfaces' emission and the environment's light they reflect.
Collocation::ChannelValues RadiositySolver::right_hand_side(std::size_t channel) const {
  Collocation::ChannelValues v = channel_values(channel);
  if (scene_.sees_environment(channel)) v.E += v.rho.cwiseProduct(environment_light(channel));
  return v;
}

ChannelSolve RadiositySolver::solve(std::size_t channel) const {
  const Collocation::ChannelValues v = right_hand_side(channel);
  return solve_values(v.rho, v.E, "channel " + scene_.channels()[channel]);
}

ChannelSolve RadiositySolver::solve(const Eigen::VectorXd& rho, const Eigen::VectorXd& E) const {
  if (rho.size() != info_.n || E.size() != info_.n)
    throw std::invalid_argument("solve: rho and E need one value per collocation point (n = " +
                                std::to_string(info_.n) + ")");
  for (Index i = 0; i < info_.n; ++i) {
    const std::string problem = reflectivity_problem(rho[i]);
    if (!problem.empty())
      throw std::invalid_argument("solve: rho = " + number(rho[i]) + " at collocation point " + std::to_string(i) +
                                  " " + problem);
    if (!std::isfinite(E[i]))
      throw std::invalid_argument("solve: E = " + number(E[i]) + " at collocation point " + std::to_string(i) +
                                  " is not a finite number");
  }
  return solve_values(rho, E, "data");
}

SolverOptions RadiositySolver::iteration_options(const std::string& label) const {
  SolverOptions solver = options_.solver;
  solver.tolerance = info_.tolerance;
  solver.communicator = options_.communicator;
  if (options_.progress)
    solver.progress = [this, label](int products, double estimate) {
      say(label + fmt(": product %.0f, error estimate %.2e", products, estimate));
    };
  return solver;
}

SolverKind RadiositySolver::solver_kind(double max_rho) const {
  return options_.solver.kind == SolverKind::automatic ? choose_solver(max_rho, info_.tolerance) : options_.solver.kind;
}

namespace {

ChannelSolve channel_solve(SolveResult&& r) {
  ChannelSolve out;
  out.status = r.status;
  out.message = std::move(r.message);
  out.u = std::move(r.u);
  out.solver = r.choice.empty() ? r.solver : r.choice;
  out.iterations = r.iterations;
  out.error_estimate = r.error_estimate;
  out.residual = r.residual;
  out.convergence_ratio = r.convergence_ratio;
  out.seconds = r.seconds;
  return out;
}

// The Neumann steps after which solve_channels compares the channels' expected costs: the
// ratio (36) is then measured over two successive steps.
constexpr int kStepsBeforeChoice = 3;
// The cost of each column of a block product beyond the first, in products of one column: the
// stored far field is read once for all columns (FastOperator::apply_block). Measured, 2 threads:
// 3 columns cost 1.35 single products on the Cornell box (n = 49,152, single-precision
// coefficients; bench/visibility) and 1.77 on the cube (n = 49,152, double; bench/product):
// 0.18 and 0.39 a column; the larger is taken.
constexpr double kBlockColumnCost = 0.4;

}  // namespace

ChannelSolve RadiositySolver::solve_values(const Eigen::VectorXd& rho, const Eigen::VectorXd& E,
                                           const std::string& label) const {
  if (options_.fold_reflectivity && !(rho.array() == collocation_->reflectivity().array()).all())
    throw std::invalid_argument("solve: the operator holds K_n with channel 0's rho (fold_reflectivity); "
                                "another rho needs a solver without fold_reflectivity");
  const double max_rho = rho.maxCoeff();
  const SolverOptions solver = iteration_options(label);
  stage_ = "solving " + label + " (32) with " + to_string(solver_kind(max_rho));
  stage_bytes_ = info_.memory.solver;
  SolveResult r;
  try {
    if (options_.fold_reflectivity) {
      r = panelrad::solve(*op_, held(E), solver, max_rho);
    } else {
      const ScaledOperator K(*op_, held(rho));
      r = panelrad::solve(K, held(E), solver, max_rho);
    }
    r.u = whole(r.u);
  } catch (const std::bad_alloc&) {
    throw ResourceError(out_of_memory_message(stage_, static_cast<double>(info_.n), stage_bytes_));
  }
  return channel_solve(std::move(r));
}

// The Neumann channels of solve_channels: (I - diag(rho_c) H) u_c = E_c, each its own iteration.
struct RadiositySolver::ChannelIteration {
  std::size_t slot;
  Eigen::VectorXd rho;
  double max_rho;
  NeumannIteration iteration;
  Stopwatch clock;
  bool handed = false;  // continued by GMRES (automatic)
};

std::vector<ChannelSolve> RadiositySolver::solve_channels(const std::vector<std::size_t>& channels) const {
  if (options_.fold_reflectivity)
    throw std::logic_error("solve_channels: the operator holds K_n = diag(rho) H (fold_reflectivity), not H");
  std::vector<ChannelSolve> out(channels.size());
  // automatic with several channels: Neumann steps them together (one block product a pass), and
  // each channel is handed to GMRES once its measured ratio says that costs fewer products.
  const bool automatic = options_.solver.kind == SolverKind::automatic;
  const bool together = automatic && channels.size() >= 2;
  std::vector<ChannelIteration> group;
  std::vector<std::string> labels(channels.size());
  for (std::size_t s = 0; s < channels.size(); ++s) {
    const Collocation::ChannelValues v = right_hand_side(channels[s]);
    labels[s] = "channel " + scene_.channels()[channels[s]];
    const double max_rho = v.rho.maxCoeff();
    const bool neumann = together ? std::isfinite(max_rho) : solver_kind(max_rho) == SolverKind::neumann;
    if (!neumann) {
      out[s] = solve_values(v.rho, v.E, labels[s]);
      out[s].irradiance = irradiance(out[s].u);
      continue;
    }
    if (!v.E.allFinite()) throw std::invalid_argument("solver: right-hand side has NaN or Inf entries");
    group.push_back({s, held(v.rho), max_rho, NeumannIteration(held(v.E), iteration_options(labels[s])), Stopwatch()});
  }
  stage_ = "solving " + std::to_string(group.size()) + " channels (32) together with neumann";
  stage_bytes_ = info_.memory.solver;
  try {
    iterate_together(group, labels, together, out);
  } catch (const std::bad_alloc&) {
    throw ResourceError(out_of_memory_message(stage_, static_cast<double>(info_.n), stage_bytes_));
  }
  for (std::size_t s = 0; s < channels.size(); ++s)  // the light arriving from the environment too
    if (scene_.sees_environment(channels[s])) out[s].irradiance += environment_light(channels[s]);
  return out;
}

void RadiositySolver::finish_channel(ChannelIteration& g, std::size_t group_size, ChannelSolve& out) const {
  SolveResult r = g.iteration.release();
  r.u = whole(r.u);
  r.seconds = g.clock.seconds();
  if (options_.solver.kind == SolverKind::automatic)
    r.choice = "auto: Neumann, " + std::to_string(group_size) + " channels together (block products); " +
               fmt("measured ratio %.3g, ", r.convergence_ratio) + fmt("max rho %.3g", g.max_rho);
  Eigen::VectorXd arriving = std::move(out.irradiance);
  out = channel_solve(std::move(r));
  out.irradiance = std::move(arriving);
}

// Neumann's remaining products (each a share of a block pass of `columns` columns) against GMRES's
// from the current iterate, both by expected_products with the measured ratio (36); GMRES
// continues the channel when it costs less.
void RadiositySolver::hand_over(ChannelIteration& g, std::size_t columns, const std::string& label,
                                const BlockedReductions& sums, ChannelSolve& out) const {
  const NeumannIteration& it = g.iteration;
  const double u_norm = sums.inf_norm(it.next());
  if (!(u_norm > 0)) return;
  const double reduction = sums.inf_norm(it.step()) / u_norm;
  const ExpectedProducts e = expected_products(it.ratio(), g.max_rho, info_.tolerance, reduction);
  if (e.neumann <= 0 || e.gmres <= 0) return;
  const double c = static_cast<double>(columns);
  const double neumann_cost = e.neumann * (1 + kBlockColumnCost * (c - 1)) / c;
  if (!(e.gmres < neumann_cost)) return;
  const ScaledOperator K(*op_, g.rho);
  Eigen::VectorXd previous = it.next() - it.step();  // u^(k), whose residual is the step
  SolveResult r =
      solve_gmres_from(K, it.rhs(), iteration_options(label), g.max_rho, std::move(previous), it.step(), it.steps());
  r.u = whole(r.u);
  r.seconds = g.clock.seconds();
  std::ostringstream why;
  why << "auto: Neumann for " << it.steps() << " steps, then GMRES: measured ratio " << it.ratio() << ", expected "
      << e.gmres << " more products against " << e.neumann << " Neumann steps in blocks of " << columns << " ("
      << neumann_cost << " products' cost)";
  r.choice = why.str();
  out = channel_solve(std::move(r));
  out.irradiance = irradiance(out.u);
  g.handed = true;
}

// Every channel still iterating takes one Neumann step per pass over H (apply_block).
void RadiositySolver::iterate_together(std::vector<ChannelIteration>& group, const std::vector<std::string>& labels,
                                       bool together, std::vector<ChannelSolve>& out) const {
  const BlockedReductions sums(options_.communicator);
  for (ChannelIteration& g : group)
    if (g.iteration.finished()) {  // E = 0: u = 0 without a product
      finish_channel(g, group.size(), out[g.slot]);
      out[g.slot].irradiance = Eigen::VectorXd::Zero(info_.n);
    }
  Eigen::MatrixXd V, Y;
  std::vector<std::size_t> active;
  for (;;) {
    active.clear();
    for (std::size_t j = 0; j < group.size(); ++j)
      if (!group[j].iteration.finished() && !group[j].handed) active.push_back(j);
    if (active.empty()) break;
    V.resize(op_->size(), static_cast<Eigen::Index>(active.size()));
    for (std::size_t a = 0; a < active.size(); ++a) V.col(static_cast<Eigen::Index>(a)) = group[active[a]].iteration.next();
    op_->apply_block(V, Y);  // H v of every channel still iterating, in one pass
    for (std::size_t a = 0; a < active.size(); ++a) {
      ChannelIteration& g = group[active[a]];
      const bool last = g.iteration.awaiting_residual();
      const Eigen::VectorXd Hv = Y.col(static_cast<Eigen::Index>(a));
      const Eigen::VectorXd Kv = Hv.cwiseProduct(g.rho);  // (K v)_i = rho_i (H v)_i, (33)
      g.iteration.take(Kv);
      if (last) {
        out[g.slot].irradiance = whole(Hv);  // H u of the final u: the light arriving
        finish_channel(g, group.size(), out[g.slot]);
      } else if (together && !g.iteration.finished() && !g.iteration.awaiting_residual() &&
                 g.iteration.steps() == kStepsBeforeChoice) {
        hand_over(g, active.size(), labels[g.slot], sums, out[g.slot]);
      }
    }
  }
}

}  // namespace panelrad

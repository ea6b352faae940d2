#pragma once
// The solver object: the radiosity equation (1), u - K u = E, on one scene, by centroid
// collocation (section 3) with the dense matrix (33) or the fast product of section 4 (K. Atkinson
// and D. Chien, "A fast matrix-vector multiplication method for solving the radiosity equation",
// Adv. Comput. Math. 12 (2000)). Stateful, in the style of Eigen's iterative solvers: the
// constructor does the setup once, then solve() runs the iteration (32) for as many right-hand
// sides as wanted.
//
// Setup (the constructor), in this order:
//   1. the level L: options.level, or the largest with n = n0 4^L <= options.max_elements;
//   2. the operator's parameters: automatic: choose_parameters(problem_size, options.accuracy, rho_max,
//      visibility), rho_max the largest reflectivity over all channels (the conditioning
//      1 / (1 - rho_max) of every channel's equation, (11)), visibility the resolved line of sight
//      (dense where the far field would be no cheaper than the matrix); dense or fast:
//      options.op;
//   3. the memory plan (memory_plan.hpp): a level that cannot fit is refused (ResourceError,
//      with the estimate) before anything is built;
//   4. the collocation (22): the elements of the level-L refinement, rho and E of channel 0 at
//      their centroids (and u for a manufactured scene);
//   5. the operator: the irradiance operator H, (H v)_i = 1/pi Int_S v G(P_i,Q) dS_Q, so that
//      K_c = diag(rho_c) H in every channel c (33); or, with options.fold_reflectivity, K_n itself
//      with the rho of channel 0 in its rows (the fast method then skips the rows with rho = 0);
//   6. the fast method: FastOperator::self_check against self_check_threshold; automatic
//      parameters (or manual ones with tighten_on_failed_check) are tightened
//      (tighten_parameters) and the operator rebuilt until the check passes or nothing is
//      stricter (a warning then). With V computed (occluded), the settings are measured on
//      probes of the sampled rows first (FastOptions::probe_samples) and the operator is built
//      once: the first setting when it passes, else the cheapest passing stricter_settings;
//   then solve_channels solves every channel, the Neumann ones in one pass over H per step.
//   7. the iteration's tolerance: options.solver.tolerance, or (<= 0) discretization_tolerance.
// solve(): (I - diag(rho) H) u = E by options.solver.kind (automatic: choose_solver(max rho)).
//
// Several processes (options.communicator): every process does steps 1-4 and the parameter
// choice of step 6 alike (the fast operator's self-check on probes of the sampled rows,
// FastOptions::probe_samples, whose check is the whole operator's bit for bit), then holds the
// rows of its part of the row partition (row_partition.hpp, cut by the measured cost of the rows)
// in a RowBlockOperator; the iterations run on those rows with the blocked reductions of
// solvers.hpp, and the answers (u, H u) are gathered whole on every process: the same bits as one
// process.
#include <panelrad/distributed/blocked_reductions.hpp>
#include <panelrad/distributed/row_block_operator.hpp>
#include <panelrad/distributed/row_partition.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/operator/linear_operator.hpp>
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/memory_plan.hpp>
#include <panelrad/solve/solvers.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace panelrad {

/// K v = diag(row_scale) (H v): a channel's operator K_n = diag(rho_c) H, (33).
class ScaledOperator final : public RadiosityOperator {
 public:
  /// Keeps a reference to H: H must outlive this operator.
  ScaledOperator(const RadiosityOperator& H, Eigen::VectorXd row_scale);
  geometry::Index size() const override { return H_.size(); }
  void apply(const Eigen::VectorXd& v, Eigen::VectorXd& y) const override;
  std::string name() const override { return H_.name(); }
  std::size_t bytes() const override { return H_.bytes() + static_cast<std::size_t>(scale_.size()) * sizeof(double); }

 private:
  const RadiosityOperator& H_;
  Eigen::VectorXd scale_;
};

struct SolveOptions {
  int level = -1;                        ///< refinement level; -1: the largest with n <= max_elements
  geometry::Index max_elements = 20000;  ///< used when level is -1 (level 0 at least)
  /// The operator, one struct: op.method automatic (the default) takes the measured rule of
  /// auto_parameters.hpp, self-checked and tightened, keeping op.local (the target clusters'
  /// local expansions on or off); dense or fast take op's near rule, eta and M as given.
  OperatorOptions op = [] {
    OperatorOptions o;
    o.method = OperatorMethod::automatic;
    return o;
  }();
  /// Automatic parameters (op.method automatic): the far field's error allowed, as a fraction of
  /// the discretization error (choose_parameters' margin; >= 0.05, the tightest measured).
  double accuracy = 0.05;
  /// Fast method with manual parameters: tighten them after a failed self-check, as automatic
  /// parameters always are (step 6).
  bool tighten_on_failed_check = false;
  /// V(P, Q): automatic computes it unless the scene is proven convex (Scene::shape), which is
  /// the paper's setting with no visibility work at all; occluded computes it on any scene;
  /// unoccluded on a general scene is a std::invalid_argument (V = 1 would be wrong there).
  Visibility visibility = Visibility::automatic;
  /// The iteration: kind (automatic: choose_solver), tolerance (0: discretization_tolerance(h,
  /// diam)), max_iterations, GMRES restart; its per-product callback is used when `progress` is
  /// empty.
  SolverOptions solver = [] {
    SolverOptions s;
    s.tolerance = 0;  // tied to the discretization error
    return s;
  }();
  /// K_n = diag(rho) H built into the operator with the rho of channel 0 (the paper's cube
  /// driver: rows with rho = 0 skipped). solve() then only takes that rho: another is a
  /// std::invalid_argument.
  bool fold_reflectivity = false;
  /// Bytes per element the caller will keep beside the solver (results), for the memory plan.
  std::size_t result_bytes_per_element = 0;
  /// Stage lines (subdivision, operator stages, self-check, each product) as they happen.
  std::function<void(const std::string&)> progress;
  /// The processes sharing the rows (nullptr: this process alone, holding every row). Every
  /// process makes the same calls (setup, solves) with the same scene and options; must outlive
  /// the solver. The LU solver is refused (it factors the whole matrix on one process).
  const Communicator* communicator = nullptr;
  /// std::invalid_argument naming the option and its value (option_checks.cpp), for: level below
  /// -1; max_elements < 1; accuracy outside [0.05, 1e6]; eta outside (0, 1), degree M outside
  /// 0..12, mu outside 0..8; a tolerance that is not finite, or negative (0 ties it to the
  /// discretization error); and SolverOptions::validate's max_iterations >= 1, gmres_restart >= 1.
  /// RadiositySolver (and so solve_scene, the cube runs and the Python module) calls it before
  /// any work.
  void validate() const;
};

/// One solve of (32).
struct ChannelSolve : IterationReport {
  Eigen::VectorXd u;           ///< u_n at the collocation points; the last iterate when not converged
  double convergence_ratio = 0;  ///< Neumann: (36)
  double seconds = 0;
  Eigen::VectorXd irradiance;  ///< H u, the light arriving (the product without rho): solve_channels only
};

/// What the setup did.
struct RadiositySolverInfo {
  int level = 0;
  geometry::Index n = 0;
  double mesh_size = 0, diameter = 0;  ///< h (longest element edge) and the surface's diameter
  double conditioning_reflectivity = 0;  ///< rho_max over all channels (step 2)
  OperatorOptions parameters;          ///< the operator that was built (after tightening)
  Visibility visibility = Visibility::unoccluded;  ///< resolved: unoccluded or occluded
  std::optional<FastSelfCheck> self_check;  ///< fast method: the last operator's check
  double self_check_threshold = 0;     ///< fast method: self_check_threshold(size, rho_max)
  int tightened = 0;                   ///< times automatic parameters were tightened
  double tolerance = 0;                ///< the iteration's relative tolerance (step 7)
  double subdivision_s = 0, operator_s = 0;  ///< step 4 (with rho, E, u); steps 5-6
  std::size_t operator_bytes = 0;
  LevelMemoryEstimate memory;          ///< step 3's estimate
  std::vector<std::string> warnings;   ///< e.g. a self-check above its threshold with nothing stricter
  RowPartition partition;              ///< the rows of each process (one process: [0, n))
};

class RadiositySolver {
 public:
  /// Rows sampled by the fast operator's self-check (step 6).
  static constexpr int kSelfCheckSamples = 32;
  /// Setup (header). Keeps a reference to `scene`: it must outlive the solver. Throws
  /// std::invalid_argument (bad options, SolveOptions::validate, or data, naming them),
  /// ResourceError (a size that does not fit, before any work, or an allocation that failed,
  /// naming the stage).
  explicit RadiositySolver(const Scene& scene, const SolveOptions& options = {});
  /// A temporary scene would not outlive the solver.
  RadiositySolver(Scene&&, const SolveOptions& = {}) = delete;

  const SolveOptions& options() const { return options_; }
  const RadiositySolverInfo& info() const { return info_; }
  int level() const { return info_.level; }
  geometry::Index n() const { return info_.n; }
  const OperatorOptions& parameters() const { return info_.parameters; }
  const std::optional<FastSelfCheck>& self_check() const { return info_.self_check; }
  double tolerance() const { return info_.tolerance; }
  const Collocation& collocation() const { return *collocation_; }
  /// H, or K_n with fold_reflectivity; with a communicator, the RowBlockOperator of this
  /// process's rows.
  const RadiosityOperator& op() const { return *op_; }
  std::size_t operator_bytes() const { return info_.operator_bytes; }

  /// rho_c(P_i), E_c(P_i) of the scene's channel c (checked by the scene's rule).
  Collocation::ChannelValues channel_values(std::size_t channel) const;
  /// H u: the light arriving at P_i (the product without rho). std::logic_error with
  /// fold_reflectivity (the operator has no H).
  Eigen::VectorXd irradiance(const Eigen::VectorXd& u) const;

  /// 1 - (H 1)_i, taken >= 0: the part of P_i's hemisphere (cosine-weighted) where no front side
  /// is seen, so where the light leaving P_i reaches no front side: it leaves the scene or falls on
  /// a back side. One product, on first use (every process calls it, with a communicator);
  /// std::logic_error with fold_reflectivity.
  const Eigen::VectorXd& uncovered() const;
  /// What of it is the environment (Scene::set_environment): uncovered() where the scene is not
  /// enclosed, else 0 (no product).
  Eigen::VectorXd sky() const;
  /// u_env s: the light arriving at P_i from the environment in `channel` (0 without one).
  Eigen::VectorXd environment_light(std::size_t channel) const;

  /// The scene's channel (its name in the progress lines), with its environment's light
  /// (Scene::set_environment): E + rho u_env s on the right-hand side.
  ChannelSolve solve(std::size_t channel) const;
  /// Any data at the collocation points: rho (each passing reflectivity_problem) and E (finite).
  ChannelSolve solve(const Eigen::VectorXd& rho, const Eigen::VectorXd& E) const;
  /// The scene's channels, each solved as solve(channel) solves it (the same iterates, bit for
  /// bit), with its irradiance H u (+ environment_light(channel)). The channels solved by the Neumann iteration (34) advance
  /// together: each step multiplies the iterates of all the channels still iterating in one
  /// pass over the operator (RadiosityOperator::apply_block), and the product that gives a
  /// channel's residual also gives its irradiance. Channels solved by GMRES or LU go one by
  /// one. std::logic_error with fold_reflectivity (the operator has no H).
  std::vector<ChannelSolve> solve_channels(const std::vector<std::size_t>& channels) const;

 private:
  void setup();
  void choose_parameters_and_plan();
  void discretize();
  void build_operator();
  void choose_by_probes(const Collocation& rows, OperatorOptions& op);
  std::unique_ptr<RadiosityOperator> make(const Collocation& rows, const OperatorOptions& op,
                                          const RowRange& held = {}, int probe_samples = 0);
  void build_rows_of_this_process(const Collocation& rows, OperatorOptions& op, bool tighten);
  void check_and_tighten(OperatorOptions& op, bool tighten,
                         const std::function<FastSelfCheck(const OperatorOptions&)>& check);
  /// This process's rows of a whole vector, and the whole vector from every process's rows.
  Eigen::VectorXd held(const Eigen::VectorXd& whole) const;
  Eigen::VectorXd whole(const Eigen::VectorXd& held) const;
  Collocation::ChannelValues right_hand_side(std::size_t channel) const;
  ChannelSolve solve_values(const Eigen::VectorXd& rho, const Eigen::VectorXd& E, const std::string& label) const;
  SolverOptions iteration_options(const std::string& label) const;
  SolverKind solver_kind(double max_rho) const;
  void say(const std::string& line) const;
  // solve_channels, in steps: the Neumann channels iterated together, one block product a pass.
  struct ChannelIteration;
  void iterate_together(std::vector<ChannelIteration>& group, const std::vector<std::string>& labels, bool together,
                        std::vector<ChannelSolve>& out) const;
  void finish_channel(ChannelIteration& g, std::size_t group_size, ChannelSolve& out) const;
  void hand_over(ChannelIteration& g, std::size_t columns, const std::string& label, const BlockedReductions& sums,
                 ChannelSolve& out) const;

  const Scene& scene_;
  SolveOptions options_;
  RadiositySolverInfo info_;
  std::optional<Collocation> collocation_;
  std::unique_ptr<RadiosityOperator> op_;
  const RowBlockOperator* rows_op_ = nullptr;  // op_, with a communicator
  // Where the setup is, so that an allocation failure can name the stage and its estimate.
  mutable std::string stage_;
  mutable std::size_t stage_bytes_ = 0;
  mutable std::optional<Eigen::VectorXd> uncovered_;  // uncovered(), once computed
};

/// The largest level L with n0 4^L <= max_elements (0 when even level 0 is larger).
int level_for_max_elements(geometry::Index n0, geometry::Index max_elements);

}  // namespace panelrad

#pragma once
// Solving a scene in one call: one RadiositySolver (one discretization, one operator H for all
// channels, K_c = diag(rho_c) H, (33)), every channel as one more right-hand side
// (I - diag(rho_c) H) u_c = E_c, (32), channels with identical data solved once, and the energy
// balance of each channel.
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/element_field.hpp>
#include <panelrad/solve/radiosity_solver.hpp>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace panelrad {

/// One channel's answer and its energy balance.
struct ChannelSolution : IterationReport {
  std::string name;
  Eigen::VectorXd radiosity;   ///< u_n at the collocation points (the last iterate when not converged)
  Eigen::VectorXd irradiance;  ///< H u_n: the light arriving at P_i (the product without rho)
  std::string shared_with;     ///< non-empty: identical data to this channel, solution copied
  /// Energy balance: emitted power sum A_i E_i against absorbed power sum A_i (1 - rho_i) H_i and
  /// the power that leaves front sides and reaches no front side, sum A_i u_i (1 - F_i), with
  /// F_i = (H 1)_i the visible form factors at P_i summed: it leaves the scene, or falls on the
  /// back of a one-sided surface, which neither reflects nor emits. In a closed scene F_i = 1 and
  /// emitted = absorbed; in any scene emitted = absorbed + escaped power, up to the discretization
  /// (point-to-element form factors are not reciprocal).
  double emitted = 0, absorbed = 0;
  /// The environment's power arriving, sum A_i u_env s_i (Scene::set_environment; 0 without one):
  /// on the emitted side of the balance.
  double environment_in = 0;
  /// |emitted + environment_in - absorbed - escaped power| / (emitted + environment_in) (0 when
  /// nothing enters): the error of the balance, whether the scene is closed or not.
  double energy_mismatch = 0;
  /// sum A_i u_i (1 - F_i) / (emitted + environment_in), each 1 - F_i taken >= 0: the fraction of
  /// the light that reaches no front side (0 in a closed scene, where F_i = 1 is not computed).
  /// Never negative.
  double escaped = 0;
  /// energy_balance_holds(energy_mismatch, the solution's expected_energy_mismatch).
  bool energy_balanced = true;
};

/// A mismatch above this many times its expected size fails the energy check.
inline constexpr double kEnergyMismatchAllowance = 4;
/// The energy check: `mismatch` is at most kEnergyMismatchAllowance times `expected` (false for
/// NaN).
bool energy_balance_holds(double mismatch, double expected);

struct SceneSolution {
  int level = 0;
  geometry::Index n = 0;
  double mesh_size = 0, diameter = 0;
  std::string method;                  ///< describe_parameters() of the operator that ran
  geometry::SceneShape shape = geometry::SceneShape::convex;  ///< Scene::shape
  bool closed = true;                  ///< Scene::closed: emitted = absorbed
  bool enclosed = true;                ///< Scene::enclosed: no light leaves (it may fall on back sides)
  Visibility visibility = Visibility::unoccluded;  ///< resolved (RadiositySolverInfo::visibility)
  VisibilityWork visibility_work;      ///< what computing V did (all 0 when unoccluded)
  OperatorOptions parameters;          ///< the operator that ran
  double self_check_error = -1;        ///< fast operator's measured relative product error; -1: dense
  double self_check_threshold = 0;     ///< self_check_threshold(size, rho_max over all channels)
  FastSelfCheck self_check;            ///< the last self-check, per test vector (fast method)
  int tightened = 0;                   ///< times automatic parameters were tightened after a check
  double subdivision_s = 0, operator_s = 0, solve_s = 0, total_s = 0;
  std::size_t operator_bytes = 0;
  double peak_rss_mb = 0;
  /// Expected size of the energy mismatch from the discretization: 0.5 h/diam (measured at most
  /// 0.35 h/diam); a mismatch above kEnergyMismatchAllowance times it fails the energy check.
  double expected_energy_mismatch = 0;
  /// Every channel passed the energy check. False: the solution breaks the conservation of
  /// energy far beyond its discretization error (an inaccurate operator, or front sides that see
  /// what the scene's shape says they cannot), so it is not to be trusted; a warning names the
  /// channel, and require_energy_balance() throws.
  bool energy_balanced = true;
  std::vector<ChannelSolution> channels;
  std::vector<std::string> warnings;   ///< e.g. an energy mismatch far above its expected size
  ElementField field;                  ///< everything the output writers need
  /// Every channel converged.
  bool converged() const;
  /// Throws SolverError with the message of the first channel that did not converge.
  void require_converged() const;
  /// Throws EnergyBalanceError with the message of the first channel that failed the energy check.
  void require_energy_balance() const;
};

/// Discretizes, builds one operator, solves every channel and checks the energy balance.
/// options.fold_reflectivity must be false (one H for every channel). Throws
/// std::invalid_argument (bad options), ResourceError (a size that does not fit). A channel
/// whose iteration does not converge keeps its last iterate, with its status and message, and a
/// warning; solution.require_converged() throws its SolverError. A channel that fails the energy
/// check keeps its solution, with a warning; solution.require_energy_balance() throws its
/// EnergyBalanceError. A scene that is not closed costs one more product, H 1.
SceneSolution solve_scene(const Scene& scene, const SolveOptions& options = {});

}  // namespace panelrad

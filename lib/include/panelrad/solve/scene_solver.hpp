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
  /// Energy balance: emitted power sum A_i E_i against absorbed power sum A_i (1 - rho_i) H_i.
  /// Equal in a closed scene (every ray from a front side hits a face); in an open one the
  /// difference is the power that escapes.
  double emitted = 0, absorbed = 0;
  double energy_mismatch = 0;  ///< |emitted - absorbed| / emitted (0 when nothing is emitted)
  double escaped = 0;          ///< (emitted - absorbed) / emitted: open scenes, the power fraction that leaves
};

struct SceneSolution {
  int level = 0;
  geometry::Index n = 0;
  double mesh_size = 0, diameter = 0;
  std::string method;                  ///< describe_parameters() of the operator that ran
  geometry::SceneShape shape = geometry::SceneShape::convex;  ///< Scene::shape
  bool closed = true;                  ///< Scene::closed: the energy balance applies
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
  /// 0.35 h/diam); a mismatch above 4 times it is a warning.
  double expected_energy_mismatch = 0;
  std::vector<ChannelSolution> channels;
  std::vector<std::string> warnings;   ///< e.g. an energy mismatch far above its expected size
  ElementField field;                  ///< everything the output writers need
  /// Every channel converged.
  bool converged() const;
  /// Throws SolverError with the message of the first channel that did not converge.
  void require_converged() const;
};

/// Discretizes, builds one operator, solves every channel and checks the energy balance.
/// options.fold_reflectivity must be false (one H for every channel). Throws
/// std::invalid_argument (bad options), ResourceError (a size that does not fit). A channel
/// whose iteration does not converge keeps its last iterate, with its status and message, and a
/// warning; solution.require_converged() throws its SolverError.
SceneSolution solve_scene(const Scene& scene, const SolveOptions& options = {});

}  // namespace panelrad

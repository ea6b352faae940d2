#pragma once
// Solving a scene with several colour channels: one discretization and one operator
// for all channels. The operator is the irradiance operator H, (H v)_i = 1/pi Int_S v G(P_i,Q) dS_Q,
// so that K_n = diag(rho_c) H in every channel c (paper (33)); each channel is then one more
// right-hand side: (I - diag(rho_c) H) u_c = E_c, (32).
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/operator/linear_operator.hpp>
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/scene/channel_scene.hpp>
#include <panelrad/solve/element_field.hpp>
#include <panelrad/solve/solvers.hpp>

#include <Eigen/Core>

#include <functional>
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

struct SceneSolveOptions {
  int levels = -1;                    ///< refinement levels; < 0: the largest with n <= max_elements
  geometry::Index max_elements = 20000;  ///< used when levels < 0 (level 0 at least)
  std::string method = "auto";        ///< auto (the measured rule of auto_parameters.hpp, self-checked) | dense | fast
  OperatorOptions manual;             ///< near rule, eta, M when method is dense or fast
  SolverKind solver = SolverKind::automatic;
  double tolerance = 0;               ///< relative; 0: discretization_tolerance(h, diam)
  /// Stage messages (subdivision, near field, far field, each iteration) as they happen.
  std::function<void(const std::string&)> progress;
};

/// One channel's answer and its energy balance.
struct ChannelSolution {
  std::string name;
  Eigen::VectorXd radiosity;   ///< u_n at the collocation points
  Eigen::VectorXd irradiance;  ///< H u_n: the light arriving at P_i (the product without rho)
  std::string solver;          ///< what ran, with the automatic choice's reason
  int iterations = 0;
  double residual = 0;         ///< ||E - (I - K) u||_inf / ||E||_inf
  double error_estimate = 0;   ///< solver's bound on ||u_n - u^(k)||_inf
  std::string shared_with;     ///< non-empty: identical data to this channel, solution copied
  /// Energy balance on a closed convex scene (every ray hits the surface): emitted power
  /// sum A_i E_i equals absorbed power sum A_i (1 - rho_i) H_i.
  double emitted = 0, absorbed = 0;
  double energy_mismatch = 0;  ///< |emitted - absorbed| / emitted (0 when nothing is emitted)
};

struct SceneSolution {
  int level = 0;
  geometry::Index n = 0;
  double mesh_size = 0, diameter = 0;
  std::string method;                  ///< describe_parameters() of the operator that ran
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
};

/// The largest level L with n0 4^L <= max_elements (0 when even level 0 is larger).
int level_for_max_elements(geometry::Index n0, geometry::Index max_elements);

/// Discretizes, builds one operator, solves every channel and checks the energy balance.
/// Throws std::invalid_argument (bad options), geometry::MeshError / std::runtime_error (a size
/// that does not fit), SolverError (no convergence).
SceneSolution solve_channel_scene(const ChannelScene& scene, const SceneSolveOptions& options = {});

}  // namespace panelrad

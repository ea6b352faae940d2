#pragma once
// Gray diffuse radiative heat transfer between surfaces, in SI units (lengths in metres): the
// radiosity equation (1) with the radiosity J (W/m^2), the irradiance H = H J + u_env s (the light
// arriving from the surfaces, by the solver's operator H of (33), and from the environment through
// the part s = 1 - H 1 of each hemisphere no front side covers), and per surface either
//   - a temperature T (K) and an emissivity eps in (0, 1]: E = eps sigma T^4, rho = 1 - eps, so
//     J = eps sigma T^4 + (1 - eps) H; or
//   - a net flux q = J - H (W/m^2, positive leaving; q = 0 an adiabatic, re-radiating wall):
//     E = q, rho = 1, so J = q + H; its temperature follows from J = eps sigma T^4 + (1 - eps) H:
//     sigma T^4 = H + q / eps.
// The environment (an open scene's sky) is black at T_env: u_env = sigma T_env^4. With rho = 1 on
// the re-radiating rows the Neumann series need not converge: (I - diag(rho) H) J = E + rho u_env s
// is solved by GMRES, its convergence reported. It is nonsingular when some surface with a given
// temperature absorbs (eps > 0) or an open scene sees its environment; without either (every
// surface's flux given) the temperatures are not determined and the problem is refused.
// Bands (a non-gray, band model): with wavelength band edges given, each band k is solved as its own
// radiosity equation, with eps_k in place of eps and the blackbody's share F_k(T) sigma T^4 of
// each band (blackbody.hpp) in place of sigma T^4; the environment emits F_k(T_env) sigma T_env^4 in
// band k. Where q is given the band emissions depend on the unknown T: such a surface emits in all
// bands together what it absorbs plus q, e = sum_k eps_k H_k + q, split among the bands in the
// ratios a_k = eps_k F_k(T) / sum_j eps_j F_j(T); so J_k = a_k (sum_j eps_j H_j + q) + (1 - eps_k) H_k.
// For a given split this couples the bands linearly (GMRES on the n B unknowns, one block product
// of H per step); T then follows from e = sum_k eps_k F_k(T) sigma T^4 (band_temperature), the
// split from T, and the two alternate until T changes by less than 1e-10 (a gray model needs no
// split: one band, a_1 = 1). J, H, q are reported summed over the bands.
// Energy: the net heat rates Q_I = sum_{i in I} A_i q_i of all groups sum to the net rate into
// the environment, sum_i A_i s_i (J_i - u_env) (0 in an enclosed scene), up to the discretization:
// the defect is reported.
#include <panelrad/scene/scene.hpp>
#include <panelrad/thermal/blackbody.hpp>
#include <panelrad/solve/radiosity_solver.hpp>
#include <panelrad/viewfactors/view_factors.hpp>

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace panelrad {

/// What one group's surfaces are held to.
struct SurfaceCondition {
  enum class Given { temperature, heat_flux };
  Given given = Given::temperature;
  /// T in K (finite, > 0) or the net flux q = J - H in W/m^2 (finite; 0: adiabatic).
  double value = 0;
  /// eps in (0, 1]: rho = 1 - eps where T is given; where q is given, eps only enters the
  /// temperature (sigma T^4 = H + q / eps).
  double emissivity = 1;
  /// With bands (ThermalOptions::band_edges_um): eps_k per band, each in [0, 1], some > 0; empty:
  /// `emissivity` in every band (a gray surface in a band model).
  std::vector<double> band_emissivity;
  /// eps in band k (0-based) of a model of `bands` bands.
  double emissivity_in(std::size_t k) const { return band_emissivity.empty() ? emissivity : band_emissivity[k]; }
};

struct ThermalOptions {
  /// The discretization and the operator, as a solve takes them (level or max_elements, method,
  /// accuracy, visibility, progress); the iteration below replaces its solver.
  SolveOptions solve;
  /// The environment's temperature in K (black): required for a scene that is not enclosed; an
  /// enclosed scene never sees it (an error to give one there is not made: it is unused, and
  /// ThermalSolution::warnings says so).
  std::optional<double> environment_temperature;
  /// GMRES's stopping tolerance (relative), and its limits.
  double tolerance = 1e-9;
  int max_iterations = 2000;
  /// Wavelength band edges in micrometres, finite, > 0 and increasing: the bands [0, e_0], [e_0,
  /// e_1], ..., [e_last, infinity). Empty: a gray model.
  std::vector<double> band_edges_um;
  /// The alternation of the split and the temperatures (bands with given fluxes): at most this
  /// many rounds.
  int max_band_rounds = 60;
};

struct ThermalSolution {
  int level = 0;
  geometry::Index n = 0;
  std::string method;             ///< describe_parameters of the operator
  double self_check_error = -1;   ///< the fast operator's measured relative product error; -1: dense
  IterationReport iteration;      ///< GMRES on (I - diag(rho) H) J = E + rho u_env s (bands: the last round's)
  std::vector<double> band_edges_um;  ///< as given (empty: gray)
  int band_rounds = 0;            ///< rounds of split and temperatures (0: gray, or no flux given)
  double band_change = 0;         ///< the last round's largest relative change of a temperature
  int band_products = 0;          ///< products of H with the bands' block, all rounds (0: gray)
  double seconds = 0;
  /// Per element of the finest level.
  std::vector<geometry::Index> facet, group;
  std::vector<std::array<geometry::Vec3, 3>> triangle;  ///< corners, as ElementField::triangle
  std::vector<geometry::Vec3> inner_normal;             ///< the front normal n of (1), as ElementField's
  std::vector<geometry::Vec3> centroid;
  Eigen::VectorXd area;
  Eigen::VectorXd J, H, q, T;     ///< W/m^2, W/m^2, W/m^2 (J - H), K
  /// Per group (area-weighted means; Q the net heat rate leaving, W).
  std::vector<std::string> names;
  Eigen::VectorXd group_area, group_T, group_q, group_Q;
  /// The net heat rate into the environment, sum_i A_i s_i (J_i - u_env), W (0 when enclosed).
  double environment_Q = 0;
  /// |sum_I Q_I - environment_Q| / (sum_I |Q_I| + |environment_Q|): the energy balance's defect
  /// (0 when no heat flows).
  double balance_defect = 0;
  bool enclosed = true;
  std::vector<std::string> warnings;
};

/// What is wrong with the conditions for `scene` and `groups` ("" when nothing): a count that is
/// not one per group, a temperature not finite and > 0, a flux not finite, an emissivity outside
/// (0, 1], band edges not finite, > 0 and increasing, band emissivities without band edges, not
/// one per band, outside [0, 1] or all 0, an environment temperature not finite and > 0, an open scene without one, or no
/// surface with a given temperature in an enclosed scene (the temperatures are then not
/// determined). Names the group.
std::string thermal_problem(const Scene& scene, const SurfaceGroups& groups,
                            const std::vector<SurfaceCondition>& conditions, const ThermalOptions& options);

/// Solves the problem above (thermal_problem must be "": std::invalid_argument with it otherwise).
/// The solver's errors pass through (ResourceError, std::invalid_argument for bad options); an
/// iteration that does not converge keeps its last iterate, with a warning.
ThermalSolution solve_thermal(const Scene& scene, const SurfaceGroups& groups,
                              const std::vector<SurfaceCondition>& conditions, const ThermalOptions& options = {});

}  // namespace panelrad

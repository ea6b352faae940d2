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
// Energy: the net heat rates Q_I = sum_{i in I} A_i q_i of all groups sum to the net rate into
// the environment, sum_i A_i s_i (J_i - u_env) (0 in an enclosed scene), up to the discretization:
// the defect is reported.
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/radiosity_solver.hpp>
#include <panelrad/viewfactors/view_factors.hpp>

#include <Eigen/Core>

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace panelrad {

/// The Stefan-Boltzmann constant, W m^-2 K^-4 (CODATA 2018, exact in the SI).
inline constexpr double kStefanBoltzmann = 5.670374419e-8;

/// What one group's surfaces are held to.
struct SurfaceCondition {
  enum class Given { temperature, heat_flux };
  Given given = Given::temperature;
  /// T in K (finite, > 0) or the net flux q = J - H in W/m^2 (finite; 0: adiabatic).
  double value = 0;
  /// eps in (0, 1]: rho = 1 - eps where T is given; where q is given, eps only enters the
  /// temperature (sigma T^4 = H + q / eps).
  double emissivity = 1;
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
};

struct ThermalSolution {
  int level = 0;
  geometry::Index n = 0;
  std::string method;             ///< describe_parameters of the operator
  double self_check_error = -1;   ///< the fast operator's measured relative product error; -1: dense
  IterationReport iteration;      ///< GMRES on (I - diag(rho) H) J = E + rho u_env s
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
/// (0, 1], an environment temperature not finite and > 0, an open scene without one, or no
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

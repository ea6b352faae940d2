// Gray diffuse radiative heat transfer (thermal_solve.hpp): the radiosity equation with given
// temperatures or net fluxes, solved by GMRES on the solver's operator H.
#include <panelrad/thermal/thermal_solve.hpp>

#include "band_solve.hpp"

#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/solve/solvers.hpp>
#include <panelrad/support/resources.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace panelrad {

using geometry::Index;

namespace {

// The reflectivity the operator's setup takes where a flux is given (rho = 1 there): the automatic
// parameters and the memory plan need rho < 1 (their conditioning 1 / (1 - rho), (11)); 0.9 asks
// for a far field ten times more accurate than at rho = 0, and GMRES then reports the solve.
constexpr double kReradiatingSetupReflectivity = 0.9;

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

/// A copy of the scene with rho per facet as the conditions give it (for the setup only).
Scene setup_scene(const Scene& scene, const SurfaceGroups& groups, const std::vector<SurfaceCondition>& conditions) {
  Scene setup = scene;
  std::vector<double> rho(static_cast<std::size_t>(scene.num_facets()));
  for (std::size_t f = 0; f < rho.size(); ++f) {
    const SurfaceCondition& c = conditions[static_cast<std::size_t>(groups.of_facet[f])];
    if (c.given != SurfaceCondition::Given::temperature) {
      rho[f] = kReradiatingSetupReflectivity;
    } else if (c.band_emissivity.empty()) {
      rho[f] = 1 - c.emissivity;
    } else {  // the band that reflects most, as a flux row where it reflects all
      rho[f] = std::min(1 - *std::min_element(c.band_emissivity.begin(), c.band_emissivity.end()),
                        kReradiatingSetupReflectivity);
    }
  }
  for (std::size_t ch = 0; ch < setup.num_channels(); ++ch) {
    setup.set_reflectivity(rho, ch);
    setup.set_emissivity(0.0, ch);
    setup.set_environment(0.0, ch);
  }
  return setup;
}

/// The groups' areas, mean temperatures and fluxes and net rates, the environment's rate and the
/// energy balance's defect, from the elements' values (sums in element order: the same for any
/// thread count).
void sum_groups(const std::vector<SurfaceCondition>& conditions, const Eigen::VectorXd& sky, double u_env,
                ThermalSolution& out) {
  const Index n = out.area.size();
  const Index G = static_cast<Index>(out.names.size());
  out.group_area = out.group_T = out.group_q = out.group_Q = Eigen::VectorXd::Zero(G);
  for (Index i = 0; i < n; ++i) {
    const Index g = out.group[static_cast<std::size_t>(i)];
    out.group_area[g] += out.area[i];
    out.group_T[g] += out.area[i] * out.T[i];
    out.group_Q[g] += out.area[i] * out.q[i];
    out.environment_Q += out.area[i] * sky[i] * (out.J[i] - u_env);
  }
  double flowing = std::abs(out.environment_Q);
  for (Index g = 0; g < G; ++g) {
    const SurfaceCondition& c = conditions[static_cast<std::size_t>(g)];
    out.group_T[g] = c.given == SurfaceCondition::Given::temperature ? c.value : out.group_T[g] / out.group_area[g];
    out.group_q[g] = out.group_Q[g] / out.group_area[g];
    flowing += std::abs(out.group_Q[g]);
  }
  if (std::isnan(out.T.sum()))
    out.warnings.push_back("some element's sigma T^4 = H + q / eps is negative (a flux drawn from it larger than "
                           "what it receives): its temperature is not defined (NaN)");
  out.balance_defect = flowing > 0 ? std::abs(out.group_Q.sum() - out.environment_Q) / flowing : 0;
}

/// The band model (band_solve.hpp): J, H, q and T summed over the bands, the groups' sums.
void solve_with_bands(const RadiositySolver& solver, const std::vector<SurfaceCondition>& conditions,
                      const ThermalOptions& options, const Eigen::VectorXd& sky, double u_env, ThermalSolution& out) {
  thermal_detail::BandProblem problem;
  problem.solver = &solver;
  problem.conditions = &conditions;
  problem.group = &out.group;
  problem.area = out.area;
  problem.sky = sky;
  problem.environment_temperature = u_env > 0 ? *options.environment_temperature : 0.0;
  thermal_detail::BandAnswer bands = thermal_detail::solve_bands(problem, options);
  out.band_edges_um = options.band_edges_um;
  out.iteration = bands.iteration;
  out.band_rounds = bands.rounds;
  out.band_change = bands.change;
  out.band_products = bands.products;
  if (!bands.iteration.converged()) out.warnings.push_back("the iteration did not converge: " + bands.iteration.message);
  for (std::string& w : bands.warnings) out.warnings.push_back(std::move(w));
  out.J = std::move(bands.J);
  out.H = std::move(bands.H);
  out.q = out.J - out.H;
  out.T = std::move(bands.T);
  sum_groups(conditions, sky, u_env, out);
}

}  // namespace

std::string thermal_problem(const Scene& scene, const SurfaceGroups& groups,
                            const std::vector<SurfaceCondition>& conditions, const ThermalOptions& options) {
  if (std::string why = groups_problem(scene, groups); !why.empty()) return why;
  if (conditions.size() != groups.names.size())
    return "thermal: " + std::to_string(conditions.size()) + " conditions for " + std::to_string(groups.names.size()) +
           " groups";
  const std::vector<double>& edges = options.band_edges_um;
  for (std::size_t k = 0; k < edges.size(); ++k)
    if (!(std::isfinite(edges[k]) && edges[k] > 0 && (k == 0 || edges[k] > edges[k - 1])))
      return "thermal: the band edges must be finite, > 0 and increasing (micrometres); edge " + std::to_string(k + 1) +
             " is " + number(edges[k]);
  bool absorbing = false;
  for (std::size_t g = 0; g < conditions.size(); ++g) {
    const SurfaceCondition& c = conditions[g];
    const std::string who = "thermal: group '" + groups.names[g] + "': ";
    if (!c.band_emissivity.empty()) {
      if (edges.empty()) return who + "an emissivity per band, but no band edges are given";
      if (c.band_emissivity.size() != edges.size() + 1)
        return who + std::to_string(c.band_emissivity.size()) + " band emissivities for " +
               std::to_string(edges.size() + 1) + " bands (" + std::to_string(edges.size()) + " edges)";
      bool some = false;
      for (std::size_t k = 0; k < c.band_emissivity.size(); ++k) {
        const double e = c.band_emissivity[k];
        if (!(e >= 0 && e <= 1)) return who + "the emissivity of band " + std::to_string(k + 1) + ", " + number(e) + ", is not in [0, 1]";
        some = some || e > 0;
      }
      if (!some) return who + "every band emissivity is 0: the surface neither emits nor absorbs, so its temperature is not defined";
      if (c.given == SurfaceCondition::Given::temperature) {
        if (!(std::isfinite(c.value) && c.value > 0)) return who + "temperature " + number(c.value) + " K is not finite and > 0";
        absorbing = true;
      } else if (!std::isfinite(c.value)) {
        return who + "heat flux " + number(c.value) + " W/m^2 is not finite";
      }
      continue;
    }
    if (!(c.emissivity > 0 && c.emissivity <= 1)) return who + "emissivity " + number(c.emissivity) + " is not in (0, 1]";
    if (c.given == SurfaceCondition::Given::temperature) {
      if (!(std::isfinite(c.value) && c.value > 0)) return who + "temperature " + number(c.value) + " K is not finite and > 0";
      absorbing = true;
    } else if (!std::isfinite(c.value)) {
      return who + "heat flux " + number(c.value) + " W/m^2 is not finite";
    }
  }
  if (options.environment_temperature) {
    const double t = *options.environment_temperature;
    if (!(std::isfinite(t) && t > 0)) return "thermal: the environment's temperature " + number(t) + " K is not finite and > 0";
  } else if (!scene.enclosed()) {
    return "thermal: the scene is open (light leaves it): give the environment's temperature, or close the scene";
  }
  if (!absorbing && scene.enclosed())
    return "thermal: every group has a given heat flux and the scene is enclosed: nothing fixes the temperatures "
           "(give one group a temperature)";
  return "";
}

ThermalSolution solve_thermal(const Scene& scene, const SurfaceGroups& groups,
                              const std::vector<SurfaceCondition>& conditions, const ThermalOptions& options) {
  if (const std::string why = thermal_problem(scene, groups, conditions, options); !why.empty())
    throw std::invalid_argument(why);
  if (options.solve.communicator) throw std::invalid_argument("thermal: one process only (the solver's communicator is set)");
  Stopwatch clock;
  const Scene setup = setup_scene(scene, groups, conditions);
  const RadiositySolver solver(setup, options.solve);
  const Collocation& col = solver.collocation();
  const Index n = col.size();
  ThermalSolution out;
  out.level = solver.level();
  out.n = n;
  out.method = describe_parameters(solver.parameters());
  if (solver.self_check()) out.self_check_error = solver.self_check()->relative_error;
  out.enclosed = scene.enclosed();
  out.names = groups.names;
  if (options.environment_temperature && scene.enclosed())
    out.warnings.push_back("the scene is enclosed: no surface sees the environment, whose temperature is unused");
  const double sigma = kStefanBoltzmann;
  const double u_env = options.environment_temperature && !scene.enclosed()
                           ? sigma * std::pow(*options.environment_temperature, 4)
                           : 0.0;
  const Eigen::VectorXd sky = u_env > 0 ? solver.sky() : Eigen::VectorXd::Zero(n);
  Eigen::VectorXd rho(n), E(n);
  out.area.resize(n);
  for (Index i = 0; i < n; ++i) {
    const Index g = groups.of_facet[static_cast<std::size_t>(col.facet(i))];
    const SurfaceCondition& c = conditions[static_cast<std::size_t>(g)];
    const bool hot = c.given == SurfaceCondition::Given::temperature;
    rho[i] = hot ? 1 - c.emissivity : 1.0;
    E[i] = hot ? c.emissivity * sigma * std::pow(c.value, 4) : c.value;
    E[i] += rho[i] * u_env * sky[i];
    const geometry::Cluster& e = col.tree().elements()[static_cast<std::size_t>(i)];
    out.facet.push_back(col.facet(i));
    out.group.push_back(g);
    out.triangle.push_back(e.vertex);
    out.inner_normal.push_back(e.normal);
    out.centroid.push_back(col.collocation_point(i));
    out.area[i] = e.area;
  }
  if (!options.band_edges_um.empty()) {
    solve_with_bands(solver, conditions, options, sky, u_env, out);
    out.seconds = clock.seconds();
    return out;
  }
  // (I - diag(rho) H) J = E + rho u_env s by GMRES (rho = 1 on the re-radiating rows).
  SolverOptions gmres;
  gmres.kind = SolverKind::gmres;
  gmres.tolerance = options.tolerance;
  gmres.max_iterations = options.max_iterations;
  const ScaledOperator K(solver.op(), rho);
  SolveResult r = solve_gmres(K, E, gmres, rho.maxCoeff());
  out.iteration = r;
  if (!r.converged()) out.warnings.push_back("the iteration did not converge: " + r.message);
  out.J = std::move(r.u);
  out.H = solver.irradiance(out.J) + u_env * sky;
  out.q = out.J - out.H;
  out.T.resize(n);
  for (Index i = 0; i < n; ++i) {
    const SurfaceCondition& c = conditions[static_cast<std::size_t>(out.group[static_cast<std::size_t>(i)])];
    if (c.given == SurfaceCondition::Given::temperature) {
      out.T[i] = c.value;
      continue;
    }
    const double fourth = (out.H[i] + out.q[i] / c.emissivity) / sigma;
    out.T[i] = fourth >= 0 ? std::pow(fourth, 0.25) : std::nan("");
  }
  sum_groups(conditions, sky, u_env, out);
  out.seconds = clock.seconds();
  return out;
}

}  // namespace panelrad

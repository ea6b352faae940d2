// panelrad thermal: temperatures and net radiative heat fluxes of gray diffuse surfaces with given
// temperatures or fluxes (thermal/thermal_solve.hpp), in SI units, written as CSV and VTK.
#include "commands.hpp"
#include "options.hpp"
#include "processes.hpp"

#include <panelrad/io/scene_file.hpp>
#include <panelrad/io/text_output.hpp>
#include <panelrad/io/thermal_file.hpp>
#include <panelrad/io/thermal_output.hpp>
#include <panelrad/support/resources.hpp>
#include <panelrad/thermal/thermal_solve.hpp>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace panelrad::cli {

namespace {

const char* kThermalUsage =
    "usage: panelrad thermal SCENE --bc FILE [--groups facet|object|material] [--levels L | --max-elements N]\n"
    "                        [--method auto|dense|fast] [--eta E] [--degree M] [--near exact|quadrature] [--mu K]\n"
    "                        [--visibility auto|occluded] [--tol T] [--out PREFIX] [--threads T] [--quiet]\n"
    "  SCENE: an OFF, OBJ or STL mesh in metres (any set of planar polygons that do not cross, as `solve`\n"
    "  takes). Gray diffuse radiative exchange: FILE (JSON) gives every group either a temperature \"T\"\n"
    "  (K) and an \"emissivity\", or a net flux \"q\" leaving (W/m^2; 0: an adiabatic, re-radiating wall),\n"
    "  and the environment {\"T\": K} of an open scene (or \"none\"); a band model gives \"band_edges_um\"\n"
    "  and an emissivity per band: see docs/thermal.md. Groups as in\n"
    "  `viewfactors` (--groups, default object). The radiosity equation with rho = 1 - eps where T is\n"
    "  given and rho = 1, E = q where q is given is solved by GMRES (--tol, default 1e-9) on the fast\n"
    "  operator, the line of sight computed unless the scene is proven convex. Writes PREFIX_groups.csv\n"
    "  (group,area_m2,T_K,q_W_m2,Q_W and the environment's row), PREFIX.csv (per element J, H, q, T)\n"
    "  PREFIX.vtk, PREFIX.ply and PREFIX.png (T); PREFIX defaults to the scene's name with '_thermal' in the current directory.\n"
    "  The summary gives every group's rate and the energy balance (sum of the rates against what the\n"
    "  environment takes) with its defect.\n"
    "  Exit status: 0 written; 1 invalid input or failed run (nothing written); 2 usage error.\n";

struct ThermalCommandLine {
  std::string scene_path, bc_path, prefix, groups = "object";
  ThermalOptions o;
  bool quiet = false;
  int threads = 0;
};

void add_thermal_options(CLI::App& app, ThermalCommandLine& line) {
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  app.add_option("SCENE", line.scene_path);
  add_operator_options(app, line.o.solve);
  app.add_option("--bc", line.bc_path)->type_name("FILE");
  app.add_option("--groups", line.groups)->type_name("facet|object|material")->check(one_of({"facet", "object", "material"}));
  app.add_option("--tol", line.o.tolerance)->type_name("T")->transform(tolerance_in(1e-15, 0.5));
  app.add_option("--out", line.prefix)->type_name("PREFIX")->check([](const std::string& prefix) {
    return prefix.empty() ? std::string("the prefix is empty") : std::string();
  });
  app.add_option("--threads", line.threads)->type_name("T")->transform(thread_count());
  app.add_flag("--quiet", line.quiet);
}

void print_summary(const ThermalSolution& s, const std::string& scene_path) {
  std::printf("scene: %s\n", scene_path.c_str());
  std::printf("level %d, n = %d, %s", s.level, static_cast<int>(s.n), s.method.c_str());
  if (s.self_check_error >= 0) std::printf(", self-check %.2e", s.self_check_error);
  std::printf(", %.2f s\n", s.seconds);
  std::printf("iteration: %s, %d products, residual %.2e\n", s.iteration.converged() ? "converged" : "NOT converged",
              s.iteration.iterations, s.iteration.residual);
  if (!s.band_edges_um.empty()) {
    std::printf("bands: %d (edges", static_cast<int>(s.band_edges_um.size() + 1));
    for (double e : s.band_edges_um) std::printf(" %g", e);
    std::printf(" um); %d rounds of the split with the temperatures (last change %.1e), %d block products in all\n",
                s.band_rounds, s.band_change, s.band_products);
  }
  std::printf("%-24s %12s %10s %14s %14s\n", "group", "area m^2", "T K", "q W/m^2", "Q W");
  for (std::size_t g = 0; g < s.names.size(); ++g) {
    const auto k = static_cast<Eigen::Index>(g);
    std::printf("%-24s %12.6g %10.4f %14.6g %14.6g\n", s.names[g].c_str(), s.group_area[k], s.group_T[k], s.group_q[k],
                s.group_Q[k]);
  }
  if (s.enclosed)
    std::printf("energy balance: the scene is enclosed, so the net rates sum to 0: sum %.6g W, defect %.2e\n",
                s.group_Q.sum(), s.balance_defect);
  else
    std::printf("energy balance: the net rates sum to what the environment takes, %.6g W: sum %.6g W, defect %.2e\n",
                s.environment_Q, s.group_Q.sum(), s.balance_defect);
}

int run_thermal(const CLI::App& app, ThermalCommandLine& line) {
  if (app.count("SCENE") == 0) throw UsageError("no scene given");
  if (line.bc_path.empty()) throw UsageError("no boundary conditions given (--bc FILE)");
  check_operator_options(app, line.o.solve);
  if (line.prefix.empty()) line.prefix = std::filesystem::path(line.scene_path).stem().string() + "_thermal";
  check_prefix(line.prefix);
  if (!writes_outputs()) return 0;  // one process computes (solve_thermal shares no rows)
  install_output_signal_handlers();
  set_threads(line.threads);
  ThermalOptions o = line.o;
  if (!line.quiet) o.solve.progress = [](const std::string& s) { std::cerr << "panelrad thermal: " << s << "\n"; };
  LoadOptions load;
  load.geometry_only = line.groups != "material";
  const Scene scene = load_scene(line.scene_path, load);  // errors: exit 1 (main)
  if (!line.quiet)
    for (const std::string& note : scene.notes()) std::cerr << "panelrad thermal: note: " << note << "\n";
  SurfaceGroups groups;
  try {
    groups = line.groups == "facet"    ? groups_by_facet(scene)
             : line.groups == "object" ? groups_by_object(scene)
                                       : groups_by_material(scene);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(line.scene_path + ": " + e.what());
  }
  const ThermalConditions bc = read_thermal_conditions(line.bc_path, groups);
  o.environment_temperature = bc.environment_temperature;
  o.band_edges_um = bc.band_edges_um;
  if (const std::string why = thermal_problem(scene, groups, bc.conditions, o); !why.empty())
    throw std::runtime_error(line.bc_path + ": " + why);
  for (const std::string& path : thermal_paths(line.prefix)) check_output_path(path);
  const ThermalSolution s = solve_thermal(scene, groups, bc.conditions, o);
  if (!s.iteration.converged()) throw std::runtime_error("thermal: " + s.iteration.message);
  const std::vector<std::string> written = write_thermal(s, line.prefix);
  print_summary(s, line.scene_path);
  for (const std::string& w : s.warnings) std::fprintf(stderr, "panelrad thermal: warning: %s\n", w.c_str());
  for (const std::string& f : written) std::printf("wrote %s\n", f.c_str());
  return 0;
}

}  // namespace

Command add_thermal(CLI::App& panelrad) {
  auto line = std::make_shared<ThermalCommandLine>();
  CLI::App* app = panelrad.add_subcommand("thermal", "temperatures and heat fluxes of gray diffuse surfaces, SI units");
  set_usage(*app, kThermalUsage);
  add_thermal_options(*app, *line);
  return {app, [app, line] { return run_thermal(*app, *line); }};
}

}  // namespace panelrad::cli

// panelrad viewfactors: the view factors between groups of a scene's surfaces, written as CSV and
// .npy, with their closure, reciprocity and error estimates.
#include "commands.hpp"
#include "options.hpp"
#include "processes.hpp"

#include <panelrad/io/scene_file.hpp>
#include <panelrad/io/text_output.hpp>
#include <panelrad/io/view_factor_output.hpp>
#include <panelrad/support/resources.hpp>
#include <panelrad/viewfactors/view_factors.hpp>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace panelrad::cli {

namespace {

const char* kViewFactorsUsage =
    "usage: panelrad viewfactors SCENE [--groups facet|object|material] [--levels L | --max-elements N]\n"
    "                            [--method auto|dense|fast] [--eta E] [--degree M] [--near exact|quadrature]\n"
    "                            [--mu K] [--visibility auto|occluded]\n"
    "                            [--no-estimate] [--reciprocal] [--two-sided GROUP]... [--elements]\n"
    "                            [--elements-to GROUP]...\n"
    "                            [--out PREFIX] [--threads T] [--quiet]\n"
    "  SCENE: an OFF, OBJ or STL mesh (any set of planar polygons that do not cross, as `solve` takes).\n"
    "  F_IJ is the fraction of the radiation leaving group I diffusely that reaches group J directly,\n"
    "  the line of sight computed unless the scene is proven convex. --groups facet (default): every\n"
    "  input face its own group; object: the faces of one OBJ object or group (o, g) or ASCII STL solid;\n"
    "  material: the faces of one OBJ material (usemtl; the OBJ's MTL is read). A sheet is one-sided,\n"
    "  its front side from the file's winding; --two-sided GROUP (repeatable) gives the group's back\n"
    "  side as a group of its own, 'GROUP (back)'.\n"
    "  --levels L refines L times (n = 4^L n0); --max-elements N (default 20000) takes the largest level\n"
    "  with n <= N. The factors are also computed one level coarser and |F(L) - F(L-1)| is written as\n"
    "  their error estimate (--no-estimate: not). --reciprocal makes the matrix reciprocal (A_I F_IJ =\n"
    "  A_J F_JI) and closed (rows summing to 1 in an enclosed scene), as thermal models need, and says\n"
    "  by how much it moved. Writes PREFIX.csv (per group: area, F to every group, and 1 - sum_J F_IJ:\n"
    "  the sky view factor of an open scene, the closure defect of an enclosed one), PREFIX_error.csv\n"
    "  (the estimates), PREFIX.npy (F as float64, numpy.load) and with --elements PREFIX_elements.csv\n"
    "  PREFIX_elements.vtk and PREFIX_elements.ply (per element its group, centroid, area and sky view factor, and with\n"
    "  --elements-to GROUP, repeatable, its view factor to that group); PREFIX defaults to the scene's name\n"
    "  with '_viewfactors' in the current directory. A summary goes to stdout.\n"
    "  Exit status: 0 written; 1 invalid input or failed run (nothing written); 2 usage error.\n";

struct ViewFactorsCommandLine {
  std::string scene_path, prefix, groups = "facet";
  std::vector<std::string> two_sided;  // --two-sided: groups whose back sides radiate too
  ViewFactorOptions o;
  bool no_estimate = false, quiet = false;
  int threads = 0;
};

void add_view_factor_options(CLI::App& app, ViewFactorsCommandLine& line) {
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  app.add_option("SCENE", line.scene_path);
  add_operator_options(app, line.o.solve);
  app.add_option("--groups", line.groups)->type_name("facet|object|material")->check(one_of({"facet", "object", "material"}));
  app.add_option("--out", line.prefix)->type_name("PREFIX")->check([](const std::string& prefix) {
    return prefix.empty() ? std::string("the prefix is empty") : std::string();
  });
  app.add_flag("--no-estimate", line.no_estimate);
  app.add_flag("--reciprocal", line.o.reciprocal);
  app.add_option("--two-sided", line.two_sided)->type_name("GROUP")->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  app.add_flag("--elements", line.o.elements);
  app.add_option("--elements-to", line.o.element_targets)
      ->type_name("GROUP")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  app.add_option("--threads", line.threads)->type_name("T")->transform(thread_count());
  app.add_flag("--quiet", line.quiet);
}

void print_summary(const ViewFactors& v, const std::string& scene_path, const std::string& groups) {
  std::printf("scene: %s\n", scene_path.c_str());
  std::printf("groups: %zu (%s)\n", v.names.size(), groups.c_str());
  std::printf("level %d, n = %d, %s", v.level, static_cast<int>(v.n), v.method.c_str());
  if (v.self_check_error >= 0) std::printf(", self-check %.2e", v.self_check_error);
  std::printf(", %.2f s\n", v.seconds);
  double largest = 0, largest_error = 0;
  for (Eigen::Index I = 0; I < v.uncovered.size(); ++I) largest = std::max(largest, std::abs(v.uncovered[I]));
  if (v.error.size() > 0) largest_error = v.error.maxCoeff();
  if (v.enclosed)
    std::printf("closure: the scene is enclosed; largest |1 - sum_J F_IJ| %.3e\n", largest);
  else
    std::printf("sky: the scene is open; largest sky view factor %.6f\n", v.uncovered.maxCoeff());
  if (v.reciprocity_I >= 0)
    std::printf("reciprocity: largest |A_I F_IJ - A_J F_JI| / max %.3e (%s, %s)\n", v.reciprocity_defect,
                v.names[static_cast<std::size_t>(v.reciprocity_I)].c_str(),
                v.names[static_cast<std::size_t>(v.reciprocity_J)].c_str());
  if (v.correction > 0) std::printf("made reciprocal and closed: F moved by %.3e at most\n", v.correction);
  if (v.error.size() > 0)
    std::printf("error estimate: largest |F(L) - F(L-1)| %.3e\n", largest_error);
  else
    std::printf("error estimate: not computed (%s)\n", v.level == 0 ? "level 0" : "--no-estimate");
}

int run_view_factors(const CLI::App& app, ViewFactorsCommandLine& line) {
  if (app.count("SCENE") == 0) throw UsageError("no scene given");
  check_operator_options(app, line.o.solve);
  if (line.prefix.empty()) line.prefix = std::filesystem::path(line.scene_path).stem().string() + "_viewfactors";
  check_prefix(line.prefix);
  // One process computes the view factors (compute_view_factors shares no rows); under mpirun the
  // other ranks have nothing to do.
  if (!writes_outputs()) return 0;
  const std::string& prefix = line.prefix;
  install_output_signal_handlers();
  set_threads(line.threads);
  ViewFactorOptions o = line.o;
  o.estimate_error = !line.no_estimate;
  if (!line.quiet) o.solve.progress = [](const std::string& s) { std::cerr << "panelrad viewfactors: " << s << "\n"; };
  LoadOptions load;
  load.geometry_only = line.groups != "material";  // the mesh alone; materials only to group by them
  std::optional<Scene> scene = load_scene(line.scene_path, load);  // errors: exit 1 (main)
  SurfaceGroups groups;
  try {
    groups = line.groups == "facet"    ? groups_by_facet(*scene)
             : line.groups == "object" ? groups_by_object(*scene)
                                       : groups_by_material(*scene);
    if (!line.two_sided.empty()) {
      TwoSidedScene two = with_back_sides(*scene, groups, line.two_sided);
      scene.emplace(std::move(two.scene));
      groups = std::move(two.groups);
    }
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(line.scene_path + ": " + e.what());
  }
  if (!line.quiet)
    for (const std::string& note : scene->notes()) std::cerr << "panelrad viewfactors: note: " << note << "\n";
  const bool with_elements = o.elements || !o.element_targets.empty();
  for (const std::string& path : view_factor_paths(prefix, o.estimate_error, with_elements)) check_output_path(path);
  const ViewFactors v = compute_view_factors(*scene, groups, o);
  const std::vector<std::string> written = write_view_factors(v, prefix);
  print_summary(v, line.scene_path, line.groups);
  for (const std::string& f : written) std::printf("wrote %s\n", f.c_str());
  return 0;
}

}  // namespace

Command add_view_factors(CLI::App& panelrad) {
  auto line = std::make_shared<ViewFactorsCommandLine>();
  CLI::App* app =
      panelrad.add_subcommand("viewfactors", "view factors between groups of surfaces of a scene, written as CSV/NPY");
  set_usage(*app, kViewFactorsUsage);
  add_view_factor_options(*app, *line);
  return {app, [app, line] { return run_view_factors(*app, *line); }};
}

}  // namespace panelrad::cli

// panelrad solve: a user's scene (OBJ + MTL, or OFF + JSON sidecar) solved in every colour channel
// with one operator, written as CSV, PLY, VTK and a PNG picture (issue 6).
#include "commands.hpp"
#include "options.hpp"

#include <panelrad/auto_parameters.hpp>
#include <panelrad/resources.hpp>
#include <panelrad/scene_file.hpp>
#include <panelrad/scene_output.hpp>
#include <panelrad/scene_solver.hpp>
#include <panelrad/text_output.hpp>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace panelrad::cli {

namespace {
const char* kSolveUsage =
    "usage: panelrad solve SCENE [--levels L | --max-elements N] [--out PREFIX] [--materials JSON]\n"
    "                      [--formats csv,ply,vtk,png] [--method auto|dense|fast] [--eta E] [--degree M]\n"
    "                      [--near exact|quadrature] [--mu K] [--solver auto|neumann|gmres] [--tol T|auto]\n"
    "                      [--threads T] [--quiet]\n"
    "  SCENE: an OBJ whose MTL gives Kd (reflectivity rho) and Ke (emission E) per face through usemtl,\n"
    "  or an OFF with a JSON sidecar (SCENE with extension .json, or --materials) giving rho and E per\n"
    "  facet. The scene must be a closed convex polyhedron. Every colour channel is solved with one\n"
    "  operator. --levels L refines L times (n = 4^L n0); --max-elements N (default 20000) takes the\n"
    "  largest level with n <= N. Writes PREFIX.csv (per-element radiosity), PREFIX.ply (per-face\n"
    "  colours), PREFIX.vtk (ParaView) and PREFIX.png (a picture of the inside); PREFIX defaults to\n"
    "  the scene's name with '_radiosity' in the current directory. Progress goes to stderr\n"
    "  (--quiet: none); a summary with the energy balance to stdout.\n";

std::string default_prefix(const std::string& scene) {
  return std::filesystem::path(scene).stem().string() + "_radiosity";
}
}  // namespace

int run_solve(int argc, char** argv) {
  std::string scene_path, prefix, materials, formats = "csv,ply,vtk,png";
  SceneSolveOptions o;
  bool quiet = false, levels_given = false, max_given = false, manual = false;
  int threads = 0;
  std::set<std::string> wanted;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "-h" || a == "--help") {
        std::cout << kSolveUsage;
        return 0;
      }
      if (a == "--quiet") {
        quiet = true;
        continue;
      }
      if (a.rfind("--", 0) != 0) {
        if (!scene_path.empty()) throw UsageError("more than one scene given ('" + scene_path + "', '" + a + "')");
        scene_path = a;
        continue;
      }
      if (i + 1 >= argc) throw UsageError("option '" + a + "' needs a value (or is unknown)");
      const std::string v = argv[++i];
      if (a == "--levels") {
        o.levels = parse_int(a, v, 0, 12);
        levels_given = true;
      } else if (a == "--max-elements") {
        o.max_elements = parse_int(a, v, 1, 1 << 30);
        max_given = true;
      } else if (a == "--out") prefix = v;
      else if (a == "--materials") materials = v;
      else if (a == "--formats") formats = v;
      else if (a == "--method") {
        if (v != "auto" && v != "dense" && v != "fast") throw UsageError("--method must be auto, dense or fast, got '" + v + "'");
        o.method = v;
      } else if (a == "--eta") {
        o.manual.eta = parse_double(a, v, 1e-3, 0.99);
        manual = true;
      } else if (a == "--degree") {
        o.manual.degree = parse_int(a, v, 0, 12);
        manual = true;
      } else if (a == "--near") {
        if (v != "exact" && v != "quadrature") throw UsageError("--near must be exact or quadrature, got '" + v + "'");
        o.manual.near.rule = parse_near_rule(v);
        manual = true;
      } else if (a == "--mu") {
        o.manual.near.mu = parse_int(a, v, 0, 6);
        manual = true;
      } else if (a == "--solver") {
        if (v != "auto" && v != "neumann" && v != "gmres")
          throw UsageError("--solver must be auto, neumann or gmres, got '" + v + "'");
        o.solver = parse_solver(v);
      } else if (a == "--tol") o.tolerance = v == "auto" ? 0.0 : parse_double(a, v, 1e-15, 0.5);
      else if (a == "--threads") threads = parse_int(a, v, 0, 1024);
      else throw UsageError("unknown option '" + a + "'");
    }
    if (scene_path.empty()) throw UsageError("no scene given");
    if (levels_given && max_given) throw UsageError("give --levels or --max-elements, not both");
    if (manual && o.method == "auto") throw UsageError("--eta, --degree, --near and --mu need --method dense or fast");
    std::stringstream list(formats);
    for (std::string f; std::getline(list, f, ',');) {
      if (f != "csv" && f != "ply" && f != "vtk" && f != "png")
        throw UsageError("--formats: '" + f + "' is not csv, ply, vtk or png");
      wanted.insert(f);
    }
  } catch (const UsageError& e) {
    std::cerr << "panelrad solve: " << e.what() << "\n" << kSolveUsage;
    return 2;
  }
  const auto wants = [&](const char* f) { return wanted.count(f) > 0; };
  if (prefix.empty()) prefix = default_prefix(scene_path);
  set_threads(threads);
  if (!quiet) o.progress = [](const std::string& line) { std::cerr << "panelrad solve: " << line << "\n"; };

  const ChannelScene scene = load_channel_scene(scene_path, materials);  // errors: exit 1 (main)
  if (!quiet)
    for (const std::string& note : scene.notes) std::cerr << "panelrad solve: note: " << note << "\n";
  // Fail on an unwritable output before a long run, not after it.
  write_file_atomically(prefix + ".probe", "");
  std::filesystem::remove(prefix + ".probe");

  const SceneSolution s = solve_channel_scene(scene, o);
  std::vector<std::string> written;
  if (wants("csv")) write_radiosity_csv(prefix + ".csv", s.field), written.push_back(prefix + ".csv");
  if (wants("ply")) write_radiosity_ply(prefix + ".ply", s.field), written.push_back(prefix + ".ply");
  if (wants("vtk")) write_radiosity_vtk(prefix + ".vtk", s.field), written.push_back(prefix + ".vtk");
  if (wants("png")) {
    RenderOptions view;
    view.view_direction = brightest_view_direction(s.field);  // look towards the light
    write_radiosity_png(prefix + ".png", s.field, view);
    written.push_back(prefix + ".png");
  }

  // Summary.
  std::printf("scene %s: %d facets, %zu channel%s\n", scene_path.c_str(), static_cast<int>(scene.mesh.num_facets),
              scene.num_channels(), scene.num_channels() > 1 ? "s" : "");
  std::printf("n = %d (level %d), h/diam = %.3e, %s\n", static_cast<int>(s.n), s.level, s.mesh_size / s.diameter,
              s.method.c_str());
  if (s.self_check_error >= 0)
    std::printf("fast product self-check: relative error %.2e (accepted up to %.2e%s)\n", s.self_check_error,
                s.self_check_threshold, s.tightened ? ", after tightening" : "");
  std::printf("time: subdivision %.2f s, operator %.2f s (%s), solve %.2f s, total %.2f s; peak memory %.0f MB\n",
              s.subdivision_s, s.operator_s, format_bytes(static_cast<double>(s.operator_bytes)).c_str(), s.solve_s,
              s.total_s, s.peak_rss_mb);
  std::printf("%-8s %10s %10s %12s %12s %12s  %s\n", "channel", "products", "residual", "emitted", "absorbed",
              "mismatch", "solver");
  for (const ChannelSolution& c : s.channels) {
    const std::string how = c.shared_with.empty() ? c.solver : "same data as " + c.shared_with;
    std::printf("%-8s %10d %10.2e %12.5e %12.5e %12.2e  %s\n", c.name.c_str(), c.iterations, c.residual, c.emitted,
                c.absorbed, c.energy_mismatch, how.c_str());
  }
  std::printf("energy balance: emitted = absorbed on a closed convex scene; mismatch expected below 0.5 h/diam = %.2e\n",
              s.expected_energy_mismatch);
  for (const std::string& w : s.warnings) std::fprintf(stderr, "panelrad solve: warning: %s\n", w.c_str());
  for (const std::string& f : written) std::printf("wrote %s\n", f.c_str());
  return 0;
}

}  // namespace panelrad::cli

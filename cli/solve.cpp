// panelrad solve: a user's scene (OBJ + MTL, or OFF + JSON sidecar) solved in every colour channel
// with one operator, written as CSV, PLY, VTK and a PNG picture.
#include "commands.hpp"
#include "options.hpp"
#include "processes.hpp"

#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/support/resources.hpp>
#include <panelrad/io/outputs.hpp>
#include <panelrad/io/scene_file.hpp>
#include <panelrad/io/scene_output.hpp>
#include <panelrad/solve/scene_solver.hpp>
#include <panelrad/io/text_output.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace panelrad::cli {

namespace {
const char* kSolveUsage =
    "usage: panelrad solve SCENE [--levels L | --max-elements N] [--out PREFIX] [--materials JSON]\n"
    "                      [--formats csv,ply,vtk,png] [--method auto|dense|fast] [--eta E] [--degree M]\n"
    "                      [--near exact|quadrature] [--mu K] [--solver auto|neumann|gmres] [--tol T|auto]\n"
    "                      [--visibility auto|occluded] [--environment U[,U..]] [--view X,Y,Z] [--up X,Y,Z]\n"
    "                      [--threads T] [--quiet]\n"
    "  SCENE: an OBJ whose MTL gives Kd (reflectivity rho) and Ke (emission E) per face through usemtl,\n"
    "  or an OFF with a JSON sidecar (SCENE with extension .json, or --materials) giving rho and E per\n"
    "  facet. Any set of planar polygons that do not cross: closed bodies (a room is seen from inside,\n"
    "  the bodies in it from outside) and open surfaces (front side counter-clockwise). The line of\n"
    "  sight V(P,Q) is computed unless the scene is proven convex (--visibility occluded: always).\n"
  "  Every colour channel is solved with one operator. --environment: the radiosity of the sky an\n"
    "  open scene sees where no surface covers a point's hemisphere (one value, or one per channel;\n"
    "  default 0, black). --levels L refines L times (n = 4^L n0);\n"
    "  --max-elements N (default 20000) takes the largest level with n <= N. Writes PREFIX.csv\n"
    "  (per-element radiosity), PREFIX.ply (per-face colours), PREFIX.vtk (ParaView) and PREFIX.png\n"
    "  (a cut-away picture seen from --view, the direction from the scene towards the viewer;\n"
    "  default: a room from in front of its open side or through a wall, looking at the lit\n"
    "  interior, a body from its brightest diagonal; --up: the scene's upward direction, default\n"
    "  y when the lights face along y, else z); PREFIX\n"
    "  defaults to the scene's name with '_radiosity' in\n"
    "  the current directory. Progress goes to stderr\n"
    "  (--quiet: none); a summary with the energy balance to stdout.\n"
    "  Exit status: 0 solved; 1 invalid input or failed run (no outputs); 2 usage error; 3 energy check\n"
    "  failed: the solution breaks the conservation of energy far beyond its discretization error, and\n"
    "  the outputs are written for inspection only.\n";

std::string default_prefix(const std::string& scene) {
  return std::filesystem::path(scene).stem().string() + "_radiosity";
}

/// --formats: a comma-separated list of at least one format; an empty entry ("", ",", "csv,")
/// is an error, not "write nothing".
std::string check_formats(const std::string& formats, std::set<std::string>* wanted) {
  for (std::size_t begin = 0;;) {
    const std::size_t end = std::min(formats.find(',', begin), formats.size());
    const std::string f = formats.substr(begin, end - begin);
    if (f != "csv" && f != "ply" && f != "vtk" && f != "png")
      return "in '" + formats + "', " + (f.empty() ? std::string("an empty entry") : "'" + f + "'") +
             " is not csv, ply, vtk or png";
    if (wanted) wanted->insert(f);
    if (end == formats.size()) return {};
    begin = end + 1;
  }
}

/// What the command line says, in the library's option structs.
struct SolveCommandLine {
  std::string scene_path, prefix, materials, formats = "csv,ply,vtk,png";
  SolveOptions o;
  bool quiet = false;
  int threads = 0;
  std::set<std::string> wanted;  // from formats
  std::optional<geometry::Vec3> view;  // --view: the PNG's direction towards the viewer
  std::optional<geometry::Vec3> up;  // --up: the PNG's upward direction
  std::vector<double> environment;     // --environment: one value, or one per channel
};

/// --view X,Y,Z: three finite numbers, not all 0; what is wrong, or "".
std::string view_problem(const std::string& text, geometry::Vec3* out) {
  geometry::Vec3 d;
  std::size_t begin = 0;
  for (int k = 0; k < 3; ++k) {
    const std::size_t end = k < 2 ? text.find(',', begin) : text.size();
    if (end == std::string::npos) return "needs three numbers X,Y,Z, got '" + text + "'";
    const std::string part = text.substr(begin, end - begin);
    std::size_t used = 0;
    try {
      d[k] = std::stod(part, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (part.empty() || used != part.size() || !std::isfinite(d[k]))
      return "'" + part + "' in '" + text + "' is not a finite number";
    begin = end + 1;
  }
  if (d.squaredNorm() == 0) return "the direction '" + text + "' is zero";
  if (out) *out = d;
  return "";
}

void add_solve_options(CLI::App& app, SolveCommandLine& line) {
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);  // repeated: the last counts
  SolveOptions& o = line.o;
  app.add_option("SCENE", line.scene_path);  // checked after parsing, so an unknown option is said first
  add_operator_options(app, o);
  app.add_option("--out", line.prefix)->type_name("PREFIX")->check([](const std::string& prefix) {
    return prefix.empty() ? std::string("the prefix is empty") : std::string();
  });
  app.add_option("--materials", line.materials)->type_name("JSON");
  app.add_option("--formats", line.formats)->type_name("csv,ply,vtk,png")->check([](const std::string& formats) {
    return check_formats(formats, nullptr);
  });
  app.add_option_function<std::string>("--solver", [&o](const std::string& v) { o.solver.kind = parse_solver(v); })
      ->type_name("auto|neumann|gmres")
      ->check(one_of({"auto", "neumann", "gmres"}));
  app.add_option("--tol", o.solver.tolerance)->type_name("T|auto")->transform(tolerance_in(1e-15, 0.5));
  app.add_option("--threads", line.threads)->type_name("T")->transform(thread_count());
  app.add_option_function<std::string>("--view", [&line](const std::string& v) {
       geometry::Vec3 d;
       (void)view_problem(v, &d);
       line.view = d;
     })
      ->type_name("X,Y,Z")
      ->check([](const std::string& v) { return view_problem(v, nullptr); });
  app.add_option_function<std::string>("--up", [&line](const std::string& v) {
       geometry::Vec3 u;
       (void)view_problem(v, &u);
       line.up = u;
     })
      ->type_name("X,Y,Z")
      ->check([](const std::string& v) { return view_problem(v, nullptr); });
  app.add_option("--environment", line.environment)
      ->type_name("U[,U..]")
      ->delimiter(',')
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
      ->check([](const std::string& v) {
        try {
          std::size_t used = 0;
          const double u = std::stod(v, &used);
          if (used != v.size()) return "'" + v + "' is not a number";
          const std::string problem = emission_problem(u);
          return problem.empty() ? std::string() : "the environment's radiosity " + v + " " + problem;
        } catch (const std::exception&) {
          return "'" + v + "' is not a number";
        }
      });
  app.add_flag("--quiet", line.quiet);
}

/// The combinations of options, once the command line is parsed.
void check_solve_options(const CLI::App& app, SolveCommandLine& line) {
  if (app.count("SCENE") == 0) throw UsageError("no scene given");
  check_operator_options(app, line.o);
  (void)check_formats(line.formats, &line.wanted);  // checked by the option's validator
  if (line.prefix.empty()) line.prefix = default_prefix(line.scene_path);
  check_prefix(line.prefix);  // given or derived from SCENE
}

/// --environment: one value for every channel, or one per channel of the scene.
void set_environment(const std::vector<double>& values, const std::string& scene_path, Scene& scene) {
  if (values.empty()) return;
  const std::size_t channels = scene.num_channels();
  if (values.size() != 1 && values.size() != channels)
    throw std::runtime_error(scene_path + ": --environment gives " + std::to_string(values.size()) +
                             " values; the scene has " + std::to_string(channels) + " channel" +
                             (channels > 1 ? "s" : "") + " (give one value, or one per channel)");
  for (std::size_t c = 0; c < channels; ++c) scene.set_environment(values[values.size() == 1 ? 0 : c], c);
}

/// The scene, with what loading did on stderr (unless quiet), and a note when --max-elements is
/// below n0 (said even when quiet: the run then does not do what was asked). Only the process
/// that writes the outputs says anything.
Scene read_scene(const SolveCommandLine& line, bool max_given, bool writer) {
  LoadOptions load;
  load.materials_path = line.materials;
  Scene scene = load_scene(line.scene_path, load);  // errors: exit 1 (main)
  set_environment(line.environment, line.scene_path, scene);
  if (!line.environment.empty() && scene.enclosed() && writer && !line.quiet)
    std::cerr << "panelrad solve: note: the scene is enclosed, so no point sees the environment (--environment)\n";
  if (!line.quiet && writer)
    for (const std::string& note : scene.notes()) std::cerr << "panelrad solve: note: " << note << "\n";
  if (writer && line.o.level < 0 && static_cast<long long>(scene.mesh().triangles.size()) > line.o.max_elements)
    std::cerr << "panelrad solve: note: " << (max_given ? "--max-elements " : "the default --max-elements ")
              << line.o.max_elements << " is below the scene's " << scene.mesh().triangles.size()
              << " triangles (n0): solving level 0, n = " << scene.mesh().triangles.size() << "\n";
  return scene;
}

/// Everything about the outputs that can be checked is checked before a long run, not after it:
/// the channel names as CSV columns, and that each output's directory takes a new file (a
/// uniquely named temporary, removed again) and the output is not a directory.
void check_outputs(const Scene& scene, const std::string& scene_path, const std::vector<std::string>& outputs) {
  try {
    check_channel_names(scene.channels());
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(scene_path + ": " + e.what());
  }
  for (const std::string& path : outputs) check_output_path(path);
}

/// The energy balance line: what emitted = absorbed (+ the light no front side takes) means for
/// this scene, and the mismatch's expected size.
void print_energy_balance(const SceneSolution& s) {
  const auto fractions = [&s] {
    for (const ChannelSolution& c : s.channels) std::printf(" %s %.4f", c.name.c_str(), c.escaped);
  };
  if (s.shape == geometry::SceneShape::convex) {
    std::printf("energy balance: emitted = absorbed on a closed convex scene;");
  } else if (s.closed) {
    std::printf("energy balance: emitted = absorbed in a closed scene;");
  } else if (s.enclosed) {
    std::printf("energy balance: the scene is enclosed (no light leaves it), but the back sides of its one-sided "
                "surfaces take the light that falls on them, so emitted = absorbed + taken by back sides; back-side "
                "fraction:");
    fractions();
    std::printf(";");
  } else if (std::any_of(s.channels.begin(), s.channels.end(), [](const ChannelSolution& c) { return c.environment_in > 0; })) {
    std::printf("energy balance: the scene is open, so emitted + arriving from the environment = absorbed + escaped; "
                "environment's share of what enters:");
    for (const ChannelSolution& c : s.channels)
      std::printf(" %s %.4f", c.name.c_str(),
                  c.emitted + c.environment_in > 0 ? c.environment_in / (c.emitted + c.environment_in) : 0.0);
    std::printf("; escaped fraction:");
    fractions();
    std::printf(";");
  } else {
    std::printf("energy balance: the scene is open, so emitted = absorbed + escaped; escaped fraction:");
    fractions();
    std::printf(";");
  }
  std::printf(" mismatch expected below 0.5 h/diam = %.2e\n", s.expected_energy_mismatch);
}

/// The energy check failed: which channels, and what that makes of the outputs.
void print_failed_energy_check(const SceneSolution& s) {
  std::string failed;
  int count = 0;
  for (const ChannelSolution& c : s.channels)
    if (!c.energy_balanced) failed += (count++ == 0 ? "" : ", ") + c.name;
  std::printf("energy check FAILED (channel%s %s): the mismatch is more than %g times its expected size, so the solution "
              "breaks the conservation of energy and is not to be trusted; the outputs are written for inspection "
              "only (exit status %d)\n",
              count > 1 ? "s" : "", failed.c_str(), kEnergyMismatchAllowance, kExitEnergyCheckFailed);
}

/// The summary on stdout: size, method, self-check, times, each channel's energy balance.
void print_summary(const Scene& scene, const std::string& scene_path, const SceneSolution& s) {
  std::printf("scene %s: %d facets, %zu channel%s\n", scene_path.c_str(), static_cast<int>(scene.mesh().num_facets),
              scene.num_channels(), scene.num_channels() > 1 ? "s" : "");
  std::printf("n = %d (level %d), h/diam = %.3e, %s\n", static_cast<int>(s.n), s.level, s.mesh_size / s.diameter,
              s.method.c_str());
  const VisibilityWork& w = s.visibility_work;
  if (!w.computed) {
    std::printf("visibility: V = 1 (the scene is proven convex): no visibility work\n");
  } else {
    std::printf("visibility: V computed (%s scene): pairs %zu visible, %zu hidden, %zu partly visible; %zu elements "
                "clipped to their visible part; %zu rays cast\n",
                geometry::to_string(s.shape), w.visible_pairs, w.hidden_pairs, w.partial_pairs, w.clipped_elements,
                w.rays_cast);
  }
  if (s.self_check_error >= 0) {
    std::printf("fast product self-check: relative error %.2e (accepted up to %.2e%s)\n", s.self_check_error,
                s.self_check_threshold, s.tightened ? ", after tightening" : "");
    std::printf("  worst over %d sampled rows, per test vector:", s.self_check.rows);
    for (const SelfCheckVector& v : s.self_check.vectors)
      std::printf("%s %s %.2e", &v == s.self_check.vectors.data() ? "" : ";", v.name.c_str(), v.relative_error);
    std::printf("\n");
  }
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
  print_energy_balance(s);
}

int run_solve(const CLI::App& app, const SolveCommandLine& command_line) {
  SolveOptions o = command_line.o;
  const std::vector<std::string> formats(command_line.wanted.begin(), command_line.wanted.end());
  const std::vector<std::string> outputs = output_paths(command_line.prefix, formats);  // in writing order
  // SIGINT/SIGTERM/SIGHUP remove the outputs' temporaries and end the run (status 128 + signal).
  install_output_signal_handlers();
  set_threads(command_line.threads);
  // Several processes (mpirun): each solves its share of the rows; rank 0 alone says and writes.
  o.communicator = shared_solve();
  const bool writer = writes_outputs();
  if (!command_line.quiet && writer)
    o.progress = [](const std::string& line) { std::cerr << "panelrad solve: " << line << "\n"; };

  const Scene scene = read_scene(command_line, app.count("--max-elements") > 0, writer);
  if (writer) check_outputs(scene, command_line.scene_path, outputs);
  const SceneSolution s = solve_scene(scene, o);
  s.require_converged();  // a channel out of iterations: exit 1 with the SolverError's message, no outputs
  // A failed energy check is said by the process that writes (every process holds the same answer).
  if (!writer) return 0;
  OutputOptions picture;
  picture.view_direction = command_line.view;
  picture.up = command_line.up;
  write_outputs(s, command_line.prefix, formats, picture);

  print_summary(scene, command_line.scene_path, s);
  for (const std::string& w : s.warnings) std::fprintf(stderr, "panelrad solve: warning: %s\n", w.c_str());
  if (!s.energy_balanced) print_failed_energy_check(s);
  for (const std::string& f : outputs) std::printf("wrote %s%s\n", f.c_str(), s.energy_balanced ? "" : " (for inspection only)");
  if (s.energy_balanced) return 0;
  std::fflush(stdout);  // a failed status may end the run at once (several processes: MPI_Abort)
  return kExitEnergyCheckFailed;
}

}  // namespace

Command add_solve(CLI::App& panelrad) {
  auto line = std::make_shared<SolveCommandLine>();
  CLI::App* app = panelrad.add_subcommand("solve", "solve an OBJ+MTL or OFF+JSON scene, write CSV/PLY/VTK/PNG");
  set_usage(*app, kSolveUsage);
  add_solve_options(*app, *line);
  return {app, [app, line] {
            check_solve_options(*app, *line);
            return run_solve(*app, *line);
          }};
}

}  // namespace panelrad::cli

// panelrad cube: the paper's cube example (section 3, Table 1; section 5, Tables 2-4).
#include "commands.hpp"
#include "hints.hpp"
#include "options.hpp"
#include "processes.hpp"

#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/paper/cube_example.hpp>
#include <panelrad/support/resources.hpp>
#include <panelrad/io/text_output.hpp>

#include <filesystem>

#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace panelrad::cli {

namespace {
const char* kCubeUsage =
    "usage: panelrad cube [--levels L] [--min-level L0] [--method dense|fast] [--near exact|quadrature]\n"
    "                     [--mu K] [--rule stroud7|three_point|degreeK] [--eta E] [--degree M]\n"
    "                     [--solver auto|neumann|gmres|lu] [--tol T|auto] [--target-clusters on|off]\n"
    "                     [--threads T] [--csv PATH]\n"
    "  Solves the paper's cube example (rho 0.5/0.4/0.3, u = x^2+y^2+z^2) for n = 12 * 4^l,\n"
    "  l = L0..L (default 0..3), and prints a table like the paper's Table 1 / Tables 2-4.\n"
    "  L is at most 13 (n must have a 32-bit index), and every level must fit in memory: both are\n"
    "  checked before level L0 is solved.\n"
    "  --tol auto (default) iterates until the iteration error is ~1e-5 h/diam, far below the\n"
    "  discretization error O(h).\n"
    "  --accuracy auto|manual: auto (the default) picks method, near rule, eta and M per level so\n"
    "  that the error stays within 5% of the discretization error at the least measured cost\n"
    "  (auto_parameters.hpp); any of --method --near --mu --rule --eta --degree, or --solver lu,\n"
    "  means manual (defaults for the rest: dense, exact near field, eta 0.2, M 2).\n"
    "  --target-clusters off: the fast method's per-point coverings alone, as in the paper (default\n"
    "  on: large target clusters share the far field through local expansions).\n";

/// --csv PATH: a file (the empty path: no CSV); a path whose last part names a directory ("d/",
/// "d/.", "..") is a usage error.
CLI::Validator csv_file() {
  return CLI::Validator(
      [](std::string& path) {
        const std::string name = std::filesystem::path(path).filename().string();
        if (!path.empty() && (name.empty() || name == "." || name == ".."))
          return "the path '" + path + "' names a directory, not a file";
        return std::string();
      },
      "", "csv_file");
}

/// What the command line says, in the library's option structs.
struct CubeCommandLine {
  CubeRunOptions o;
  std::string csv;
  int threads = 0;
  std::string accuracy;    // "", "auto" or "manual" as given
  std::string manual_opt;  // the first option that sets a parameter by hand
  CubeCommandLine() { o.solver.tolerance = 0; }  // auto: tied to the discretization error
};

void add_cube_options(CLI::App& app, CubeCommandLine& line) {
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);  // repeated: the last counts
  CubeRunOptions& o = line.o;
  app.add_option("--accuracy", line.accuracy)->type_name("auto|manual")->check(one_of({"auto", "manual"}));
  app.add_option("--levels", o.max_level)->type_name("L")->transform(level_number());
  app.add_option("--min-level", o.min_level)->type_name("L0")->transform(level_number());
  app.add_option_function<std::string>("--method", [&o](const std::string& v) { o.op.method = parse_operator_method(v); })
      ->type_name("dense|fast")
      ->check(one_of({"dense", "fast"}));
  app.add_option_function<std::string>("--near", [&o](const std::string& v) { o.op.near.rule = parse_near_rule(v); })
      ->type_name("exact|quadrature")
      ->check(one_of({"exact", "quadrature"}));
  app.add_option("--mu", o.op.near.mu)->type_name("K")->transform(integer_in(0, 6));
  app.add_option("--rule", o.op.near.basic_rule)->type_name("RULE")->check(quadrature_rule());
  app.add_option("--eta", o.op.eta)->type_name("E")->transform(number_in(1e-3, 0.99));
  app.add_option("--degree", o.op.degree)->type_name("M")->transform(integer_in(0, 12));
  app.add_option_function<std::string>("--solver", [&o](const std::string& v) { o.solver.kind = parse_solver(v); })
      ->type_name("auto|neumann|gmres|lu")
      ->check(one_of({"auto", "neumann", "gmres", "lu"}));
  app.add_option("--tol", o.solver.tolerance)->type_name("T|auto")->transform(tolerance_in(1e-15, 0.5));
  app.add_option_function<std::string>("--target-clusters",
                                       [&o](const std::string& v) { o.op.local.enabled = v == "on"; })
      ->type_name("on|off")
      ->check(one_of({"on", "off"}));
  app.add_option("--threads", line.threads)->type_name("T")->transform(thread_count());
  app.add_option("--csv", line.csv)->type_name("PATH")->check(csv_file());
}

/// The combinations of options, once the command line is parsed.
void check_cube_options(const CLI::App& app, CubeCommandLine& line) {
  for (const CLI::Option* opt : app.parse_order()) {
    const std::string name = opt->get_name();
    if (name == "--method" || name == "--near" || name == "--mu" || name == "--rule" || name == "--eta" ||
        name == "--degree") {
      line.manual_opt = name;
      break;
    }
  }
  const CubeRunOptions& o = line.o;
  if (o.min_level > o.max_level) throw UsageError("--min-level is above --levels");
  if (line.accuracy == "auto" && !line.manual_opt.empty())
    throw UsageError("--accuracy auto chooses the parameters itself; " + line.manual_opt +
                     " needs --accuracy manual");
  if (o.solver.kind == SolverKind::lu && o.op.method != OperatorMethod::dense) throw UsageError("--solver lu needs --method dense");
}

int run_cube(const CubeCommandLine& line) {
  CubeRunOptions o = line.o;
  o.communicator = shared_solve();
  const std::string& csv = line.csv;
  const std::string& accuracy = line.accuracy;
  const std::string& manual_opt = line.manual_opt;
  const int threads = line.threads;
  set_threads(threads);
  // SIGINT/SIGTERM/SIGHUP remove the CSV's temporary and end the run (status 128 + signal).
  install_output_signal_handlers();
  // Several processes (mpirun): each solves its share of the rows; rank 0 alone writes (main
  // sends the other ranks' standard output to /dev/null).
  const bool writer = writes_outputs();
  if (!csv.empty() && writer) {  // fail before a long run, not after it; an existing CSV.probe is not touched
    try {
      check_output_path(csv);
    } catch (const std::exception& e) {
      std::cerr << "panelrad cube: error: " << e.what() << "\n";
      return 1;
    }
  }
  // --solver lu needs the dense matrix: it implies manual (dense) unless auto was asked for.
  if (accuracy == "auto" && o.solver.kind == SolverKind::lu)
    throw UsageError("--solver lu needs --accuracy manual (dense)");
  const bool automatic = accuracy != "manual" && manual_opt.empty() && o.solver.kind != SolverKind::lu;
  std::vector<CubeRow> rows;
  try {
    // Every level, with the parameters it will get, is checked to fit before level 0 is solved.
    check_paper_cube_fits(o, automatic);
    if (!automatic) {
      print_cube_header(std::cout, o);
      rows = run_paper_cube(o, [](const CubeRow& r) { print_cube_row(std::cout, r); });
    } else {
      // Levels with the same automatic choice run as one group, under one header.
      const geometry::TriangleMesh cube = make_paper_cube_scene().mesh();
      for (int level = o.min_level; level <= o.max_level;) {
        CubeRunOptions group = o;
        group.op = choose_parameters(problem_size(cube, level));
        group.tighten_on_failed_check = true;  // the self-check can only make it stricter
        group.min_level = level;
        while (level + 1 <= o.max_level &&
               choose_parameters(problem_size(cube, level + 1)) == group.op)
          ++level;
        group.max_level = level++;
        std::cout << "accuracy auto: levels " << group.min_level << ".." << group.max_level << ": "
                  << describe_parameters(group.op) << "\n";
        print_cube_header(std::cout, group);
        const double previous = rows.empty() ? 0.0 : rows.back().max_error;
        const auto part = run_paper_cube(group, [previous, first = true](const CubeRow& r) mutable {
          CubeRow shown = r;  // the error ratio continues across groups
          if (first && previous > 0 && r.max_error > 0) shown.error_ratio = previous / r.max_error;
          first = false;
          print_cube_row(std::cout, shown);
        });
        for (CubeRow r : part) {
          if (r.error_ratio == 0 && !rows.empty() && r.max_error > 0) r.error_ratio = rows.back().max_error / r.max_error;
          rows.push_back(r);
        }
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "panelrad cube: error: " << e.what() << "\n";
    if (const std::string hint = hint_for(e); !hint.empty()) std::cerr << "panelrad cube: " << hint << "\n";
    return 1;
  }
  if (!rows.empty()) std::cout << "solver: " << rows.back().solver << "\n";
  print_cube_growth(std::cout, rows);
  if (!csv.empty() && writer) {
    write_cube_csv(rows, csv);
    std::cout << "wrote " << csv << "\n";
  }
  return 0;
}

}  // namespace

Command add_cube(CLI::App& panelrad) {
  auto line = std::make_shared<CubeCommandLine>();
  CLI::App* app = panelrad.add_subcommand("cube", "the paper's cube example (Table 1)");
  set_usage(*app, kCubeUsage);
  add_cube_options(*app, *line);
  return {app, [app, line] {
            check_cube_options(*app, *line);
            return run_cube(*line);
          }};
}

}  // namespace panelrad::cli

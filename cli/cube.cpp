// panelrad cube: the paper's cube example (section 3, Table 1; section 5, Tables 2-4).
#include "commands.hpp"
#include "options.hpp"

#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/paper/cube_example.hpp>
#include <panelrad/support/resources.hpp>
#include <panelrad/io/text_output.hpp>

#include <filesystem>

#include <iostream>
#include <string>
#include <vector>

namespace panelrad::cli {

namespace {
const char* kCubeUsage =
    "usage: panelrad cube [--levels L] [--min-level L0] [--method dense|fast] [--near exact|quadrature]\n"
    "                     [--mu K] [--rule stroud7|three_point|degreeK] [--eta E] [--degree M]\n"
    "                     [--solver auto|neumann|gmres|lu] [--tol T|auto] [--threads T] [--csv PATH]\n"
    "  Solves the paper's cube example (rho 0.5/0.4/0.3, u = x^2+y^2+z^2) for n = 12 * 4^l,\n"
    "  l = L0..L (default 0..3), and prints a table like the paper's Table 1 / Tables 2-4.\n"
    "  --tol auto (default) iterates until the iteration error is ~1e-5 h/diam, far below the\n"
    "  discretization error O(h).\n"
    "  --accuracy auto|manual: auto (the default) picks method, near rule, eta and M per level so\n"
    "  that the error stays within 5% of the discretization error at the least measured cost\n"
    "  (auto_parameters.hpp); any of --method --near --mu --rule --eta --degree, or --solver lu,\n"
    "  means manual (defaults for the rest: dense, exact near field, eta 0.2, M 2).\n";
}  // namespace

int run_cube(int argc, char** argv) {
  CubeRunOptions o;
  o.solver.tolerance = 0;  // auto: tied to the discretization error
  std::string csv;
  int threads = 0;
  std::string accuracy;    // "", "auto" or "manual" as given
  std::string manual_opt;  // the first option that sets a parameter by hand
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "-h" || a == "--help") {
        std::cout << kCubeUsage;
        return 0;
      }
      if (i + 1 >= argc) throw UsageError("option '" + a + "' needs a value (or is unknown)");
      const std::string v = argv[++i];
      if (a == "--method" || a == "--near" || a == "--mu" || a == "--rule" || a == "--eta" || a == "--degree") {
        if (manual_opt.empty()) manual_opt = a;
      }
      if (a == "--accuracy") {
        if (v != "auto" && v != "manual") throw UsageError("--accuracy must be auto or manual, got '" + v + "'");
        accuracy = v;
      } else if (a == "--levels") o.max_level = parse_int(a, v, 0, 12);
      else if (a == "--min-level") o.min_level = parse_int(a, v, 0, 12);
      else if (a == "--method") {
        if (v != "dense" && v != "fast") throw UsageError("--method must be dense or fast, got '" + v + "'");
        o.op.method = v;
      } else if (a == "--near") {
        if (v != "exact" && v != "quadrature") throw UsageError("--near must be exact or quadrature, got '" + v + "'");
        o.op.near.rule = parse_near_rule(v);
      } else if (a == "--mu") o.op.near.mu = parse_int(a, v, 0, 6);
      else if (a == "--rule") {
        check_quadrature_rule(a, v);
        o.op.near.basic_rule = v;
      } else if (a == "--eta") o.op.eta = parse_double(a, v, 1e-3, 0.99);
      else if (a == "--degree") o.op.degree = parse_int(a, v, 0, 12);
      else if (a == "--solver") {
        if (v != "auto" && v != "neumann" && v != "gmres" && v != "lu")
          throw UsageError("--solver must be auto, neumann, gmres or lu, got '" + v + "'");
        o.solver.kind = parse_solver(v);
      } else if (a == "--tol") o.solver.tolerance = v == "auto" ? 0.0 : parse_double(a, v, 1e-15, 0.5);
      else if (a == "--threads") threads = parse_threads(a, v);
      else if (a == "--csv") csv = v;
      else throw UsageError("unknown option '" + a + "'");
    }
    if (o.min_level > o.max_level) throw UsageError("--min-level is above --levels");
    if (accuracy == "auto" && !manual_opt.empty())
      throw UsageError("--accuracy auto chooses the parameters itself; " + manual_opt + " needs --accuracy manual");
    if (o.solver.kind == SolverKind::lu && o.op.method != "dense")
      throw UsageError("--solver lu needs --method dense");
    if (!csv.empty()) {
      const std::string name = std::filesystem::path(csv).filename().string();
      if (name.empty() || name == "." || name == "..")
        throw UsageError("--csv '" + csv + "': the path names a directory, not a file");
    }
  } catch (const UsageError& e) {
    std::cerr << "panelrad cube: " << e.what() << "\n" << kCubeUsage;
    return 2;
  }
  set_threads(threads);
  // SIGINT/SIGTERM/SIGHUP remove the CSV's temporary and end the run (status 128 + signal).
  install_output_signal_handlers();
  if (!csv.empty()) {  // fail before a long run, not after it; an existing CSV.probe is not touched
    try {
      check_output_path(csv);
    } catch (const std::exception& e) {
      std::cerr << "panelrad cube: error: " << e.what() << "\n";
      return 1;
    }
  }
  // --solver lu needs the dense matrix: it implies manual (dense) unless auto was asked for.
  if (accuracy == "auto" && o.solver.kind == SolverKind::lu) {
    std::cerr << "panelrad cube: --solver lu needs --accuracy manual (dense)\n" << kCubeUsage;
    return 2;
  }
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
               describe_parameters(choose_parameters(problem_size(cube, level + 1))) == describe_parameters(group.op))
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
    return 1;
  }
  if (!rows.empty()) std::cout << "solver: " << rows.back().solver << "\n";
  print_cube_growth(std::cout, rows);
  if (!csv.empty()) {
    write_cube_csv(rows, csv);
    std::cout << "wrote " << csv << "\n";
  }
  return 0;
}

}  // namespace panelrad::cli

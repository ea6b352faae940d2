// Section 5.1 of the paper, measured in one run: on the cube example at n = 3072 and 12288,
//   (a) dense setup + LU, (b) dense setup + Neumann iteration, (c) fast method + Neumann with the
//   paper's (eta, M) = (0.2, 2) and with the automatic setting,
//   (d) the library's defaults: automatic parameters and solver (GMRES where it needs fewer products),
// all to the same accuracy. Prints times, errors, speed-ups and peak memory; optional CSV.
//   usage: section51 [--levels L0 L1] [--threads T] [--csv PATH] [--skip-lu]
#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/support/resources.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/radiosity_solver.hpp>
#include <panelrad/solve/solvers.hpp>
#include <panelrad/io/text_output.hpp>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <sstream>
#include <string>

using namespace panelrad;

namespace {
struct Timing {
  std::string what;
  Index n = 0;
  double setup_s = 0, solve_s = 0, error = 0;
  int iterations = 0;
  std::string solver;  // what ran, with the automatic choice's reason
  double total() const { return setup_s + solve_s; }
};

// One solver object on the cube at `level` with the rho of (31) in the operator's rows; the
// Neumann iteration (34) to the tolerance tied to the discretization error (as the paper stopped
// at the best possible accuracy). Setup: the cluster tree and the operator (E manufacturing is
// test data, not counted).
SolveOptions cube_options(int level, OperatorMethod method, const OperatorOptions& manual = {},
                                    SolverKind solver = SolverKind::neumann) {
  SolveOptions o;
  o.level = level;
  o.op = manual;
  o.op.method = method;
  o.fold_reflectivity = true;
  o.solver.kind = solver;
  return o;
}

Timing solve_row(const std::string& what, const RadiositySolver& solver) {
  const ChannelSolve r = solver.solve(0);
  if (!r.converged()) throw SolverError(r.message);
  return {what, solver.n(), solver.collocation().tree_seconds() + solver.info().operator_s, r.seconds,
          solver.collocation().max_error(r.u), r.iterations, r.solver};
}
}  // namespace

int main(int argc, char** argv) {
  int l0 = 4, l1 = 5;
  bool skip_lu = false;
  std::string csv;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--levels") && i + 2 < argc) {
      l0 = std::atoi(argv[++i]);
      l1 = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) {
      set_threads(std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--csv") && i + 1 < argc) {
      csv = argv[++i];
    } else if (!std::strcmp(argv[i], "--skip-lu")) {
      skip_lu = true;
    } else {
      std::cerr << "usage: section51 [--levels L0 L1] [--threads T] [--csv PATH] [--skip-lu]\n";
      return 2;
    }
  }
  const Scene scene = make_paper_cube_scene();
  std::vector<Timing> all;
  std::printf("Section 5.1 comparison on the cube, threads %d\n", max_threads());
  std::printf("%-40s %7s %10s %10s %10s %6s %11s %9s\n", "method", "n", "setup s", "solve s", "total s", "iters",
              "max error", "peak MB");
  for (int level = l0; level <= l1; ++level) {
    std::vector<Timing> rows;
    {
      const RadiositySolver dense(scene, cube_options(level, OperatorMethod::dense));
      rows.push_back(solve_row("dense setup + Neumann", dense));
      if (!skip_lu) {  // the direct baseline on the same matrix
        const Collocation& col = dense.collocation();
        const auto lu = solve_lu(dynamic_cast<const DenseOperator&>(dense.op()), col.emissivity());
        rows.push_back({"dense setup + LU", col.size(), rows.back().setup_s, lu.seconds, col.max_error(lu.u), 0, "lu"});
      }
    }
    // The fast method with the paper's (eta, M) = (0.2, 2), and with the setting --accuracy auto
    // picks for this size (auto_parameters.hpp: the cheapest measured setting whose solution stays
    // within 5% of the discretization error, i.e. the same accuracy as the dense method).
    const std::size_t dense_rows = rows.size();
    OperatorOptions paper;
    paper.method = OperatorMethod::fast;  // eta 0.2, M 2, exact near field
    rows.push_back(solve_row("fast (0.2, exact, M=2) + Neumann", RadiositySolver(scene, cube_options(level, OperatorMethod::fast, paper))));
    if (choose_parameters(problem_size(scene.mesh(), level)).method == OperatorMethod::fast) {  // dense for n <= 768
      const RadiositySolver automatic(scene, cube_options(level, OperatorMethod::automatic));
      char auto_name[64];
      std::snprintf(auto_name, sizeof auto_name, "fast auto (%g, exact, M=%d) + Neumann", automatic.parameters().eta,
                    automatic.parameters().degree);
      rows.push_back(solve_row(auto_name, automatic));
      // The library's defaults: automatic parameters and the automatic solver (the iteration of
      // fewer expected products, solvers.hpp), the same tolerance.
      const RadiositySolver defaults(scene, cube_options(level, OperatorMethod::automatic, {}, SolverKind::automatic));
      Timing t = solve_row("", defaults);
      std::snprintf(auto_name, sizeof auto_name, "fast auto (%g, exact, M=%d) + %s", defaults.parameters().eta,
                    defaults.parameters().degree, t.solver.find("GMRES") != std::string::npos ? "auto GMRES" : "auto Neumann");
      t.what = auto_name;
      rows.push_back(t);
    }
    for (const auto& r : rows) {
      std::printf("%-40s %7d %10.3f %10.3f %10.3f %6d %11.4e %9.0f\n", r.what.c_str(), static_cast<int>(r.n), r.setup_s,
                  r.solve_s, r.total(), r.iterations, r.error, peak_rss_mb());
      all.push_back(r);
    }
    for (std::size_t k = dense_rows; k < rows.size(); ++k) {
      std::printf("  speed-up of %s: %.1fx vs dense setup + Neumann", rows[k].what.c_str(), rows[0].total() / rows[k].total());
      if (!skip_lu) std::printf(", %.1fx vs dense setup + LU", rows[1].total() / rows[k].total());
      std::printf("\n");
    }
  }
  if (!csv.empty()) {
    std::ostringstream os;
    os << "method,n,setup_s,solve_s,total_s,iterations,max_error\n";
    for (const auto& r : all)
      os << r.what << "," << r.n << "," << r.setup_s << "," << r.solve_s << "," << r.total() << "," << r.iterations << ","
         << r.error << "\n";
    write_file_atomically(csv, os.str());
  }
  return 0;
}

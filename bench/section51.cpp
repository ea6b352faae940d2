// Section 5.1 of the paper, measured in one run: on the cube example at n = 3072 and 12288,
//   (a) dense setup + LU, (b) dense setup + Neumann iteration, (c) fast method + Neumann with the
//   paper's (eta, M) = (0.2, 2) and with the automatic setting,
// all to the same accuracy. Prints times, errors, speed-ups and peak memory; optional CSV.
//   usage: section51 [--levels L0 L1] [--threads T] [--csv PATH] [--skip-lu]
#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/support/resources.hpp>
#include <panelrad/scene/scene.hpp>
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
  double total() const { return setup_s + solve_s; }
};
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
  std::printf("%-38s %7s %10s %10s %10s %6s %11s %9s\n", "method", "n", "setup s", "solve s", "total s", "iters",
              "max error", "peak MB");
  for (int level = l0; level <= l1; ++level) {
    const Collocation col(scene, level);
    // Iterate to the same tolerance for all, tied to the discretization error (as the paper
    // stopped at the best possible accuracy).
    SolverOptions it;
    it.tolerance = discretization_tolerance(col.tree().mesh_size(), col.tree().diameter());
    std::vector<Timing> rows;
    Stopwatch clock;
    {
      const DenseOperator dense(col, NearFieldOptions{});
      const double setup = col.tree_seconds() + clock.seconds();
      const auto neumann = solve_neumann(dense, col.emissivity(), it);
      rows.push_back({"dense setup + Neumann", col.size(), setup, neumann.seconds, col.max_error(neumann.u),
                      neumann.iterations});
      if (!skip_lu) {
        const auto lu = solve_lu(dense, col.emissivity());
        rows.push_back({"dense setup + LU", col.size(), setup, lu.seconds, col.max_error(lu.u), 0});
      }
    }
    // The fast method with the paper's (eta, M) = (0.2, 2), and with the setting --accuracy auto
    // picks for this size (auto_parameters.hpp: the cheapest measured setting whose solution stays
    // within 5% of the discretization error, i.e. the same accuracy as the dense method).
    const std::size_t dense_rows = rows.size();
    FastOptions paper;
    const OperatorOptions chosen = choose_parameters(problem_size(scene.mesh(), level));
    FastOptions automatic;
    automatic.eta = chosen.eta;
    automatic.degree = chosen.degree;
    automatic.near = chosen.near;
    char auto_name[64];
    std::snprintf(auto_name, sizeof auto_name, "fast auto (%g, exact, M=%d) + Neumann", chosen.eta, chosen.degree);
    std::vector<std::pair<std::string, FastOptions>> fast_runs = {{"fast (0.2, exact, M=2) + Neumann", paper}};
    if (chosen.method == "fast") fast_runs.emplace_back(auto_name, automatic);  // dense for n <= 768
    for (const auto& [name, options] : fast_runs) {
      clock.restart();
      const FastOperator fast(col, options);
      const double setup = col.tree_seconds() + clock.seconds();
      const auto fs = solve_neumann(fast, col.emissivity(), it);
      rows.push_back({name, col.size(), setup, fs.seconds, col.max_error(fs.u), fs.iterations});
    }
    for (const auto& r : rows) {
      std::printf("%-38s %7d %10.3f %10.3f %10.3f %6d %11.4e %9.0f\n", r.what.c_str(), static_cast<int>(r.n), r.setup_s,
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

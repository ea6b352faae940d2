// The fast product K_n v of section 4 against its accuracy, on the paper's cube (31), for the
// comparison with an H-matrix code at matched accuracy: for each setting (eta of (41), M of (44))
// one operator, and for it
//   - setup: the cluster frames, the minimal admissible coverings (42), the near field (43) and,
//     when stored, the far coefficients (44)-(45);
//   - the time of setup (the median of --setups K, default 1: the first setup of the process, on
//     memory not touched before; later ones reuse memory the allocator kept);
//   - the time of one product (the median of --products K, default 9) and of one block of 3;
//   - the bytes the operator holds, in all and per element;
//   - the product's error for each test vector of the self-check (FastSelfCheck: constant,
//     smooth, oscillating "cos 7x + sin(5y) z", piecewise constant by facet, random +-1), on
//     --rows S sampled exact rows (default 256), relative to max_k (K|v|)_k.
// Rows are weighted by rho of (31), as in the solver.
// and the local expansions of target clusters (LocalExpansionOptions): their finest level, the
// (target, source) pairs and the (point, cluster) pairs they stand for; --local D ETA_T MIN sets
// their degree, target admissibility and fewest points (-1 0 0: the defaults), --no-local turns
// them off.
//   usage: product [--level L] [--threads T] [--products K] [--setups K] [--rows S] [--double | --single]
//                  [--recompute] [--no-local] [--local D ETA_T MIN] [--setting ETA M]...
// Default settings: (0.5, 6) (0.4, 7) (0.3, 7) (0.3, 8) at level 6 (n = 49,152).
#include "fast_settings.hpp"
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/support/resources.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

using namespace panelrad;

using bench::median;

int main(int argc, char** argv) {
  int level = 6, products = 9, rows = 256, setups = 1;
  bench::FastSettings fast;
  LocalExpansionOptions local;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--level") && i + 1 < argc) {
      level = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) {
      set_threads(std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--products") && i + 1 < argc) {
      products = std::max(1, std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--setups") && i + 1 < argc) {
      setups = std::max(1, std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--rows") && i + 1 < argc) {
      rows = std::max(1, std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--no-local")) {
      local.enabled = false;
    } else if (!std::strcmp(argv[i], "--local") && i + 3 < argc) {
      local.degree = std::atoi(argv[++i]);
      local.eta = std::atof(argv[++i]);
      local.min_points = std::atoi(argv[++i]);
    } else if (!fast.parse(i, argc, argv)) {
      std::cerr << "usage: product [--level L] [--threads T] [--products K] [--setups K] [--rows S] [--double | --single] "
                   "[--recompute] [--no-local] [--local D ETA_T MIN] [--setting ETA M]...\n";
      return 2;
    }
  }
  if (fast.settings.empty()) fast.settings = {{0.5, 6}, {0.4, 7}, {0.3, 7}, {0.3, 8}};
  try {
    const Scene cube = make_paper_cube_scene();
    Stopwatch clock;
    const Collocation col(cube, level);
    std::printf("fast product on the cube, level %d, n = %d, threads %d (collocation and E: %.1f s)\n", level,
                static_cast<int>(col.size()), max_threads(), clock.seconds());
    std::printf("%5s %3s %6s %12s %9s %10s %10s %10s %9s  %s\n", "eta", "M", "store", "far pairs", "setup s",
                "product s", "3 cols s", "MB", "B/elem", "error per self-check vector (max over vectors, self-check s)");
    for (const auto& [eta, degree] : fast.settings) {
      FastOptions o = fast.options(eta, degree);
      o.local = local;
      std::vector<double> setup_s;
      for (int k = 1; k < setups; ++k) {  // the first setups: timed, then released
        clock.restart();
        const FastOperator warm(col, o);
        setup_s.push_back(clock.seconds());
      }
      clock.restart();
      const FastOperator op(col, o);
      setup_s.push_back(clock.seconds());
      const double setup = median(setup_s);
      const Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(col.size(), 0.25, 1.0);
      Eigen::MatrixXd V(col.size(), 3), Y;
      V.col(0) = v;
      V.col(1) = Eigen::VectorXd::Ones(col.size());
      V.col(2) = Eigen::VectorXd::LinSpaced(col.size(), 1.0, 0.5);
      Eigen::VectorXd y;
      std::vector<double> single, block;
      for (int k = 0; k < products; ++k) {
        clock.restart();
        op.apply(v, y);
        single.push_back(clock.seconds());
        clock.restart();
        op.apply_block(V, Y);
        block.push_back(clock.seconds());
      }
      const FastSelfCheck check = op.self_check(rows);
      const FastStatistics& s = op.statistics();
      std::printf("%5.2f %3d %6s %12zu %9.4f %10.4f %10.4f %10.1f %9.0f ", eta, degree,
                  !s.far_stored ? "none" : o.single_precision_coefficients ? "float" : "double", s.far_pairs, setup,
                  median(single), median(block), static_cast<double>(op.bytes()) / 1e6,
                  static_cast<double>(op.bytes()) / static_cast<double>(col.size()));
      for (const SelfCheckVector& c : check.vectors) std::printf(" %.2e", c.relative_error);
      std::printf("  (%.2e, %.3f s)  setup: geometry %.3f, targets %.3f, coverings %.3f, far %.3f s",
                  check.relative_error, check.seconds, s.geometry_s, s.targets_s, s.covering_s, s.far_s);
      if (s.target_level >= 0)
        std::printf("; local: levels 0..%d, d %d, %zu targets, %zu pairs for %zu point pairs\n", s.target_level,
                    s.local_degree, s.target_clusters, s.target_pairs, s.target_point_pairs);
      else
        std::printf("; local: none\n");
      std::fflush(stdout);
    }
    std::printf("self-check vectors:");
    {
      FastOptions o;
      o.probe_samples = 1;
      const FastOperator probe(col, o);
      for (const auto& v : probe.self_check_vectors()) std::printf(" [%s]", v.first.c_str());
    }
    std::printf("; rows sampled %d; peak memory %.0f MB\n", rows, peak_rss_mb());
  } catch (const std::exception& e) {
    std::cerr << "product: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

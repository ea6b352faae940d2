// The cost of the line-of-sight function V(P, Q) in the fast product (section 4 with the shaft
// classification of each (P_i, cluster) pair, lib/src/operator/visible_covering.hpp), measured in
// one run for each level:
//   - the paper's cube (convex) without visibility: V = 1, today's path;
//   - the same cube with V computed anyway (occluded): the overhead of classifying on a scene that
//     needs none;
//   - a general scene (default: the real Cornell box; with n0 = 48 its level L has the n of the
//     cube's level L + 1, n = 48 4^L).
// Each row: n, the operator's setup time (covering (42) with the classification, near field (43),
// far coefficients), the time of one product K_n v (the median of --products K, default 9), that
// of one block product of 3 vectors (apply_block, as the three colour channels of a scene are
// iterated: the stored far field read once for all three; the median of K), the bytes held per
// element, and the pairs classified. The parameters are the same for every row of
// a level: choose_parameters for the general scene's size (the automatic choice at 5% of the
// discretization error, with rho_max 0.5; no self-check, so no tightening), or --setting's.
//   usage: visibility [--scene OBJ] [--levels L0 L1] [--threads T] [--products K] [--no-cube] [--setting ETA M]
// Levels are those of the general scene; the cube runs at the level with the same n, when there is
// one (the scene's n0 is 12 4^k).
#include <panelrad/io/scene_file.hpp>
#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/support/resources.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

using namespace panelrad;

namespace {

struct Row {
  std::string scene;
  Visibility visibility;
  Index n = 0;
  double setup_s = 0, product_s = 0, block3_s = 0, bytes_per_element = 0;
  VisibilityWork work;
  std::string detail;  // the fast operator's pair counts
};

int g_products = 9;  // products timed per operator (the median is reported)
bool g_cube = true;  // also the cube rows
double g_eta = 0;    // --setting ETA M: these instead of the rule's
int g_degree = 0;

Row measure(const std::string& name, const Scene& scene, int level, const OperatorOptions& op, Visibility visibility) {
  const Collocation col(scene, level);
  const Collocation unit = col.with_row_weights(Eigen::VectorXd::Ones(col.size()));
  Stopwatch clock;
  const std::unique_ptr<RadiosityOperator> H = make_operator(unit, op, visibility);
  Row r{name, visibility, col.size(), clock.seconds(), 0, 0, 0, visibility_work(*H), {}};
  const Eigen::VectorXd v = Eigen::VectorXd::Ones(col.size());
  Eigen::MatrixXd V(col.size(), 3), Y;
  V.col(0) = v;
  V.col(1) = Eigen::VectorXd::LinSpaced(col.size(), 0.5, 1.5);
  V.col(2) = Eigen::VectorXd::LinSpaced(col.size(), 1.0, 0.25);
  Eigen::VectorXd y;
  const auto median = [](std::vector<double> t) {
    std::sort(t.begin(), t.end());
    return t[t.size() / 2];
  };
  std::vector<double> single, block;
  for (int k = 0; k < g_products; ++k) {
    clock.restart();
    H->apply(v, y);
    single.push_back(clock.seconds());
    clock.restart();
    H->apply_block(V, Y);
    block.push_back(clock.seconds());
  }
  r.product_s = median(single);
  r.block3_s = median(block);
  r.bytes_per_element = static_cast<double>(H->bytes()) / static_cast<double>(col.size());
  if (const auto* fast = dynamic_cast<const FastOperator*>(H.get())) {
    const FastStatistics& st = fast->statistics();
    char d[512];
    std::snprintf(d, sizeof d,
                  "  pairs: near %zu, far %zu (coefficients %s); target clusters of levels 0..%d: %zu sources, "
                  "%zu hidden, %zu admissible undecided; setup s: targets %.2f, coverings %.2f, far %.2f",
                  st.near_pairs, st.far_pairs, st.far_stored ? "stored" : "recomputed", st.target_level, st.target_pairs,
                  st.target_hidden_pairs, st.target_undecided_pairs, st.targets_s, st.covering_s, st.far_s);
    r.detail = d;
  }
  return r;
}

void print(const Row& r) {
  std::printf("%-22s %-10s %8d %9.2f %9.4f %9.4f %9.0f %12zu %12zu %12zu %10zu\n", r.scene.c_str(),
              to_string(r.visibility), static_cast<int>(r.n), r.setup_s, r.product_s, r.block3_s, r.bytes_per_element,
              r.work.visible_pairs,
              r.work.hidden_pairs, r.work.partial_pairs, r.work.clipped_elements);
  if (!r.detail.empty()) std::printf("%s\n", r.detail.c_str());
  std::fflush(stdout);
}

int cube_level_for(Index n) {
  int level = 0;
  while ((Index{12} << (2 * level)) < n) ++level;
  return (Index{12} << (2 * level)) == n ? level : -1;
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene_path = "examples/scenes/cornell_box.obj";
  int l0 = 2, l1 = 5;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--scene") && i + 1 < argc) {
      scene_path = argv[++i];
    } else if (!std::strcmp(argv[i], "--levels") && i + 2 < argc) {
      l0 = std::atoi(argv[++i]);
      l1 = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) {
      set_threads(std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--setting") && i + 2 < argc) {
      g_eta = std::atof(argv[++i]);
      g_degree = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--products") && i + 1 < argc) {
      g_products = std::max(1, std::atoi(argv[++i]));
    } else if (!std::strcmp(argv[i], "--no-cube")) {
      g_cube = false;
    } else {
      std::cerr << "usage: visibility [--scene OBJ] [--levels L0 L1] [--threads T] [--products K] [--no-cube] [--setting ETA M]\n";
      return 2;
    }
  }
  try {
    const Scene general = load_scene(scene_path);
    const Scene cube = make_paper_cube_scene();
    std::printf("visibility cost, threads %d, scene %s (%zu triangles, %s)\n", max_threads(), scene_path.c_str(),
                general.mesh().triangles.size(), geometry::to_string(general.shape()));
    std::printf("%-22s %-10s %8s %9s %9s %9s %9s %12s %12s %12s %10s\n", "scene", "V", "n", "setup s", "product s",
                "3 cols s", "B/elem", "visible", "hidden", "partial", "clipped");
    for (int level = l0; level <= l1; ++level) {
      const Index n = static_cast<Index>(general.mesh().triangles.size()) << (2 * level);
      OperatorOptions op = choose_parameters(problem_size(general.mesh(), level), 0.05, 0.5);
      op.method = OperatorMethod::fast;
      if (g_eta > 0) {
        op.eta = g_eta;
        op.degree = g_degree;
      }
      std::printf("n = %d: %s\n", static_cast<int>(n), describe_parameters(op).c_str());
      if (const int cl = cube_level_for(n); g_cube && cl >= 0) {
        print(measure("cube (convex)", cube, cl, op, Visibility::unoccluded));
        print(measure("cube (convex)", cube, cl, op, Visibility::occluded));
      }
      print(measure(std::filesystem::path(scene_path).filename().string(), general, level, op, Visibility::occluded));
    }
    std::printf("peak memory %.0f MB\n", peak_rss_mb());
  } catch (const std::exception& e) {
    std::cerr << "visibility: " << e.what() << "\n";
    return 1;
  }
  return 0;
}

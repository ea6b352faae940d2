#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/geometry/cluster_tree.hpp>
#include <panelrad/solve/memory_plan.hpp>
#include <panelrad/scene/scene.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <utility>
#include <sstream>

namespace panelrad {

namespace {

constexpr std::size_t kMax = std::numeric_limits<std::size_t>::max();

std::size_t saturate(long double bytes) {
  return bytes >= static_cast<long double>(kMax) ? kMax : static_cast<std::size_t>(std::max(0.0L, bytes));
}

std::size_t add(std::size_t a, std::size_t b) { return a > kMax - b ? kMax : a + b; }

std::string show(std::size_t bytes) { return bytes == kMax ? std::string("more than 18 EB") : format_bytes(static_cast<double>(bytes)); }

// Far pairs per row of the fast operator on the coverings (42) of `coarse` (every row counts):
// a lower bound for every finer level (see memory_plan.hpp).
double far_pairs_per_row(const Collocation& coarse, double eta, int degree) {
  const FastOperator::MemoryEstimate e = FastOperator::estimate_memory(coarse, eta, degree);
  return static_cast<double>(e.far_pairs) / static_cast<double>(coarse.size());
}

}  // namespace

std::size_t LevelMemoryEstimate::total() const { return add(add(add(add(tree, collocation), op), solver), fields); }

std::string LevelMemoryEstimate::breakdown() const {
  std::ostringstream os;
  os << "cluster tree " << show(tree) << " + collocation " << show(collocation) << " + operator "
     << (op_is_lower_bound ? "at least " : "") << show(op) << " + solver " << show(solver);
  if (fields > 0) os << " + results " << show(fields);
  os << " = " << (op_is_lower_bound ? "at least " : "") << show(total());
  return os.str();
}

std::vector<LevelMemoryEstimate> estimate_levels_memory(const geometry::TriangleMesh& mesh,
                                                        const std::vector<PlannedLevel>& levels,
                                                        const SolverOptions& solver, double /*max_reflectivity*/,
                                                        const LevelMemoryOptions& options) {
  if (mesh.triangles.empty()) throw std::invalid_argument("memory estimate: the mesh has no triangles");
  const long long n0 = static_cast<long long>(mesh.triangles.size());
  // One coarse level for the far pairs per row of every fast level finer than it: the largest
  // with n0 4^l <= kCoarseElements (0 when n0 alone is larger). Levels at or below it hold at
  // most kCoarseElements elements; their lists are left to the precise gate.
  int coarse_level = 0;
  while ((n0 << (2 * (coarse_level + 1))) <= kCoarseElements) ++coarse_level;
  std::unique_ptr<Collocation> coarse;  // built on first use
  std::vector<std::pair<double, double>> far_per_row;  // (eta, pairs per row), measured once per eta
  std::vector<LevelMemoryEstimate> out;
  for (const PlannedLevel& planned : levels) {
    const int level = planned.level;
    const OperatorOptions& op = planned.op;
    if (level < 0) throw std::invalid_argument("levels: " + std::to_string(level) + " is negative");
    LevelMemoryEstimate e;
    e.level = level;
    const long double n = e.n = std::ldexp(static_cast<long double>(n0), 2 * level);
    e.method = describe_parameters(op);
    const bool fits_index = n + n / 3 < static_cast<long double>(std::numeric_limits<Index>::max());
    e.tree = fits_index ? geometry::ClusterTree::estimate_bytes(static_cast<Index>(n0), level) : kMax;
    e.collocation = saturate(n * options.collocation_vectors * sizeof(double));
    e.fields = saturate(n * static_cast<long double>(options.field_bytes_per_element));
    if (op.method == OperatorMethod::dense) {
      e.op = fits_index ? DenseOperator::matrix_bytes(static_cast<Index>(n)) : kMax;
    } else if (!fits_index) {
      e.op = kMax;
    } else {
      e.op_is_lower_bound = true;
      const long double clusters = n * 4 / 3;  // n0 (4^(L+1) - 1) / 3
      long double bytes = static_cast<long double>(
          FastOperator::fixed_bytes(static_cast<std::size_t>(n), static_cast<std::size_t>(clusters), op.degree));
      if (level > coarse_level && !(options.target_clusters && op.local.enabled)) {
        auto it = std::find_if(far_per_row.begin(), far_per_row.end(), [&](const auto& p) { return p.first == op.eta; });
        if (it == far_per_row.end()) {
          if (!coarse) {
            Scene scene(mesh);
            scene.set_reflectivity(0.5);  // every row counts
            coarse = std::make_unique<Collocation>(scene, coarse_level);
          }
          far_per_row.emplace_back(op.eta, far_pairs_per_row(*coarse, op.eta, op.degree));
          it = far_per_row.end() - 1;
        }
        // The far lists (one cluster index per pair) are held twice during setup (per block,
        // then concatenated), as FastOperator's own refusal counts them.
        bytes += 2 * n * static_cast<long double>(it->second) * sizeof(Index);
      }
      e.op = saturate(bytes);
    }
    SolverKind kind = solver.kind;
    // automatic may run either iteration (several channels start with Neumann and may continue
    // with GMRES): the larger need, GMRES's basis.
    if (kind == SolverKind::automatic) kind = SolverKind::gmres;
    switch (kind) {
      case SolverKind::lu:
        e.solver = add(e.op, saturate(3 * n * sizeof(double)));  // I - K_n factored in a copy
        break;
      case SolverKind::gmres: {  // the Krylov basis V (n x (m+1)) and five more vectors
        const long double m = std::min<long double>(std::max(1, solver.gmres_restart), n);
        e.solver = saturate((m + 6) * n * sizeof(double));
        break;
      }
      default: {  // Neumann: u, K u, the step, the next iterate, the previous step and a residual
        // Per equation iterated together, also E, rho and its columns of the block product
        // (V, H V), and for the fast operator each column's moments (48) of the block, interleaved.
        const long double together = std::max(1, options.channels_together);
        long double bytes = (together == 1 ? 6 : 10 * together) * n * sizeof(double);
        if (op.method == OperatorMethod::fast && together > 1)
          bytes += std::min<long double>(together, FastOperator::kBlockColumns) * (n * 4 / 3) *
                   num_taylor_terms(op.degree) * sizeof(double);
        e.solver = saturate(bytes);
      }
    }
    out.push_back(e);
  }
  return out;
}

LevelMemoryEstimate estimate_level_memory(const geometry::TriangleMesh& mesh, int level, const OperatorOptions& op,
                                          const SolverOptions& solver, double max_reflectivity,
                                          const LevelMemoryOptions& options) {
  return estimate_levels_memory(mesh, {{level, op}}, solver, max_reflectivity, options).front();
}

void refuse_levels_that_cannot_fit(const std::vector<LevelMemoryEstimate>& levels, const std::string& what,
                                   const MemoryAvailability& available) {
  for (const LevelMemoryEstimate& e : levels) {
    // n0 = n / 4^level, exact (a power of two apart); taken as 1 should n be beyond even a long
    // double (a level in the thousands), which is refused all the same.
    const long double n0 = std::ldexp(e.n, -2 * std::min(e.level, 1 << 20));
    const Index roots = n0 >= 1 && n0 <= std::numeric_limits<Index>::max() ? static_cast<Index>(n0) : 1;
    if (const std::string problem = geometry::level_size_problem(roots, e.level); !problem.empty())
      throw ResourceError(what + problem);
  }
  const std::size_t avail = available.bytes();
  for (const LevelMemoryEstimate& e : levels) {
    if (e.total() <= avail / 10 * 9) continue;
    std::ostringstream os;
    os.precision(0);
    os << what << "level " << e.level << " (n = " << std::fixed << e.n << ", " << e.method << ") needs "
       << e.breakdown() << ", more than the " << format_bytes(static_cast<double>(avail)) << " available ("
       << available.binding() << ", 10% kept in reserve); refused before any work: use fewer levels";
    if (e.method.rfind("dense", 0) == 0) os << " or the fast method (section 4)";
    if (levels.size() > 1) os << " (every level is checked before the first is solved)";
    throw ResourceError(os.str());
  }
}

std::string out_of_memory_message(const std::string& stage, double n, std::size_t need_bytes) {
  std::ostringstream os;
  os.precision(0);
  os << "out of memory while " << stage << " (n = " << std::fixed << n;
  if (need_bytes > 0) os << "; about " << show(need_bytes) << " needed";
  os << "; " << describe_available_memory() << ")";
  return os.str();
}

}  // namespace panelrad

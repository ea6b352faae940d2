#pragma once
// Memory a solve needs at a given refinement level, estimated from the input mesh alone, before
// anything is built: the cluster tree (40), the collocation data (32), the operator (the dense
// K_n of (33), or the fast operator of section 4) and the solver's work vectors. A command checks
// every level it will solve before it computes the first one, and refuses (ResourceError, with
// the estimate) a level that cannot fit in the memory this process may still allocate
// (available_memory_bytes: MemAvailable, ulimit -v and the cgroup limit).
//
// The fast operator's estimate here is a first gate, a lower bound: its exact per-element and
// per-cluster arrays plus the far-field lists (44) at the far pairs per row measured on the
// coverings (42) of a coarse level of the same mesh (at most kCoarseElements elements; 256
// sampled rows, FastOperator::estimate_memory). Refining
// never removes a far pair: a cluster admissible (41) for P stays in the finer tree and stays
// admissible, and a non-admissible leaf is replaced by its children, some of them far; so the
// coarse count bounds the fine one from below (measured on the cube, eta 0.5: 74, 84, 89 far
// pairs per row at n = 768, 3072, 12288). The near field, whose pairs per row can fall with
// refinement, and the optional stored far-field coefficients are left out. The precise gate,
// FastOperator::estimate_memory on the built tree's sampled coverings, runs again before the
// operator allocates anything.
#include <panelrad/geometry/mesh.hpp>
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/support/resources.hpp>
#include <panelrad/solve/solvers.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace panelrad {

/// Largest coarse level used for the fast operator's far pairs per row: n0 4^l <= this. Levels
/// of at most this many elements get no list estimate (their lists take a few MB at most).
inline constexpr long long kCoarseElements = 1024;

/// Estimated bytes of one level, each part saturating at SIZE_MAX.
struct LevelMemoryEstimate {
  int level = 0;
  long double n = 0;            ///< n0 4^level (may exceed the 32-bit index: then refused)
  std::string method;           ///< describe_parameters() of the operator planned
  std::size_t tree = 0;         ///< geometry::ClusterTree::estimate_bytes
  std::size_t collocation = 0;  ///< rho, E (and u) per element
  std::size_t op = 0;           ///< dense: n^2 doubles; fast: lower bound (see above)
  bool op_is_lower_bound = false;
  std::size_t solver = 0;       ///< work vectors of the iteration; LU: a second n x n matrix
  std::size_t fields = 0;       ///< the caller's per-element results (e.g. the scene's outputs)
  std::size_t total() const;
  /// "cluster tree 9.66 GB + collocation 1.21 GB + operator >= 7.20 GB + solver 2.42 GB = 20.5 GB"
  std::string breakdown() const;
};

/// What a level's solve holds besides the tree and the operator.
struct LevelMemoryOptions {
  int collocation_vectors = 3;           ///< doubles per element kept by the collocation(s)
  std::size_t field_bytes_per_element = 0;  ///< results kept per element by the caller
  /// Equations iterated together (RadiositySolver::solve_channels: the Neumann channels of a
  /// scene), each with its vectors, and the fast operator's moments (48) of up to
  /// FastOperator::kBlockColumns of them per block product.
  int channels_together = 1;
  /// The fast operator will have target clusters (options.local on a convex scene): its
  /// per-point coverings start below the targets and hold fewer pairs per row as the level grows
  /// (on the cube, eta 0.5, M 6: 12.4, 6.3 and 3.2 far pairs per row at n = 196,608, 786,432 and
  /// 3,145,728), so a coarse level bounds them from above, not below: the lower bound counts no
  /// far lists, and the precise gate (FastOperator::estimate_memory with the targets) counts them.
  bool target_clusters = false;
};

/// A level to be solved and the operator it will get.
struct PlannedLevel {
  int level = 0;
  OperatorOptions op;
};

/// The estimates of several levels of one mesh (one coarse covering per eta, shared by them).
std::vector<LevelMemoryEstimate> estimate_levels_memory(const geometry::TriangleMesh& mesh,
                                                        const std::vector<PlannedLevel>& levels,
                                                        const SolverOptions& solver, double max_reflectivity,
                                                        const LevelMemoryOptions& options = {});

/// The estimate for `mesh` refined `level` times with operator `op` and solver `solver`
/// (automatic: GMRES's need, the larger, since it may run; `max_reflectivity` is kept for callers).
LevelMemoryEstimate estimate_level_memory(const geometry::TriangleMesh& mesh, int level, const OperatorOptions& op,
                                          const SolverOptions& solver, double max_reflectivity,
                                          const LevelMemoryOptions& options = {});

/// Throws ResourceError for the first level whose elements or clusters exceed the 32-bit index
/// (geometry::level_size_problem: its count, before any memory figure), else for the first
/// estimate whose total exceeds 90% of available_bytes (10% is left for what is not counted:
/// strings, the allocator, thread stacks), naming `what` (a prefix: "cube ", "scene.obj: "), the
/// level, n, the breakdown, what is available and which limit gives it.
void refuse_levels_that_cannot_fit(const std::vector<LevelMemoryEstimate>& levels, const std::string& what,
                                   const MemoryAvailability& available = memory_availability());

/// Runs `stage` and turns a std::bad_alloc into a ResourceError naming the stage and what was
/// being allocated: "out of memory while building the near field (n = 196608; about 1.21 GB
/// needed, 0.80 GB available (address-space limit, ulimit -v))". `need_bytes` 0: not known.
template <class F>
decltype(auto) run_stage(const std::string& stage, double n, std::size_t need_bytes, F&& f);

/// The message run_stage throws.
std::string out_of_memory_message(const std::string& stage, double n, std::size_t need_bytes);

template <class F>
decltype(auto) run_stage(const std::string& stage, double n, std::size_t need_bytes, F&& f) {
  try {
    return f();
  } catch (const std::bad_alloc&) {
    throw ResourceError(out_of_memory_message(stage, n, need_bytes));
  }
}

}  // namespace panelrad

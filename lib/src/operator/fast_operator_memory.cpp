// The fast operator's memory: the estimate before setup (from the coverings of sampled rows),
// the refusal of what will not fit, and the bytes held after setup.
#include <panelrad/operator/fast_operator.hpp>

#include "admissible_covering.hpp"
#include "fast_operator_common.hpp"
#include "target_clusters.hpp"
#include <panelrad/support/chunk_pool.hpp>
#include <panelrad/support/resources.hpp>

#include <algorithm>
#include <exception>

namespace panelrad {

using geometry::Index;

// Refuses what will not fit, before any large allocation.
void FastOperator::refuse_beyond_memory(const Collocation& collocation, const TargetClusters* targets) const {
  // What is available is read (files of /proc and the cgroup, serial) by one thread while the
  // others sample the coverings.
  std::size_t limit = options_.memory_limit;
  const MemoryEstimate est = estimate_memory(collocation, options_.eta, options_.degree, rows(), targets, [&] {
    if (!limit) limit = available_memory_bytes();
  });
  const std::size_t peak = est.bytes + est.list_bytes;
  if (peak > limit && !options_.memory_limit && ChunkPool::process().kept_bytes() > 0) {
    ChunkPool::process().release();  // the lists' chunks kept from earlier setups, before refusing
    limit = available_memory_bytes();
  }
  if (peak > limit)
    throw ResourceError("fast operator for n = " + std::to_string(n_) + rows_note() + " needs about " +
                        format_bytes(static_cast<double>(peak)) + " during setup (" +
                        format_bytes(static_cast<double>(est.list_bytes)) + " of near/far lists for about " +
                        std::to_string(est.far_pairs) + " far pairs), more than the " +
                        format_bytes(static_cast<double>(limit)) + " available; use fewer levels or a larger eta");
}

std::size_t FastOperator::held_bytes() const {
  const std::size_t num_clusters = static_cast<std::size_t>(level_offset_.back());
  std::size_t lists = 0;
  for (const RowBlock& blk : blocks_) lists += blk.bytes();
  return lists + far_coef_.bytes() + far_coef_single_.bytes() +
         cluster_origin_.size() * sizeof(ClusterOrigin) + root_axes_.size() * sizeof(PlaneFrame) + leaf_shift_.size() * sizeof(double) +
         to_parent_.size() * sizeof(to_parent_[0]) +
         (shape_moments_.size() + child_shape_moments_.size()) * sizeof(double) + rho_.size() * sizeof(double) +
         (num_clusters - static_cast<std::size_t>(n_)) * static_cast<std::size_t>(terms_) * sizeof(double) /* moments per product, above the finest level */ +
         (targets_ ? targets_->bytes() + local_slot_.size() * sizeof(std::int64_t) + active_targets_.size() * sizeof(Index) +
                         active_targets_.size() * static_cast<std::size_t>(num_local_points(targets_->degree)) *
                             sizeof(double) /* values per product */
                   : 0);
}

FastOperator::MemoryEstimate FastOperator::estimate_memory(const Collocation& collocation, double eta, int degree,
                                                           const RowRange& row_range) {
  return estimate_memory(collocation, eta, degree, row_range, nullptr);
}

FastOperator::MemoryEstimate FastOperator::estimate_memory(const Collocation& collocation, const FastOptions& options) {
  const std::shared_ptr<TargetClusters> targets = make_target_clusters(collocation.tree(), options);
  return estimate_memory(collocation, options.eta, options.degree, options.rows, targets.get());
}

FastOperator::MemoryEstimate FastOperator::estimate_memory(const Collocation& collocation, double eta, int degree,
                                                           const RowRange& row_range, const TargetClusters* targets,
                                                           const std::function<void()>& alongside) {
  const geometry::ClusterTree& tree = collocation.tree();
  const Index n = tree.num_elements();
  const auto [begin, end] = resolve_rows(row_range, n);
  const Index m = end - begin;
  const int L = tree.finest_level();
  const std::size_t T = static_cast<std::size_t>(num_taylor_terms(degree));
  std::size_t clusters = 0;
  for (int l = 0; l <= L; ++l) clusters += static_cast<std::size_t>(tree.level_size(l));
  const Index samples = std::min<Index>(m, 256);
  std::size_t near = 0, far = 0, sampled = 0, rows = 0;  // integer sums: the same for any thread count
  std::exception_ptr alongside_failed;
#pragma omp parallel reduction(+ : rows, near, far, sampled)
  {
    if (alongside) {
#pragma omp single nowait
      try {
        alongside();
      } catch (...) {
        alongside_failed = std::current_exception();
      }
    }
#pragma omp for schedule(dynamic, kLightChunk) nowait
    for (Index i = begin; i < end; ++i) rows += collocation.reflectivity()[i] != 0;
#pragma omp for schedule(dynamic, 1) nowait
    for (Index s = 0; s < samples; ++s) {
      const Index i = begin + static_cast<Index>((static_cast<std::int64_t>(s) * m + m / 2) / samples);
      if (collocation.reflectivity()[i] == 0) continue;
      ++sampled;
      const ClusterRef* starts = nullptr;  // the per-point covering from the roots, or below P's targets
      std::int64_t count = 0;
      if (targets) {
        const std::size_t a = static_cast<std::size_t>(i >> (2 * (L - targets->finest_level)));
        starts = targets->start.data() + targets->start_start[a];
        count = targets->start_start[a + 1] - targets->start_start[a];
      }
      cover(tree, collocation.collocation_point(i), tree.plane(L, i), eta, starts, count, [&](int, Index) { ++far; },
            [&](Index) { ++near; }, [] {});
    }
  }
  if (alongside_failed) std::rethrow_exception(alongside_failed);
  MemoryEstimate e;
  const double per_row = sampled ? 1.0 / static_cast<double>(sampled) : 0.0;
  const std::size_t near_pairs = static_cast<std::size_t>(static_cast<double>(near) * per_row * static_cast<double>(rows));
  e.far_pairs = static_cast<std::size_t>(static_cast<double>(far) * per_row * static_cast<double>(rows));
  e.near_pairs = near_pairs;
  e.list_bytes = near_pairs * (sizeof(Index) + sizeof(double)) + e.far_pairs * sizeof(Index);
  e.coefficient_bytes = e.far_pairs * T * sizeof(double);
  e.bytes = e.list_bytes + fixed_bytes(static_cast<std::size_t>(n), clusters, degree, static_cast<std::size_t>(m));
  if (targets) {  // the targets and their sources, a slot each and its values in a product (every target with one)
    const std::size_t num_targets = targets->box.size();
    e.bytes += targets->bytes() +
               num_targets * (sizeof(std::int64_t) + sizeof(Index) +
                              static_cast<std::size_t>(num_local_points(targets->degree)) * sizeof(double));
  }
  return e;
}

std::size_t FastOperator::fixed_bytes(std::size_t n, std::size_t clusters, int degree) {
  return fixed_bytes(n, clusters, degree, n);
}

std::size_t FastOperator::fixed_bytes(std::size_t n, std::size_t clusters, int degree, std::size_t rows) {
  const std::size_t T = static_cast<std::size_t>(num_taylor_terms(degree));
  // Per cluster above the finest level (clusters - n): frame, offset to the parent and moments
  // per product (an element's frame and moments are formed when read); per element: rho; per row
  // held: the near/far row starts; the element moments by shape, two per root (one at level 0:
  // n = n0), and four sets per placement class of level L - 1 (none at level 0);
  // n0 = 4 n - 3 clusters since clusters = n0 (4^(L+1) - 1) / 3 and n = n0 4^L.
  const std::size_t roots = 4 * n - 3 * clusters;
  const std::size_t shapes = std::min(n, 2 * roots);
  int L = 0;  // n = n0 4^L
  while (roots > 0 && L < 31 && (roots << (2 * L)) < n) ++L;
  const std::size_t parent_shapes = L >= 1 ? roots * static_cast<std::size_t>(placement_classes(L - 1)) : 0;  // 4 T each
  return (clusters - std::min(clusters, n)) * (sizeof(ClusterOrigin) + (T + 2) * sizeof(double)) +
         roots * (sizeof(PlaneFrame) + 6 * sizeof(double)) +
         n * sizeof(double) + (shapes + 4 * parent_shapes) * T * sizeof(double) + rows * 2 * sizeof(std::uint32_t) +
         (rows + static_cast<std::size_t>(kRowBlock) - 1) / static_cast<std::size_t>(kRowBlock) * (sizeof(RowBlock) + 2 * sizeof(std::uint32_t));
}

}  // namespace panelrad

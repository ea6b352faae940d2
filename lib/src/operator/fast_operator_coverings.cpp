// The fast operator's coverings: for each row held, the minimal admissible covering (42) of the
// surface by the clusters of the tree (the walk of admissible_covering.hpp, or with V that of
// visible_covering.hpp), its near-field integrals (43), and the row lists that hold them.
#include <panelrad/operator/fast_operator.hpp>

#include "admissible_covering.hpp"
#include "fast_operator_common.hpp"
#include "target_clusters.hpp"
#include "visible_covering.hpp"
#include <panelrad/support/resources.hpp>

#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <new>
#include <stdexcept>

namespace panelrad {

using geometry::Index;

// The lists of the block being built, per thread (reused from block to block): per row its
// counts, and the block's near-field element ids with their integrals and far-field cluster ids.
struct FastOperator::CoveringLists {
  std::vector<std::int64_t> near_count, far_count;
  std::vector<Index> near_col, far_cluster;
  std::vector<double> near_val;
  VisibleCoveringScratch scratch;
  NearFieldIntegrator integrate_near;
};

// Integer counts, summed over the threads at the end (the same for any thread count).
struct FastOperator::CoveringTally {
  std::size_t skipped = 0, skipped_rows = 0;
  VisibilityCounts counts;
  bool out_of_memory = false, too_long = false;
  void add(const CoveringTally& t) {
    skipped += t.skipped;
    skipped_rows += t.skipped_rows;
    counts += t.counts;
    out_of_memory = out_of_memory || t.out_of_memory;
    too_long = too_long || t.too_long;
  }
};

// One traversal per row held, in blocks of kRowBlock rows (dynamically scheduled): each thread
// gathers a block's coverings (42) (and the near-field integrals, (43) first sum) in lists of its
// own, reused from block to block, then writes them once into one piece of exactly their size in
// its own chunks (list_chunks_, kept by the process between operators: chunk_pool.hpp). Every
// block depends on its rows alone, so the lists are identical for any thread count.
void FastOperator::cover_rows() {
  const Index num_blocks = (row_end_ - row_begin_ + kRowBlock - 1) / kRowBlock;
  blocks_.clear();
  blocks_.resize(static_cast<std::size_t>(num_blocks));
  list_chunks_.reset(omp_get_max_threads());
  CoveringTally total;
#pragma omp parallel
  {
    CoveringLists lists{{}, {}, {}, {}, {}, {}, NearFieldIntegrator(options_.near, tree_->mesh_size())};
    CoveringTally tally;
#pragma omp for schedule(dynamic, 1)
    for (Index b = 0; b < num_blocks; ++b) try {
      cover_block(b, lists, tally);
      if (std::max(lists.near_col.size(), lists.far_cluster.size()) > std::numeric_limits<std::uint32_t>::max()) {
        tally.too_long = true;
        continue;
      }
      store_block(b, lists);
    } catch (const std::bad_alloc&) {
      tally.out_of_memory = true;
    }
#pragma omp critical(panelrad_covering_tally)
    total.add(tally);
  }
  if (total.out_of_memory || total.too_long) {
    blocks_.clear();
    list_chunks_.clear();
    if (total.too_long)
      throw ResourceError("fast operator for n = " + std::to_string(n_) + rows_note() + ": a block of " +
                          std::to_string(kRowBlock) + " rows has more than 2^32 near or far pairs; use a larger eta");
    throw ResourceError("fast operator for n = " + std::to_string(n_) + rows_note() +
                        ": out of memory while building the near and far field lists (" + describe_available_memory() +
                        "); use fewer levels or a larger eta");
  }
  stats_.skipped_coplanar = total.skipped + total.counts.coplanar;
  stats_.skipped_rows = total.skipped_rows;
  stats_.occluded = options_.occluders != nullptr;
  stats_.visible_pairs = total.counts.visible;
  stats_.hidden_pairs = total.counts.hidden;
  stats_.partial_pairs = total.counts.partial;
  stats_.clipped_elements = total.counts.clipped;
}

void FastOperator::cover_block(Index b, CoveringLists& lists, CoveringTally& tally) const {
  const Index first = row_begin_ + b * kRowBlock, last = std::min(row_end_, first + kRowBlock);
  lists.near_count.assign(static_cast<std::size_t>(last - first), 0);
  lists.far_count.assign(static_cast<std::size_t>(last - first), 0);
  lists.near_col.clear();
  lists.near_val.clear();
  lists.far_cluster.clear();
  for (Index i = first; i < last; ++i) {
    const double rho = rho_[static_cast<std::size_t>(i)];
    if (rho == 0) {  // the row is zero: not computed
      ++tally.skipped_rows;
      continue;
    }
    if (!probed_.empty() && !probed_[static_cast<std::size_t>(i - row_begin_)]) continue;  // a probe's row not sampled
    const std::size_t near_before = lists.near_col.size(), far_before = lists.far_cluster.size();
    cover_row(i, rho, lists, tally);
    lists.near_count[static_cast<std::size_t>(i - first)] = static_cast<std::int64_t>(lists.near_col.size() - near_before);
    lists.far_count[static_cast<std::size_t>(i - first)] = static_cast<std::int64_t>(lists.far_cluster.size() - far_before);
  }
}

void FastOperator::cover_row(Index i, double rho, CoveringLists& lists, CoveringTally& tally) const {
  const geometry::ClusterTree& tree = *tree_;
  const int L = tree.finest_level();
  const Vec3& P = tree.collocation_point(i);
  const Vec3& nP = tree.cluster(L, i).normal;
  const auto add_far = [&](int l, Index k) { lists.far_cluster.push_back(cluster_id(l, k)); };
  const ClusterRef* starts = nullptr;
  std::int64_t count = 0;
  if (targets_) {  // the clusters left by P's target cluster of level lt; its coplanar roots
    const std::size_t a = static_cast<std::size_t>(i >> (2 * (L - targets_->finest_level)));
    starts = targets_->start.data() + targets_->start_start[a];
    count = targets_->start_start[a + 1] - targets_->start_start[a];
    tally.skipped += static_cast<std::size_t>(targets_->coplanar_roots[static_cast<std::size_t>(i >> (2 * L))]);
  }
  if (options_.occluders) {
    // P's sight cluster: its ancestor kSightLevels up (at most 4^kSightLevels points, consecutive
    // rows), which decides each root's visibility once for all its points (cluster_sight.hpp).
    const int ls = std::max(0, L - kSightLevels);
    lists.scratch.sight.begin((std::int64_t{ls} << 48) + (i >> (2 * (L - ls))),
                              L > 0 ? &tree.cluster(ls, i >> (2 * (L - ls))) : nullptr, tree.num_roots());
    cover_visible(
        tree, *options_.occluders, P, nP, tree.plane(L, i), options_.eta, lists.integrate_near, add_far,
        [&](Index e, double value) {
          lists.near_col.push_back(e);
          lists.near_val.push_back(rho * value);  // (43), first sum, over the visible part
        },
        tally.counts, lists.scratch, starts, count);
    return;
  }
  cover(
      tree, P, tree.plane(L, i), options_.eta, starts, count, add_far,
      [&](Index e) {
        lists.near_col.push_back(e);
        lists.near_val.push_back(rho * lists.integrate_near(P, nP, tree.cluster(L, e)));  // (43), first sum
      },
      [&]() { ++tally.skipped; });
}

void FastOperator::store_block(Index b, const CoveringLists& lists) {
  RowBlock& blk = blocks_[static_cast<std::size_t>(b)];
  const std::size_t rows = lists.near_count.size();
  const std::size_t value_bytes = options_.single_precision_near ? sizeof(float) : sizeof(double);
  blk.lists = list_chunks_.allocate(omp_get_thread_num(), RowBlock::list_bytes(rows, lists.near_col.size(),
                                                                               lists.far_cluster.size(), value_bytes));
  blk.value_bytes = static_cast<std::uint32_t>(value_bytes);
  blk.rows = static_cast<std::uint32_t>(rows);
  blk.near = static_cast<std::uint32_t>(lists.near_col.size());
  blk.far = static_cast<std::uint32_t>(lists.far_cluster.size());
  std::uint32_t* near_start = blk.near_start();
  std::uint32_t* far_start = blk.far_start();
  std::uint32_t near = 0, far = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    near_start[r] = near;
    far_start[r] = far;
    near += static_cast<std::uint32_t>(lists.near_count[r]);
    far += static_cast<std::uint32_t>(lists.far_count[r]);
  }
  near_start[rows] = near;
  far_start[rows] = far;
  std::copy(lists.near_col.begin(), lists.near_col.end(), blk.near_col());
  if (options_.single_precision_near)
    std::transform(lists.near_val.begin(), lists.near_val.end(), blk.near_val_single(),
                   [](double x) { return static_cast<float>(x); });
  else
    std::copy(lists.near_val.begin(), lists.near_val.end(), blk.near_val());
  std::copy(lists.far_cluster.begin(), lists.far_cluster.end(), blk.far_cluster());
}

// The blocks' first far pairs among all (a short serial pass over the blocks), the pair counts,
// and whether the far coefficients are stored (far_storage_chosen), else they are recomputed in
// each product.
void FastOperator::store_coverings() {
  std::int64_t near = 0, far = 0;
  for (RowBlock& blk : blocks_) {
    blk.far_first = far;
    near += blk.near;
    far += blk.far;
  }
  stats_.near_pairs = static_cast<std::size_t>(near);
  stats_.far_pairs = static_cast<std::size_t>(far);
  stats_.far_stored = far_storage_chosen();
}

FastOperator::RowLists FastOperator::row_lists(std::size_t r) const {
  const RowBlock& blk = blocks_[r / static_cast<std::size_t>(kRowBlock)];
  const std::size_t k = r % static_cast<std::size_t>(kRowBlock);
  const std::uint32_t* near_start = blk.near_start();
  const std::uint32_t* far_start = blk.far_start();
  const std::uint32_t near = near_start[k], far = far_start[k];
  const bool single = blk.value_bytes == sizeof(float);
  return {blk.near_col() + near, single ? nullptr : blk.near_val() + near, single ? blk.near_val_single() + near : nullptr,
          near_start[k + 1] - near,
          blk.far_cluster() + far, far_start[k + 1] - far, blk.far_first + far};
}

std::vector<Index> FastOperator::far_clusters(Index i) const {
  const std::size_t r = local_row(i, "far_clusters");
  std::vector<Index> out, targets;
  if (row_computed(i)) append_target_ancestors(i, targets);
  for (const Index id : targets) {
    const std::int64_t first = targets_->source_start[static_cast<std::size_t>(id)];
    out.insert(out.end(), targets_->source.begin() + first, targets_->source.begin() + first + targets_->sources(id));
  }
  const RowLists row = row_lists(r);
  out.insert(out.end(), row.far_cluster, row.far_cluster + row.far_count);
  return out;
}

std::vector<Index> FastOperator::near_elements(Index i) const {
  const std::size_t r = local_row(i, "near_elements");
  const RowLists row = row_lists(r);
  return {row.near_col, row.near_col + row.near_count};
}

}  // namespace panelrad

// The fast operator's target clusters (local_expansion.hpp, target_clusters.hpp): which levels
// hold them, their slots in a product, and their local expansions' values and interpolants.
#include <panelrad/operator/fast_operator.hpp>

#include "far_field_batch.hpp"
#include <panelrad/operator/kernel.hpp>
#include "target_clusters.hpp"

#include <algorithm>
#include <stdexcept>

namespace panelrad {

using geometry::Cluster;
using geometry::Index;

// The levels, degree and eta_t of the target clusters of an operator of `options` on a tree of
// finest level L: levels 0..lt, lt the finest level whose clusters hold at least min_points
// collocation points; lt = -1 when there are none (local expansions off, or no level with that
// many points). With V the pairs are classified for whole targets (target_clusters.hpp).
FastOperator::TargetPlan FastOperator::target_plan(const FastOptions& options, int L) {
  const LocalExpansionOptions& local = options.local;
  TargetPlan plan;
  // With V one degree more: measured on the Cornell box at n = 61,440 (0.4, M 8), the self-check
  // is 9.1e-6 with d = 5, above the automatic rule's 9.0e-6, and 3.1e-6 with d = 6.
  plan.degree = local.degree >= 0 ? local.degree : default_local_degree(options.degree) + (options.occluders ? 1 : 0);
  plan.eta = local.eta > 0 ? local.eta : options.eta;
  const std::int64_t min_points = local.min_points > 0 ? local.min_points : num_local_points(plan.degree) + 1;
  if (!local.enabled) return plan;
  for (int l = 0; l <= L; ++l)
    if ((std::int64_t{1} << (2 * (L - l))) >= min_points) plan.level = l;
  return plan;
}

// The target clusters of target_plan with their sources (build_target_clusters), from the frames
// of the target levels (the same frames setup_cluster_frames makes); null when there are none.
std::shared_ptr<TargetClusters> FastOperator::make_target_clusters(const geometry::ClusterTree& tree,
                                                                   const FastOptions& options) {
  const TargetPlan plan = target_plan(options, tree.finest_level());
  if (plan.level < 0) return nullptr;
  const std::vector<Index> offset = level_offsets(tree);
  const double unit = far_field_unit(tree);
  // Written by the parallel loop below, not zeroed first by one thread; the levels are
  // independent, so no thread waits at the end of one.
  KeptVector<PlaneFrame> frames(static_cast<std::size_t>(offset[static_cast<std::size_t>(plan.level) + 1]));
#pragma omp parallel
  for (int l = 0; l <= plan.level; ++l) {
    const Index m = tree.level_size(l);
#pragma omp for schedule(dynamic, 256) nowait
    for (Index k = 0; k < m; ++k) {
      const Cluster& c = tree.cluster(l, k);
      frames[static_cast<std::size_t>(offset[static_cast<std::size_t>(l)] + k)] = make_plane_frame(unit * c.centre, c.normal);
    }
  }
  return std::make_shared<TargetClusters>(
      build_target_clusters(tree, frames.data(), offset, unit, options.eta, plan.eta, plan.level, plan.degree,
                            options.occluders.get()));
}

// The target clusters' slots: a target gets a slot for its values in a product when it holds a
// computed row and has sources of its own or a parent with a slot (whose expansion it inherits).
void FastOperator::setup_target_clusters(std::shared_ptr<TargetClusters> targets) {
  if (!targets) return;
  const geometry::ClusterTree& tree = *tree_;
  const int L = tree.finest_level();
  const int lt = targets->finest_level;
  report_stage("fast operator: target clusters of levels 0.." + std::to_string(lt) + " and their local expansions, d " +
               std::to_string(targets->degree));
  // Targets containing a computed row: marked on level lt, then up the tree.
  const Index num_targets = level_offset_[static_cast<std::size_t>(lt) + 1];
  std::vector<char> has_row(static_cast<std::size_t>(num_targets), 0);
  const Index first_target = row_begin_ >> (2 * (L - lt)), end_target = ((row_end_ - 1) >> (2 * (L - lt))) + 1;
#pragma omp parallel for schedule(dynamic, 64)
  for (Index k = first_target; k < std::max(first_target, end_target); ++k) {  // the targets of level lt: their rows
    const Index first = std::max(row_begin_, tree.first_element(lt, k)), end = std::min(row_end_, tree.end_element(lt, k));
    for (Index i = first; i < end && !has_row[static_cast<std::size_t>(cluster_id(lt, k))]; ++i)
      if (row_computed(i)) has_row[static_cast<std::size_t>(cluster_id(lt, k))] = 1;
  }
  for (int l = lt - 1; l >= 0; --l)
    for (Index k = 0; k < tree.level_size(l); ++k)
      for (Index c = 0; c < 4; ++c)
        has_row[static_cast<std::size_t>(cluster_id(l, k))] |= has_row[static_cast<std::size_t>(cluster_id(l + 1, 4 * k + c))];
  local_slot_.assign(static_cast<std::size_t>(num_targets), -1);
  for (int l = 0; l <= lt; ++l)
    for (Index k = 0; k < tree.level_size(l); ++k) {
      // A slot for every target with a computed row whose own or inherited expansion is not empty.
      const Index id = cluster_id(l, k);
      const bool inherits = l > 0 && local_slot_[static_cast<std::size_t>(cluster_id(l - 1, k / 4))] >= 0;
      if (!has_row[static_cast<std::size_t>(id)] || (targets->sources(id) == 0 && !inherits)) continue;
      local_slot_[static_cast<std::size_t>(id)] = static_cast<std::int64_t>(active_targets_.size());
      active_targets_.push_back(id);
      if (targets->sources(id) == 0) continue;
      ++stats_.target_clusters;
      stats_.target_pairs += static_cast<std::size_t>(targets->sources(id));
      stats_.target_point_pairs += static_cast<std::size_t>(targets->sources(id)) << (2 * (L - l));
    }
  stats_.target_hidden_pairs = targets->hidden_pairs;
  stats_.target_undecided_pairs = targets->undecided_pairs;
  stats_.target_level = lt;
  stats_.local_degree = targets->degree;
  targets_ = std::move(targets);
}

// Measured with bench/product on the cube at n = 49,152 (eta 0.5, M 6..8, 256 sampled rows): d = 4
// (25 points) adds no visible error to M <= 8 and is the fastest there (d = 3 gives 3e-4 at M 7,
// 13x the per-point error); above M = 7 the degree follows the Taylor degree, d = M - 3.
int default_local_degree(int M) { return M <= 4 ? M : std::max(4, M - 3); }

void FastOperator::append_target_ancestors(Index i, std::vector<Index>& out) const {
  if (!targets_) return;
  const int L = tree_->finest_level();
  for (int l = 0; l <= targets_->finest_level; ++l) {
    const Index id = cluster_id(l, i >> (2 * (L - l)));
    if (local_slot_[static_cast<std::size_t>(id)] >= 0) out.push_back(id);
  }
}

void FastOperator::evaluate_local_expansions(const double* moments, const double* v, int C,
                                             const std::vector<Index>& targets, std::vector<double>& values) const {
  evaluate_target_sources(moments, v, C, targets, values);
  inherit_parent_expansions(C, targets, values);
}

// Each target's values at its (d+1)^2 points: a far-field row (47) of the point (with the
// target's n_P and the factor 1/pi; rho_i multiplies the interpolant) over the target's sources,
// by the recomputing kernels of far_field_batch.hpp. Independent per target: any thread count
// gives the same values.
void FastOperator::evaluate_target_sources(const double* moments, const double* v, int C,
                                           const std::vector<Index>& targets, std::vector<double>& values) const {
  const int d = targets_->degree;
  const int N = num_local_points(d);
  const std::size_t table = static_cast<std::size_t>(N) * static_cast<std::size_t>(C);
  values.assign(active_targets_.size() * table, 0.0);
  const far_field_batch::Kernels& kernels = far_field_batch::kernels();
  const Index count = static_cast<Index>(targets.size());
  const far_field_batch::ClusterMoments all_moments = cluster_moments(moments, v);
  bool failed = false;
#pragma omp parallel for schedule(dynamic, 1)
  for (Index t = 0; t < count; ++t) {
    const Index id = targets[static_cast<std::size_t>(t)];
    if (targets_->sources(id) == 0) continue;  // inherits its parent's expansion only
    const auto [l, k] = cluster_of_id(id);
    const Vec3& normal = tree_->cluster(l, k).normal;
    Vec3 points[num_local_points(kMaxLocalDegree)];
    targets_->box[static_cast<std::size_t>(id)].points(frame(id), d, points);
    far_field_batch::RowPoint rows[num_local_points(kMaxLocalDegree)];
    for (int q = 0; q < N; ++q)
      rows[q] = {{points[q][0], points[q][1], points[q][2]}, {normal[0], normal[1], normal[2]}, 1.0 / pi};
    const std::int64_t first = targets_->source_start[static_cast<std::size_t>(id)];
    double* out = values.data() + static_cast<std::size_t>(local_slot_[static_cast<std::size_t>(id)]) * table;
    if (!far_field_batch::add_points(kernels, options_.degree, rows, N, cluster_frames(), targets_->source.data() + first,
                                     targets_->sources(id), all_moments, C, out)) {
#pragma omp atomic write
      failed = true;
    }
  }
  if (failed)
    throw std::invalid_argument("FastOperator: an interpolation point of a target cluster coincides with the centre "
                                "A(tau) of one of its sources or is not finite");
}

// Downward, level by level: each target adds its parent's expansion, evaluated at its own points
// (the parent's interpolant, a tensor polynomial of degree d, is re-interpolated exactly up to
// rounding: the child's rectangle lies in the parent's, in the same plane).
void FastOperator::inherit_parent_expansions(int C, const std::vector<Index>& targets,
                                             std::vector<double>& values) const {
  const int d = targets_->degree;
  const int N = num_local_points(d);
  const std::size_t table = static_cast<std::size_t>(N) * static_cast<std::size_t>(C);
  const std::size_t C_ = static_cast<std::size_t>(C);
  for (int l = 1; l <= targets_->finest_level; ++l) {  // targets is ascending: level l's ids are one range
    const auto begin = std::lower_bound(targets.begin(), targets.end(), level_offset_[static_cast<std::size_t>(l)]);
    const auto end = std::lower_bound(begin, targets.end(), level_offset_[static_cast<std::size_t>(l) + 1]);
    const std::int64_t first = begin - targets.begin(), last = end - targets.begin();
#pragma omp parallel for schedule(dynamic, 16)
    for (std::int64_t t = first; t < last; ++t) {
      const Index id = targets[static_cast<std::size_t>(t)];
      const Index parent = cluster_id(l - 1, (id - cluster_id(l, 0)) / 4);
      const std::int64_t parent_slot = local_slot_[static_cast<std::size_t>(parent)];
      if (parent_slot < 0) continue;
      Vec3 points[num_local_points(kMaxLocalDegree)];
      targets_->box[static_cast<std::size_t>(id)].points(frame(id), d, points);
      const LocalBox& parent_box = targets_->box[static_cast<std::size_t>(parent)];
      const PlaneFrame parent_frame = frame(parent);
      const double* from = values.data() + static_cast<std::size_t>(parent_slot) * table;
      double* out = values.data() + static_cast<std::size_t>(local_slot_[static_cast<std::size_t>(id)]) * table;
      for (int q = 0; q < N; ++q) {
        double part[4];
        parent_box.interpolate(parent_frame, d, from, C, points[q], part);
        for (std::size_t c = 0; c < C_; ++c) out[static_cast<std::size_t>(q) * C_ + c] += part[c];
      }
    }
  }
}

template <int C>
void FastOperator::add_local_expansions(Index i, const double* values, double* sum) const {
  const int L = tree_->finest_level();
  const int d = targets_->degree;
  const std::size_t table = static_cast<std::size_t>(num_local_points(d)) * C;
  const Vec3 P = unit_scale_ * tree_->collocation_point(i);
  const int l = targets_->finest_level;  // its expansion holds those of its ancestors (evaluate_local_expansions)
  const Index id = cluster_id(l, i >> (2 * (L - l)));
  const std::int64_t slot = local_slot_[static_cast<std::size_t>(id)];
  if (slot < 0) return;
  double part[C];
  targets_->box[static_cast<std::size_t>(id)].interpolate(frame(id), d,
                                                           values + static_cast<std::size_t>(slot) * table, C, P, part);
  for (int c = 0; c < C; ++c) sum[c] += part[c];
}

// The block products' column counts (fast_operator_product.cpp).
template void FastOperator::add_local_expansions<1>(Index, const double*, double*) const;
template void FastOperator::add_local_expansions<2>(Index, const double*, double*) const;
template void FastOperator::add_local_expansions<3>(Index, const double*, double*) const;
template void FastOperator::add_local_expansions<4>(Index, const double*, double*) const;

}  // namespace panelrad

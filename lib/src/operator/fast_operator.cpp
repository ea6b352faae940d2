// The fast operator's setup (fast_operator.hpp): the options checked, the stages in order, and
// the rows held. The stages are in their own files: cluster frames and element moments
// (fast_operator_geometry.cpp), target clusters (fast_operator_targets.cpp), coverings
// (fast_operator_coverings.cpp), far store (fast_operator_far_store.cpp), memory estimate
// (fast_operator_memory.cpp); the product in fast_operator_product.cpp and the self-check's rows
// in fast_operator_self_check.cpp.
#include <panelrad/operator/fast_operator.hpp>

#include "fast_operator_common.hpp"
#include "target_clusters.hpp"
#include <panelrad/support/resources.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <tuple>

namespace panelrad {

using geometry::Index;

std::pair<Index, Index> resolve_rows(const RowRange& rows, Index n) {
  const Index end = rows.end == -1 ? n : rows.end;
  if (rows.begin < 0 || rows.begin > end || end > n)
    throw std::invalid_argument("fast method: row range [" + std::to_string(rows.begin) + ", " +
                                std::to_string(rows.end) + ") is not within the rows [0, n) = [0, " +
                                std::to_string(n) + ") (need 0 <= begin <= end <= n; end -1 means n)");
  return {rows.begin, end};
}

FastOperator::FastOperator(const Collocation& collocation, const FastOptions& options)
    : tree_(collocation.shared_tree()), options_(options) {
  check_options();
  n_ = tree_->num_elements();
  std::tie(row_begin_, row_end_) = resolve_rows(options_.rows, n_);
  terms_ = num_taylor_terms(options_.degree);
  Stopwatch clock;
  // The target clusters first (small: levels 0..lt), so that the memory gate counts the
  // per-point coverings that start below them.
  std::shared_ptr<TargetClusters> targets = make_target_clusters(*tree_, options_);
  stats_.targets_s = clock.seconds();
  if (options_.probe_samples > 0) {
    probed_.assign(static_cast<std::size_t>(row_end_ - row_begin_), 0);
    for (const Index i : self_check_rows(options_.probe_samples)) probed_[static_cast<std::size_t>(i - row_begin_)] = 1;
  } else {
    refuse_beyond_memory(collocation, targets.get());  // a probe holds a few rows beside the arrays of (48)
  }
  clock.restart();
  report_stage("fast operator, n = " + std::to_string(n_) + rows_note() + ": cluster frames and element moments");
  setup_cluster_frames();
  setup_element_data(collocation);
  stats_.geometry_s = clock.seconds();
  clock.restart();
  setup_target_clusters(std::move(targets));
  stats_.targets_s += clock.seconds();
  clock.restart();
  {
    char eta[32];
    std::snprintf(eta, sizeof eta, "%g", options_.eta);
    report_stage("fast operator: minimal admissible coverings (42) and near field (43), eta " + std::string(eta) +
                 ", M " + std::to_string(options_.degree));
  }
  cover_rows();
  store_coverings();
  stats_.covering_s = clock.seconds();  // covering (42) and near field (43)
  clock.restart();
  report_stage("fast operator: far field (44)-(45), " + std::to_string(stats_.far_pairs) + " (point, cluster) pairs, " +
               (stats_.far_stored ? "coefficients stored" : "coefficients recomputed per product (memory)"));
  setup_far_coefficients();
  stats_.far_s = clock.seconds();
  stats_.bytes = held_bytes();
}

void FastOperator::check_options() {
  if (!(options_.eta > 0 && options_.eta < 1))
    throw std::invalid_argument("fast method: eta = " + std::to_string(options_.eta) + " is outside (0, 1)");
  if (options_.degree < 0 || options_.degree > 12)
    throw std::invalid_argument("fast method: degree M = " + std::to_string(options_.degree) + " is outside [0, 12]");
  const LocalExpansionOptions& local = options_.local;
  if (local.degree < -1 || local.degree > kMaxLocalDegree)
    throw std::invalid_argument("fast method: local expansion degree d = " + std::to_string(local.degree) +
                                " is outside [0, " + std::to_string(kMaxLocalDegree) + "] (or -1: M)");
  if (!(local.eta >= 0 && local.eta <= 1))
    throw std::invalid_argument("fast method: target admissibility eta_t = " + std::to_string(local.eta) +
                                " is outside (0, 1] (or 0: eta)");
  if (local.min_points < 0)
    throw std::invalid_argument("fast method: local expansion min_points = " + std::to_string(local.min_points) +
                                " is negative");
}

// ", rows [begin, end)" when only some rows are held; empty for the whole operator.
std::string FastOperator::rows_note() const {
  if (holds_all_rows()) return "";
  return ", rows [" + std::to_string(row_begin_) + ", " + std::to_string(row_end_) + ")";
}

void FastOperator::report_stage(const std::string& what) const {
  if (options_.progress) options_.progress(what);
}

bool FastOperator::row_computed(Index i) const {
  return rho_[static_cast<std::size_t>(i)] != 0 && (probed_.empty() || probed_[static_cast<std::size_t>(i - row_begin_)]);
}

// Position of row i in the arrays of the rows held; std::out_of_range for a row not held.
std::size_t FastOperator::local_row(Index i, const char* who) const {
  if (i < row_begin_ || i >= row_end_)
    throw std::out_of_range(std::string("FastOperator::") + who + ": row " + std::to_string(i) +
                            " is not among the rows held, [" + std::to_string(row_begin_) + ", " +
                            std::to_string(row_end_) + ")");
  return static_cast<std::size_t>(i - row_begin_);
}

// The far field's length unit 2^k ~ diameter of the surface: G dS is invariant under scaling
// (G ~ length^-2), and scaling by a power of two is exact, so the Taylor coefficients
// (~ |P-A|^-(2+p+q)) and moments (~ R^(2+p+q)) stay far from overflow and underflow at any scene
// size that validation accepts (lengths 1e-75 .. 1e75), up to M = 12.
double FastOperator::far_field_unit(const geometry::ClusterTree& tree) { return std::ldexp(1.0, -std::ilogb(tree.diameter())); }

// Global cluster ids: the first id of each level l = 0..L+1 (the last: the number of clusters).
std::vector<Index> FastOperator::level_offsets(const geometry::ClusterTree& tree) {
  const int L = tree.finest_level();
  std::vector<Index> offset(static_cast<std::size_t>(L) + 2, 0);
  for (int l = 0; l <= L; ++l) offset[static_cast<std::size_t>(l) + 1] = offset[static_cast<std::size_t>(l)] + tree.level_size(l);
  return offset;
}

std::pair<int, Index> FastOperator::cluster_of_id(Index id) const {
  const auto it = std::upper_bound(level_offset_.begin(), level_offset_.end(), id);
  const int level = static_cast<int>(it - level_offset_.begin()) - 1;
  return {level, id - level_offset_[static_cast<std::size_t>(level)]};
}

}  // namespace panelrad

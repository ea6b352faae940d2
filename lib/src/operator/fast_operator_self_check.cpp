// The fast operator's self-check (self_check.hpp): the exact side on the rows held, with the
// operator's row weights and occluders, and the fast side on the sampled rows alone (apply_row,
// with the local expansions of those rows' target clusters only): the values of apply() on those
// rows, bit for bit, at the cost of those rows.
#include <panelrad/operator/fast_operator.hpp>

#include "target_clusters.hpp"

#include <algorithm>
#include <stdexcept>

namespace panelrad {

using geometry::Index;

SelfCheckVectors FastOperator::self_check_vectors() const { return panelrad::self_check_vectors(*tree_); }

std::vector<Index> FastOperator::self_check_rows(int samples) const {
  return panelrad::self_check_rows(*tree_, row_begin_, row_end_, samples);
}

FastSelfCheckReference FastOperator::self_check_reference(int samples) const {
  if (row_end_ == row_begin_) return {};
  return panelrad::self_check_reference(*tree_, {rho_.data(), rho_.size()}, options_.occluders.get(), samples,
                                        row_begin_, row_end_);
}

FastSelfCheck FastOperator::self_check(int samples) const {
  if (row_end_ == row_begin_) return {};
  return self_check(self_check_reference(samples));
}

FastSelfCheck FastOperator::self_check(const FastSelfCheckReference& reference) const {
  if (row_end_ == row_begin_) return {};
  for (const Index i : reference.rows)
    if (i < row_begin_ || i >= row_end_)
      throw std::invalid_argument("FastOperator::self_check: reference row " + std::to_string(i) +
                                  " is not among the rows held");
  std::vector<Index> targets;  // the sampled rows' target ancestors: only their local expansions are needed
  for (const Index i : reference.rows) append_target_ancestors(i, targets);
  std::sort(targets.begin(), targets.end());
  targets.erase(std::unique(targets.begin(), targets.end()), targets.end());
  // One vector at a time through one array of cluster moments (48): the moments are the largest
  // array of a product (T doubles per cluster above the finest level, n/3 clusters), so holding
  // all vectors at once would take as many times a product's memory.
  std::unique_lock<std::mutex> lock;
  ProductWorkspace own;
  ProductWorkspace& w = acquire_workspace(lock, own);
  return measure_self_check(reference, n_, [&](const Eigen::VectorXd& v, std::span<const Index> rows, std::span<double> out) {
    apply_sampled_rows(v, rows, targets, w, out);
  });
}

void FastOperator::apply_sampled_rows(const Eigen::VectorXd& v, std::span<const Index> rows,
                                      const std::vector<Index>& targets, ProductWorkspace& workspace,
                                      std::span<double> out) const {
  UninitializedVector<double>& moments = workspace.moments;
  std::vector<double>& local_values = workspace.local_values;
  compute_moments(v, moments);
  if (targets_) evaluate_local_expansions(moments.data(), v.data(), 1, targets, local_values);
  const std::size_t S = rows.size();
#pragma omp parallel
  {
    std::vector<double> scratch(static_cast<std::size_t>(terms_));
#pragma omp for schedule(dynamic, 1)
    for (std::size_t r = 0; r < S; ++r) out[r] = apply_row(rows[r], v, moments, local_values, scratch.data());
  }
}

}  // namespace panelrad

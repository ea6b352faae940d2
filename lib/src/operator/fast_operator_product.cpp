// The fast product K_n v (43)-(47): per row held, the near field from its list, the far field from
// the cluster moments (48) with stored or recomputed coefficients, and the local expansions of its
// target clusters; for one vector or a block of columns read together.
#include <panelrad/operator/fast_operator.hpp>

#include "fast_operator_common.hpp"
#include "far_field_batch.hpp"
#include "target_clusters.hpp"

#include <algorithm>
#include <stdexcept>

namespace panelrad {

using geometry::Index;

namespace {

// sum[c] += sum_t coef[t] m[t C + c], (47), t in order for every column c; the stored coefficients
// in double or single precision (widened exactly to double before the product). Reading them is
// what a stored product costs; packets of columns keep the C sums in SIMD registers (Eigen's SIMD
// arithmetic is the scalar IEEE arithmetic, lane by lane, so each column's sum is the C = 1 sum).
template <int C, class Coef>
inline void add_far_terms(const Coef* coef, const double* m, std::size_t T, double* sum) {
  if constexpr (C % 2 == 0) {
    using Packet = Eigen::Array<double, C, 1>;
    Packet acc = Eigen::Map<const Packet>(sum);
    for (std::size_t t = 0; t < T; ++t) acc += static_cast<double>(coef[t]) * Eigen::Map<const Packet>(m + t * C);
    Eigen::Map<Packet> sums(sum);
    sums = acc;
  } else {
    for (std::size_t t = 0; t < T; ++t)
      for (int c = 0; c < C; ++c) sum[c] += static_cast<double>(coef[t]) * m[t * C + c];
  }
}

// The near field of a row (43), first sum, for C columns: entries stored double or float (widened
// exactly), each column's sum in the order of the list.
template <int C, class Value>
void add_near_terms(const Value* val, const Index* col, std::int64_t count, const double* v, double* near) {
  for (std::int64_t j = 0; j < count; ++j) {
    const double k = static_cast<double>(val[j]);
    const double* vj = v + static_cast<std::size_t>(col[j]) * C;
    for (int c = 0; c < C; ++c) near[c] += k * vj[c];
  }
}

}  // namespace

// Row i (held) of the fast product (43) for C vectors, from their cluster moments: near field plus
// far field (47). v and moments hold the C columns interleaved (entry j of column c at j C + c), so
// that the C sums advance together; the lists and far coefficients are read once for all C.
// Recomputed coefficients: the far pairs go kFarFieldLanes at a time through the SIMD kernels of
// far_field_batch.hpp. Stored ones (double or float, widened exactly): pair by pair with
// add_far_terms. Both fix the order of every column's sums independently of C, so a column of a
// block product is bit-identical to the product of that column alone, for any thread count.
template <int C>
void FastOperator::apply_row_columns(Index i, const double* v, const double* moments, const double* local_values,
                                     double* /*scratch*/, double* out) const {
  const std::size_t r = static_cast<std::size_t>(i - row_begin_);
  double near[C], local[C];
  for (int c = 0; c < C; ++c) near[c] = local[c] = 0;
  if (targets_ && row_computed(i)) {
    add_local_expansions<C>(i, local_values, local);
    const double rho = rho_[static_cast<std::size_t>(i)];
    for (int c = 0; c < C; ++c) local[c] *= rho;
  }
  const RowLists row = row_lists(r);
  if (row.near_val_single)
    add_near_terms<C>(row.near_val_single, row.near_col, row.near_count, v, near);
  else
    add_near_terms<C>(row.near_val, row.near_col, row.near_count, v, near);
  const std::int64_t first = row.far_first, count = row.far_count;
  const Index* clusters = row.far_cluster;
  const far_field_batch::Kernels& kernels = far_field_batch::kernels();
  const std::size_t at = static_cast<std::size_t>(first) * static_cast<std::size_t>(terms_);  // pair's coefficients
  far_field_batch::RowSums sums;
  if (!stats_.far_stored) {
    if (!far_field_batch::add_recomputed_row(kernels, options_.degree, far_row_point(i), cluster_frames(), clusters,
                                             count, cluster_moments(moments, v), C, sums))
      throw std::invalid_argument("FastOperator: collocation point " + std::to_string(i) +
                                  " coincides with the centre A(tau) of a far cluster or is not finite");
  } else {
    // Stored: pair by pair, each column's sum in the same order for every C (the block products of
    // several channels read the coefficients once: measured faster than the lanes here).
    const std::size_t T = static_cast<std::size_t>(terms_);
    const far_field_batch::ClusterMoments all_moments = cluster_moments(moments, v);
    double far[C], buffer[far_field_batch::kMaxTerms * C];
    for (int c = 0; c < C; ++c) far[c] = 0;
    for (std::int64_t j = 0; j < count; ++j) {
      const double* m = far_field_batch::cluster_moments(all_moments, clusters[j], terms_, C, buffer);
      if (options_.single_precision_coefficients) add_far_terms<C>(far_coef_single_.data() + at + static_cast<std::size_t>(j) * T, m, T, far);
      else add_far_terms<C>(far_coef_.data() + at + static_cast<std::size_t>(j) * T, m, T, far);
    }
    for (int c = 0; c < C; ++c) out[c] = near[c] + far[c] + local[c];
    return;
  }
  for (int c = 0; c < C; ++c) out[c] = near[c] + sums.total(c) + local[c];
}

double FastOperator::apply_row(Index i, const Eigen::VectorXd& v, const UninitializedVector<double>& moments,
                               const std::vector<double>& local_values, double* scratch) const {
  double out;
  apply_row_columns<1>(i, v.data(), moments.data(), local_values.data(), scratch, &out);
  return out;
}

void FastOperator::apply(const Eigen::VectorXd& v, Eigen::VectorXd& y) const {
  if (!holds_all_rows())
    throw std::logic_error("FastOperator::apply: the operator holds only rows [" + std::to_string(row_begin_) + ", " +
                           std::to_string(row_end_) + ") of n = " + std::to_string(n_) +
                           "; apply_rows gives those rows");
  if (v.size() != n_) throw std::invalid_argument("FastOperator::apply: vector size differs from n");
  apply_rows(v, y);
}

FastOperator::ProductWorkspace& FastOperator::acquire_workspace(std::unique_lock<std::mutex>& lock,
                                                               ProductWorkspace& own) const {
  lock = std::unique_lock<std::mutex>(workspace_mutex_, std::try_to_lock);  // a concurrent product: its own
  return lock.owns_lock() ? workspace_ : own;
}

void FastOperator::apply_rows(const Eigen::VectorXd& v, Eigen::VectorXd& y_block) const {
  if (v.size() != n_) throw std::invalid_argument("FastOperator::apply_rows: vector size differs from n");
  std::unique_lock<std::mutex> lock;
  ProductWorkspace own;
  ProductWorkspace& w = acquire_workspace(lock, own);
  UninitializedVector<double>& moments = w.moments;
  std::vector<double>& local_values = w.local_values;
  compute_moments(v, moments);
  if (targets_) evaluate_local_expansions(moments.data(), v.data(), 1, active_targets_, local_values);
  const Index rows = row_end_ - row_begin_;
  y_block.resize(rows);
#pragma omp parallel
  {
    std::vector<double> scratch(static_cast<std::size_t>(terms_));
#pragma omp for schedule(dynamic, 256)
    for (Index r = 0; r < rows; ++r) y_block[r] = apply_row(row_begin_ + r, v, moments, local_values, scratch.data());
  }
}

void FastOperator::apply_block(const Eigen::MatrixXd& V, Eigen::MatrixXd& Y) const {
  if (!holds_all_rows())
    throw std::logic_error("FastOperator::apply_block: the operator holds only rows [" + std::to_string(row_begin_) +
                           ", " + std::to_string(row_end_) + ") of n = " + std::to_string(n_) +
                           "; apply_rows_block gives those rows");
  apply_rows_block(V, Y);
}

void FastOperator::apply_rows_block(const Eigen::MatrixXd& V, Eigen::MatrixXd& Y) const {
  if (V.rows() != n_) throw std::invalid_argument("FastOperator::apply_block: vector size differs from n");
  static_assert(kBlockColumns == 4, "apply_block dispatches on 1..4 columns");
  const Index columns = static_cast<Index>(V.cols());
  const Index rows = row_end_ - row_begin_;
  Y.resize(rows, columns);
  const std::size_t n = static_cast<std::size_t>(n_);
  std::unique_lock<std::mutex> lock;
  ProductWorkspace own;
  ProductWorkspace& w = acquire_workspace(lock, own);
  UninitializedVector<double>& moments = w.moments;
  UninitializedVector<double>& v_block = w.v_block;
  UninitializedVector<double>& m_block = w.m_block;
  std::vector<double>& local_values = w.local_values;
  for (Index first = 0; first < columns; first += kBlockColumns) {
    const int C = static_cast<int>(std::min<Index>(kBlockColumns, columns - first));
    // The group's columns and their moments (48), interleaved: entry j of column c at j C + c.
    v_block.resize(n * static_cast<std::size_t>(C));
    for (int c = 0; c < C; ++c) {
      const Eigen::VectorXd column = V.col(first + c);  // compute_moments reads a vector
      compute_moments(column, moments);
      if (c == 0) m_block.resize(moments.size() * static_cast<std::size_t>(C));
      const std::size_t M = moments.size();
#pragma omp parallel for schedule(dynamic, kLightChunk)
      for (std::size_t j = 0; j < std::max(n, M); ++j) {
        if (j < n) v_block[j * static_cast<std::size_t>(C) + static_cast<std::size_t>(c)] = column[static_cast<Index>(j)];
        if (j < M) m_block[j * static_cast<std::size_t>(C) + static_cast<std::size_t>(c)] = moments[j];
      }
    }
    if (targets_) evaluate_local_expansions(m_block.data(), v_block.data(), C, active_targets_, local_values);
    const double* lv = local_values.data();
#pragma omp parallel
    {
      std::vector<double> scratch(static_cast<std::size_t>(terms_));
      double out[kBlockColumns];
#pragma omp for schedule(dynamic, 256)
      for (Index r = 0; r < rows; ++r) {
        const Index i = row_begin_ + r;
        switch (C) {
          case 1: apply_row_columns<1>(i, v_block.data(), m_block.data(), lv, scratch.data(), out); break;
          case 2: apply_row_columns<2>(i, v_block.data(), m_block.data(), lv, scratch.data(), out); break;
          case 3: apply_row_columns<3>(i, v_block.data(), m_block.data(), lv, scratch.data(), out); break;
          default: apply_row_columns<4>(i, v_block.data(), m_block.data(), lv, scratch.data(), out); break;
        }
        for (int c = 0; c < C; ++c) Y(r, first + c) = out[c];
      }
    }
  }
}

}  // namespace panelrad

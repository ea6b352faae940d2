#include <panelrad/distributed/row_block_operator.hpp>

#include <stdexcept>

namespace panelrad {

RowBlockOperator::RowBlockOperator(std::unique_ptr<RadiosityOperator> op, RowRange rows, const Communicator& communicator)
    : op_(std::move(op)), rows_(rows), comm_(communicator) {
  if (!op_) throw std::invalid_argument("RowBlockOperator: no operator");
  n_ = op_->size();
  const auto* fast = dynamic_cast<const FastOperator*>(op_.get());
  if (fast && !fast->holds_all_rows()) {
    if (!(fast->rows() == rows_))
      throw std::invalid_argument("RowBlockOperator: the fast operator holds other rows than those given");
    fast_rows_ = fast;
  }
  if (rows_.begin < 0 || rows_.end < rows_.begin || rows_.end > n_)
    throw std::invalid_argument("RowBlockOperator: rows [" + std::to_string(rows_.begin) + ", " +
                                std::to_string(rows_.end) + ") are not within n = " + std::to_string(n_));
}

Eigen::VectorXd RowBlockOperator::rows_of(const Eigen::VectorXd& whole) const {
  if (whole.size() != n_) throw std::invalid_argument("RowBlockOperator::rows_of: vector size differs from n");
  return whole.segment(rows_.begin, size());
}

void RowBlockOperator::gather_into(const double* held, Eigen::VectorXd& whole) const {
  comm_.all_gather(held, static_cast<std::size_t>(size()), whole);
  if (whole.size() != n_) throw std::logic_error("RowBlockOperator: the processes' rows do not make n");
}

Eigen::VectorXd RowBlockOperator::gather(const Eigen::VectorXd& held) const {
  if (held.size() != size()) throw std::invalid_argument("RowBlockOperator::gather: vector size differs from the rows held");
  Eigen::VectorXd whole;
  gather_into(held.data(), whole);
  return whole;
}

void RowBlockOperator::apply(const Eigen::VectorXd& v, Eigen::VectorXd& y) const {
  if (v.size() != size()) throw std::invalid_argument("RowBlockOperator::apply: vector size differs from the rows held");
  gather_into(v.data(), whole_);
  if (fast_rows_) {
    fast_rows_->apply_rows(whole_, y);
  } else {
    Eigen::VectorXd all;
    op_->apply(whole_, all);
    y = all.segment(rows_.begin, size());
  }
}

void RowBlockOperator::apply_block(const Eigen::MatrixXd& V, Eigen::MatrixXd& Y) const {
  if (V.rows() != size())
    throw std::invalid_argument("RowBlockOperator::apply_block: vector size differs from the rows held");
  Eigen::MatrixXd whole(n_, V.cols());
  for (Eigen::Index c = 0; c < V.cols(); ++c) {
    gather_into(V.col(c).data(), whole_);  // column-major: each column contiguous
    whole.col(c) = whole_;
  }
  if (fast_rows_) {
    fast_rows_->apply_rows_block(whole, Y);
  } else {
    Eigen::MatrixXd all;
    op_->apply_block(whole, all);
    Y = all.middleRows(rows_.begin, size());
  }
}

}  // namespace panelrad

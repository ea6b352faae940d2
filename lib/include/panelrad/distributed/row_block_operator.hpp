#pragma once
// K_n on the rows one process holds: the operator the solvers see when the rows are spread over
// processes (row_partition.hpp). Its vectors are this process's rows [begin, end) of the whole
// vectors; a product gathers v from every process (the cluster moments (48) integrate v over the
// whole surface) and computes the rows held: FastOperator::apply_rows of a fast operator set up
// for those rows only (FastOptions::rows), bit-identical to the rows of the whole operator's
// product, or rows [begin, end) of the product of an operator holding every row (the dense matrix
// (33)).
#include <panelrad/distributed/communicator.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/operator/linear_operator.hpp>

#include <memory>
#include <string>

namespace panelrad {

class RowBlockOperator final : public RadiosityOperator {
 public:
  /// `op` holds the rows `rows` (a FastOperator of those rows) or all of them; `communicator`
  /// must outlive this operator.
  RowBlockOperator(std::unique_ptr<RadiosityOperator> op, RowRange rows, const Communicator& communicator);
  /// The rows held: the length of the vectors of apply().
  geometry::Index size() const override { return rows_.end - rows_.begin; }
  /// y = the rows held of K_n v, v the rows held of the whole vector (a collective: every process
  /// calls it with its own rows).
  void apply(const Eigen::VectorXd& v, Eigen::VectorXd& y) const override;
  /// The same for several columns at once (the fast operator's block product over the rows held,
  /// FastOperator::apply_rows_block): column c bit-identical to apply(V.col(c)).
  void apply_block(const Eigen::MatrixXd& V, Eigen::MatrixXd& Y) const override;
  std::string name() const override { return op_->name(); }
  std::size_t bytes() const override { return op_->bytes(); }
  RowRange rows() const { return rows_; }
  /// The whole-vector length n.
  geometry::Index columns() const { return n_; }
  const RadiosityOperator& local() const { return *op_; }
  /// The rows held of a whole vector, and the whole vector from every process's rows (a collective).
  Eigen::VectorXd rows_of(const Eigen::VectorXd& whole) const;
  Eigen::VectorXd gather(const Eigen::VectorXd& held) const;

 private:
  std::unique_ptr<RadiosityOperator> op_;
  const FastOperator* fast_rows_ = nullptr;  // op_, when a FastOperator of some rows only
  RowRange rows_;
  geometry::Index n_ = 0;
  const Communicator& comm_;
  void gather_into(const double* held, Eigen::VectorXd& whole) const;
  mutable Eigen::VectorXd whole_;  // the gathered v of a product
};

}  // namespace panelrad

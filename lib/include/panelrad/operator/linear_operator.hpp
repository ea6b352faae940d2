#pragma once
// The one operator interface of the solvers: anything that computes y = K_n v, (38).
#include <panelrad/geometry/mesh.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <string>

namespace panelrad {

class RadiosityOperator {
 public:
  virtual ~RadiosityOperator() = default;
  virtual geometry::Index size() const = 0;
  /// y = K_n v (y is resized). Deterministic: bit-identical for any thread count.
  virtual void apply(const Eigen::VectorXd& v, Eigen::VectorXd& y) const = 0;
  /// Y = K_n V for several vectors at once (Y is resized): column c of Y is bit-identical to
  /// apply(V.col(c)). This default applies column by column; an operator that reads large stored
  /// data per product (the fast operator's far field) reads it once for all the columns.
  virtual void apply_block(const Eigen::MatrixXd& V, Eigen::MatrixXd& Y) const {
    Y.resize(V.rows(), V.cols());
    Eigen::VectorXd v, y;
    for (Eigen::Index c = 0; c < V.cols(); ++c) {
      v = V.col(c);
      apply(v, y);
      Y.col(c) = y;
    }
  }
  virtual std::string name() const = 0;
  /// Bytes held by the operator.
  virtual std::size_t bytes() const = 0;
};

}  // namespace panelrad

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
  virtual std::string name() const = 0;
  /// Bytes held by the operator.
  virtual std::size_t bytes() const = 0;
};

}  // namespace panelrad

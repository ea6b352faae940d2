#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/operator/operator_factory.hpp>

#include <stdexcept>

namespace panelrad {

std::unique_ptr<RadiosityOperator> make_operator(const Collocation& collocation, const OperatorOptions& options) {
  if (options.method == "dense") {
    if (options.progress) options.progress("dense matrix, n = " + std::to_string(collocation.size()));
    return std::make_unique<DenseOperator>(collocation, options.near);
  }
  if (options.method == "fast") {
    FastOptions fast;
    fast.eta = options.eta;
    fast.degree = options.degree;
    fast.near = options.near;
    fast.progress = options.progress;
    return std::make_unique<FastOperator>(collocation, fast);
  }
  throw std::invalid_argument("method '" + options.method + "' is not 'dense' or 'fast'");
}

}  // namespace panelrad

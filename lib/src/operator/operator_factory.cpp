#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/operator/operator_factory.hpp>

#include <stdexcept>

namespace panelrad {

const char* to_string(OperatorMethod method) {
  switch (method) {
    case OperatorMethod::automatic: return "auto";
    case OperatorMethod::dense: return "dense";
    case OperatorMethod::fast: return "fast";
  }
  return "?";
}

OperatorMethod parse_operator_method(const std::string& name) {
  if (name == "auto") return OperatorMethod::automatic;
  if (name == "dense") return OperatorMethod::dense;
  if (name == "fast") return OperatorMethod::fast;
  throw std::invalid_argument("operator method '" + name + "' is not auto, dense or fast");
}

const char* to_string(Visibility visibility) {
  switch (visibility) {
    case Visibility::unoccluded: return "unoccluded";
  }
  return "?";
}

std::unique_ptr<RadiosityOperator> make_operator(const Collocation& collocation, const OperatorOptions& options,
                                                 Visibility visibility, const SetupProgress& progress) {
  // The one policy: V(P, Q) = 1, exact on a convex surface (operator_factory.hpp); both operators
  // integrate G without a visibility factor.
  if (visibility != Visibility::unoccluded) throw std::invalid_argument("make_operator: unknown visibility policy");
  switch (options.method) {
    case OperatorMethod::dense:
      if (progress) progress("dense matrix, n = " + std::to_string(collocation.size()));
      return std::make_unique<DenseOperator>(collocation, options.near);
    case OperatorMethod::fast: {
      FastOptions fast;
      static_cast<ClusteringParameters&>(fast) = options;
      fast.near = options.near;
      fast.progress = progress;
      return std::make_unique<FastOperator>(collocation, fast);
    }
    case OperatorMethod::automatic: break;
  }
  throw std::invalid_argument(std::string("make_operator: method '") + to_string(options.method) +
                              "' is not an operator: dense or fast (choose_parameters resolves auto)");
}

}  // namespace panelrad

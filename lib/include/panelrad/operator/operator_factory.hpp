#pragma once
// Builds the operator K_n for a method name: "dense" (the matrix (33)) or "fast" (section 4).
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/linear_operator.hpp>
#include <panelrad/operator/near_field.hpp>

#include <functional>
#include <memory>
#include <string>

namespace panelrad {

struct OperatorOptions {
  std::string method = "dense";  ///< "dense" | "fast"
  NearFieldOptions near;         ///< near-field rule (dense: every entry)
  double eta = 0.2;              ///< admissibility parameter of (41), fast method
  int degree = 2;                ///< Taylor degree M of (44), fast method
  /// Setup stages as they start (fast method), e.g. for progress on stderr. May be empty.
  std::function<void(const std::string&)> progress;
};

std::unique_ptr<RadiosityOperator> make_operator(const Collocation& collocation, const OperatorOptions& options);

}  // namespace panelrad

#pragma once
// The fast operator's choice between storing the far coefficients (44)-(45) at setup and
// recomputing them in every product: a fixed cost model per (point, cluster) pair, from
// measurements (the constants and how they were measured: lib/src/operator/far_store_tuning.hpp).
// Fixed, not timed at run time, so the choice, and with it the product's rounding, never varies
// between runs.
#include <cstddef>

namespace panelrad {

/// The cost model of storing against recomputing the far coefficients (44)-(45), per (point,
/// cluster) pair in nanoseconds of one core (far_store_tuning.hpp).
struct FarFieldCosts {
  double recompute_ns = 0;  ///< computing one pair's coefficients (kernel_taylor_coefficients)
  double fill_ns = 0;       ///< computing and writing them once at setup (first touch of new memory)
  double read_ns = 0;       ///< reading them back in a product
  /// Whether `products` products repay storing: products x (recompute - read) > fill.
  bool store_pays(int products) const { return products * (recompute_ns - read_ns) > fill_ns; }
};
/// The model for degree M with coefficients of `bytes_per_term` bytes (8 double, 4 float).
FarFieldCosts far_field_costs(int degree, std::size_t bytes_per_term);

}  // namespace panelrad

#pragma once
// Gauss-Legendre rules on [0, 1]: the one source of Gauss-Legendre nodes and weights for the
// collapsed triangle rules (triangle_rules.hpp) and the separated pieces of the singular
// integration (singular_integration.hpp).
#include <vector>

namespace panelrad::quadrature {

/// Largest number of points of a tabulated Gauss-Legendre rule.
inline constexpr int kMaxGaussLegendrePoints = 32;

/// Int_0^1 g(x) dx ~= sum_i weight[i] g(node[i]): exact for polynomials of degree <= 2n - 1.
struct GaussLegendreRule {
  std::vector<double> node;    ///< (1 - z_i) / 2 for the zeros z_i of P_n, increasing in (0, 1)
  std::vector<double> weight;  ///< 1 / ((1 - z_i^2) P_n'(z_i)^2), positive, summing to 1
};

/// The n-point rule, 1 <= n <= kMaxGaussLegendrePoints (std::invalid_argument otherwise). The
/// zeros of P_n and the weights come from Boost.Math (legendre_p_zeros, legendre_p_prime),
/// evaluated in long double and rounded once to double; the table is built on first use
/// (thread-safe). Weights are exactly symmetric, w_i = w_{n-1-i}; nodes are symmetric about
/// 1/2 to within rounding.
const GaussLegendreRule& gauss_legendre_01(int n);

}  // namespace panelrad::quadrature

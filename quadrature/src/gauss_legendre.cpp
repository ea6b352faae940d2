#include <panelrad/quadrature/gauss_legendre.hpp>

#include <boost/math/special_functions/legendre.hpp>

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>

namespace panelrad::quadrature {
namespace {

// Boost.Math's fixed-size gauss<Real, N> (boost/math/quadrature/gauss.hpp) takes N at compile
// time and tabulates only N = 7, 10, 15, 20, 25, 30; for other N it computes the zeros with
// legendre_p_zeros, as done here for every n. In long double (64-bit significand on x86-64) the
// zeros and P_n' are accurate to far below the double rounding of the nodes on [0, 1].
GaussLegendreRule make_rule(int n) {
  using Real = long double;
  // The non-negative zeros of P_n in increasing order (0 first when n is odd).
  const std::vector<Real> zeros = boost::math::legendre_p_zeros<Real>(n);
  const auto un = static_cast<std::size_t>(n);
  GaussLegendreRule rule;
  rule.node.resize(un);
  rule.weight.resize(un);
  for (std::size_t j = 0; j < zeros.size(); ++j) {
    const Real z = zeros[j];
    const Real dp = boost::math::legendre_p_prime(n, z);
    // [-1, 1] -> [0, 1]: x = (1 -+ z) / 2, weight 2 / ((1 - z^2) P'^2) halved.
    const double w = static_cast<double>(1 / ((1 - z * z) * dp * dp));
    const std::size_t lo = (un - 1) / 2 - j, hi = un - 1 - lo;  // x(lo) <= 1/2 <= x(hi)
    rule.node[lo] = static_cast<double>((1 - z) / 2);
    rule.node[hi] = static_cast<double>((1 + z) / 2);
    rule.weight[lo] = w;
    rule.weight[hi] = w;
  }
  return rule;
}

}  // namespace

const GaussLegendreRule& gauss_legendre_01(int n) {
  static const std::array<GaussLegendreRule, kMaxGaussLegendrePoints> table = [] {
    std::array<GaussLegendreRule, kMaxGaussLegendrePoints> t;
    for (int k = 1; k <= kMaxGaussLegendrePoints; ++k) t[static_cast<std::size_t>(k - 1)] = make_rule(k);
    return t;
  }();
  if (n < 1 || n > kMaxGaussLegendrePoints)
    throw std::invalid_argument("gauss_legendre_01: n = " + std::to_string(n) + " is outside [1, " +
                                std::to_string(kMaxGaussLegendrePoints) + "]");
  return table[static_cast<std::size_t>(n - 1)];
}

}  // namespace panelrad::quadrature

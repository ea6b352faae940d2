#include <panelrad/quadrature/exact_integrals.hpp>
#include <panelrad/quadrature/triangle_rules.hpp>

#include <cmath>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <vector>

namespace panelrad::quadrature {
namespace {

constexpr int kMaxTotalDegree = 150;  // (deg+2)! must stay finite in double (170! ~ 7e306)

double factorial(int n) {
  static const std::vector<double> table = [] {
    std::vector<double> t(kMaxTotalDegree + 3, 1.0);
    for (std::size_t i = 1; i < t.size(); ++i) t[i] = t[i - 1] * static_cast<double>(i);
    return t;
  }();
  return table[static_cast<std::size_t>(n)];
}

void check_exponents(const char* where, std::initializer_list<int> exps) {
  int total = 0;
  for (int e : exps) {
    if (e < 0)
      throw std::invalid_argument(std::string(where) + ": negative exponent " + std::to_string(e));
    total += e;
  }
  if (total > kMaxTotalDegree)
    throw std::invalid_argument(std::string(where) + ": total degree " + std::to_string(total) +
                                " exceeds " + std::to_string(kMaxTotalDegree));
}

/// A homogeneous polynomial in the barycentric coordinates (l1,l2,l3): coefficient of
/// l1^p1 l2^p2 l3^(m-p1-p2) at [p1 * stride + p2].
struct BarycentricPoly {
  int degree = 0;
  int stride;
  std::vector<double> coef;
  explicit BarycentricPoly(int max_degree)
      : stride(max_degree + 1), coef(static_cast<std::size_t>(stride * stride), 0.0) {
    coef[0] = 1.0;
  }
  double& at(int p1, int p2) { return coef[static_cast<std::size_t>(p1 * stride + p2)]; }
  /// Multiply by the linear form x = v1 l1 + v2 l2 + v3 l3 (a coordinate of the triangle).
  void multiply(double v1, double v2, double v3) {
    const int m = degree + 1;
    for (int p1 = m; p1 >= 0; --p1) {
      for (int p2 = m - p1; p2 >= 0; --p2) {
        const int p3 = m - p1 - p2;
        double s = 0;
        if (p1 > 0) s += v1 * at(p1 - 1, p2);
        if (p2 > 0) s += v2 * at(p1, p2 - 1);
        if (p3 > 0 && p1 + p2 <= degree) s += v3 * at(p1, p2);
        at(p1, p2) = s;
      }
    }
    degree = m;
  }
  /// Int_Delta poly dA / (2 area) = sum c p1! p2! p3! / (m+2)!.
  double integral_over_twice_area() {
    double sum = 0;
    for (int p1 = 0; p1 <= degree; ++p1)
      for (int p2 = 0; p1 + p2 <= degree; ++p2)
        sum += at(p1, p2) * factorial(p1) * factorial(p2) * factorial(degree - p1 - p2);
    return sum / factorial(degree + 2);
  }
};

}  // namespace

double monomial_integral(const Vec3& a, const Vec3& b, const Vec3& c, int i, int j, int k) {
  check_exponents("monomial_integral", {i, j, k});
  BarycentricPoly poly(i + j + k);
  for (int n = 0; n < i; ++n) poly.multiply(a.x(), b.x(), c.x());
  for (int n = 0; n < j; ++n) poly.multiply(a.y(), b.y(), c.y());
  for (int n = 0; n < k; ++n) poly.multiply(a.z(), b.z(), c.z());
  const double twice_area = (b - a).cross(c - a).norm();
  return twice_area * poly.integral_over_twice_area();
}

double monomial_integral_2d(const std::array<double, 2>& a, const std::array<double, 2>& b,
                            const std::array<double, 2>& c, int p, int q) {
  check_exponents("monomial_integral_2d", {p, q});
  BarycentricPoly poly(p + q);
  for (int n = 0; n < p; ++n) poly.multiply(a[0], b[0], c[0]);
  for (int n = 0; n < q; ++n) poly.multiply(a[1], b[1], c[1]);
  const double twice_area =
      std::abs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
  return twice_area * poly.integral_over_twice_area();
}

std::vector<double> monomial_moments_2d(const std::array<double, 2>& a,
                                        const std::array<double, 2>& b,
                                        const std::array<double, 2>& c, int M) {
  check_exponents("monomial_moments_2d", {M});
  const auto count = static_cast<std::size_t>((M + 1) * (M + 2) / 2);
  std::vector<double> moments(count, 0.0);
  const int n = (M + 3) / 2;  // collapsed Gauss rule of degree 2n-2 >= M: exact for all moments
  if (n > kMaxCollapsedGaussPoints) {
    std::size_t idx = 0;
    for (int d = 0; d <= M; ++d)
      for (int p = d; p >= 0; --p) moments[idx++] = monomial_integral_2d(a, b, c, p, d - p);
    return moments;
  }
  const TriangleRule& rule = collapsed_gauss_rule(n);
  const double area =
      0.5 * std::abs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
  std::vector<double> xp(static_cast<std::size_t>(M + 1)), yp(static_cast<std::size_t>(M + 1));
  for (std::size_t i = 0; i < rule.size(); ++i) {
    const auto& l = rule.barycentric[i];
    const double x = l[0] * a[0] + l[1] * b[0] + l[2] * c[0];
    const double y = l[0] * a[1] + l[1] * b[1] + l[2] * c[1];
    xp[0] = rule.weight[i] * area;
    yp[0] = 1.0;
    for (std::size_t e = 1; e < xp.size(); ++e) {
      xp[e] = xp[e - 1] * x;
      yp[e] = yp[e - 1] * y;
    }
    std::size_t idx = 0;
    for (int d = 0; d <= M; ++d)
      for (int p = d; p >= 0; --p)
        moments[idx++] += xp[static_cast<std::size_t>(p)] * yp[static_cast<std::size_t>(d - p)];
  }
  return moments;
}

}  // namespace panelrad::quadrature

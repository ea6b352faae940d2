#include <panelrad/quadrature/triangle_rules.hpp>
#include <panelrad/quadrature/gauss_legendre.hpp>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

namespace panelrad::quadrature {
namespace {

/// Collapsed (Duffy) Gauss-Legendre product rule with n points per direction: (s,t) =
/// (u, (1-u) v), Jacobian (1-u). Exact for total degree 2n-2 (the u-direction carries the extra
/// factor 1-u), all weights positive, all points strictly inside.
TriangleRule collapsed_gauss(int n) {
  const GaussLegendreRule& gauss = gauss_legendre_01(n);
  const std::vector<double>& x = gauss.node;
  const std::vector<double>& w = gauss.weight;
  TriangleRule rule;
  rule.degree = 2 * n - 2;
  rule.name = "degree" + std::to_string(rule.degree);
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (std::size_t j = 0; j < x.size(); ++j) {
      const double s = x[i], t = (1.0 - x[i]) * x[j];
      // Reference simplex has area 1/2: normalised weight = 2 * w_i w_j (1 - u).
      rule.barycentric.push_back({s, t, 1.0 - s - t});
      rule.weight.push_back(2.0 * w[i] * w[j] * (1.0 - x[i]));
    }
  }
  return rule;
}

TriangleRule make_centroid() {
  TriangleRule r;
  r.name = "centroid";
  r.degree = 1;
  r.barycentric = {{1.0 / 3, 1.0 / 3, 1.0 / 3}};
  r.weight = {1.0};
  return r;
}

// Section 5.1: (1/6)[f(0,1/2) + f(1/2,0) + f(1/2,1/2)] on sigma, i.e. the three edge midpoints
// with weight 1/3 of the area each.
TriangleRule make_three_point() {
  TriangleRule r;
  r.name = "three_point";
  r.degree = 2;
  r.barycentric = {{0.0, 0.5, 0.5}, {0.5, 0.0, 0.5}, {0.5, 0.5, 0.0}};
  r.weight = {1.0 / 3, 1.0 / 3, 1.0 / 3};
  return r;
}

// Stroud T2:5-1 (Radon 1948): the centroid with weight 9/40 and two 3-point orbits
// (a, a, 1-2a) with a = (6 -+ sqrt 15)/21 and weights (155 -+ sqrt 15)/1200.
TriangleRule make_stroud() {
  const double s15 = std::sqrt(15.0);
  const double a1 = (6.0 - s15) / 21.0, a2 = (6.0 + s15) / 21.0;
  const double w1 = (155.0 - s15) / 1200.0, w2 = (155.0 + s15) / 1200.0;
  TriangleRule r;
  r.name = "stroud7";
  r.degree = 5;
  r.barycentric = {{1.0 / 3, 1.0 / 3, 1.0 / 3},
                   {a1, a1, 1 - 2 * a1}, {a1, 1 - 2 * a1, a1}, {1 - 2 * a1, a1, a1},
                   {a2, a2, 1 - 2 * a2}, {a2, 1 - 2 * a2, a2}, {1 - 2 * a2, a2, a2}};
  r.weight = {9.0 / 40, w1, w1, w1, w2, w2, w2};
  return r;
}

constexpr int kMaxDegree = 20;

}  // namespace

const TriangleRule& centroid_rule() {
  static const TriangleRule rule = make_centroid();
  return rule;
}

const TriangleRule& three_point_rule() {
  static const TriangleRule rule = make_three_point();
  return rule;
}

const TriangleRule& stroud_t2_5_1() {
  static const TriangleRule rule = make_stroud();
  return rule;
}

const TriangleRule& collapsed_gauss_rule(int n) {
  static const std::vector<TriangleRule> rules = [] {
    std::vector<TriangleRule> v;
    for (int k = 1; k <= kMaxCollapsedGaussPoints; ++k) v.push_back(collapsed_gauss(k));
    return v;
  }();
  if (n < 1 || n > kMaxCollapsedGaussPoints)
    throw std::invalid_argument("collapsed_gauss_rule: n = " + std::to_string(n) +
                                " is outside [1, " + std::to_string(kMaxCollapsedGaussPoints) + "]");
  return rules[static_cast<std::size_t>(n - 1)];
}

const TriangleRule& rule_of_degree(int degree) {
  if (degree < 0 || degree > kMaxDegree)
    throw std::invalid_argument("rule_of_degree: degree " + std::to_string(degree) +
                                " is outside [0, " + std::to_string(kMaxDegree) + "]");
  if (degree <= 1) return centroid_rule();
  if (degree == 2) return three_point_rule();
  if (degree <= 5) return stroud_t2_5_1();
  return collapsed_gauss_rule((degree + 3) / 2);  // n = ceil((degree+2)/2): degree 2n-2 >= degree
}

const TriangleRule& rule_by_name(const std::string& name) {
  if (name == "centroid") return centroid_rule();
  if (name == "three_point" || name == "three-point" || name == "3point") return three_point_rule();
  if (name == "stroud7" || name == "stroud" || name == "T2:5-1") return stroud_t2_5_1();
  if (name.rfind("degree", 0) == 0 && name.size() > 6 && name.size() <= 8) {
    int d = 0;
    for (std::size_t i = 6; i < name.size(); ++i) {
      if (name[i] < '0' || name[i] > '9') d = -1;
      if (d >= 0) d = 10 * d + (name[i] - '0');
    }
    if (d >= 1 && d <= kMaxDegree) return rule_of_degree(d);
  }
  throw std::invalid_argument("unknown quadrature rule '" + name +
                              "' (expected centroid, three_point, stroud7 or degreeK with 1 <= K <= " +
                              std::to_string(kMaxDegree) + ")");
}

}  // namespace panelrad::quadrature

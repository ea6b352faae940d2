#pragma once
// Quadrature rules on a triangle and the composite scheme of the paper's section 4.2.
#include <panelrad/geometry/mesh.hpp>
#include <panelrad/geometry/subdivision.hpp>

#include <Eigen/Geometry>  // cross products

#include <array>
#include <string>
#include <vector>

namespace panelrad::quadrature {

using geometry::Vec3;

/// A rule on the reference simplex sigma = {(s,t): s,t >= 0, s+t <= 1}, stored as barycentric
/// points and weights normalised to sum 1: Int_Delta f dS ~= area(Delta) * sum_i w_i f(x_i).
struct TriangleRule {
  std::string name;
  int degree = 0;  ///< degree of precision: polynomials up to this degree integrate exactly
  std::vector<std::array<double, 3>> barycentric;
  std::vector<double> weight;
  std::size_t size() const { return weight.size(); }
};

const TriangleRule& centroid_rule();       ///< 1 point, degree 1
const TriangleRule& three_point_rule();    ///< 3 edge midpoints, degree 2 (paper section 5.1)
const TriangleRule& stroud_t2_5_1();       ///< 7 points, degree 5 (Stroud T2:5-1, paper 4.2)
/// A rule of degree >= `degree` (1 <= degree <= 20, positive weights, points inside).
const TriangleRule& rule_of_degree(int degree);
/// Largest n accepted by collapsed_gauss_rule.
inline constexpr int kMaxCollapsedGaussPoints = 16;
/// Collapsed (Duffy) Gauss-Legendre product rule with n x n points, degree 2n-2, positive weights,
/// points strictly inside (1 <= n <= kMaxCollapsedGaussPoints).
const TriangleRule& collapsed_gauss_rule(int n);
/// Named rules for option parsing: "centroid", "three_point", "stroud7", "degreeK".
const TriangleRule& rule_by_name(const std::string& name);

/// Int_Delta f dS with a single rule on the triangle (a,b,c).
template <class F>
double integrate(const TriangleRule& rule, const Vec3& a, const Vec3& b, const Vec3& c, F&& f) {
  const double area = 0.5 * (b - a).cross(c - a).norm();
  double sum = 0;
  for (std::size_t i = 0; i < rule.size(); ++i) {
    const auto& l = rule.barycentric[i];
    sum += rule.weight[i] * f(Vec3(l[0] * a + l[1] * b + l[2] * c));
  }
  return area * sum;
}

/// The rule applied on each of the 4^levels triangles of `levels` uniform midpoint subdivisions.
template <class F>
double integrate_composite(const TriangleRule& rule, const Vec3& a, const Vec3& b, const Vec3& c,
                           int levels, F&& f) {
  if (levels <= 0) return integrate(rule, a, b, c, f);
  const auto t = geometry::midpoint_subdivision(a, b, c);
  return integrate_composite(rule, t[0][0], t[0][1], t[0][2], levels - 1, f) +
         integrate_composite(rule, t[1][0], t[1][1], t[1][2], levels - 1, f) +
         integrate_composite(rule, t[2][0], t[2][1], t[2][2], levels - 1, f) +
         integrate_composite(rule, t[3][0], t[3][1], t[3][2], levels - 1, f);
}

/// Subdivision levels of the section 4.2 scheme: mu when 0 < dist <= h, mu-1 when h < dist <= 2h,
/// ..., 0 beyond. h is the mesh size.
int composite_levels(double dist, double h, int mu);

/// Euclidean distance from P to the closed triangle (a,b,c).
double distance_point_triangle(const Vec3& P, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace panelrad::quadrature

// The rounding model of input coordinates (input_rounding.hpp) and the bound(t, v) it gives on how
// far a vertex can lie outside a triangle's plane when the true, unrounded mesh is convex
// (validate_closed_convex in validation.hpp derives it).
#include "validation_internal.hpp"

#include <panelrad/geometry/input_rounding.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

namespace panelrad::geometry {

namespace {

/// Significant decimal digits of the shortest decimal form that reads back exactly as x (0 for 0).
int shortest_digits(double x) {
  if (x == 0) return 0;
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::scientific);
  int digits = 0;
  for (const char* c = buf; c != res.ptr && *c != 'e'; ++c)
    if (*c >= '0' && *c <= '9') ++digits;
  return digits;
}

/// Smallest triangle height |n| / longest edge.
double smallest_height(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  return (b - a).cross(c - a).norm() / longest;
}

}  // namespace

InputRounding input_rounding(const TriangleMesh& mesh) {
  InputRounding r;
  for (const Vec3& p : mesh.vertices)
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(p[k])) throw MeshError("input_rounding: non-finite vertex coordinate");
      r.magnitude = std::max(r.magnitude, std::abs(p[k]));
      r.digits = std::max(r.digits, shortest_digits(p[k]));
    }
  const double u = std::numeric_limits<double>::epsilon() / 2;
  r.decimal = r.digits <= 16;
  r.assumed_digits = r.decimal ? std::max(6, r.digits) : 17;
  r.relative = (r.decimal ? 0.5 * std::pow(10.0, 1 - r.assumed_digits) : 0.0) + 16 * u;
  r.per_coordinate = r.relative * r.magnitude;
  return r;
}

std::string InputRounding::describe() const {
  std::string s = decimal ? "coordinates rounded to " + std::to_string(assumed_digits) + " significant digits"
                          : std::string("double-precision coordinates (16 ulp, covering a rotation in double)");
  return s + " of magnitude " + validation_detail::num(magnitude);
}

namespace validation_detail {

/// bound(t, v) of validation.hpp: how far rounding by eta per coordinate can put v outside the plane
/// of (a, b, c) when the true mesh is convex; negative when the triangle is too small for the
/// first-order barycentric argument (sqrt(3) eta > h / 16).
double rounding_bound(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& v, double eta) {
  const Vec3 e1 = b - a, e2 = c - a, x = v - a;
  const Vec3 n = e1.cross(e2);
  const double n2 = n.squaredNorm();
  if (!(std::sqrt(3.0) * eta <= smallest_height(a, b, c) / 16)) return -1;
  // x = l_b e1 + l_c e2 + h n: (x x e2) . n = l_b |n|^2, (e1 x x) . n = l_c |n|^2.
  const double lb = x.cross(e2).dot(n) / n2, lc = e1.cross(x).dot(n) / n2, la = 1 - lb - lc;
  const double n1 = n.lpNorm<1>() / std::sqrt(n2);
  return 1.25 * eta * n1 * (1 + std::abs(la) + std::abs(lb) + std::abs(lc));
}

}  // namespace validation_detail

}  // namespace panelrad::geometry

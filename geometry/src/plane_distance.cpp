// The size of a convexity violation, for the report and the rounding bound: the distance of a
// vertex from a triangle's plane (double precision where its error bound allows, else exact with
// CGAL::Mpzf, so that a nonzero distance never comes out as 0), and the mesh diameter it is
// measured against. Distances report a violation; they never decide one (exact_convexity.cpp).
#include "validation_internal.hpp"

#include <panelrad/geometry/bounding_box.hpp>

#include <CGAL/Gmpq.h>
#include <CGAL/Mpzf.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace panelrad::geometry::validation_detail {

double diameter(const TriangleMesh& mesh) {
  const auto& v = mesh.vertices;
  if (v.size() > 5000) {  // O(V^2) is too slow: the bounding box diagonal is within sqrt(3) of it
    return bounding_box_diameter(v);
  }
  double d2 = 0;
  for (Sz i = 0; i < v.size(); ++i)
    for (Sz j = i + 1; j < v.size(); ++j) d2 = std::max(d2, (v[i] - v[j]).squaredNorm());
  return std::sqrt(d2);
}

/// An upper bound on |distance of v from the plane of (a, b, c)| in double arithmetic with its
/// rounding error bound (see plane_distance); infinity when double precision cannot bound it.
double plane_distance_upper(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& v) {
  const Vec3 e1 = b - a, e2 = c - a, x = v - a;
  const Vec3 n = e1.cross(e2);
  const Vec3 a1 = e1.cwiseAbs(), a2 = e2.cwiseAbs();
  const Vec3 nabs(a1.y() * a2.z() + a1.z() * a2.y(), a1.z() * a2.x() + a1.x() * a2.z(),
                  a1.x() * a2.y() + a1.y() * a2.x());
  const double u = std::numeric_limits<double>::epsilon() / 2;
  const double det_hi = std::abs(n.dot(x)) + 9 * u * nabs.dot(x.cwiseAbs());
  const double n_lo = n.norm() * (1 - 4 * u) - 4 * u * nabs.norm();
  const double hi = det_hi / n_lo * (1 + 4 * u);
  return n_lo > 0 && std::isfinite(hi) ? hi : std::numeric_limits<double>::infinity();
}

/// Signed distance of v from the plane of (a, b, c), positive on the side of (b - a) x (c - a),
/// accurate to a relative 1e-4 or better: double arithmetic when its error bound allows, else exact
/// rational arithmetic (a nonzero exact distance never comes out as 0).
double plane_distance(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& v) {
  const Vec3 e1 = b - a, e2 = c - a, x = v - a;
  const Vec3 n = e1.cross(e2);
  const double det = n.dot(x);
  const Vec3 a1 = e1.cwiseAbs(), a2 = e2.cwiseAbs();
  const Vec3 nabs(a1.y() * a2.z() + a1.z() * a2.y(), a1.z() * a2.x() + a1.x() * a2.z(),
                  a1.x() * a2.y() + a1.y() * a2.x());
  const double u = std::numeric_limits<double>::epsilon() / 2;
  // Rounded differences, products and sums: |det - exact| <= 8 u nabs.|x| (the permanent; orient3d's
  // bound is (7 + 56 u) u of it) and |n_i - exact_i| <= 3 u nabs_i. 1e4 times those leaves 1e-4.
  const double n_norm = n.norm();
  if (std::abs(det) >= 1e4 * 8 * u * nabs.dot(x.cwiseAbs()) && n_norm >= 1e4 * 3 * u * nabs.norm() &&
      std::isfinite(det) && n_norm > 0)
    return det / n_norm;
  // Exact: CGAL::Mpzf (multiprecision floats: sums and products of doubles without rounding and
  // without the gcds of rationals).
  using CGAL::Mpzf;
  const auto q = [](const Vec3& p, const Vec3& o, int k) { return Mpzf(p[k]) - Mpzf(o[k]); };
  const Mpzf e1x = q(b, a, 0), e1y = q(b, a, 1), e1z = q(b, a, 2), e2x = q(c, a, 0), e2y = q(c, a, 1),
             e2z = q(c, a, 2);
  const Mpzf nx = e1y * e2z - e1z * e2y, ny = e1z * e2x - e1x * e2z, nz = e1x * e2y - e1y * e2x;
  const Mpzf exact = nx * q(v, a, 0) + ny * q(v, a, 1) + nz * q(v, a, 2);
  const int sign = exact.sign();
  if (sign == 0) return 0.0;
  const Mpzf n2 = nx * nx + ny * ny + nz * nz;
  const double num = exact.to_double(), den = n2.to_double();
  if (std::isnormal(num) && std::isnormal(den) && std::isnormal(num / std::sqrt(den))) return num / std::sqrt(den);
  // Outside the normal double range (coordinates far below 1): scale exactly through rationals.
  const CGAL::Gmpq qn{exact}, qd{n2};
  const double dist = CGAL::to_double(qn) / std::sqrt(CGAL::to_double(qd));
  if (dist == 0.0 || !std::isfinite(dist)) return sign * std::numeric_limits<double>::denorm_min();
  return dist;
}

}  // namespace panelrad::geometry::validation_detail

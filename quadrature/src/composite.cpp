#include <panelrad/quadrature/triangle_rules.hpp>

#include <algorithm>
#include <cmath>

namespace panelrad::quadrature {

// Section 4.2: mu levels when 0 < dist <= h, mu-1 when h < dist <= 2h, ..., none beyond.
int composite_levels(double dist, double h, int mu) {
  if (mu <= 0 || !(h > 0)) return 0;
  if (dist <= h) return mu;
  const double steps = std::ceil(dist / h) - 1.0;  // dist in (k h, (k+1) h] -> k steps down
  if (steps >= static_cast<double>(mu)) return 0;
  return mu - static_cast<int>(steps);
}

// Closest point on a triangle (Ericson, Real-Time Collision Detection, 5.1.5), then the distance.
double distance_point_triangle(const Vec3& P, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = P - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.norm();
  const Vec3 bp = P - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (P - (a + (d1 / (d1 - d3)) * ab)).norm();
  const Vec3 cp = P - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (P - (a + (d2 / (d2 - d6)) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return (P - (b + w * (c - b))).norm();
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return (P - (a + ab * v + ac * w)).norm();
}

}  // namespace panelrad::quadrature

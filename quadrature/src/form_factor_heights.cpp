// The height of a point over a triangle's plane and the signed distances of its foot from the
// edge lines, with errors far below the rounding of their double-precision dot products however
// close the point is to the plane or to an edge's line (the near-edge path of form_factor,
// exact_integrals.hpp).
//
// With N = (V1 - V0) x (V2 - V0) (counter-clockwise about the front normal, so N points to the
// front) and the outward in-plane normal n_k = t_k x N / |N| of edge k (t_k its unit direction),
//   h   = N.(P - V0) / |N|,
//   e_k = (V_k - P).n_k = N.((V_k - P) x (V_k+1 - P)) / (L_k |N|)
// (the triple product (V_k - P).(t_k x N) = N.((V_k - P) x t_k), and (V_k - P) x (V_k+1 - V_k) =
// (V_k - P) x (V_k+1 - P)). The differences of the coordinates are exact as double-double
// (two_sum), the products and sums of the numerators are formed in double-double (each operation
// with a relative error of about 2^-104 of its operands), and only the final quotients are
// rounded: the absolute errors are about 2^-100 R in h and 2^-100 R^2 / L_k in e_k (R the distance
// from P to the corners), against a rounding of a few eps R in the dot products of the double path.
// The terms of the contour formula divide them by D_k >= |h|; for a height above the visibility
// margin (1e-12 of the scene's size) that leaves them accurate to a few eps.
#include <panelrad/quadrature/exact_integrals.hpp>

#include <cmath>

namespace panelrad::quadrature::detail {
namespace {

/// A double-double number hi + lo, |lo| <= ulp(hi) / 2.
struct DD {
  double hi = 0, lo = 0;
};

/// s + err = a + b exactly (Knuth's two-sum).
DD two_sum(double a, double b) {
  const double s = a + b;
  const double bb = s - a;
  return {s, (a - (s - bb)) + (b - bb)};
}

/// s + err = a + b exactly, |a| >= |b| or a = 0 (Dekker's fast two-sum).
DD fast_two_sum(double a, double b) {
  const double s = a + b;
  return {s, b - (s - a)};
}

/// p + err = a b exactly (the error of the product by a fused multiply-add).
DD two_prod(double a, double b) {
  const double p = a * b;
  return {p, std::fma(a, b, -p)};
}

DD operator+(const DD& a, const DD& b) {
  // The accurate addition (both parts summed with their errors): relative error a few 2^-106 of
  // |a| + |b| even under cancellation.
  DD s = two_sum(a.hi, b.hi);
  const DD t = two_sum(a.lo, b.lo);
  s.lo += t.hi;
  s = fast_two_sum(s.hi, s.lo);
  s.lo += t.lo;
  return fast_two_sum(s.hi, s.lo);
}

DD operator-(const DD& a) { return {-a.hi, -a.lo}; }
DD operator-(const DD& a, const DD& b) { return a + (-b); }

DD operator*(const DD& a, const DD& b) {
  DD p = two_prod(a.hi, b.hi);
  p.lo += a.hi * b.lo + a.lo * b.hi;
  return fast_two_sum(p.hi, p.lo);
}

struct DDVec {
  DD x, y, z;
};

/// a - b exactly.
DDVec difference(const Vec3& a, const Vec3& b) {
  return {two_sum(a.x(), -b.x()), two_sum(a.y(), -b.y()), two_sum(a.z(), -b.z())};
}

DDVec cross(const DDVec& a, const DDVec& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

DD dot(const DDVec& a, const DDVec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

}  // namespace

void accurate_heights(const Vec3& P, const Vec3& V0, const Vec3& V1, const Vec3& V2, const double L[3], double& h,
                      double e[3]) {
  const DDVec N = cross(difference(V1, V0), difference(V2, V0));
  const double norm_N = std::sqrt(N.x.hi * N.x.hi + N.y.hi * N.y.hi + N.z.hi * N.z.hi);
  h = dot(N, difference(P, V0)).hi / norm_N;
  const Vec3* V[4] = {&V0, &V1, &V2, &V0};
  for (int k = 0; k < 3; ++k)
    e[k] = dot(N, cross(difference(*V[k], P), difference(*V[k + 1], P))).hi / (L[k] * norm_N);
}

}  // namespace panelrad::quadrature::detail

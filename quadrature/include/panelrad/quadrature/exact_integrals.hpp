#pragma once
// Exact integrals over planar triangles: monomials, and the point-to-triangle form factor.
#include <panelrad/geometry/mesh.hpp>

#include <Eigen/Geometry>  // cross products

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace panelrad::quadrature {

using geometry::Vec3;

/// Int_Delta x^i y^j z^k dS over the triangle (a,b,c), exactly (closed form via the
/// multinomial expansion in barycentric coordinates, Int l1^p l2^q l3^r = 2A p!q!r!/(p+q+r+2)!).
double monomial_integral(const Vec3& a, const Vec3& b, const Vec3& c, int i, int j, int k);

/// 2-D version for a triangle given in local plane coordinates: Int x^p y^q dA, exact.
double monomial_integral_2d(const std::array<double, 2>& a, const std::array<double, 2>& b,
                            const std::array<double, 2>& c, int p, int q);

/// All 2-D moments Int x^p y^q dA with p+q <= M, in graded order (0,0),(1,0),(0,1),(2,0),(1,1),
/// (0,2),... : (M+1)(M+2)/2 values.
std::vector<double> monomial_moments_2d(const std::array<double, 2>& a,
                                        const std::array<double, 2>& b,
                                        const std::array<double, 2>& c, int M);

/// (1/pi) Int_Delta G(P,Q) dS_Q in closed form, G = [(Q-P).nP][(P-Q).nQ] / |P-Q|^4 (paper (2)),
/// for the planar triangle (a,b,c) with unit normal nQ (either orientation of a,b,c). This is
/// the point-to-polygon form factor by the contour-integral formula, computed with
/// atan2(|R_k x R_k+1|, R_k . R_k+1) and a series where the cross product vanishes. Exactly 0 when
/// P lies in the triangle's plane (paper 4.2, case (a)). Signed: positive for a convex scene
/// with inner normals. Defined inline below (hot path: called once per near-field pair).
inline double form_factor(const Vec3& P, const Vec3& nP, const Vec3& a, const Vec3& b,
                          const Vec3& c, const Vec3& nQ);

/// The same for a convex planar polygon of m corners, counter-clockwise about its unit normal nQ
/// (a visible piece of an element): one contour sum over its m edges, where its fan of m - 2
/// triangles would sum 3 (m - 2) edges, the fan's inner diagonals cancelling. Where P lies near an
/// edge's line (the accurate path of form_factor), and for more than 16 corners, the fan's sum.
/// Repeated or collinear corners add nothing.
inline double convex_polygon_form_factor(const Vec3& P, const Vec3& nP, const Vec3* corners, int m, const Vec3& nQ);

// ------------------------------------------------------------------------------------------------
// Implementation of form_factor.
//
// Write Q - P = rho - h nQ with h = (P - a).nQ (constant over the plane) and rho the in-plane
// vector from the foot of P, and nP = t + nu nQ (t in-plane). Then (paper (2))
//   (1/pi) Int G dS = (h/pi) [ t . Int rho/(r^2+h^2)^2 dS  -  h nu Int dS/(r^2+h^2)^2 ],
// and both integrands are divergences of fields regular at the foot:
//   rho/(r^2+h^2)^2 = -grad( 1/(2(r^2+h^2)) ),  1/(r^2+h^2)^2 = div( rho / (2h^2 (r^2+h^2)) ).
// On edge k (outward in-plane normal n_k, foot at signed distance e_k inside its line, P at
// distance D_k = sqrt(e_k^2 + h^2) of the line, arc parameters s1 < s2 from P's projection)
//   Int_edge ds/(r^2+h^2) = gamma_k / D_k,  gamma_k = atan2(D_k L_k, D_k^2 + s1 s2),
// the angle subtended by the edge at P (D_k L_k = |R_k x R_k+1|, D_k^2 + s1 s2 = R_k . R_k+1).
// Hence the contour formula
//   F = -(1/2pi) sum_k [ h (nP.n_k) + nu e_k ] gamma_k / D_k,
// which is the classical (1/2pi) sum gamma_k nP.(R_k x R_k+1)/|R_k x R_k+1| written per edge.
// When the foot lies outside the triangle and P is close to the plane, sum_k e_k gamma_k/D_k
// is O(h^2) made of O(1) terms; it is then recomputed cancellation-free as
//   sum_k sgn(e_k) [ (|e_k|/D_k - 1) gamma_k + (gamma_k(D_k) - gamma_k(|e_k|)) ]
// (the in-plane winding sum sgn(e_k) gamma_k(|e_k|) is exactly 0 outside), each bracket
// evaluated from differences formed analytically (D - |e| = h^2/(D + |e|)).
// Rounding. Each edge vector is projected onto the plane (nQ unit) before its direction is
// taken, so that an edge much shorter than h, whose corners are in the plane only to rounding,
// does not tilt out of it. h and e_k computed as dot products with P - a and V_k - P carry absolute errors of a
// few eps R (R the distance from P to the corners); the terms [h (nP.n_k) + nu e_k] gamma_k / D_k
// then carry a few eps R / D_k. Where P lies close to an edge's line relative to R (a point a
// narrow gap h away from a plane, its foot near an edge of an element there), that is a relative
// error eps R / h in the factor, and the two elements sharing the edge do not cancel it (each rounds
// its own e_k). So when some D_k < R / kNearEdgeRatio, h and the e_k are recomputed from the
// corners and P themselves, exactly in their differences and in double-double arithmetic:
//   h = N.(P - a) / |N|,  e_k = N.((V_k - P) x (V_k+1 - P)) / (L_k |N|),  N = (b - a) x (c - a)
// (accurate_heights), which leaves each term accurate to a few eps; elsewhere the double path is
// kept (its error is then at most a few eps kNearEdgeRatio in each term).
/// P within R / kNearEdgeRatio of an edge's line (R its distance from the edge's corners): h and
/// the e_k are recomputed by accurate_heights.
inline constexpr double kNearEdgeRatio = 64;
/// The largest in-plane winding sum of a triangle seen from a foot outside it (exactly 0) that is
/// taken as rounding: beyond it the cancellation-free form of form_factor is not used.
inline constexpr double kWindingRounding = 1e-12;

namespace detail {

/// The height h of P over the plane of the triangle (V0, V1, V2) (counter-clockwise about its
/// front normal, h > 0 in front) and the signed distances e[k] of P's foot inside the edge lines
/// (V_k, V_k+1), L[k] the edges' lengths: differences of the coordinates exact, products and sums
/// in double-double, absolute errors about 2^-100 R in h and 2^-100 R^2 / L_k in e_k (R the
/// distance from P to the corners).
void accurate_heights(const Vec3& P, const Vec3& V0, const Vec3& V1, const Vec3& V2, const double L[3], double& h,
                      double e[3]);

/// gamma / D with gamma = atan2(D L, den): the angle subtended by an edge of length L seen from a
/// point at distance D of its line, den = R_k . R_k+1. Series in t = D L / den when t is tiny
/// (avoids 0/0 when the cross product vanishes and keeps full relative accuracy).
inline double angle_over_distance(double D, double L, double den) {
  const double x = D * L;
  if (den > 0 && x < 1e-3 * den) {
    const double t = x / den, t2 = t * t;  // atan(t)/t = 1 - t^2/3 + t^4/5 - t^6/7 + O(t^8)
    return (L / den) * (1.0 - t2 * (1.0 / 3.0 - t2 * (1.0 / 5.0 - t2 * (1.0 / 7.0))));
  }
  return std::atan2(x, den) / D;
}

}  // namespace detail

namespace detail {

/// The most corners of a polygon that convex_polygon_form_factor takes in one contour sum.
inline constexpr int kMaxContourCorners = 16;

/// The contour formula above over the m edges (V[k], V[k+1]) of a convex planar polygon, V[m] =
/// V[0], counter-clockwise about its unit normal nQ, h = (P - V[0]).nQ != 0. When P lies near an
/// edge's line (the accurate path), h and the e_k are recomputed by accurate_heights for a
/// triangle (m = 3); for m > 3 the sum is not taken and false is returned (the caller sums the fan
/// of triangles instead). An edge with no length in the plane adds nothing.
inline bool contour_form_factor(const Vec3& P, const Vec3& nP, const Vec3* const* V, int m, const Vec3& nQ, double h,
                                double& out) {
  const double nu = nP.dot(nQ);
  double e[kMaxContourCorners], D[kMaxContourCorners], L[kMaxContourCorners], nPnk[kMaxContourCorners],
      s1[kMaxContourCorners], s2[kMaxContourCorners];
  bool near_edge = false;
  for (int k = 0; k < m; ++k) {
    // The edge taken in the plane: its corners lie in it only to rounding, a tilt of about
    // eps |V| / L out of it, which s1 and s2 would take in as h times the tilt (for a sliver's
    // edge of length 1e-11 a millionth of h, against an in-plane angle of that order).
    Vec3 E = *V[k + 1] - *V[k];
    E -= E.dot(nQ) * nQ;
    L[k] = E.norm();
    if (!(L[k] > 0)) {  // no length in the plane: a triangle has no area there, a polygon's edge adds nothing
      if (m == 3) {
        out = 0;
        return true;
      }
      e[k] = D[k] = s1[k] = s2[k] = nPnk[k] = 0;
      continue;
    }
    const Vec3 tau = E / L[k];
    const Vec3 nk = tau.cross(nQ);  // outward in-plane normal of edge k
    const Vec3 w0 = *V[k] - P, w1 = *V[k + 1] - P;
    e[k] = w0.dot(nk);
    s1[k] = w0.dot(tau);
    s2[k] = w1.dot(tau);
    nPnk[k] = nP.dot(nk);
    D[k] = std::sqrt(e[k] * e[k] + h * h);
    near_edge |= D[k] * kNearEdgeRatio < std::max(w0.cwiseAbs().maxCoeff(), w1.cwiseAbs().maxCoeff());
  }
  if (near_edge) {
    if (m != 3) return false;
    accurate_heights(P, *V[0], *V[1], *V[2], L, h, e);
    if (h == 0) {  // P in the plane after all
      out = 0;
      return true;
    }
    for (int k = 0; k < 3; ++k) D[k] = std::sqrt(e[k] * e[k] + h * h);
  }
  const double h2 = h * h;
  double sum_t = 0, sum_n = 0, mag_n = 0;
  bool outside = false;
  double g[kMaxContourCorners];
  for (int k = 0; k < m; ++k) {
    g[k] = L[k] > 0 ? angle_over_distance(D[k], L[k], D[k] * D[k] + s1[k] * s2[k]) : 0;
    sum_t += nPnk[k] * g[k];
    const double term = e[k] * g[k];
    sum_n += term;
    mag_n += std::abs(term);
    outside |= e[k] < 0;
  }
  if (outside && nu != 0 && std::abs(sum_n) * 64.0 < mag_n) {
    // Cancellation-free form; the winding term is 0 since the foot is outside, which holds for
    // the in-plane angles as computed only while the foot is not within rounding of a corner
    // (the tip of a sliver a few 1e-9 from the foot: angles off by 1e-7). There the direct sum
    // is kept: its terms are then as small as the sliver, and so is their rounding.
    double cancellation_free = 0, winding = 0;
    for (int k = 0; k < m; ++k) {
      if (e[k] == 0) continue;
      const double ae = std::abs(e[k]);
      const double q = h2 / (D[k] + ae);  // D - |e|
      const double delta = std::atan2(-s2[k] * q, D[k] * ae + s2[k] * s2[k]) -
                           std::atan2(-s1[k] * q, D[k] * ae + s1[k] * s1[k]);
      const double bracket = -q * g[k] + delta;  // (|e|/D - 1) gamma + gamma(D) - gamma(|e|)
      cancellation_free += e[k] > 0 ? bracket : -bracket;
      const double in_plane = std::atan2(ae * L[k], ae * ae + s1[k] * s2[k]);
      winding += e[k] > 0 ? in_plane : -in_plane;
    }
    if (std::abs(winding) <= kWindingRounding) sum_n = cancellation_free;
  }
  constexpr double inv_two_pi = 0.15915494309189533577;  // 1/(2 pi)
  out = -(h * sum_t + nu * sum_n) * inv_two_pi;
  return true;
}

}  // namespace detail

inline double form_factor(const Vec3& P, const Vec3& nP, const Vec3& a, const Vec3& b,
                          const Vec3& c, const Vec3& nQ) {
  const double h = (P - a).dot(nQ);  // (P - Q).nQ for every Q of the plane
  if (h == 0) return 0;              // paper 4.2, case (a): coplanar, exactly zero
  const bool flip = (b - a).cross(c - a).dot(nQ) < 0;  // walk the edges counter-clockwise about nQ
  const Vec3* V[4] = {&a, flip ? &c : &b, flip ? &b : &c, &a};
  double out = 0;
  detail::contour_form_factor(P, nP, V, 3, nQ, h, out);
  return out;
}

inline double convex_polygon_form_factor(const Vec3& P, const Vec3& nP, const Vec3* corners, int m, const Vec3& nQ) {
  if (m < 3) return 0;
  const auto fan = [&] {
    double sum = 0;
    for (int k = 1; k + 1 < m; ++k) {
      const Vec3 &a = corners[0], &b = corners[k], &c = corners[k + 1];
      if ((b - a).cross(c - a).squaredNorm() == 0) continue;
      sum += form_factor(P, nP, a, b, c, nQ);
    }
    return sum;
  };
  if (m == 3 || m > detail::kMaxContourCorners) return fan();
  const double h = (P - corners[0]).dot(nQ);
  if (h == 0) return 0;  // paper 4.2, case (a)
  // Walked counter-clockwise about nQ whichever way the corners are listed (the sign of twice the
  // signed area, a sum of fan cross products).
  double twice_area = 0;
  for (int k = 1; k + 1 < m; ++k) twice_area += (corners[k] - corners[0]).cross(corners[k + 1] - corners[0]).dot(nQ);
  if (twice_area == 0) return 0;
  const Vec3* V[detail::kMaxContourCorners + 1];
  for (int k = 0; k < m; ++k) V[k] = &corners[twice_area > 0 ? k : (m - k) % m];
  V[m] = V[0];
  double out = 0;
  return detail::contour_form_factor(P, nP, V, m, nQ, h, out) ? out : fan();
}

}  // namespace panelrad::quadrature

#pragma once
// Local expansions of target clusters: the cluster-cluster far field of the fast product.
//
// For a target cluster sigma (a triangle of the tree, in one plane with one inner normal n_P) and
// a source cluster tau admissible for every point of a rectangle bounding sigma, the far field
// (47) of tau, f_tau(P) = sum_t c_t(P) m_t(tau), is an analytic function of P on sigma's plane.
// Its local expansion is the tensor polynomial of degree d in each in-plane coordinate that
// interpolates f_tau at the (d+1)^2 Chebyshev points of the rectangle. Values at the points are
// additive over the sources, so a target cluster holds one table of (d+1)^2 values: the sum over
// its sources tau of f_tau at the points, each value a far-field row (47) of the point with n_P.
// A (sigma, tau) pair then costs (d+1)^2 point-cluster pairs instead of |sigma|, one per
// collocation point of sigma, and each collocation point adds the interpolants of its ancestors.
//
// Error. Along a line of the rectangle through its centre c (s the coordinate, half-width h),
// f_tau(c + s e) is singular only where |P(s) - Q|^2 = 0 for some Q in tau, which for complex
// s = a + i b needs b^2 = |P(a) - Q|^2, so |s|^2 >= a^2 + (delta - |a|)^2 >= delta^2 / 2 with
// delta the distance from the line's real points to tau near c. Chebyshev interpolation of degree
// d then converges like r^-(d+1), r >= about sqrt(2) delta / h (the Bernstein ellipse that avoids
// |s| < delta/sqrt(2)), times the Lebesgue constant (2/pi log(d+1) + 1)^2 of the tensor points.
// The target admissibility R(box) <= eta_t (|c - A(tau)| - R(tau)) keeps h/delta <= about eta_t;
// the fast operator's self-check measures the product's error with the interpolation in it.
#include <panelrad/operator/far_field.hpp>

#include <array>

namespace panelrad {

/// Largest interpolation degree d of a local expansion (stack arrays are sized for it).
inline constexpr int kMaxLocalDegree = 12;

/// Values of a local expansion of degree d: (d+1)^2.
constexpr int num_local_points(int d) { return (d + 1) * (d + 1); }

/// The Chebyshev points of the first kind on [-1, 1], t_j = cos((2j+1) pi / (2(d+1))), j = 0..d
/// (decreasing), d in [0, kMaxLocalDegree]; std::invalid_argument otherwise.
std::array<double, kMaxLocalDegree + 1> chebyshev_points(int d);

/// The Lagrange basis a_j(s) of the first-kind Chebyshev points at s (any finite s), by the
/// barycentric formula with weights (-1)^j sin((2j+1) pi / (2(d+1))) (second barycentric form:
/// the a_j sum to 1 in floating point up to one rounding; at s = t_j exactly, a = e_j).
void chebyshev_basis(int d, double s, double* a);

/// A rectangle of a cluster's plane in its frame's local coordinates: centre (cx, cy) and
/// half-widths hx, hy > 0 along e1, e2. Bounds a target cluster; carries its interpolation points.
struct LocalBox {
  double cx = 0, cy = 0, hx = 0, hy = 0;

  /// The rectangle bounding the triangle (a, b, c) of the plane of `frame` (its corners'
  /// local coordinates), widened by a relative 2^-40 so that rounded points of the triangle lie
  /// inside. Throws std::invalid_argument when it is degenerate or not finite.
  static LocalBox bounding(const PlaneFrame& frame, const Vec3& a, const Vec3& b, const Vec3& c);
  /// Half of the diagonal: every point of the rectangle lies within it of the centre.
  double half_diagonal() const;
  /// The centre as a point of space (frame's origin + cx e1 + cy e2).
  Vec3 centre(const PlaneFrame& frame) const;
  /// The (d+1)^2 interpolation points, index i (d+1) + j at cx + hx t_i, cy + hy t_j.
  void points(const PlaneFrame& frame, int d, Vec3* out) const;
  /// The interpolant of `values` ((d+1)^2 values at points(), C series interleaved: value k of
  /// series c at values[k C + c], C in 1..4) at the point P of the plane, into out[0..C): the sum
  /// over i of a_i(s) sum over j of b_j(t) values, (s, t) the scaled local coordinates of P.
  /// std::invalid_argument for d or C out of range.
  void interpolate(const PlaneFrame& frame, int d, const double* values, int C, const Vec3& P, double* out) const;
};

}  // namespace panelrad

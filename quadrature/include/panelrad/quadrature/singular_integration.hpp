#pragma once
// High-accuracy integration of f(Q) G(P,Q) over a triangle, also when P is very close to the
// triangle's edges (nearly singular integrand): used to manufacture E = u - K u from a known
// solution u, the paper's test method (section 3, example (31)).
#include <panelrad/geometry/mesh.hpp>

#include <Eigen/Geometry>  // cross products

#include <array>
#include <functional>
#include <optional>
#include <span>

namespace panelrad::quadrature {

using geometry::Vec3;

struct SingularIntegralResult {
  double value = 0;
  double error_estimate = 0;  ///< absolute
  int evaluations = 0;
};

/// (1/pi) Int_Delta f(Q) G(P,Q) dS_Q to relative accuracy `rel_tol` (effective tolerance
/// max(rel_tol, 1e-12); for an integral that cancels, f changing sign, an absolute floor of
/// 0.1 tol pi |form factor| max|f| applies), for f smooth on the triangle.
/// The triangle is split hierarchically (4-way midpoint subdivision) before choosing the method:
/// pieces S with dist(P, S) >= 0.4 diam(S) take a collapsed Gauss n x n rule (n from the ratio,
/// error estimated against the (n-2) x (n-2) rule), pieces with P hanging closely over their
/// interior take polar coordinates about the foot of P (angle split at the vertex directions and
/// graded logarithmically, radius in atan(r/|h|) and ln r, adaptive Gauss-Kronrod 7/15), other
/// pieces are split; then the piece with the largest estimate is refined (order n+2, or split)
/// until the summed estimates meet the tolerance. Accurate also when P is within 1e-7 of an edge.
/// 0 (and 0 evaluations) when P lies exactly in the plane of the triangle (h == 0).
/// Rounding floor: a piece whose two rules differ by at most 100 eps sum |w f h| (|R.nP| + |R|)
/// / r^4 (R = Q - P; the computed (Q - P).nP carries an error of a few eps |R| whatever its
/// value) is not refined further. When P lies in the triangle's plane within rounding (a
/// slanted planar face given as several triangles with rounded coordinates: h ~ 1e-17 instead
/// of 0) the integrand is rounding noise; the result is then a value and an estimate at that
/// rounding level, reached in a few thousand evaluations, instead of an unreachable relative
/// tolerance.
/// Errors: std::invalid_argument for an empty f, rel_tol <= 0, non-finite input or a zero-area
/// triangle; std::runtime_error for a non-finite result or no convergence within 5e7
/// evaluations (f not smooth on the triangle), naming P and the triangle.
SingularIntegralResult integrate_kernel_times(const std::function<double(const Vec3&)>& f,
                                              const Vec3& P, const Vec3& nP, const Vec3& a,
                                              const Vec3& b, const Vec3& c, const Vec3& nQ,
                                              double rel_tol = 1e-11);

/// (1/pi) Int_Delta p(Q) G(P,Q) dS_Q for the quadratic p taking `values` at a, b, c and at the
/// midpoints of a-b, b-c, c-a (the quadratic Lagrange nodes), to relative accuracy
/// max(rel_tol, 1e-12) (absolute floor as for integrate_kernel_times). Polar coordinates about
/// the foot F = P - h nQ of P with the radial integral in closed form (atan and log terms);
/// the triangle as the signed sum of the triangles (F, edge); along each edge's line, at
/// distance d from F, the angle theta = gd(w) (position d sinh w), in which the integrand is
/// analytic in |Im w| < pi/2 whatever the distances: Gauss-Legendre panels with an error bound
/// from that strip. Accurate and cheap also when P is within 1e-8 (and less) of an edge: some
/// hundred evaluations of the radial closed form, none of a function f.
/// 0 when P lies exactly in the plane of the triangle (h == 0).
/// Errors: std::invalid_argument for rel_tol <= 0, non-finite input or a zero-area triangle;
/// std::runtime_error when the estimate does not meet the tolerance, naming P and the triangle:
/// when the foot of P lies outside the triangle and |h| is small against its distance, the
/// signed parts cancel and their rounding exceeds the tolerance (integrate_kernel_times then).
SingularIntegralResult integrate_kernel_times_quadratic(const std::array<double, 6>& values,
                                                        const Vec3& P, const Vec3& nP,
                                                        const Vec3& a, const Vec3& b,
                                                        const Vec3& c, const Vec3& nQ,
                                                        double rel_tol = 1e-11);

/// (1/pi) Int_S f(Q) G(P,Q) dS_Q over a planar facet S given as triangles (index triples into
/// `vertices`, either orientation each) with unit normal nQ, to relative accuracy
/// max(rel_tol, 1e-12) of the value (G has one sign on S here, so the value is the integral's
/// scale), by the rule of
/// integrate_kernel_times_quadratic over the facet's boundary (the triangles' edges shared by
/// two of them cancel in the signed sum), when f is quadratic on S within rounding: p from f at
/// the Lagrange nodes of the largest triangle, |f - p| <= 64 eps max|f| at the nodes and 7
/// interior points of every triangle. std::nullopt when the rule does not apply or does not
/// certify its tolerance: f not quadratic on S (or not finite there), (Q - P).nP changing sign
/// over S, S not planar within 1e-12 of its size, |h| <= 1e-10 of its size (P nearly in its
/// plane), an edge used twice in one direction, cancellation of the signed parts; the caller
/// then integrates the triangles one by one (integrate_kernel_times).
std::optional<SingularIntegralResult> integrate_kernel_times_quadratic_facet(
    const std::function<double(const Vec3&)>& f, const Vec3& P, const Vec3& nP,
    std::span<const Vec3> vertices, std::span<const std::array<geometry::Index, 3>> triangles,
    const Vec3& nQ, double rel_tol = 1e-11);

}  // namespace panelrad::quadrature

#pragma once
// High-accuracy integration of f(Q) G(P,Q) over a triangle, also when P is very close to the
// triangle's edges (nearly singular integrand): used to manufacture E = u - K u from a known
// solution u, the paper's test method (section 3, example (31)).
#include <panelrad/geometry/mesh.hpp>

#include <Eigen/Geometry>  // cross products

#include <functional>

namespace panelrad::quadrature {

using geometry::Vec3;

struct SingularIntegralResult {
  double value = 0;
  double error_estimate = 0;  ///< absolute
  int evaluations = 0;
};

/// (1/pi) Int_Delta f(Q) G(P,Q) dS_Q to relative accuracy `rel_tol` (effective tolerance
/// max(rel_tol, 1e-12)), for f smooth on the triangle.
/// Well-separated P (dist >= 2 diam): adaptive midpoint subdivision with an embedded pair of
/// collapsed Gauss rules (degree 10 / 8). Otherwise polar coordinates about the foot of P on the
/// triangle's plane, angle split at the vertex directions and graded logarithmically towards
/// directions parallel to an edge, radius in atan(r/|h|) below |h| and in ln r above, adaptive
/// Gauss-Kronrod (7/15) in both: accurate also when P is within 1e-7 of an edge.
/// 0 (and 0 evaluations) when P lies exactly in the plane of the triangle (h == 0).
/// Errors: std::invalid_argument for an empty f, rel_tol <= 0, non-finite input or a zero-area
/// triangle; std::runtime_error for a non-finite result or no convergence.
SingularIntegralResult integrate_kernel_times(const std::function<double(const Vec3&)>& f,
                                              const Vec3& P, const Vec3& nP, const Vec3& a,
                                              const Vec3& b, const Vec3& c, const Vec3& nQ,
                                              double rel_tol = 1e-11);

}  // namespace panelrad::quadrature

#pragma once
// High-accuracy integration of f(Q) G(P,Q) over a triangle, also when P is very close to the
// triangle's edges (nearly singular integrand): used to manufacture E = u - K u from a known
// solution u, the paper's test method (section 3, example (31)).
#include <panelrad/geometry/mesh.hpp>

#include <functional>

namespace panelrad::quadrature {

using geometry::Vec3;

struct SingularIntegralResult {
  double value = 0;
  double error_estimate = 0;  ///< absolute
  int evaluations = 0;
};

/// (1/pi) Int_Delta f(Q) G(P,Q) dS_Q to relative accuracy `rel_tol` (down to ~1e-12), by polar
/// coordinates about the foot of P on the triangle's plane with a radial substitution that
/// absorbs the near singularity, and adaptive Gauss-Kronrod in angle and radius.
/// 0 when P lies in the plane of the triangle.
SingularIntegralResult integrate_kernel_times(const std::function<double(const Vec3&)>& f,
                                              const Vec3& P, const Vec3& nP, const Vec3& a,
                                              const Vec3& b, const Vec3& c, const Vec3& nQ,
                                              double rel_tol = 1e-11);

}  // namespace panelrad::quadrature

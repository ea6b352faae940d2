#pragma once
// Exact integrals over planar triangles: monomials, and the point-to-triangle form factor.
#include <panelrad/geometry/mesh.hpp>

#include <array>
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
/// with inner normals.
double form_factor(const Vec3& P, const Vec3& nP, const Vec3& a, const Vec3& b, const Vec3& c,
                   const Vec3& nQ);

}  // namespace panelrad::quadrature

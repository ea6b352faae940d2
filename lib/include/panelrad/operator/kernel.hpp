#pragma once
// The radiosity kernel of the paper, (2): G(P,Q) = [(Q-P).n_P][(P-Q).n_Q] / |P-Q|^4, with n the
// inner unit normal. For an unoccluded (convex) surface V = 1 and K(P,Q) = rho(P) G(P,Q) / pi.
#include <panelrad/geometry/mesh.hpp>

namespace panelrad {

using geometry::Index;
using geometry::Vec3;

inline constexpr double pi = 3.14159265358979323846;

/// G(P,Q), paper (2). Zero when Q == P (coplanar case (a) of section 4.2 gives 0 anyway).
inline double radiosity_G(const Vec3& P, const Vec3& nP, const Vec3& Q, const Vec3& nQ) {
  const Vec3 d = Q - P;
  const double r2 = d.squaredNorm();
  if (r2 == 0) return 0;
  return (d.dot(nP)) * (-d.dot(nQ)) / (r2 * r2);
}

}  // namespace panelrad

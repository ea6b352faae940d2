#pragma once
// The admissibility condition (41): R(tau) <= eta |P - A(tau)|, decided exactly on the double
// inputs: a double test with a rigorous error bound (inline, no CGAL), and exact arithmetic (CGAL,
// in geometry/src/admissibility.cpp) only when the double result is uncertain, so the covering
// never depends on rounding.
#include <panelrad/geometry/mesh.hpp>

namespace panelrad::geometry {

namespace detail {
/// Exact decision of R^2 <= eta^2 |P - A|^2 on the given doubles (counts one fallback).
/// Throws std::invalid_argument for NaN/Inf input, R < 0 or eta < 0.
bool is_admissible_exact(const Vec3& P, const Vec3& A, double R, double eta);
}  // namespace detail

/// True when R <= eta * |P - A| holds exactly for the given double values (R, eta >= 0; else
/// std::invalid_argument, as for NaN or Inf input).
///
/// Fast path: lhs = fl(R*R) and rhs = fl(fl(eta*eta) * s), s = fl(dx^2 + dy^2 + dz^2) with
/// d = fl(P - A). With u = 2^-53 and no underflow/overflow, every operation rounds once
/// (an FMA, if the compiler contracts, rounds less), so, all terms being non-negative,
///   s   = |P-A|^2 (1 + t),  |t| <= gamma_5  (d_i: 1 rounding, entering squared: 2; the square: 1;
///                                              the two additions: 2)
///   rhs = eta^2 |P-A|^2 (1 + t'), |t'| <= gamma_7 (eta*eta and the product: 2 more)
///   lhs = R^2 (1 + t''),  |t''| <= u,            gamma_k = k u / (1 - k u) < 7.001 u for k <= 7.
/// Hence if rhs - lhs > 7.001 u (lhs + rhs) the exact R^2 <= exact eta^2|P-A|^2, and if
/// lhs - rhs > 7.001 u (lhs + rhs) the exact R^2 > exact eta^2|P-A|^2. The test below uses the
/// margin 16 u fl(lhs + rhs) = 2^-49 fl(lhs + rhs) (the scaling is exact; fl(lhs + rhs) and
/// fl(rhs - lhs) each add one relative u, covered by the factor 16/7.001). Underflow: every
/// quantity lhs, s, eta^2, rhs is required to be >= 2^-900, so the few subnormal roundings of
/// tiny squared components (each <= 2^-1075 absolute) are below 2^-170 relative: covered too.
/// Overflow gives Inf/NaN, on which both comparisons fail: the exact path decides (or throws).
inline bool is_admissible(const Vec3& P, const Vec3& A, double R, double eta) {
  const double dx = P.x() - A.x();
  const double dy = P.y() - A.y();
  const double dz = P.z() - A.z();
  const double s = dx * dx + dy * dy + dz * dz;
  const double e2 = eta * eta;
  const double rhs = e2 * s;  // eta^2 |P - A|^2
  const double lhs = R * R;   // R^2
  constexpr double tiny = 0x1p-900;
  if (R >= 0 && eta >= 0 && lhs >= tiny && s >= tiny && e2 >= tiny && rhs >= tiny) {
    const double margin = 0x1p-49 * (lhs + rhs);
    const double diff = rhs - lhs;
    if (diff > margin) return true;
    if (diff < -margin) return false;
  }
  return detail::is_admissible_exact(P, A, R, eta);
}

/// Counts how often the exact fallback ran (for tests and reports); thread-safe.
unsigned long long admissibility_exact_fallbacks();

}  // namespace panelrad::geometry

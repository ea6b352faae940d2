#pragma once
// The admissibility condition (41): R(tau) <= eta |P - A(tau)|, decided exactly on the double
// inputs: a double test with a rigorous error bound, and exact rational arithmetic (CGAL) only
// when the double result is uncertain, so the covering never depends on rounding.
#include <panelrad/geometry/mesh.hpp>

namespace panelrad::geometry {

/// True when R <= eta * |P - A| holds exactly for the given double values (R, eta >= 0).
bool is_admissible(const Vec3& P, const Vec3& A, double R, double eta);

/// Counts how often the exact fallback ran (for tests and reports); thread-safe.
unsigned long long admissibility_exact_fallbacks();

}  // namespace panelrad::geometry

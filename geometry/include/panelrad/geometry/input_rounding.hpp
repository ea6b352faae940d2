#pragma once
// The rounding model of input coordinates: how far the rounding of a mesh's coordinates can have
// moved each vertex, inferred from the digits the coordinates show. validate_closed_convex
// (validation.hpp) accepts a convexity violation within the bound(t, v) this model gives.
#include <panelrad/geometry/mesh.hpp>

#include <string>

namespace panelrad::geometry {

/// What the rounding of the input coordinates can have moved each vertex by.
///
/// A coordinate written with d significant decimal digits is off from the value it rounds by at most
/// half a unit in its last digit, 0.5 * 10^(e + 1 - d) <= 0.5 * 10^(1 - d) * |x| (e = its decimal
/// exponent); a double computed by a rotation x' = R x in double precision (R's entries rounded, each
/// coordinate a 3-term dot product) is off by at most about 4 u |R| |x| <= 12 u M with u = 2^-53, and
/// 16 u M is taken. Relative to the largest coordinate magnitude M (not the diameter: a translated
/// mesh carries the rounding of its absolute coordinates):
///   eta = (rho_d + 16 u) M,  rho_d = 0.5 * 10^(1 - d) for decimal input, 0 for binary doubles.
/// The digits d are inferred from the coordinates themselves: `digits` = the most significant
/// digits any coordinate's shortest round-trip decimal form needs (what %.{d}g must print for every
/// coordinate to read back exactly). digits <= 16 is taken as a decimal export with
/// assumed_digits = max(6, digits) (6 = printf's %g and iostream's default, the coarsest precision
/// assumed: short hand-written coordinates such as integers are not taken as 1-digit roundings);
/// 17 as binary doubles. Per input precision, with M the coordinate magnitude:
///   17 digits (binary): eta = 1.8e-15 M;  15 digits: eta = 6.8e-15 M;  6 digits: eta = 5.0e-6 M;
///   the largest violation accepted is bound(t, v) of validate_closed_convex (validation.hpp), a
///   few eta for well-shaped triangles.
/// A dent smaller than what that rounding can produce cannot be told from it (a 6-digit file
/// cannot show a 1e-6 dent of a mesh around the origin). Only the digits the file shows count: a
/// mesh rounded to 6 digits, then rotated and written with 17, carries a 6-digit error that its
/// digits no longer show; it is accepted only when the exact hull re-triangulation applies.
struct InputRounding {
  int digits = 0;               ///< most significant digits a coordinate needs to read back (1..17)
  int assumed_digits = 17;      ///< precision assumed for the export; 17 = binary double
  bool decimal = false;         ///< digits <= 16: taken as decimal rounding to assumed_digits
  double magnitude = 0.0;       ///< M = max |coordinate|
  double relative = 0.0;        ///< rho_d + 16 u
  double per_coordinate = 0.0;  ///< eta = relative * M, bound on |rounded - true| per coordinate
  std::string describe() const; ///< "coordinates rounded to 6 significant digits of magnitude 1.37"
};

/// The rounding model of a mesh's coordinates (finite coordinates required).
InputRounding input_rounding(const TriangleMesh& mesh);

/// Largest violation, relative to the mesh diameter, that is ever attributed to rounding, whatever
/// the input precision: above it the input is too coarse to be called convex.
inline constexpr double kMaxRoundingViolation = 1e-4;

}  // namespace panelrad::geometry

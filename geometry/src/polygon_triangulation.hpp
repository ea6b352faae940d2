#pragma once
// Triangulation of one polygonal input face (an OFF or OBJ face with four or more corners) into
// triangles on its own corners, or the reason why the polygon is not a planar simple polygon.
//
// The polygon P = (p_0, ..., p_{n-1}) is accepted when
//   - its corners are pairwise distinct points,
//   - not all of them lie on one straight line (positive area),
//   - it is planar: every corner lies within the tolerance below of the plane through the centroid
//     of the corners with the Newell normal N = sum_i (p_i - c) x (p_{i+1} - c); between that
//     tolerance and kFlatnessLimit of its size it is accepted with a note, beyond it refused,
//   - its projection onto the coordinate plane that drops the largest component of N is a simple
//     polygon: sides meet only at the corner two consecutive sides share (exact predicates).
// Flatness tolerance: a corner may lie at most
//   max(kFlatnessRelative * s, kFlatnessRoundings * eta)
// from that plane, s the diagonal of the polygon's axis-parallel bounding box, eta the
// per-coordinate rounding of the mesh's coordinates (InputRounding::per_coordinate,
// input_rounding.hpp).
//
// The triangles use only the corners (the projection keeps the input coordinates exactly, no point
// is added), have positive area and run in the polygon's rotational direction, so the facet keeps
// the winding the file gives it. When the fan from p_0, (p_0, p_k, p_{k+1}) for k = 1..n-2, is a
// triangulation of P (every fan triangle has the polygon's orientation and the fan turns around p_0
// by less than a full turn), the fan is returned; otherwise the constrained Delaunay triangulation
// of the projected polygon restricted to its interior.
#include <panelrad/geometry/mesh.hpp>

#include <array>
#include <string>
#include <vector>

namespace panelrad::geometry::polygon_detail {

/// Flatness tolerance relative to the polygon's size (double precision on exactly planar data).
inline constexpr double kFlatnessRelative = 1e-9;
/// Flatness tolerance in units of the per-coordinate rounding eta of the input.
inline constexpr double kFlatnessRoundings = 4.0;
/// Beyond the tolerance, up to this fraction of the polygon's size (the largest violation ever
/// attributed to rounding, kMaxRoundingViolation of input_rounding.hpp), a polygon is triangulated
/// as projected along its normal with a note (each triangle in its own plane: a rounded export
/// whose digits no longer show its rounding); beyond it, refused.
inline constexpr double kFlatnessLimit = 1e-4;

/// The triangles of one polygon, or why it has none.
struct PolygonTriangulation {
  /// Corner numbers (0-based positions in the polygon's corner list), n - 2 triangles.
  std::vector<std::array<Index, 3>> triangles;
  /// Empty when triangulated; else what is wrong, a phrase that completes "input face F (line L) ",
  /// e.g. "is not planar: ...".
  std::string refusal;
  /// When triangulated although not planar within the tolerance: why, completing the same phrase.
  std::string note;
};

/// Triangulates the polygon with the given corners (n >= 3, finite coordinates); `eta` is the
/// per-coordinate rounding of the input coordinates (0 for exact data). A triangle is returned as is.
PolygonTriangulation triangulate_polygon(const std::vector<Vec3>& corners, double eta);

}  // namespace panelrad::geometry::polygon_detail

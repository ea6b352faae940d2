#pragma once
// Maximal planar facets of a triangulated surface, exactly or within the rounding of the input
// (input_rounding.hpp).
#include <panelrad/geometry/input_rounding.hpp>
#include <panelrad/geometry/mesh.hpp>

#include <cstddef>

namespace panelrad::geometry {

/// Number of maximal planar facets: classes of triangles joined across shared edges whose four
/// vertices are coplanar (a square split in two is one): exactly, or within the rounding of the
/// input (each far vertex within bound(t, v) of the other triangle's plane, as in
/// validate_closed_convex (validation.hpp), and within kMaxRoundingViolation of the diameter), so
/// that a rotated or rounded cube still has 6. Works on any mesh with finite coordinates (edges not
/// shared by exactly two triangles simply join nothing).
std::size_t count_planar_facets(const TriangleMesh& mesh);

}  // namespace panelrad::geometry

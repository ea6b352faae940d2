#pragma once
// Maximal planar facets of a triangulated surface, exactly or within the rounding of the input
// (input_rounding.hpp).
#include <panelrad/geometry/input_rounding.hpp>
#include <panelrad/geometry/mesh.hpp>

#include <cstddef>
#include <vector>

namespace panelrad::geometry {

/// Number of maximal planar facets: classes of triangles joined across shared edges whose four
/// vertices are coplanar (a square split in two is one): exactly, or within the rounding of the
/// input (each far vertex within bound(t, v) of the other triangle's plane, as in
/// validate_closed_convex (validation.hpp), and within kMaxRoundingViolation of the diameter), so
/// that a rotated or rounded cube still has 6. Works on any mesh with finite coordinates (edges not
/// shared by exactly two triangles simply join nothing).
std::size_t count_planar_facets(const TriangleMesh& mesh);

/// Which facets facet_planes may put in one plane besides exactly coplanar ones.
enum class PlaneGrouping {
  exact,            ///< exactly coplanar only: a general scene, whose faces may face each other
                    ///< across any positive gap and whose answer must not depend on the digits
                    ///< of unrelated coordinates
  within_rounding,  ///< also within the rounding of the input when both face the same way: a
                    ///< closed convex surface accepted within rounding (validation.hpp)
};

/// The supporting plane of each facet: per facet id, a plane id in [0, number of planes), the same
/// for facets whose triangles lie in one plane (in order of their first facet), whether or not they
/// touch. A facet is in the plane of an earlier facet's first triangle when each corner of its own
/// first triangle is exactly coplanar with it (CGAL's filtered orientation predicate), whichever
/// way the two face; with PlaneGrouping::within_rounding also when both face the same way and the
/// corners lie within the rounding of the input as count_planar_facets joins triangles (bound(t, v)
/// and kMaxRoundingViolation). Faces of opposite orientation across a positive gap are never in one
/// plane: they face each other (or turn their backs to each other) and G(P, Q) is not zero between
/// them. The facets' triangles are planar by validation. A point of a plane sees nothing of that
/// plane: G(P, Q) of (2) has the factor (Q - P).n_P = 0 there, so every cluster in P's plane is
/// coplanar with P (section 4.2, case (a)), whatever facet it lies in. Throws MeshError for
/// inconsistent meshes (bad index, non-finite coordinate, a degenerate first triangle); a facet id
/// that no triangle has gets -1.
std::vector<Index> facet_planes(const TriangleMesh& mesh, PlaneGrouping grouping = PlaneGrouping::within_rounding);

/// The supporting plane of each triangle: its facet's (facet_planes), except that with
/// PlaneGrouping::exact a triangle whose corners are not all exactly coplanar with its facet's
/// first triangle (a face written rounded, bent by its digits) gets a plane id of its own, after
/// those of the facets: G(P, Q) between the two halves of a bent face is not zero.
std::vector<Index> triangle_planes(const TriangleMesh& mesh, PlaneGrouping grouping = PlaneGrouping::within_rounding);

}  // namespace panelrad::geometry

#pragma once
// T-junctions: a vertex of the surface lying in the open segment of an edge of another triangle.
// The topology rules match edges by vertex indices, so an edge (a, b) whose neighbours meet it in
// the two edges (a, v) and (v, b) is seen as a boundary edge of an open surface although the
// surface closes geometrically. Inserting v into (a, b) restores the index matching.
// Private to geometry/src (t_junctions.cpp); the declaration needs no CGAL type, so that the tests
// can call it directly.
#include <panelrad/geometry/mesh.hpp>

#include <cstddef>
#include <vector>

namespace panelrad::geometry::validation_detail {

/// Inserts every vertex lying strictly inside a boundary edge into that edge: a boundary edge is an
/// undirected edge {a, b} (by vertex indices) used by exactly one triangle, and a vertex v (used by
/// some triangle) lies strictly inside it when a, v, b are collinear and v is strictly between a
/// and b, both decided by exact predicates (no tolerance; a vertex at the coordinates of a or b is
/// not inside). The triangle (a, b, c) with v_1, ..., v_k inside (a, b), ordered from a to b, is
/// replaced by the fan (a, v_1, c), (v_1, v_2, c), ..., (v_k, b, c): the same orientation, the
/// same facet, the same area and no degenerate piece (c is off the line (a, b), and the v_i are
/// distinct points of it). Repeated until no boundary edge has a vertex inside;
/// triangles with collinear vertices are left as they are. Returns the number of vertices inserted
/// into edges (0: mesh unchanged). Vertices are never added or moved.
/// Cost: O(T log T) per round plus the exact tests of the candidate pairs, found by
/// CGAL::box_intersection_d between the vertices and boxes covering each boundary edge in pieces of
/// about the median edge length. At most three rounds change the mesh (a triangle is split along
/// one edge per round, and the edges a split creates have no vertex inside).
/// `origin`, when given, holds a value per triangle and is carried to the triangles it is split
/// into. `tolerance` > 0: a vertex within that distance of the open segment, and further than it
/// from both ends, lies inside it too (corners written rounded: a corner of one solid on the edge
/// of another, an ulp off its line).
/// x lies within `tolerance` of the open segment (a, b) and further than it from both ends (along
/// the segment): a corner on that edge within the rounding of the coordinates.
bool near_open_segment(const Vec3& a, const Vec3& b, const Vec3& x, double tolerance);

std::size_t split_t_junctions(TriangleMesh& mesh, std::vector<Index>* origin = nullptr, double tolerance = 0);

}  // namespace panelrad::geometry::validation_detail

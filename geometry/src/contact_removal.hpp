#pragma once
// Faces in contact of validate_scene (scene_validation.hpp): coincident faces with opposite front
// sides cut along the contact outline, the parts inside solid matter removed (contact_removal.cpp).
#include "validation_internal.hpp"

#include <optional>
#include <set>
#include <utility>
#include <vector>

namespace panelrad::geometry::validation_detail {

/// The projections of triangles t and u along the dominant axis of t's normal overlap by more
/// than `tol` (separating axes in double precision): faces meeting along an edge within the
/// rounding of their corners only touch.
bool projections_overlap(const TriangleMesh& mesh, const Tri& t, const Tri& u, double tol);

/// The part of ContactTolerance::of that comes from the rounding of faces f and g as written
/// alone (0 for exact coordinates), and the largest tolerance of any pair of faces of a scene of
/// size `size` (written_rounding.cpp).
double rounding_tolerance(const ContactTolerance& tolerance, Index f, Index g, double pair_size);
double largest_tolerance(const ContactTolerance& tolerance, double size);
/// The distance within which a corner lies on another face's open edge (a T-junction,
/// split_t_junctions): largest_tolerance, and beyond its cap 4 times the largest rounding of the
/// numbers as written (a corner's and the edge line's roundings, sqrt(3) times each: 2 sqrt(3) < 4).
/// Only open edges are joined, so that the cap, which keeps faces meant apart or crossing from
/// being taken for a contact, is not needed here: a corner within the printing's reach of an open
/// edge is that edge's, as the digits can say no more (written_rounding.cpp).
double t_junction_tolerance(const ContactTolerance& tolerance, double size);

/// Drops the vertices no triangle uses, keeping the order of the others (close_corners.cpp).
void drop_unused_vertices(TriangleMesh& mesh);

/// Joins the corners closer than `tolerance` in every coordinate into one (the lowest-numbered of
/// each class keeps its coordinates) and drops the triangles that this leaves with two equal or
/// three collinear corners, and the corners no triangle uses (close_corners.cpp). Returns the
/// number of corners joined into others (0: the mesh is unchanged). `origin`, when given, holds a
/// value per triangle and is kept for the triangles kept.
Sz join_close_corners(TriangleMesh& mesh, double tolerance, std::vector<Index>* origin = nullptr);

/// Faces whose coordinates were written rounded (their ContactTolerance above the resolution),
/// moved back onto the planes they stand for: triangles within the tolerance of each other's plane
/// and touching or overlapping within it (one face's triangles, flush sides, faces in contact)
/// share one least-squares plane, and every corner moves to the nearest point on the planes of its
/// triangles, those shared by several input faces exactly (common_planes.cpp). Returns the number
/// of corners moved; exact and 17-digit coordinates are left bit for bit.
Sz snap_to_common_planes(TriangleMesh& mesh, const ContactTolerance& tolerance);

/// What merge_contacts_into_closed_pieces and remove_contacts removed.
struct ContactReport {
  struct Touch {
    Index face_a = 0, face_b = 0;         ///< two input faces in contact (face_a < face_b)
    double removed_a = 0, removed_b = 0;  ///< area removed from each input face by all its contacts
  };
  std::set<std::pair<Index, Index>> pairs;  ///< input faces in contact (smaller id first)
  std::vector<double> removed_of_facet;     ///< per input face, the area removed
  Sz triangles_cut = 0;  ///< input triangles cut or removed
  Sz across_gap = 0;     ///< pairs of triangles facing each other across a gap below the resolution
  std::set<std::pair<Index, Index>> two_sided;  ///< input faces back to back in one plane, both open: a two-sided sheet
  double area_removed() const;
  std::vector<Touch> touching() const;  ///< per pair of input faces in contact
};

/// Solids in contact whose faces as written make no closed piece: two solids sharing the
/// corners of their touching faces (stacked boxes, a box on a floor tile), which the readers join
/// by vertex index, so that the touching edges are shared by four triangles and neither solid
/// closes, whatever the diagonals of the touching faces. Overlaps in one plane (or within the
/// rounding) between open pieces are cut out of both faces (their common part, exactly); each such
/// contact is kept when what is left next to it is in closed pieces (the solids joined into one
/// closed surface around the contact, which lay inside matter), and left as it was otherwise (two
/// sheets back to back, a polygon given twice). On success `pieces` is oriented on the cut mesh
/// and `overlaps` found again on it; false when nothing was cut.
bool merge_contacts_into_closed_pieces(TriangleMesh& mesh, std::vector<Overlap>& overlaps, ScenePieces& pieces,
                                       const ContactTolerance& tolerance, ContactReport& out);

/// `overlaps`: pairs of triangles that overlap with positive area in one plane or within the
/// rounding (check_no_crossing), or across a gap below the tolerance (faces_across_a_gap).
/// `in_closed_piece`: per triangle, whether its piece is closed (bounds matter). Needs the front
/// sides of orient_scene_pieces (triangles clockwise seen from the front). Refuses overlaps with
/// the same front side (rule "crossing"), and an open piece's face that would be removed whole
/// (its front looking into a solid: a window written on a wall); keeps back-to-back overlaps of
/// two open pieces (a two-sided sheet: each is seen from its own front side); otherwise cuts each
/// triangle along the outlines of the triangles that cover it (opposite front sides, one of the two
/// in a closed piece) and removes the covered part, keeping facet ids and front sides, and drops
/// the vertices no triangle uses any more.
/// Pieces of the cut no higher than `sliver` are dropped (a slit within the tolerance of the
/// contact: the visibility's resolution, or the rounding of the coordinates as written).
std::optional<Failure> remove_contacts(TriangleMesh& mesh, const std::vector<Overlap>& overlaps,
                                       const std::vector<char>& in_closed_piece, double resolution,
                                       double sliver, ContactReport& out);

/// Pairs (i < j, sorted) of triangles whose bounding boxes, widened by `widen`, intersect
/// (CGAL::box_self_intersection_d).
std::vector<std::pair<Index, Index>> nearby_triangle_pairs(const TriangleMesh& mesh, double widen);
/// Every corner of u within `tol` of the plane of t (plane_distance, double precision).
bool corners_near_plane(const TriangleMesh& mesh, const Tri& t, const Tri& u, double tol);
/// The longest edge of t.
double longest_edge(const TriangleMesh& mesh, const Tri& t);

/// Pairs of triangles of different input faces, each strictly on one side of the other's plane
/// and every corner within the pair's tolerance of it (`tolerance`: the visibility's resolution, or the rounding
/// of the pair's coordinates as written when larger), whose projections overlap with positive area, not
/// back to back: faces across a gap the visibility cannot resolve (occluders.hpp:
/// visibility_margin), which remove_contacts treats as in contact (facing each other) or as the
/// same surface twice (facing the same way). Exact side tests; distances in double precision.
std::vector<Overlap> faces_across_a_gap(const TriangleMesh& mesh, const ContactTolerance& tolerance);

/// Pairs of overlapping triangles (in projection, by more than `tol`) of input faces with the same
/// corners: one polygon given twice (solids that share a face's vertices, a polygon written twice).
/// Each is the same surface twice however the rounding of its corners bends it, so it is listed
/// as an overlap within the rounding (a contact, a two-sided sheet or a duplicate, as
/// remove_contacts decides) even where the bend exceeds the contact tolerance.
std::vector<Overlap> copies_of_one_polygon(const TriangleMesh& mesh, double tol);

/// Closes the gaps of the pairs of faces_across_a_gap that face each other, and of the overlaps
/// within the rounding of the numbers as written (check_no_crossing): the corners of the
/// smaller triangle are moved onto the plane of the larger (by less than the resolution; exactly
/// onto it for a plane normal to an axis), so that no slit narrower than the visibility resolves
/// is left between two solids in contact. The larger's plane is the better determined by its
/// rounded corners; a small triangle's plane extended over a large one would tilt it (a leg's top
/// under a table's top, 1e6 from the origin: 1e-8 at the far corners, 1e-8 in u). Pairs facing the
/// same way are left (refused later).
void close_gaps(TriangleMesh& mesh, const std::vector<Overlap>& across_gap);

}  // namespace panelrad::geometry::validation_detail

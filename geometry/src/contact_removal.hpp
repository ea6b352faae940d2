#pragma once
// Faces in contact of validate_scene (scene_validation.hpp): coincident faces with opposite front
// sides cut along the contact outline, the parts inside solid matter removed (contact_removal.cpp).
#include "validation_internal.hpp"

#include <optional>
#include <set>
#include <utility>
#include <vector>

namespace panelrad::geometry::validation_detail {

/// What remove_shared_contact_faces and remove_contacts removed.
struct ContactReport {
  struct Touch {
    Index face_a = 0, face_b = 0;         ///< two input faces in contact (face_a < face_b)
    double removed_a = 0, removed_b = 0;  ///< area removed from each input face by all its contacts
  };
  std::set<std::pair<Index, Index>> pairs;  ///< input faces in contact (smaller id first)
  std::vector<double> removed_of_facet;     ///< per input face, the area removed
  Sz triangles_cut = 0;  ///< input triangles cut or removed
  Sz across_gap = 0;     ///< pairs of triangles facing each other across a gap below the resolution
  double area_removed() const;
  std::vector<Touch> touching() const;  ///< per pair of input faces in contact
};

/// Faces in contact given over shared vertices: two triangles over the same three vertices (two
/// solids whose touching faces were merged by the reader, wound either way). Their edges join
/// four triangles, so no piece would close; without them the two solids' sides join across those
/// edges into one closed surface. They are removed, and `pieces` oriented on what is left, when
/// every triangle next to a removed one is then in a closed piece (the contact is inside matter);
/// otherwise the mesh is left as it is and false returned (orient_scene_pieces and remove_contacts
/// decide as for any overlap). `overlaps` is renumbered to the remaining triangles.
bool remove_shared_contact_faces(TriangleMesh& mesh, std::vector<Overlap>& overlaps, ScenePieces& pieces,
                                 ContactReport& out);

/// `overlaps`: pairs of triangles that overlap with positive area in one plane (check_no_crossing),
/// or across a gap below `resolution` (faces_across_a_gap).
/// `in_closed_piece`: per triangle, whether its piece is closed (bounds matter). Needs the front
/// sides of orient_scene_pieces (triangles clockwise seen from the front). Refuses overlaps with
/// the same front side, and back-to-back overlaps of two open pieces (two one-sided sheets, neither
/// bounding matter, would both stay in one place) (rule "crossing"); otherwise cuts each triangle along the outlines of the
/// triangles of closed pieces that cover it and removes the covered part, keeping facet ids and
/// front sides, and drops the vertices no triangle uses any more.
std::optional<Failure> remove_contacts(TriangleMesh& mesh, const std::vector<Overlap>& overlaps,
                                       const std::vector<char>& in_closed_piece, double resolution,
                                       ContactReport& out);

/// Pairs of triangles of different input faces, each strictly on one side of the other's plane
/// and every corner within `resolution` of it, whose projections overlap with positive area, not
/// back to back: faces across a gap the visibility cannot resolve (occluders.hpp:
/// visibility_margin), which remove_contacts treats as in contact (facing each other) or as the
/// same surface twice (facing the same way). Exact side tests; distances in double precision.
std::vector<Overlap> faces_across_a_gap(const TriangleMesh& mesh, double resolution);

/// Closes the gaps of the pairs of faces_across_a_gap that face each other: the corners of the
/// second triangle are moved onto the plane of the first (by less than the resolution; exactly
/// onto it for a plane normal to an axis), so that no slit narrower than the visibility resolves
/// is left between two solids in contact. Pairs facing the same way are left (refused later).
void close_gaps(TriangleMesh& mesh, const std::vector<Overlap>& across_gap);

}  // namespace panelrad::geometry::validation_detail

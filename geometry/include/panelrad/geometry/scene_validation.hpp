#pragma once
// Validation of a general scene for the radiosity equation (1) with its visibility term V(P, Q):
// any set of planar polygons, closed bodies and open one-sided surfaces alike. The convex case of
// the paper (V = 1) is proven first, by validate_closed_convex, and then taken unchanged.
#include <panelrad/geometry/validation.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace panelrad::geometry {

/// What the shape of a scene lets the solver skip.
enum class SceneShape {
  convex,   ///< one closed convex surface, proven by validate_closed_convex: V = 1 for every pair
  general,  ///< any other valid scene: V(P, Q) is computed (occluders.hpp)
};
const char* to_string(SceneShape shape);  ///< "convex" | "general"

/// Two input faces in contact (validate_scene): coincident, with opposite front sides; the area
/// removed from each (by all its contacts) is the part inside solid matter.
struct SceneContact {
  Index face_a = 0, face_b = 0;         ///< input faces (facet ids), face_a < face_b
  double removed_a = 0, removed_b = 0;  ///< area removed from face_a, face_b
};

/// Outcome of validate_scene().
struct SceneValidationReport {
  bool valid = false;
  SceneShape shape = SceneShape::general;
  std::string rule;     ///< broken rule when invalid: "structure", "non-empty", "finite",
                        ///< "non-degenerate", "crossing" (two faces whose interiors meet),
                        ///< (or overlap in one plane with the same front side), "orientable" (a
                        ///< piece that has no consistent orientation); empty when valid
  std::string message;  ///< one line: the rule, where (faces with their indices and a point), and
                        ///< what to do about it
  std::vector<std::string> notes;  ///< what was decided: why the convex path does not apply, each
                                   ///< piece's front side and faces flipped to it
  ValidationReport convex_report;  ///< validate_closed_convex's report (its rule says why a valid
                                   ///< general scene is not convex)
  std::size_t pieces = 0;          ///< connected pieces (triangles joined across edges they share)
  std::size_t closed_pieces = 0;   ///< of which closed (every edge in two of its triangles)
  std::size_t pieces_against_file = 0;  ///< closed pieces whose front side is the back side of the
                                        ///< file's winding (the rule below overrode it)
  std::size_t t_junctions_split = 0;    ///< vertices inserted into edges they lay inside
  std::vector<SceneContact> contacts;   ///< pairs of input faces in contact
  double contact_area_removed = 0;      ///< area removed in all from faces in contact
  std::size_t flipped_faces = 0;   ///< triangles re-oriented relative to the input: on the convex
                                   ///< path validate_closed_convex's count; on the general path the
                                   ///< triangles flipped to agree with most of their piece's area
                                   ///< (the storage convention below is not counted)
  /// No light leaves the scene: every closed piece inside no other is an enclosure and every open
  /// piece lies inside one of them, so every ray from a front side ends on a face (front or back).
  /// True on the convex path.
  bool enclosed = false;
  /// Every ray from a front side ends on a front side: enclosed, and no part of an open piece is
  /// left once the faces in contact were removed (its back side would take light that nothing
  /// reflects or emits). Faces in contact do not open a scene: a box standing on the floor leaves
  /// no hole, its bottom and the floor under it are both gone. Then the visible form factors at
  /// every point sum to 1 and the energy balance emitted = absorbed holds. True on the convex path.
  bool closed = false;
};

/// Validates `mesh` as a scene and orients it.
///
/// 1. Convex path: validate_closed_convex on a copy. When it succeeds the mesh becomes exactly its
///    result (outward, re-triangulated or accepted within rounding as it decides) and the shape is
///    convex: today's path, bit for bit.
/// 2. Otherwise, when the convex check failed for the shape only (its rules "closed", "manifold",
///    "connected", "convex", or a flat surface that encloses no volume), the general rules, checked
///    with CGAL exact predicates (filtered):
///    - well formed, non-empty, finite, no zero-area triangle (as the convex path);
///    - T-junctions: a vertex lying strictly inside an edge of one triangle only is inserted into
///      that edge, so that a surface that closes geometrically is closed (noted); when the result
///      is one closed convex surface, the convex path takes it;
///    - no two faces cross: their intersection contains no point interior to both (a transversal
///      cut). Faces may touch along edges or at points, shared or not (a block standing on an
///      uncut floor);
///    - every connected piece (triangles joined across edges that exactly two triangles share) is
///      orientable; its triangles are made consistent with the orientation of most of its area.
///    Front sides (the side that emits, reflects and sees: the paper's inner normal n), by nesting
///    of the closed pieces (ray parity, exact predicates):
///    - an open piece: the side from which the input polygons run counter-clockwise (OBJ/OFF);
///    - a closed piece: as the file winds it (the side most of its area runs counter-clockwise
///      from), unless physics forbids it. A closed piece directly in the air of an enclosure or a
///      cavity is an object (front outward), directly in an object's solid a cavity (front
///      inward), so each tree of the nesting has two readings from its outermost piece: a room
///      (enclosure) or a solid (object). Kept: the one with fewer pieces against the file's
///      winding, a tie going to the room. An open piece lies in air: inside closed pieces, in the
///      innermost one's (an enclosure or a cavity); inside none, around every top-level closed
///      piece it lies outside of (each an object); where that asks for one reading, it is taken.
///      A closed piece alone in the scene (others, if any, on its surface) is an enclosure.
///      Separate top-level closed pieces do not constrain each other (docs/scenes-and-visibility.md).
///    Notes name each piece, what it is, whether as the file winds it, and the rule that decided
///    (for a piece against the file, the physical rule that forced it).
///    - faces in contact: two faces overlapping in one plane with opposite front sides (a box
///      standing on a floor, two boxes face to face) are cut along the contact outline, and the
///      part of each that lies against a face of a closed piece (so inside solid matter) is
///      removed; notes and `contacts` say which faces touched and how much area was removed.
///      Overlaps with the same front side (a face given twice, z-fighting) are refused as
///      "crossing".
/// On success every triangle is stored clockwise seen from its front side, i.e. its geometric normal
/// (b - a) x (c - a) points to the back and the inner normal n is its negative: the convention of
/// the convex path, where triangles run counter-clockwise seen from outside.
SceneValidationReport validate_scene(TriangleMesh& mesh);

/// A mesh that passed validate_scene, oriented as it decided (the storage convention above), with
/// its shape. Only validate_mesh() and try_validate() make one, so whatever holds a ValidatedMesh (a
/// Scene) knows its visibility policy: V = 1 only for a proven convex surface. Validating is not
/// idempotent for general scenes (the stored triangles run clockwise seen from the front, the
/// input's counter-clockwise), which is why the validated state is a type and not a flag.
class ValidatedMesh {
 public:
  const TriangleMesh& mesh() const { return mesh_; }
  SceneShape shape() const { return shape_; }
  /// SceneValidationReport::closed: every ray from a front side ends on a front side.
  bool closed() const { return closed_; }
  /// SceneValidationReport::enclosed: no light leaves the scene (it may end on a back side).
  bool enclosed() const { return enclosed_; }
  /// The mesh, leaving this object empty (for the Scene that takes it over).
  TriangleMesh take_mesh() && { return std::move(mesh_); }

 private:
  ValidatedMesh(TriangleMesh mesh, const SceneValidationReport& report)
      : mesh_(std::move(mesh)), shape_(report.shape), closed_(report.closed), enclosed_(report.enclosed) {}
  friend std::optional<ValidatedMesh> try_validate(TriangleMesh mesh, SceneValidationReport& report);

  TriangleMesh mesh_;
  SceneShape shape_;
  bool closed_, enclosed_;
};

/// validate_scene on a mesh as read (input convention: open faces counter-clockwise seen from
/// their front); the report in `report`, and the validated mesh, or nullopt when invalid.
std::optional<ValidatedMesh> try_validate(TriangleMesh mesh, SceneValidationReport& report);
/// As try_validate, throwing MeshError ("<source>: invalid scene: <the report's message>") when
/// invalid; the validation's notes, each prefixed by the mesh's source, are appended to `notes`.
ValidatedMesh validate_mesh(TriangleMesh mesh, std::vector<std::string>* notes = nullptr);

/// Reads ("builtin:NAME" or an OFF/OBJ file, as load_closed_convex) and validates (validate_mesh());
/// notes (reader's and validation's) are appended to `notes` when given.
ValidatedMesh load_scene_mesh(const std::string& path_or_builtin, std::vector<std::string>* notes = nullptr);

}  // namespace panelrad::geometry

#pragma once
// Validation of a general scene for the radiosity equation (1) with its visibility term V(P, Q):
// any set of planar polygons, closed bodies and open one-sided surfaces alike. The convex case of
// the paper (V = 1) is proven first, by validate_closed_convex, and then taken unchanged.
#include <panelrad/geometry/validation.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace panelrad::geometry {

/// What the shape of a scene lets the solver skip.
enum class SceneShape {
  convex,   ///< one closed convex surface, proven by validate_closed_convex: V = 1 for every pair
  general,  ///< any other valid scene: V(P, Q) is computed (occluders.hpp)
};
const char* to_string(SceneShape shape);  ///< "convex" | "general"

/// Outcome of validate_scene().
struct SceneValidationReport {
  bool valid = false;
  SceneShape shape = SceneShape::general;
  std::string rule;     ///< broken rule when invalid: "structure", "non-empty", "finite",
                        ///< "non-degenerate", "crossing" (two faces whose interiors meet),
                        ///< "orientable" (a piece that has no consistent orientation); empty when valid
  std::string message;  ///< one line: the rule, where (faces with their indices and a point), and
                        ///< what to do about it
  std::vector<std::string> notes;  ///< what was decided: why the convex path does not apply, each
                                   ///< piece's front side and faces flipped to it
  ValidationReport convex_report;  ///< validate_closed_convex's report (its rule says why a valid
                                   ///< general scene is not convex)
  std::size_t pieces = 0;          ///< connected pieces (triangles joined across edges they share)
  std::size_t closed_pieces = 0;   ///< of which closed (every edge in two of its triangles)
  std::size_t flipped_faces = 0;   ///< triangles re-oriented relative to the input: on the convex
                                   ///< path validate_closed_convex's count; on the general path the
                                   ///< triangles flipped to agree with most of their piece's area
                                   ///< (the storage convention below is not counted)
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
///    - no two faces cross: their intersection contains no point interior to both (a transversal
///      cut, or coplanar overlap of positive area). Faces may touch along edges or at points,
///      shared or not (a block standing on an uncut floor);
///    - every connected piece (triangles joined across edges that exactly two triangles share) is
///      orientable; its triangles are made consistent with the orientation of most of its area.
///    Front sides (the side that emits, reflects and sees: the paper's inner normal n):
///    - an open piece: the side from which the input polygons run counter-clockwise (OBJ/OFF);
///    - a closed piece inside no other closed piece: an enclosure, seen from inside;
///    - a closed piece inside another: an object, seen from outside.
///    Notes name each decision.
/// On success every triangle is stored clockwise seen from its front side, i.e. its geometric normal
/// (b - a) x (c - a) points to the back and the inner normal n is its negative: the convention of
/// the convex path, where triangles run counter-clockwise seen from outside.
SceneValidationReport validate_scene(TriangleMesh& mesh);

/// Reads ("builtin:NAME" or an OFF/OBJ file, as load_closed_convex) and validates with
/// validate_scene; throws MeshError with the report's message when invalid. `shape` receives the
/// shape; notes (reader's and validation's) are appended to `notes` when given.
TriangleMesh load_scene_mesh(const std::string& path_or_builtin, SceneShape& shape,
                             std::vector<std::string>* notes = nullptr);

}  // namespace panelrad::geometry

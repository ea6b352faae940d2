// Validation of a general scene (scene_validation.hpp): the convex path of the paper first
// (validate_closed_convex, V = 1), taken unchanged when it succeeds; otherwise, when it failed for
// the shape only, the general rules in order: well formed, finite, non-degenerate (as the convex
// path), no two faces crossing (face_crossing.cpp), every piece orientable, and the front sides
// (piece_orientation.cpp).
#include "validation_internal.hpp"

#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/mesh_io.hpp>
#include <panelrad/geometry/scene_validation.hpp>

#include <utility>

namespace panelrad::geometry {

using namespace validation_detail;

namespace {

/// The convex path refused the mesh for its shape only: not closed, not a 2-manifold, not one
/// piece, not convex, or flat (a single planar polygon encloses no volume but is a valid scene).
bool refused_for_shape(const ValidationReport& convex) {
  if (convex.rule == "closed" || convex.rule == "manifold" || convex.rule == "connected" || convex.rule == "convex")
    return true;
  return convex.rule == "non-degenerate" && convex.message.find("all vertices are coplanar") != std::string::npos;
}

SceneValidationReport rejected(SceneValidationReport report, const Failure& failure) {
  report.valid = false;
  report.rule = failure.rule;
  report.message = failure.rule + ": " + failure.message;
  return report;
}

}  // namespace

const char* to_string(SceneShape shape) {
  switch (shape) {
    case SceneShape::convex: return "convex";
    case SceneShape::general: return "general";
  }
  return "general";
}

SceneValidationReport validate_scene(TriangleMesh& mesh) {
  SceneValidationReport report;
  // 1. The convex path, on a copy: on success the mesh becomes its result, bit for bit.
  TriangleMesh convex = mesh;
  report.convex_report = validate_closed_convex(convex);
  const ValidationReport& cr = report.convex_report;
  if (cr.valid) {
    mesh = std::move(convex);
    report.valid = true;
    report.shape = SceneShape::convex;
    report.notes = cr.notes;
    report.pieces = 1;
    report.closed_pieces = 1;
    report.flipped_faces = cr.flipped_faces;
    return report;
  }
  if (!refused_for_shape(cr)) {
    report.rule = cr.rule;
    report.message = cr.message;
    return report;
  }

  // 2. The general rules. Well formed, non-empty, finite and no zero-area triangle passed on the
  // convex path already (it checks them before any rule of shape); checked again here so that
  // this path does not depend on that order.
  if (auto f = check_well_formed(mesh)) return rejected(std::move(report), *f);
  const std::vector<Point> pts = exact_points(mesh);
  if (auto f = check_measurable(mesh, pts)) return rejected(std::move(report), *f);
  if (auto f = check_no_crossing(mesh, pts)) return rejected(std::move(report), *f);
  const std::vector<Tri> input_triangles = mesh.triangles;
  ScenePieces pieces;
  if (auto f = orient_scene_pieces(mesh, pieces)) {
    mesh.triangles = input_triangles;  // unchanged when refused
    return rejected(std::move(report), *f);
  }
  report.valid = true;
  report.shape = SceneShape::general;
  report.pieces = pieces.pieces;
  report.closed_pieces = pieces.closed_pieces;
  report.flipped_faces = pieces.flipped;
  report.notes.push_back("not one closed convex surface (" + cr.message + "): the visibility V(P, Q) is computed");
  for (std::string& n : pieces.notes) report.notes.push_back(std::move(n));
  return report;
}

TriangleMesh load_scene_mesh(const std::string& path_or_builtin, SceneShape& shape, std::vector<std::string>* notes) {
  std::vector<std::string> local;
  TriangleMesh mesh = path_or_builtin.rfind("builtin:", 0) == 0 ? make_builtin(path_or_builtin.substr(8))
                                                                 : read_mesh(path_or_builtin, &local);
  const SceneValidationReport report = validate_scene(mesh);
  if (!report.valid) throw MeshError(mesh.source + ": invalid scene: " + report.message);
  shape = report.shape;
  if (notes) {
    notes->insert(notes->end(), local.begin(), local.end());
    for (const std::string& n : report.notes) notes->push_back(mesh.source + ": " + n);
  }
  return mesh;
}

}  // namespace panelrad::geometry

// Validation of a general scene (scene_validation.hpp): the convex path of the paper first
// (validate_closed_convex, V = 1), taken unchanged when it succeeds; otherwise, when it failed for
// the shape only, the general rules in order: well formed, finite, non-degenerate (as the convex
// path), T-junctions split (t_junctions.cpp), no two faces crossing (face_crossing.cpp), every piece
// orientable and the front sides (piece_orientation.cpp), faces in contact cut and their covered
// parts removed (contact_removal.cpp).
#include "contact_removal.hpp"
#include "t_junctions.hpp"
#include "validation_internal.hpp"

#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/mesh_io.hpp>
#include <panelrad/geometry/occluders.hpp>
#include <panelrad/geometry/scene_validation.hpp>

#include <algorithm>
#include <set>
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

/// The scene accepted on the convex path: report.convex_report is valid, its notes follow the
/// report's own.
SceneValidationReport accepted_convex(SceneValidationReport report) {
  const ValidationReport& cr = report.convex_report;
  report.valid = true;
  report.shape = SceneShape::convex;
  report.notes.insert(report.notes.end(), cr.notes.begin(), cr.notes.end());
  report.pieces = 1;
  report.closed_pieces = 1;
  report.flipped_faces = cr.flipped_faces;
  report.enclosed = report.closed = true;  // one closed convex surface seen from inside
  return report;
}

/// The pairs of faces_across_a_gap that `overlaps` does not list already (a pair found within the
/// rounding, touching, is not a gap as well).
std::vector<Overlap> gaps_not_in(const TriangleMesh& mesh, const ContactTolerance& tolerance,
                                 const std::vector<Overlap>& overlaps) {
  std::vector<Overlap> gaps = faces_across_a_gap(mesh, tolerance);
  std::set<std::pair<Index, Index>> known;
  for (const Overlap& o : overlaps) known.emplace(o.i, o.j);
  std::erase_if(gaps, [&](const Overlap& o) { return known.count({o.i, o.j}) > 0; });
  return gaps;
}

/// The faces in contact, one note per pair up to kMaxContactNotes, then one summary.
constexpr std::size_t kMaxContactNotes = 8;

void note_contacts(const TriangleMesh& mesh, SceneValidationReport& report) {
  const Describe d{mesh};
  const auto& c = report.contacts;
  if (c.empty()) return;
  std::size_t listed = 0;
  for (const SceneContact& t : c) {
    if (listed++ == kMaxContactNotes) break;
    report.notes.push_back(d.faces(t.face_a, t.face_b) +
                           " touch with their front sides against each other: the parts inside solid matter are "
                           "not surfaces of the scene and were removed (area " + num(t.removed_a) + " of face " +
                           std::to_string(t.face_a) + ", " + num(t.removed_b) + " of face " +
                           std::to_string(t.face_b) + ", from all their contacts)");
  }
  if (c.size() > kMaxContactNotes)
    report.notes.push_back("and " + std::to_string(c.size() - kMaxContactNotes) + " more pairs of faces in contact");
  report.notes.push_back("contacts: " + std::to_string(c.size()) + (c.size() == 1 ? " pair" : " pairs") +
                         " of faces touch; area removed in all " + num(report.contact_area_removed));
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
    return accepted_convex(std::move(report));
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
  if (auto f = check_measurable(mesh, exact_points(mesh))) return rejected(std::move(report), *f);
  const TriangleMesh input = mesh;  // unchanged when refused
  // Corners closer than the visibility's resolution are one corner (four times the shadow tests'
  // margin: no slit narrower than it is seen).
  const double resolution = 4 * visibility_margin(mesh);
  const Sz corners_joined = join_close_corners(mesh, resolution);
  if (corners_joined > 0)
    report.notes.push_back(std::to_string(corners_joined) + (corners_joined == 1 ? " corner lay" : " corners lay") +
                           " closer than " +
                           sci(resolution) + " to another (below the visibility's resolution) and joined it");
  if (mesh.triangles.empty())
    return rejected(std::move(report), Failure{"non-degenerate", "every triangle is thinner than the visibility's "
                                                                 "resolution (" + sci(resolution) + ")"});
  // An edge that ends on the middle of another edge joins nothing by vertex index: the vertex is
  // inserted into that edge, so that a surface that closes geometrically is closed. A closed
  // convex surface may then appear: the convex path again.
  const ContactTolerance tolerance(mesh, resolution);
  const double capped = largest_tolerance(tolerance, diameter(mesh));
  const double t_tolerance = t_junction_tolerance(tolerance, diameter(mesh));
  report.t_junctions_split = split_t_junctions(mesh, nullptr, capped);
  if (t_tolerance > capped) {
    // Printed too coarsely for the contact rules: a corner within the printing's reach of an open
    // edge is still that edge's, said in a note with what more digits would settle.
    const Sz coarse = split_t_junctions(mesh, nullptr, t_tolerance);
    report.t_junctions_split += coarse;
    if (coarse > 0)
      report.notes.push_back(std::to_string(coarse) + (coarse == 1 ? " vertex lay" : " vertices lay") + " within " +
                             sci(t_tolerance) + " of an open edge of another face, which the rounding of the "
                             "coordinates as written can account for (more than 1e-4 of the scene's size): "
                             "taken as on it; if they were meant apart, write the coordinates with more digits");
  }
  if (report.t_junctions_split > 0) {
    const std::string split_note = std::to_string(report.t_junctions_split) +
                                   (report.t_junctions_split == 1 ? " vertex lay" : " vertices lay") +
                                   " inside an edge of another triangle (a T-junction); the edges were split there";
    report.notes.push_back(split_note);
    TriangleMesh split = mesh;
    ValidationReport again = validate_closed_convex(split);
    if (again.valid) {
      mesh = std::move(split);
      report.convex_report = std::move(again);
      return accepted_convex(std::move(report));
    }
  }
  // Faces written rounded stand for planes that their corners as written miss by up to the
  // rounding: the corners move onto them once, for the whole scene, so that the contacts below
  // are decided on faces that are flat and meet where they were meant to.
  if (const Sz snapped = snap_to_common_planes(mesh, tolerance); snapped > 0) {
    join_close_corners(mesh, resolution);
    report.notes.push_back(std::to_string(snapped) + (snapped == 1 ? " corner was" : " corners were") +
                           " moved onto the planes of their faces and of the faces those touch, which the "
                           "coordinates as written miss by their rounding");
  }
  // Faces facing each other closer than the visibility can resolve are in contact for it: the
  // resolution is four times the shadow tests' margin, so that any gap beyond it is seen. Faces
  // whose coordinates were written rounded are the contact they stand for within that rounding
  // (ContactTolerance, written_rounding.cpp).
  std::vector<Overlap> overlaps;
  if (auto f = check_no_crossing(mesh, exact_points(mesh), &overlaps, &tolerance)) {
    mesh = input;
    return rejected(std::move(report), *f);
  }
  {
    // One polygon given twice is one surface twice, whatever the rounding of its corners.
    std::set<std::pair<Index, Index>> known;
    for (const Overlap& o : overlaps) known.emplace(o.i, o.j);
    for (const Overlap& o : copies_of_one_polygon(mesh, resolution))
      if (known.emplace(o.i, o.j).second) overlaps.push_back(o);
  }
  ScenePieces pieces;
  ContactReport contacts;
  {
    // Solids sharing the corners of their touching faces join into closed pieces across their
    // contacts, also where those lie a gap within the tolerance apart (a face bent by rounding).
    std::vector<Overlap> candidates = overlaps;
    const std::vector<Overlap> gaps = gaps_not_in(mesh, tolerance, overlaps);
    candidates.insert(candidates.end(), gaps.begin(), gaps.end());
    if (merge_contacts_into_closed_pieces(mesh, candidates, pieces, tolerance, contacts))
      overlaps = std::move(candidates);  // found again on the cut mesh
    else if (auto f = orient_scene_pieces(mesh, pieces)) {
      mesh = input;
      return rejected(std::move(report), *f);
    }
  }
  // The input faces of open pieces: whether any part of them is left once the contacts are removed.
  std::vector<char> open_facet(at(mesh.num_facets), 0);
  for (Sz t = 0; t < mesh.triangles.size(); ++t)
    if (!pieces.in_closed_piece[t]) open_facet[at(mesh.facet_of_triangle[t])] = 1;
  std::vector<Overlap> to_close = gaps_not_in(mesh, tolerance, overlaps);
  overlaps.insert(overlaps.end(), to_close.begin(), to_close.end());
  for (const Overlap& o : overlaps)
    if (o.within_rounding) to_close.push_back(o);
  close_gaps(mesh, to_close);
  if (auto f = remove_contacts(mesh, overlaps, pieces.in_closed_piece, resolution,
                                largest_tolerance(tolerance, diameter(mesh)), contacts)) {
    mesh = input;
    return rejected(std::move(report), *f);
  }
  if (!contacts.pairs.empty()) {
    // The corners of the cut, rounded once, an ulp from an old corner are that corner.
    join_close_corners(mesh, resolution);
    // What the contacts left: something to see, and new corners (rounded once) that still span
    // triangles of positive area.
    std::optional<Failure> f;
    if (mesh.triangles.empty())
      f = Failure{"non-empty", "every face lies against a face of a solid, so nothing of the scene is left to see"};
    else
      f = check_measurable(mesh, exact_points(mesh));
    if (f) {
      mesh = input;
      f->message += " (after the parts of faces in contact were removed)";
      return rejected(std::move(report), *f);
    }
  }
  report.valid = true;
  report.shape = SceneShape::general;
  report.pieces = pieces.pieces;
  report.closed_pieces = pieces.closed_pieces;
  report.flipped_faces = pieces.flipped;
  report.pieces_against_file = pieces.against_file;
  report.enclosed = pieces.enclosed;
  report.closed = pieces.enclosed && std::none_of(mesh.facet_of_triangle.begin(), mesh.facet_of_triangle.end(),
                                                  [&](Index f) { return open_facet[at(f)] != 0; });
  report.notes.insert(report.notes.begin(),
                      "not one closed convex surface (" + cr.message + "): the visibility V(P, Q) is computed");
  for (std::string& n : pieces.notes) report.notes.push_back(std::move(n));
  report.contact_area_removed = contacts.area_removed();
  for (const ContactReport::Touch& t : contacts.touching())
    report.contacts.push_back({t.face_a, t.face_b, t.removed_a, t.removed_b});
  note_contacts(mesh, report);
  {
    const Describe d{mesh};
    Sz listed = 0;
    for (const auto& [a, b] : contacts.two_sided)
      if (listed++ < kMaxContactNotes)
        report.notes.push_back(d.faces(a, b) + " lie back to back in one plane, neither part of a closed surface: a "
                                               "two-sided sheet, each face seen from its own front side");
    if (contacts.two_sided.size() > kMaxContactNotes)
      report.notes.push_back("and " + std::to_string(contacts.two_sided.size() - kMaxContactNotes) +
                             " more pairs of faces back to back (two-sided sheets)");
  }
  if (contacts.across_gap > 0)
    report.notes.push_back(std::to_string(contacts.across_gap) +
                           " pairs of triangles face each other across a gap below the visibility's resolution (" +
                           sci(resolution) + ", four times its margin): taken as in contact, the gap closed by "
                           "moving corners onto the other face's plane");
  return report;
}

std::optional<ValidatedMesh> try_validate(TriangleMesh mesh, SceneValidationReport& report) {
  report = validate_scene(mesh);
  if (!report.valid) return std::nullopt;
  return ValidatedMesh(std::move(mesh), report);
}

ValidatedMesh validate_mesh(TriangleMesh mesh, std::vector<std::string>* notes) {
  SceneValidationReport report;
  const std::string source = mesh.source;
  std::optional<ValidatedMesh> v = try_validate(std::move(mesh), report);
  if (!v) throw MeshError(source + ": invalid scene: " + report.message);
  if (notes)
    for (const std::string& n : report.notes) notes->push_back(source + ": " + n);
  return std::move(*v);
}

ValidatedMesh load_scene_mesh(const std::string& path_or_builtin, std::vector<std::string>* notes) {
  std::vector<std::string> local;
  TriangleMesh mesh = path_or_builtin.rfind("builtin:", 0) == 0 ? make_builtin(path_or_builtin.substr(8))
                                                                 : read_mesh(path_or_builtin, &local);
  std::vector<std::string> validation;
  ValidatedMesh v = validate_mesh(std::move(mesh), &validation);
  if (notes) {
    notes->insert(notes->end(), local.begin(), local.end());
    notes->insert(notes->end(), validation.begin(), validation.end());
  }
  return v;
}

}  // namespace panelrad::geometry

// Exact validation of a closed convex polyhedral surface: the rules of validate_closed_convex
// (validation.hpp), applied in their order, each in its own source (validation_internal.hpp lists
// them).
//
// Every geometric decision is a CGAL exact predicate (Epick: filtered double arithmetic with an
// exact fallback), never a tolerance: collinear() for zero-area triangles, orientation() for the
// side of a plane. Distances are computed in double only to *report* the size of a convexity
// violation, never to decide one. A violation that is not exactly 0 but within what the rounding
// of the input coordinates can produce (input_rounding.hpp, bound(t, v)) is accepted with a note.
#include "validation_internal.hpp"

#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/mesh_io.hpp>
#include <panelrad/geometry/validation.hpp>

#include <algorithm>
#include <utility>

namespace panelrad::geometry {

using namespace validation_detail;

namespace {

ValidationReport rejected(ValidationReport report, const Failure& failure) {
  report.valid = false;
  report.rule = failure.rule;
  report.message = failure.rule + ": " + failure.message;
  return report;
}

/// Rule 3 again, globally: the surface must enclose a volume; then orient it outward.
std::optional<Failure> orient_outward(TriangleMesh& mesh, const std::array<Index, 4>& tetra) {
  const int sign = volume_sign(mesh, mesh.vertices[at(tetra[0])]);
  if (sign == 0) return Failure{"non-degenerate", "the surface encloses zero volume"};
  if (sign < 0)
    for (Tri& tr : mesh.triangles) std::swap(tr[1], tr[2]);
  return std::nullopt;
}

/// The faces re-oriented, against the triangles as they were input.
void note_flipped_faces(const TriangleMesh& mesh, const std::vector<Tri>& input_triangles,
                        ValidationReport& report) {
  const Sz nt = mesh.triangles.size();
  std::vector<char> flipped_triangle(nt, 0);
  for (Sz t = 0; t < nt; ++t) flipped_triangle[t] = mesh.triangles[t] != input_triangles[t];
  const Sz flipped = static_cast<Sz>(std::count(flipped_triangle.begin(), flipped_triangle.end(), 1));
  report.flipped_faces = flipped;
  if (flipped == 0) return;  // stored as input: counter-clockwise from outside
  // Stored counter-clockwise from outside, the front side (inner normal n) inward: the file put
  // the front inside where it ran its triangles the other way (most of them decide).
  const bool file_front_inward = 2 * flipped > nt;
  const std::string front = "the closed convex surface is " + front_side_words(FrontSide::enclosure, !file_front_inward);
  if (flipped == nt) {
    report.notes.push_back(front);
    return;
  }
  // The minority: triangles that ran against most of the others, and their input faces.
  std::vector<char> facet_against(at(mesh.num_facets), 0);
  Sz against = 0;
  for (Sz t = 0; t < nt; ++t)
    if (static_cast<bool>(flipped_triangle[t]) != file_front_inward) {
      ++against;
      facet_against[at(mesh.facet_of_triangle[t])] = 1;
    }
  report.notes.push_back("re-oriented " + std::to_string(against) + " of " + std::to_string(nt) + " triangles (" +
                         std::to_string(std::count(facet_against.begin(), facet_against.end(), 1)) +
                         " input faces) to agree with the others; " + front);
}

/// Rule 6: convexity, exactly; when the mesh is not exactly convex, steps 1-3 of validation.hpp.
ValidationReport check_convexity(TriangleMesh& mesh, const std::vector<Point>& pts, const Adjacency& adj,
                                 const std::array<Index, 4>& tetra, ValidationReport report) {
  const Geometry g{pts, tetra};
  const Vec3 inside = interior_point(mesh, pts, tetra);
  const std::vector<Index> bad = unsupported_triangles(mesh, adj, g, inside);
  if (!bad.empty()) {
    const double diam = diameter(mesh);
    // 1. Rounded polygon faces that are not exactly planar: the exact hull's triangulation.
    const std::optional<std::string> hull_reason = retriangulate_convex_from_hull(mesh, pts, bad, g, inside, diam, report);
    if (!hull_reason) return report;
    // 2. Convex within the rounding of the input; 3. otherwise refused.
    if (auto f = accept_within_rounding(mesh, bad, g, inside, diam, *hull_reason, report))
      return rejected(std::move(report), *f);
  }
  report.valid = true;
  return report;
}

}  // namespace

ValidationReport validate_closed_convex(TriangleMesh& mesh) {
  ValidationReport report;
  // Structure, rule 1 (non-empty), rule 2 (finite coordinates).
  if (auto f = check_well_formed(mesh)) return rejected(std::move(report), *f);
  const std::vector<Point> pts = exact_points(mesh);
  // Rule 3 (no zero-area triangle), rule 2 continued (within the double range).
  if (auto f = check_measurable(mesh, pts)) return rejected(std::move(report), *f);
  // Rule 4: closed 2-manifold.
  Adjacency adj;
  if (auto f = check_closed_manifold(mesh, adj)) return rejected(std::move(report), *f);
  // Rule 5: one connected, orientable piece; orientation made consistent by flipping.
  std::vector<signed char> flip;
  if (auto f = consistent_orientation(mesh, adj, flip)) return rejected(std::move(report), *f);
  const std::vector<Tri> input_triangles = mesh.triangles;
  for (Sz t = 0; t < mesh.triangles.size(); ++t)
    if (flip[t]) std::swap(mesh.triangles[t][1], mesh.triangles[t][2]);
  // Rule 3 again, globally: an enclosed volume, oriented outward.
  const auto tetra = spanning_tetrahedron(pts);
  if (!tetra)
    return rejected(std::move(report),
                    Failure{"non-degenerate", "all vertices are coplanar: the surface encloses no volume"});
  if (auto f = orient_outward(mesh, *tetra)) return rejected(std::move(report), *f);
  note_flipped_faces(mesh, input_triangles, report);
  // Rule 6: convexity.
  return check_convexity(mesh, pts, adj, *tetra, std::move(report));
}

TriangleMesh load_closed_convex(const std::string& path_or_builtin, std::vector<std::string>* notes) {
  std::vector<std::string> local;
  TriangleMesh mesh = path_or_builtin.rfind("builtin:", 0) == 0 ? make_builtin(path_or_builtin.substr(8))
                                                                 : read_mesh(path_or_builtin, &local);
  const ValidationReport report = validate_closed_convex(mesh);
  if (!report.valid) throw MeshError(mesh.source + ": invalid mesh: " + report.message);
  if (notes) {
    notes->insert(notes->end(), local.begin(), local.end());
    for (const std::string& n : report.notes) notes->push_back(mesh.source + ": " + n);
  }
  return mesh;
}

}  // namespace panelrad::geometry

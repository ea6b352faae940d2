#pragma once
// Exact validation of a closed convex polyhedral surface (CGAL exact predicates, no tolerances).
#include <panelrad/geometry/mesh.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace panelrad::geometry {

/// Outcome of validate_closed_convex().
struct ValidationReport {
  bool valid = false;
  std::string rule;     ///< broken rule when invalid, checked in this order: "structure" (bad
                        ///< indices in a mesh built in code), "non-empty", "finite",
                        ///< "non-degenerate" (zero-area triangle, or no enclosed volume),
                        ///< "closed", "manifold" (edge in > 2 triangles, vertex not a single fan,
                        ///< unused or coincident vertices, not orientable), "connected", "convex";
                        ///< empty when valid
  std::string message;  ///< one line naming the rule, the first offending face or vertex
                        ///< (index and coordinates) and, for convexity, the worst violation
                        ///< relative to the mesh diameter
  std::vector<std::string> notes;           ///< warnings: faces flipped, hull re-triangulation
  std::size_t flipped_faces = 0;            ///< faces re-oriented to a consistent orientation
  bool retriangulated_from_hull = false;    ///< non-planar rounded polygons re-triangulated exactly
  double worst_convexity_violation = 0.0;   ///< max signed distance outside, / diameter (invalid)
};

/// Checks, with CGAL exact predicates: finite coordinates; no zero-area triangle; closed
/// 2-manifold; convex (every vertex on the inner side of, or on, every triangle's supporting
/// plane), hence unoccluded. On success the mesh is oriented outward (counter-clockwise from
/// outside), flipping inconsistently oriented faces (reported in notes). Polygon faces whose
/// fan triangulation is not exactly convex (rounded coordinates) are re-triangulated from the
/// exact convex hull when the hull has exactly the input's vertices and each hull triangle lies on
/// the vertices of one input face; otherwise the mesh is rejected.
/// A facet's vertex set is the union of the vertices of its triangles (facet_of_triangle).
ValidationReport validate_closed_convex(TriangleMesh& mesh);

/// Number of maximal planar facets: classes of triangles joined across shared edges whose four
/// vertices are exactly coplanar (a square split in two is one). Works on any mesh (edges not
/// shared by exactly two triangles simply join nothing).
std::size_t count_planar_facets(const TriangleMesh& mesh);

/// Reads ("builtin:NAME" -> make_builtin(NAME), else read_mesh) and validates; throws MeshError with the report's message when invalid.
/// Warnings (notes) are appended to `notes` when given.
TriangleMesh load_closed_convex(const std::string& path_or_builtin,
                                std::vector<std::string>* notes = nullptr);

}  // namespace panelrad::geometry

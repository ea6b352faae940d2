#pragma once
// Validation of a closed convex polyhedral surface: CGAL exact predicates decide every rule; a
// convexity violation that the rounding of the input coordinates explains (see InputRounding in
// input_rounding.hpp, and validate_closed_convex) is accepted with a note, anything larger is
// refused. Includes the rounding model and the planar facet count, which share that bound.
#include <panelrad/geometry/input_rounding.hpp>
#include <panelrad/geometry/mesh.hpp>
#include <panelrad/geometry/planar_facets.hpp>

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
  std::vector<std::string> notes;           ///< warnings: faces flipped, hull re-triangulation,
                                            ///< convex within the rounding of the input
  std::size_t flipped_faces = 0;            ///< faces re-oriented to a consistent orientation
  bool retriangulated_from_hull = false;    ///< non-planar rounded polygons re-triangulated exactly
  bool convex_within_rounding = false;      ///< accepted: not exactly convex, but every violation is
                                            ///< within the rounding bound of the input (see below)
  double worst_convexity_violation = 0.0;   ///< largest distance of a vertex outside a triangle's
                                            ///< plane, / diameter: set when refused as non-convex
                                            ///< (never 0 then) and when convex_within_rounding
  double worst_rounding_ratio = 0.0;        ///< convex_within_rounding: max over the violations of
                                            ///< distance / its rounding bound (<= 1)
};

/// Checks, with CGAL exact predicates: finite coordinates; no zero-area triangle; closed
/// 2-manifold; convex (every vertex on the inner side of, or on, every triangle's supporting
/// plane), hence unoccluded. On success the mesh is oriented outward (counter-clockwise from
/// outside), flipping inconsistently oriented faces (reported in notes).
///
/// When the mesh is not exactly convex:
/// 1. Polygon faces whose fan triangulation is not exactly convex are re-triangulated from the
///    exact convex hull when the hull has exactly the input's vertices and each hull triangle lies
///    on the vertices of one input face (a facet's vertex set is the union of the vertices of its
///    triangles, facet_of_triangle); the result is then proven convex exactly.
/// 2. Otherwise the mesh is accepted as convex within the rounding of its input
///    (convex_within_rounding, with a note naming the worst vertex, triangle and distance relative
///    to the diameter) when every vertex v strictly outside the plane of a triangle (a, b, c) lies
///    outside it by at most
///        bound(t, v) = 1.25 eta |n|_1 (1 + |l_a| + |l_b| + |l_c|),
///    n the unit normal, l the barycentric coordinates of v's projection on the plane, eta from
///    input_rounding(); every violation is at most kMaxRoundingViolation of the diameter; and the
///    surface winds once, strictly, around an interior point.
///    Derivation: let the true points p* = p - e, |e|_inf <= eta, form a convex mesh, so v* is on
///    the inner side of the plane of (a*, b*, c*). The signed distance phi(x) = (x - a) . n to the
///    rounded plane is affine; writing v* = sum l*_i p*_i + h n* with h <= 0 and n . n* > 0 gives
///    phi(v*) <= sum l*_i phi(p*_i) = -sum l*_i e_i . n <= eta |n|_1 sum |l*_i|, and
///    phi(v) = phi(v*) + e_v . n <= eta |n|_1 (1 + sum |l*_i|). The l computed from rounded points
///    differ from l* at first order in eta / h_t (h_t the triangle's smallest height); the bound is
///    used only where sqrt(3) eta <= h_t / 16, and the 25% covers that difference.
///    What V = 1 (every pair of surface points sees each other, section 2) can then be wrong by:
///    with tau the largest violation, every triangle's plane has the whole mesh within tau on its
///    outer side, so the surface departs from the convex hull of its vertices by a layer at most
///    tau thick. A segment PQ leaves the solid only through a triangle t' it crosses at a point X,
///    and then Q (or P) lies at most tau outside the plane of t': |XQ| sin(gamma) <= tau, gamma the
///    angle of PQ with t'. The points hidden from P are thus grazing strips behind ridges of height
///    <= tau; seen from a point P at distance rho from the off-plane vertices their configuration
///    factor (1/pi) Int cos(theta_P) d omega is of order tau / rho (a strip of depth tau / sin gamma
///    seen at incidence sin gamma from distance rho). The note states tau / diameter and this
///    estimate at rho = 1% of the diameter.
/// 3. Otherwise the mesh is refused ("convex"), the message naming the first non-convex triangle,
///    its farthest vertex outside and the worst violation relative to the diameter: distances
///    from an accurate determinant (exact rational arithmetic when double precision cannot
///    resolve it), so a refusal never reports a violation of 0; then why 1 and 2 do not apply.
ValidationReport validate_closed_convex(TriangleMesh& mesh);

/// Reads ("builtin:NAME" -> make_builtin(NAME), else read_mesh) and validates; throws MeshError with the report's message when invalid.
/// Warnings (notes) are appended to `notes` when given.
TriangleMesh load_closed_convex(const std::string& path_or_builtin,
                                std::vector<std::string>* notes = nullptr);

}  // namespace panelrad::geometry

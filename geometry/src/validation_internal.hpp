#pragma once
// Shared by the sources that validate a closed convex surface, each one rule of
// validate_closed_convex (validation.hpp), which validation.cpp applies in order:
//   mesh_degeneracy.cpp         structure, non-empty, finite, non-degenerate (area, enclosed volume)
//   mesh_topology.cpp           closed, manifold, connected, orientable
//   exact_convexity.cpp         convexity by exact predicates (O(F) proof, O(V F) side tests)
//   plane_distance.cpp          the size of a violation: exact plane distances, the mesh diameter
//   hull_retriangulation.cpp    rounded polygon faces re-triangulated from the exact convex hull
//   convex_within_rounding.cpp  violations within the rounding of the input, or the refusal
//   input_rounding.cpp          the rounding model and its bound(t, v)
//   validation_messages.cpp     how a vertex, a triangle and a length are named in messages
// and the rules of validate_scene (scene_validation.hpp), which scene_validation.cpp applies after
// the convex path:
//   face_crossing.cpp           no two faces cross (interiors meet)
//   piece_orientation.cpp       connected pieces, orientable, front sides (enclosure, object, open)
// Every geometric decision is a CGAL exact predicate (Epick: filtered double arithmetic with an
// exact fallback), never a tolerance. Private to geometry/src: CGAL stays out of the installed
// headers.
#include <panelrad/geometry/mesh.hpp>
#include <panelrad/geometry/validation.hpp>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <Eigen/Geometry>

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace panelrad::geometry::validation_detail {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Tri = std::array<Index, 3>;
using Sz = std::size_t;

constexpr Index kNone = -1;

inline Sz at(Index i) { return static_cast<Sz>(i); }

// --- messages (validation_messages.cpp) ---------------------------------------------------------

/// Shortest round-trip decimal form of x.
std::string num(double x);
/// x with 3 significant digits in scientific notation.
std::string sci(double x);
/// "(x, y, z)", each as num.
std::string point_text(const Vec3& x);
/// A positive length relative to the diameter, never printed as 0.
std::string relative(double dist, double diam);

/// Names vertices and triangles of `mesh` with their indices and coordinates.
struct Describe {
  const TriangleMesh& mesh;
  std::string point(Index v) const;
  std::string vertex(Index v) const;
  std::string triangle(Index t) const;
  /// "input face F (line L)", the line when the mesh was read from a file.
  std::string face(Index f) const;
  /// "input faces F (line L) and G (line M)".
  std::string faces(Index f, Index g) const;
};

/// A broken rule and the message naming where.
struct Failure {
  std::string rule;
  std::string message;
};

// --- degeneracy and finiteness (mesh_degeneracy.cpp) --------------------------------------------

/// Indices and facet ids in range (a mesh built in code), at least one triangle, finite coordinates.
std::optional<Failure> check_well_formed(const TriangleMesh& mesh);
/// No zero-area triangle (exact), and every length and area within what double precision measures.
std::optional<Failure> check_measurable(const TriangleMesh& mesh, const std::vector<Point>& pts);
/// Four vertices spanning a tetrahedron (exact), or nothing when all vertices are coplanar.
std::optional<std::array<Index, 4>> spanning_tetrahedron(const std::vector<Point>& p);
/// Sign of the enclosed volume of a consistently oriented closed surface (+1: counter-clockwise
/// from outside), exact.
int volume_sign(const TriangleMesh& mesh, const Vec3& origin);

// --- topology (mesh_topology.cpp) ---------------------------------------------------------------

/// Per triangle t and slot s (edge tr[s] -> tr[s+1]): the neighbouring triangle across that edge.
struct Adjacency {
  std::vector<Index> neighbour;  // 3 * num_triangles
};

/// Closedness (every edge in exactly two triangles) and edge-manifoldness; fills the adjacency,
/// also when it fails: kNone across a boundary edge or an edge in three or more triangles.
std::optional<Failure> build_adjacency(const TriangleMesh& mesh, Adjacency& adj);
/// Closed 2-manifold: closed, every vertex used with a single fan around it, no two vertices at
/// the same point; fills the adjacency.
std::optional<Failure> check_closed_manifold(const TriangleMesh& mesh, Adjacency& adj);
/// One connected, orientable piece: flip[t] = 1 for the triangles to reverse for a consistent
/// orientation (triangle 0 kept).
std::optional<Failure> consistent_orientation(const TriangleMesh& mesh, const Adjacency& adj,
                                              std::vector<signed char>& flip);

// --- exact convexity (exact_convexity.cpp) ------------------------------------------------------

/// The vertices as exact-predicate points.
std::vector<Point> exact_points(const TriangleMesh& mesh);

struct Geometry {
  const std::vector<Point>& p;
  std::array<Index, 4> witness;  // spans a tetrahedron: not all four lie on any one plane

  CGAL::Orientation side(const Tri& t, Index v) const {
    return CGAL::orientation(p[at(t[0])], p[at(t[1])], p[at(t[2])], p[at(v)]);
  }
  /// Orientation of the first witness off the plane of t: NEGATIVE when t faces away from it.
  CGAL::Orientation facing(const Tri& t) const {
    for (Index w : witness) {
      const CGAL::Orientation o = side(t, w);
      if (o != CGAL::COPLANAR) return o;
    }
    return CGAL::COPLANAR;  // unreachable: the witnesses are not coplanar
  }
};

/// An interior point: the mean of four vertices spanning a fat tetrahedron.
Vec3 interior_point(const TriangleMesh& mesh, const std::vector<Point>& p, const std::array<Index, 4>& fallback);
/// Sound O(F) proof of convexity; false when it cannot prove it.
bool proven_convex(const TriangleMesh& mesh, const Adjacency& adj, const Geometry& g, const Vec3& inside);
/// Triangles with some vertex strictly outside their plane (exact; empty iff convex).
std::vector<Index> unsupported_triangles(const TriangleMesh& mesh, const Adjacency& adj, const Geometry& g,
                                         const Vec3& inside);
/// The surface winds once around `inside`, which is strictly on the inner side of every plane.
bool winds_once_around(const TriangleMesh& mesh, const Geometry& g, const Vec3& inside);

// --- planar facets (planar_facets.cpp) -----------------------------------------------------------

/// Per triangle, the smallest triangle of its maximal planar facet: triangles joined across shared
/// edges whose four vertices are coplanar, exactly or within the rounding (count_planar_facets).
std::vector<Index> planar_facet_classes(const TriangleMesh& mesh);

// --- distances (plane_distance.cpp) -------------------------------------------------------------

/// The largest distance between two vertices (the bounding-box diagonal above 5000 vertices).
double diameter(const TriangleMesh& mesh);
/// An upper bound on |distance of v from the plane of (a, b, c)|; infinity when double precision
/// cannot bound it.
double plane_distance_upper(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& v);
/// Signed distance of v from the plane of (a, b, c), accurate to a relative 1e-4 or better.
double plane_distance(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& v);

// --- the rounding bound (input_rounding.cpp) ----------------------------------------------------

/// bound(t, v) of validation.hpp; negative when the triangle is too small for it.
double rounding_bound(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& v, double eta);

// --- convexity up to rounding (hull_retriangulation.cpp, convex_within_rounding.cpp) ------------

/// Step 1 of validate_closed_convex: re-triangulates the polygon faces from the exact convex hull
/// when that proves the mesh convex (replacing mesh, with a note in report); else the reason why not.
std::optional<std::string> retriangulate_convex_from_hull(TriangleMesh& mesh, const std::vector<Point>& pts,
                                                          const std::vector<Index>& bad, const Geometry& g,
                                                          const Vec3& inside, double diam,
                                                          ValidationReport& report);
/// Steps 2 and 3 of validate_closed_convex: accepts the mesh as convex within the rounding of its
/// input (report.convex_within_rounding, with a note), or returns the refusal, whose message ends
/// with hull_reason and why the rounding does not explain the violation.
std::optional<Failure> accept_within_rounding(const TriangleMesh& mesh, const std::vector<Index>& bad,
                                              const Geometry& g, const Vec3& inside, double diam,
                                              const std::string& hull_reason, ValidationReport& report);

// --- general scenes (face_crossing.cpp, piece_orientation.cpp) ----------------------------------

/// Rule "crossing" of validate_scene: no two triangles have a point interior to both (a transversal
/// cut, or a coplanar overlap of positive area); touching along edges or at points is allowed.
/// Two triangles of different input faces overlapping in one plane with positive area.
struct Overlap {
  Index i = kNone, j = kNone;  ///< the triangles, i < j
  Vec3 point;                  ///< a point interior to both
  bool across_gap = false;     ///< not coplanar: across a gap below the visibility's resolution
  bool within_rounding = false;  ///< not coplanar: each within the pair's ContactTolerance of the other's plane
};

// --- the rounding of coordinates as written (written_rounding.cpp) -------------------------------

/// How far a coordinate read from a file may lie from the value meant: half a unit in the last
/// place of its shortest decimal when that has 6 or more significant digits (at least an ulp),
/// else 0 (a short decimal is meant exactly).
double written_rounding(double x);
/// Half a unit in the last place of x's shortest decimal, whatever its digits (0.3: 0.05;
/// 0.000655: 5e-7): how far x may lie from what it was printed from.
double printed_place_rounding(double x);
/// How finely `corners` (of a polygon or a pair of triangles of size `size`) are printed: the
/// least printed_place_rounding of their nonzero coordinates (a fixed-decimal export drops
/// trailing zeros, so the finest place shows the printing; coordinates moved since they were read
/// show a finer one); 0 when all are 0, or when that place is coarser than 1e-2 of `size` (short
/// numbers meant as written: 0.3, 12.5).
double printed_rounding(const std::vector<Vec3>& corners, double size);
/// The hint of a refusal that the printing of the coordinates could explain: when `distance` (a
/// corner off its polygon's plane, the depth of a crossing) is at most `roundings` times
/// `rounding` (> 0), a sentence that says so and asks for more digits; else empty.
std::string more_digits_hint(double rounding, double distance, double roundings, double size);
/// Per input face, the largest written_rounding of its corners' coordinates; all 0 for a mesh
/// built in code (no facet_line).
std::vector<double> facet_rounding(const TriangleMesh& mesh);

/// The distance within which two faces are the contact they stand for: a gap or a crossing no
/// deeper, or two planes no further apart, is closed (written_rounding.cpp states the policy).
struct ContactTolerance {
  double resolution = 0;         ///< the visibility's resolution, the least tolerance
  std::vector<double> rounding;  ///< facet_rounding
  ContactTolerance() = default;
  ContactTolerance(const TriangleMesh& mesh, double resolution);
  /// For input faces f and g whose triangles span `pair_size`.
  double of(Index f, Index g, double pair_size) const;
};
/// With `overlaps`, a coplanar overlap of positive area between triangles of two input faces is
/// listed there instead of refused (faces in contact, contact_removal.hpp).
/// With `tolerance` too, two triangles of different faces that cross no deeper than the pair's
/// tolerance touch (the rounding of their corners as written), and two that straddle each other's
/// planes within it and overlap in projection are listed as an overlap within_rounding.
std::optional<Failure> check_no_crossing(const TriangleMesh& mesh, const std::vector<Point>& pts,
                                         std::vector<Overlap>* overlaps = nullptr,
                                         const ContactTolerance* tolerance = nullptr);

/// Which side of a piece is its front (the side that emits, reflects and sees: the paper's inner
/// normal n), in the words every report uses, on the convex path and the general one alike.
enum class FrontSide {
  open,       ///< an open surface: the side from which its faces run counter-clockwise
  enclosure,  ///< a closed surface seen from inside: front side inward
  object,     ///< a closed surface seen from outside: front side outward
  cavity,     ///< a closed surface inside an object: front side inward
};
/// "an enclosure, front side inward, as the file winds it" or "..., against the file's winding
/// (its faces run counter-clockwise seen from outside)".
std::string front_side_words(FrontSide side, bool against_file);

/// What orient_scene_pieces decided.
struct ScenePieces {
  Sz pieces = 0;
  Sz closed_pieces = 0;
  Sz flipped = 0;                  // triangles flipped to agree with most of their piece's area
  Sz against_file = 0;             // closed pieces whose front side is the back of the file's winding
  std::vector<char> in_closed_piece;  // per triangle: its piece is closed
  bool enclosed = false;           // every closed piece inside no other is an enclosure, and every open
                                   // piece lies inside one of them: no ray from a front side leaves
  std::vector<std::string> notes;  // one per piece, or a summary of many
};

/// Rule "orientable" of validate_scene, and the front sides: re-orients mesh.triangles so that
/// each is clockwise seen from its front (geometric normal to the back). Needs a scene without
/// crossings (check_no_crossing): nesting of closed pieces is decided by ray parity. On failure
/// mesh.triangles may be partly re-oriented.
std::optional<Failure> orient_scene_pieces(TriangleMesh& mesh, ScenePieces& out);

}  // namespace panelrad::geometry::validation_detail

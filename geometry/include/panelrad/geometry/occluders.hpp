#pragma once
// The line-of-sight function V(P, Q) of the radiosity equation (1) on a general scene: which
// part of a triangle tau a point P sees past the scene's faces. Every face occludes, from both of
// its sides. Built on CGAL's AABB tree (candidate faces of a shaft, segment queries); CGAL stays
// in geometry/src, this header exposes plain types.
//
// Conventions. P lies on a face whose front normal (the paper's inner normal n, the side that
// emits, reflects and sees) is nP; tau = (a, b, c) has front normal nQ. The kernel G V of (1) is
// clamped: a point sees nothing behind its own plane (cos theta_P > 0) and a face only from its
// front (cos theta_Q > 0).
//
// The shaft from P to tau is the tetrahedron conv(P, tau). An occluder meets it when the part of
// the face strictly inside (strictly in front of tau's plane, by the margin below) casts a shadow
// of positive area on tau, seen from P. Faces through P (seen edge-on) and faces in tau's plane
// (tau's own face, its coplanar neighbours) cast none: touching is not occluding.
//
// Rounding policy. The decisions are made in double precision with the margin
// kShadowMargin * diameter + 64 eps max|x| on distances to planes (the second term, the rounding of
// coordinates at |x|, matters only for a scene far from the origin relative to its size: a point
// on a face must never come out behind it) and kShadowMargin * area(tau) on shadow areas:
// a face that enters the shaft by less than the margin is ignored, and a visible area below the
// margin is empty. In detail: P within the margin of tau's plane sees tau when it is strictly in
// front of it by the exact orientation, and then no face is tested against that shaft (thinner
// than the margin: a face crossing it could hide at most tau's factor, below
// margin / (2 dist(P, tau))); a corner of tau within the margin of P's plane counts as on it; a
// face whose corners all lie within the margin outside one of the shaft's planes, or whose plane
// passes within the margin of P, casts no shadow; a shadow of area at most the area margin is none;
// in the subtraction of the shadows a corner within the margin of a shadow's edge line counts as on
// it (no sliver pieces), and pieces below a thousandth of the area margin are dropped; a ray is
// blocked only by a crossing farther than the margin from the face's edges, with P and Q farther
// than the margin from its plane. The error this makes in a form factor is of the order of the
// margin (a sliver of relative width 1e-12 seen from P), far below the discretization error; exact
// predicates are not needed for a bounded quantity of that size.
#include <panelrad/geometry/mesh.hpp>

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

namespace panelrad::geometry {

/// Relative margin of the shadow tests (see the rounding policy above).
inline constexpr double kShadowMargin = 1e-12;

/// The distance margin of the shadow tests for `mesh` (the rounding policy above):
/// kShadowMargin * (bounding-box diagonal of its triangles' corners) + 64 eps max|x|. Two faces
/// facing each other closer than this cannot see each other through these tests, so validation
/// (scene_validation.hpp) treats such faces as touching.
double visibility_margin(const TriangleMesh& mesh);

/// How much of tau a point P sees.
enum class ShaftClass : std::uint8_t {
  full,     ///< tau lies strictly in front of P's plane, P strictly in front of tau, nothing meets the shaft
  hidden,   ///< nothing of tau is seen: P on or behind tau's plane, tau on or behind P's plane, or covered by shadows
  partial,  ///< some, not all: the visible part is a set of convex polygons (visible_part)
};

/// The visible part of a triangle: convex polygons in the triangle's plane, as 3-D points.
struct VisiblePart {
  std::vector<Vec3> points;              ///< the pieces' corners, piece after piece, counter-clockwise about nQ
  std::vector<std::uint32_t> piece_end;  ///< piece k is points[piece_end[k-1], piece_end[k]) (piece_end[-1] = 0)
  double area = 0;                       ///< total area of the pieces
  /// tau lies wholly in front of P's plane (nothing of it is cut away there): the pieces and the
  /// covered pieces below then make up tau.
  bool whole_front = false;
  /// The covered part: the parts of tau's front part inside the shadows, convex pieces as above,
  /// each inside one shadow. With the pieces it makes up the front part, up to slivers within the
  /// margins of the rounding policy: an integral over the visible part is also the integral over
  /// tau minus that over the covered part, whose pieces' edges lie inside the shadows.
  std::vector<Vec3> covered_points;
  std::vector<std::uint32_t> covered_end;
  std::size_t num_pieces() const { return piece_end.size(); }
  void clear() {
    points.clear();
    piece_end.clear();
    area = 0;
    whole_front = false;
    covered_points.clear();
    covered_end.clear();
  }
};

/// A convex polygon of a plane, counter-clockwise in the plane's frame (ShadowPlane): the shadow one
/// face casts on a triangle from P (the face clipped to the shaft conv(P, tau), projected centrally
/// from P onto tau's plane). A triangle clipped by the shaft's 5 planes keeps at most 3 + 5 corners.
struct PlaneShadow {
  std::array<Eigen::Vector2d, 8> p;
  int n = 0;
  double area = 0;
  Eigen::Vector2d lo, hi;  ///< bounding box of the corners
  /// The edge lines longer than the distance margin: a point and the unit normal towards the inside.
  std::array<Eigen::Vector2d, 8> line_at, line_in;
  int lines = 0;
};

/// P and the plane of a triangle T seen from it, with the shadows the occluders cast on T: what the
/// classification of T's sub-triangles shares (Occluders::classify_within). A sub-triangle tau of
/// T lies in T's plane, so the central projection from P maps the planes of tau's shaft through P
/// and tau's edges onto tau's edge lines: the shadow a face casts on tau (the face clipped to
/// conv(P, tau), projected) is its shadow on T clipped to tau, a 2-D clip in T's frame.
struct ShadowPlane {
  Vec3 P, nP;                         ///< the point and the unit normal of its plane
  Vec3 origin, u, w, nQ;              ///< T's first corner, the frame (u, w, nQ) of T's plane, nQ T's unit front normal
  double height = 0;                  ///< distance of P from T's plane
  bool seen = false;                  ///< false: T is hidden by the plane tests alone, and so is every sub-triangle
  std::vector<PlaneShadow> shadows;   ///< the shadows on T of the faces that meet T's shaft
  std::vector<Index> faces;           ///< the face of each shadow (in the order of the candidates)
};

/// The faces that last hid a whole triangle from a point (Occluders::hidden_by_a_face), most recent
/// first: tried before the search, as the face that hid one triangle from a point often hides the
/// next one, or the same triangle from the next point. One per thread; the answers do not depend
/// on it, only their cost.
struct BlockerHints {
  std::array<Index, 4> face{-1, -1, -1, -1};
  void remember(Index f) {
    if (face[0] == f) return;
    Index carried = f;
    for (Index& slot : face) {
      std::swap(slot, carried);
      if (carried == f) break;
    }
  }
};

/// What the points of a cluster sigma see of a triangle tau, decided once for all of them
/// (Occluders::cluster_candidates).
struct ClusterSight {
  bool hidden = false;  ///< tau is hidden from every point of sigma
  bool listed = false;  ///< the faces listed hold every point's candidates
};

/// The scene's faces as occluders, with the queries of the fast product and of the dense reference.
/// Thread-safe: every query is const and uses no shared mutable state.
class Occluders {
 public:
  /// Every triangle of `mesh` is an occluder (index = triangle index). The mesh must have finite
  /// coordinates and no zero-area triangle (validate_scene).
  explicit Occluders(const TriangleMesh& mesh);
  ~Occluders();
  Occluders(Occluders&&) noexcept;
  Occluders& operator=(Occluders&&) noexcept;

  Index size() const;
  const std::array<Vec3, 3>& triangle(Index t) const;
  /// Bounding-box diagonal of the scene (the length scale of the margin).
  double diameter() const;

  /// The occluders whose bounding box meets the bounding box of the shaft conv(P, tau), and that
  /// have a point strictly in front of P's plane and strictly in front of tau's plane: a superset of
  /// those that meet the shaft. `out` is replaced, ascending (deterministic). By the AABB tree.
  /// Also left out (the margin as in the rounding policy): faces on the outer side of one of the
  /// three planes through P and tau's edges, and faces whose plane passes through P (edge-on).
  /// Empty when tau's class is hidden by the planes alone (P on or behind tau's plane, tau on or
  /// behind P's plane). Scenes of a few hundred faces are scanned face by face instead (faster for
  /// them, same result).
  void candidates(const Vec3& P, const Vec3& nP, const std::array<Vec3, 3>& tau, const Vec3& nQ,
                  std::vector<Index>& out) const;

  /// True when one face alone hides all of tau from P: every segment from P to tau crosses its
  /// interior, by a few margins of the rounding policy (tau is then hidden, as classify would find
  /// by subtracting that face's shadow, which covers tau); `out` is cleared. Otherwise false, with
  /// `out` the candidates, as candidates() gives them. The search stops at the first such face, so
  /// that the shadows of the others are never cast: in a scene of many solids most faces a point
  /// could see are hidden behind a nearer one.
  /// `hints`, when given, are tried first and updated.
  bool hidden_by_a_face(const Vec3& P, const Vec3& nP, const std::array<Vec3, 3>& tau, const Vec3& nQ,
                        std::vector<Index>& out, BlockerHints* hints = nullptr) const;

  /// hidden_by_a_face, with the faces looked at being `among` (holding every face that meets P's
  /// shaft to tau, such as cluster_candidates lists): true when one of them, or of the hints, alone
  /// hides all of tau from P. The same answer as hidden_by_a_face, without a search of the tree.
  bool hidden_by_one_of(const Vec3& P, const Vec3& nP, const std::array<Vec3, 3>& tau, const Vec3& nQ,
                        std::span<const Index> among, BlockerHints* hints = nullptr) const;

  /// For every point of a cluster sigma (a triangle, front normal nS) at once, what it sees of
  /// tau: hidden, when the planes hide tau from each point (as make_shaft decides for each) or
  /// one face is crossed by every segment from sigma to tau (by kCoverMargins margins); else
  /// listed, when `out` (ascending) holds every face that comes within two margins of the shaft
  /// conv(sigma, tau), which holds each point's shaft conv(P, tau): every face that meets P's
  /// shaft, for every P of sigma (candidates(P, tau) may hold more: faces near the shaft that pass
  /// each of its plane tests), so that classify against `out` is classify against P's candidates,
  /// bit for bit (its shadows are those of the faces that meet P's shaft, in the same order), and
  /// hidden_by_one_of against `out` is hidden_by_a_face; empty when no face comes that close.
  /// Neither when sigma and tau cross each other's planes (each point then finds its own
  /// candidates).
  ClusterSight cluster_candidates(const std::array<Vec3, 3>& sigma, const Vec3& nS, const std::array<Vec3, 3>& tau,
                                  const Vec3& nT, std::vector<Index>& out) const;

  /// Classifies tau as seen from P against the occluders `among` (candidates of tau or of a
  /// triangle containing tau: the shaft of a sub-triangle lies in its parent's). `meeting` is
  /// replaced by those among them that meet the shaft (ascending): the candidates for tau's
  /// sub-triangles. When `part` is given and the class is partial, it receives the visible part
  /// (as visible_part); otherwise it is left cleared.
  ShaftClass classify(const Vec3& P, const Vec3& nP, const std::array<Vec3, 3>& tau, const Vec3& nQ,
                      std::span<const Index> among, std::vector<Index>& meeting, VisiblePart* part = nullptr) const;

  /// classify, which also sets up `plane` for tau's sub-triangles (classify_within): tau's frame and
  /// the shadows of the faces of `among` that meet tau's shaft (those classify puts in `meeting`).
  /// The class and the visible part are those of classify, bit for bit.
  ShaftClass classify(const Vec3& P, const Vec3& nP, const std::array<Vec3, 3>& tau, const Vec3& nQ,
                      std::span<const Index> among, ShadowPlane& plane, VisiblePart* part = nullptr) const;

  /// Classifies a sub-triangle `sub` of the triangle T of `plane` (in T's plane, inside T, facing
  /// T's nQ; its distance from the plane is not looked at) as seen from plane.P, in 2-D: `among`
  /// are indices of plane.shadows (those that meet a triangle containing sub), and `meeting` is
  /// replaced by those that meet sub (in the order of `among`; empty when sub is hidden): the
  /// candidates of sub's sub-triangles. A shadow meets sub when its part inside sub has an area
  /// above the area margin (as the shadow of the face clipped to sub's shaft in classify); sub is
  /// hidden as soon as its corners are inside every edge line of one shadow (by the distance
  /// margin, as in the subtraction of the shadows). The class and the
  /// visible part are those of classify with the faces of `among` up to rounding, and the
  /// decisions up to the margins of the rounding policy; the visible part's corners are computed
  /// in T's frame.
  ShaftClass classify_within(const ShadowPlane& plane, const std::array<Vec3, 3>& sub, std::span<const Index> among,
                             std::vector<Index>& meeting, VisiblePart* part = nullptr) const;

  /// The part of tau that P sees: tau clipped to the front of P's plane, minus the shadows cast
  /// from P by the occluders `among` (central projection from P onto tau's plane of each face
  /// clipped to the shaft), as convex pieces. Empty when P is on or behind tau's plane.
  void visible_part(const Vec3& P, const Vec3& nP, const std::array<Vec3, 3>& tau, const Vec3& nQ,
                    std::span<const Index> among, VisiblePart& out) const;

  /// The class of tau seen from every point of sigma (two triangles, nS and nT their front
  /// normals), for the cluster-to-cluster far field: hidden when the planes alone hide tau from
  /// each point of sigma (as classify decides for each); full when neither crosses the other's
  /// plane by more than the margin and no face may block a segment of conv(sigma, tau) (an axis
  /// separates each face from the hull, up to the margin: the separating axis theorem); partial
  /// otherwise, which here means undecided: the points decide. With `faces` false the faces are
  /// not looked at: full then means that the planes alone allow it.
  ShaftClass classify_clusters(const std::array<Vec3, 3>& sigma, const Vec3& nS, const std::array<Vec3, 3>& tau,
                               const Vec3& nT, bool faces = true) const;

  /// V(P, Q) by one ray (a segment query of the AABB tree): false when some face other than those
  /// containing P or Q (within the margin) is crossed by the open segment PQ in its interior.
  /// For reference integrals by quadrature; the operators use classify / visible_part.
  bool visible(const Vec3& P, const Vec3& Q) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace panelrad::geometry

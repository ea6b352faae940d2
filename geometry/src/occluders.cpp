// The scene's faces as occluders of the line-of-sight function V(P, Q) in (1): CGAL's AABB tree over
// the triangles (Epick) finds the faces near a shaft conv(P, tau) and the faces near a segment PQ;
// the shaft classes and visible parts are built from the shadows of occluders_internal.hpp.
#include "occluders_internal.hpp"

#include <panelrad/geometry/bounding_box.hpp>

#include <Eigen/Geometry>

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <limits>
#include <cmath>
#include <iterator>
#include <span>
#include <stdexcept>
#include <string>

namespace panelrad::geometry {

using namespace occluder_detail;

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using CgalTriangle = K::Triangle_3;
using TriangleIterator = std::vector<CgalTriangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<K, TriangleIterator>;
using AabbTraits = CGAL::AABB_traits<K, Primitive>;
using Tree = CGAL::AABB_tree<AabbTraits>;

K::Point_3 point(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

namespace occluder_detail {

bool strictly_in_front(const Vec3& P, const std::array<Vec3, 3>& t) {
  return CGAL::orientation(point(t[0]), point(t[1]), point(t[2]), point(P)) == CGAL::POSITIVE;
}

}  // namespace occluder_detail

namespace {

/// The segment PQ meets the box widened by m (slab test). The widening covers the rounding of the
/// slab parameters (relative 1e-16), so that no face the segment crosses is missed.
bool segment_meets_box(const Vec3& P, const Vec3& Q, const CGAL::Bbox_3& b, double m) {
  double t0 = 0, t1 = 1;
  for (int i = 0; i < 3; ++i) {
    const double lo = b.min(i) - m, hi = b.max(i) + m, d = Q[i] - P[i];
    if (d == 0) {
      if (P[i] < lo || P[i] > hi) return false;
      continue;
    }
    double ta = (lo - P[i]) / d, tb = (hi - P[i]) / d;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

// Scenes of at most this many faces find the candidates of a shaft by a scan of every face
// (may_meet, whose first test is the box test) instead of the tree; both give the same list.
// Measured, microseconds per candidates() call (g++ -O3, one thread, a room [0, 1]^3 with a box
// inside, every square face cut into k x k pairs of triangles, shafts from the centroid of a random
// face to a random face; the machine shared, so +-10%):
//   faces        22    88   198   352   792  1408
//   linear scan  0.36  0.68  1.11  1.60  2.76  4.22
//   AABB tree    0.45  0.95  1.51  1.94  2.73  3.61
// Shafts to whole faces are long, so the tree prunes little below ~800 faces.
constexpr Index kLinearScanFaces = 512;

/// The largest signed distance (x - o).n over the corners x of the box b: the corner on the side
/// of n in each coordinate.
double box_max_distance(const CGAL::Bbox_3& b, const Vec3& o, const Vec3& n) {
  double d = 0;
  for (int i = 0; i < 3; ++i) d += n[i] * ((n[i] > 0 ? b.max(i) : b.min(i)) - o[i]);
  return d;
}

/// Shaft culling of a node of the AABB tree: false when the node's box lies outside one of the
/// shaft's five planes (tau's plane, P's plane, the three planes through P and tau's edges) by the
/// margin, so that may_meet refuses each of its faces. Conservative against the rounding: a node
/// is refused only when its box's largest distance comes out at most half the margin; the box's
/// largest distance bounds each face corner's, and the two computed distances differ from the exact
/// ones by a few eps max|x|, at most an eighth of the margin (visibility_margin), so every face of a
/// refused node has its computed max_distance below the margin too.
bool box_may_meet(const CGAL::Bbox_3& b, const Shaft& s) {
  const double m = 0.5 * s.margin;
  if (box_max_distance(b, s.t[0], s.nQ) <= m || box_max_distance(b, s.P, s.nP) <= m) return false;
  for (int i = 0; i < 3; ++i)
    if (box_max_distance(b, s.P, s.side_n[static_cast<std::size_t>(i)]) <= m) return false;
  return true;
}

/// The same for the cluster shaft: false when the box lies beyond one of its supporting planes
/// (outer normal out_n, n.x <= out_d on the hull) by at least `beyond`: the smallest n.x - out_d
/// over the box's corners bounds its faces' corners'. For may_block (which refuses a face whose
/// corners all lie at least -margin beyond) `beyond` is -margin / 2, for may_enter (more than 2
/// margins) 3 margins: the rounding of the two computed distances is below margin / 4 (as above).
bool box_within_planes(const CGAL::Bbox_3& b, const ClusterShaft& s, double beyond) {
  for (int k = 0; k < s.planes; ++k) {
    const Vec3& n = s.out_n[static_cast<std::size_t>(k)];
    double lowest = 0;  // the smallest n.x over the box's corners
    for (int i = 0; i < 3; ++i) lowest += n[i] * (n[i] > 0 ? b.min(i) : b.max(i));
    if (lowest - s.out_d[static_cast<std::size_t>(k)] >= beyond) return false;
  }
  return true;
}

}  // namespace

struct Occluders::Impl {
  std::vector<std::array<Vec3, 3>> triangles;
  std::vector<FaceData> faces;
  std::vector<CgalTriangle> cgal_triangles;
  Tree tree;
  double diameter = 0;
  double margin = 0;

  /// The open segment PQ crosses face f in its interior (by the margin), P and Q off its plane.
  bool blocks(const FaceData& f, const Vec3& P, const Vec3& Q) const {
    const double dP = (P - f.v[0]).dot(f.n);
    const double dQ = (Q - f.v[0]).dot(f.n);
    if (std::abs(dP) <= margin || std::abs(dQ) <= margin) return false;  // P or Q on the face's plane
    if ((dP > 0) == (dQ > 0)) return false;
    const Vec3 X = P + (dP / (dP - dQ)) * (Q - P);
    for (int i = 0; i < 3; ++i)
      if ((X - f.v[i]).dot(f.edge_in[i]) <= margin) return false;  // outside, or grazing an edge
    return true;
  }

  /// Depth-first search of the tree for a face that blocks the segment, stopping at the first.
  struct BlockingSearch {
    const Impl* impl;
    Vec3 P, Q;
    bool blocked = false;
    bool go_further() const { return !blocked; }
    void intersection(const K::Segment_3&, const Primitive& p) {
      const auto t = static_cast<std::size_t>(p.id() - impl->cgal_triangles.begin());
      if (impl->blocks(impl->faces[t], P, Q)) blocked = true;
    }
    template <class Node>
    bool do_intersect(const K::Segment_3&, const Node& node) const {
      return segment_meets_box(P, Q, node.bbox(), impl->margin);
    }
  };

  /// Depth-first search of the tree for the faces that may meet a shaft: a node is entered when its
  /// box meets the shaft's box widened by the margin and is not outside one of the shaft's planes
  /// (box_may_meet); a face is kept when may_meet holds (whose first tests are the same, so the
  /// search finds exactly what a scan of every face finds).
  /// With `stop_when_covered`, the search stops at the first face that alone hides tau
  /// (covers_shaft), setting `covered`.
  struct ShaftSearch {
    const Impl* impl;
    const Shaft* shaft;
    std::vector<Index>* out;
    bool stop_when_covered = false;
    Index covered = -1;  // the face that hides tau
    bool go_further() const { return covered < 0; }
    void intersection(const CGAL::Bbox_3&, const Primitive& p) {
      const auto t = static_cast<Index>(p.id() - impl->cgal_triangles.begin());
      const FaceData& f = impl->faces[static_cast<std::size_t>(t)];
      if (!may_meet(f, *shaft)) return;
      if (stop_when_covered && covers_shaft(f, *shaft)) covered = t;
      else out->push_back(t);
    }
    template <class Node>
    bool do_intersect(const CGAL::Bbox_3& box, const Node& node) const {
      return CGAL::do_overlap(box, node.bbox()) && box_may_meet(node.bbox(), *shaft);
    }
  };

  /// Depth-first search of the tree for a face that may block the cluster shaft, stopping at the
  /// first.
  struct ClusterShaftSearch {
    const Impl* impl;
    const ClusterShaft* shaft;
    bool blocked = false;
    bool go_further() const { return !blocked; }
    void intersection(const CGAL::Bbox_3&, const Primitive& p) {
      const auto t = static_cast<std::size_t>(p.id() - impl->cgal_triangles.begin());
      if (may_block(impl->faces[t], *shaft, impl->margin)) blocked = true;
    }
    template <class Node>
    bool do_intersect(const CGAL::Bbox_3& box, const Node& node) const {
      return CGAL::do_overlap(box, node.bbox()) && box_within_planes(node.bbox(), *shaft, -0.5 * impl->margin);
    }
  };

  /// Depth-first search of the tree for the faces that may enter the cluster shaft (may_enter),
  /// stopping at the first that every segment crosses (covers_cluster_shaft).
  struct ClusterEntrySearch {
    const Impl* impl;
    const ClusterShaft* shaft;
    std::vector<Index>* out;
    Index covered = -1;
    bool go_further() const { return covered < 0; }
    void intersection(const CGAL::Bbox_3&, const Primitive& p) {
      const auto t = static_cast<Index>(p.id() - impl->cgal_triangles.begin());
      const FaceData& f = impl->faces[static_cast<std::size_t>(t)];
      if (!may_enter(f, *shaft, impl->margin)) return;
      if (covers_cluster_shaft(f, *shaft, impl->margin)) covered = t;
      else out->push_back(t);
    }
    template <class Node>
    bool do_intersect(const CGAL::Bbox_3& box, const Node& node) const {
      return CGAL::do_overlap(box, node.bbox()) && box_within_planes(node.bbox(), *shaft, 3 * impl->margin);
    }
  };

  /// The faces that may enter the cluster shaft into `out`, ascending; the face that every segment
  /// crosses as soon as one is found (`out` then cleared), -1 otherwise.
  Index collect_entering(const ClusterShaft& s, std::vector<Index>& out) const {
    out.clear();
    const Index n = static_cast<Index>(faces.size());
    if (n <= kLinearScanFaces) {
      for (Index t = 0; t < n; ++t) {
        const FaceData& f = faces[static_cast<std::size_t>(t)];
        if (!may_enter(f, s, margin)) continue;
        if (covers_cluster_shaft(f, s, margin)) {
          out.clear();
          return t;
        }
        out.push_back(t);
      }
      return -1;
    }
    const double m = 3 * margin;
    const CGAL::Bbox_3 box(s.lo.x() - m, s.lo.y() - m, s.lo.z() - m, s.hi.x() + m, s.hi.y() + m, s.hi.z() + m);
    ClusterEntrySearch search{this, &s, &out};
    tree.traversal(box, search);
    if (search.covered >= 0) out.clear();
    else std::sort(out.begin(), out.end());
    return search.covered;
  }

  bool any_may_block(const ClusterShaft& s) const {
    if (faces.size() <= static_cast<std::size_t>(kLinearScanFaces)) {
      for (const FaceData& f : faces)
        if (may_block(f, s, margin)) return true;
      return false;
    }
    const double m = margin;
    const CGAL::Bbox_3 box(s.lo.x() - m, s.lo.y() - m, s.lo.z() - m, s.hi.x() + m, s.hi.y() + m, s.hi.z() + m);
    ClusterShaftSearch search{this, &s};
    tree.traversal(box, search);
    return search.blocked;
  }

  /// The faces that may meet the shaft into `out`, ascending. With `stop_when_covered`, the face
  /// that alone hides tau (covers_shaft) as soon as one is found, `out` then cleared; -1 otherwise.
  Index collect(const Shaft& s, std::vector<Index>& out, bool stop_when_covered = false) const {
    out.clear();
    const Index n = static_cast<Index>(faces.size());
    if (n <= kLinearScanFaces) {
      for (Index t = 0; t < n; ++t) {
        const FaceData& f = faces[static_cast<std::size_t>(t)];
        if (!may_meet(f, s)) continue;
        if (stop_when_covered && covers_shaft(f, s)) {
          out.clear();
          return t;
        }
        out.push_back(t);
      }
      return -1;
    }
    const double m = margin;
    const CGAL::Bbox_3 box(s.lo.x() - m, s.lo.y() - m, s.lo.z() - m, s.hi.x() + m, s.hi.y() + m, s.hi.z() + m);
    ShaftSearch search{this, &s, &out, stop_when_covered};
    tree.traversal(box, search);
    if (search.covered >= 0) out.clear();
    else std::sort(out.begin(), out.end());
    return search.covered;
  }

  /// The first of the hints that alone hides tau (may_meet and covers_shaft), moved to the front of
  /// them; -1 when none does.
  Index hinted_cover(const Shaft& s, BlockerHints& hints) const {
    for (const Index t : hints.face) {
      if (t < 0 || t >= static_cast<Index>(faces.size())) continue;
      const FaceData& f = faces[static_cast<std::size_t>(t)];
      if (may_meet(f, s) && covers_shaft(f, s)) {
        hints.remember(t);
        return t;
      }
    }
    return -1;
  }

  /// The shadows of the faces of `among` that meet the shaft, into `meeting` and `shadows`.
  void shadows_of(const Shaft& s, std::span<const Index> among, std::vector<Index>& meeting,
                  std::vector<Shadow>& shadows) const {
    Shadow sh;
    for (const Index t : among) {
      if (t < 0 || t >= static_cast<Index>(faces.size()))
        throw std::invalid_argument("Occluders: occluder index " + std::to_string(t) + " is not in [0, " +
                                    std::to_string(faces.size()) + ")");
      if (!may_meet(faces[t], s) || !cast_shadow(faces[t], s, sh)) continue;
      meeting.push_back(t);
      shadows.push_back(sh);
    }
  }

  /// tau's front part minus the shadows, into `pieces` (the parts inside the shadows appended to
  /// `covered` when given); returns its area.
  double visible_pieces(const Shaft& s, const std::vector<Shadow>& shadows, Pieces& pieces,
                        Pieces* covered = nullptr) const {
    front_part_of_tau(s, pieces);
    return subtract_all(shadows, 1e-3 * s.area_margin, pieces, covered);
  }

  /// pieces minus the convex polygons (each with corners p[0, n)), pieces of area at most min_area
  /// dropped, the parts inside them appended to `covered` when given; returns the area of what is
  /// left.
  template <class Polygons>
  double subtract_all(const Polygons& polygons, double min_area, Pieces& pieces, Pieces* covered = nullptr) const {
    thread_local Pieces other;
    if (covered) covered->clear();
    for (const auto& sh : polygons) {
      if (pieces.end.empty()) break;
      subtract_convex(pieces, sh.p.data(), sh.n, margin, min_area, other, covered);
      pieces.swap(other);
    }
    double area = 0;
    for (const double a : pieces.area) area += a;
    return area;
  }

  static void write(const Shaft& s, const Pieces& pieces, double area, const Pieces& covered, VisiblePart& out) {
    write(s.t[0], s.u, s.w, pieces, area, out);
    out.whole_front = !s.straddles;
    write_covered(s.t[0], s.u, s.w, covered, out);
  }

  static void write(const Vec3& origin, const Vec3& u, const Vec3& w, const Pieces& pieces, double area,
                    VisiblePart& out) {
    out.clear();
    out.points.reserve(pieces.pts.size());
    for (const Vec2& p : pieces.pts) out.points.push_back(origin + p.x() * u + p.y() * w);
    out.piece_end.assign(pieces.end.begin(), pieces.end.end());
    out.area = area;
  }

  static void write_covered(const Vec3& origin, const Vec3& u, const Vec3& w, const Pieces& covered,
                            VisiblePart& out) {
    out.covered_points.clear();
    out.covered_points.reserve(covered.pts.size());
    for (const Vec2& p : covered.pts) out.covered_points.push_back(origin + p.x() * u + p.y() * w);
    out.covered_end.assign(covered.end.begin(), covered.end.end());
  }

  static void write_whole(const Shaft& s, VisiblePart& out) {
    out.clear();
    out.points.assign(s.t.begin(), s.t.end());
    out.piece_end.push_back(3);
    out.area = s.area;
    out.whole_front = true;
  }
};

namespace {

/// The bounding-box diagonal of the corners of the mesh's triangles.
double used_diameter(const TriangleMesh& mesh) {
  std::vector<Vec3> used;
  used.reserve(3 * mesh.triangles.size());
  for (const auto& t : mesh.triangles)
    for (Index i : t) used.push_back(mesh.vertices[static_cast<std::size_t>(i)]);
  return bounding_box_diameter(used);
}

}  // namespace

double visibility_margin(const TriangleMesh& mesh) {
  // The relative margin, and never less than the rounding of the coordinates themselves: a
  // distance to a plane computed from points at |x| carries an error of a few eps |x| (a
  // collocation point on its own face may come out behind it), so 64 eps max|x| is added, which
  // matters only for scenes far from the origin relative to their size.
  double max_abs = 0;
  for (const auto& t : mesh.triangles)
    for (Index i : t) max_abs = std::max(max_abs, mesh.vertices[static_cast<std::size_t>(i)].cwiseAbs().maxCoeff());
  return kShadowMargin * used_diameter(mesh) + 64 * std::numeric_limits<double>::epsilon() * max_abs;
}

Occluders::Occluders(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  const std::size_t nv = mesh.vertices.size();
  for (std::size_t i = 0; i < nv; ++i)
    if (!mesh.vertices[i].allFinite())
      throw MeshError(mesh.source + ": vertex " + std::to_string(i) + " has a non-finite coordinate (occluders)");
  m.triangles.reserve(mesh.triangles.size());
  m.faces.reserve(mesh.triangles.size());
  m.cgal_triangles.reserve(mesh.triangles.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    std::array<Vec3, 3> v;
    for (int k = 0; k < 3; ++k) {
      const Index i = mesh.triangles[t][k];
      if (i < 0 || static_cast<std::size_t>(i) >= nv)
        throw MeshError(mesh.source + ": triangle " + std::to_string(t) + " refers to vertex " + std::to_string(i) +
                        ", not in [0, " + std::to_string(nv) + ") (occluders)");
      v[k] = mesh.vertices[i];
    }
    if (!((v[1] - v[0]).cross(v[2] - v[0]).norm() > 0))
      throw MeshError(mesh.source + ": triangle " + std::to_string(t) + " has zero area (occluders need a plane per face)");
    m.triangles.push_back(v);
    m.faces.push_back(make_face(v));
    m.cgal_triangles.emplace_back(point(v[0]), point(v[1]), point(v[2]));
  }
  m.diameter = used_diameter(mesh);
  m.margin = visibility_margin(mesh);
  m.tree.insert(m.cgal_triangles.cbegin(), m.cgal_triangles.cend());
  m.tree.build();  // now, not lazily in a const query: the queries run concurrently
}

Occluders::~Occluders() = default;
Occluders::Occluders(Occluders&&) noexcept = default;
Occluders& Occluders::operator=(Occluders&&) noexcept = default;

Index Occluders::size() const { return static_cast<Index>(impl_->triangles.size()); }

const std::array<Vec3, 3>& Occluders::triangle(Index t) const {
  if (t < 0 || t >= size())
    throw std::invalid_argument("Occluders::triangle: index " + std::to_string(t) + " is not in [0, " +
                                std::to_string(size()) + ")");
  return impl_->triangles[static_cast<std::size_t>(t)];
}

double Occluders::diameter() const { return impl_->diameter; }

void Occluders::candidates(const Vec3& P, const Vec3& nP, const std::array<Vec3, 3>& tau, const Vec3& nQ,
                           std::vector<Index>& out) const {
  Shaft s;
  if (!make_shaft(P, nP, tau, nQ, impl_->margin, s) || s.grazing) {
    out.clear();  // nothing of tau is seen: no face meets the (empty) shaft; or none is tested
    return;
  }
  complete_shaft(s);
  impl_->collect(s, out);
}

bool Occluders::hidden_by_a_face(const Vec3& P, const Vec3& nP, const std::array<Vec3, 3>& tau, const Vec3& nQ,
                                 std::vector<Index>& out, BlockerHints* hints) const {
  out.clear();
  Shaft s;
  if (!make_shaft(P, nP, tau, nQ, impl_->margin, s) || s.grazing) return false;
  complete_shaft(s);
  if (hints && impl_->hinted_cover(s, *hints) >= 0) return true;
  const Index covering = impl_->collect(s, out, true);
  if (covering < 0) return false;
  if (hints) hints->remember(covering);
  return true;
}

ShaftClass Occluders::classify_clusters(const std::array<Vec3, 3>& sigma, const Vec3& nS,
                                        const std::array<Vec3, 3>& tau, const Vec3& nT, bool faces) const {
  ClusterShaft s;
  const ShaftClass planes = make_cluster_shaft(sigma, nS, tau, nT, impl_->margin, s);
  if (planes != ShaftClass::full || !faces) return planes;
  return impl_->any_may_block(s) ? ShaftClass::partial : ShaftClass::full;
}

bool Occluders::hidden_by_one_of(const Vec3& P, const Vec3& nP, const std::array<Vec3, 3>& tau, const Vec3& nQ,
                                 std::span<const Index> among, BlockerHints* hints) const {
  Shaft s;
  if (!make_shaft(P, nP, tau, nQ, impl_->margin, s) || s.grazing || s.straddles) return false;
  complete_shaft(s);
  if (hints && impl_->hinted_cover(s, *hints) >= 0) return true;
  for (const Index t : among) {
    if (t < 0 || t >= size())
      throw std::invalid_argument("Occluders: occluder index " + std::to_string(t) + " is not in [0, " +
                                  std::to_string(size()) + ")");
    const FaceData& f = impl_->faces[static_cast<std::size_t>(t)];
    if (may_meet(f, s) && covers_shaft(f, s)) {
      if (hints) hints->remember(t);
      return true;
    }
  }
  return false;
}

ClusterSight Occluders::cluster_candidates(const std::array<Vec3, 3>& sigma, const Vec3& nS,
                                           const std::array<Vec3, 3>& tau, const Vec3& nT,
                                           std::vector<Index>& out) const {
  out.clear();
  ClusterShaft s;
  const ShaftClass planes = make_cluster_shaft(sigma, nS, tau, nT, impl_->margin, s);
  if (planes == ShaftClass::hidden) return {true, false};
  if (planes != ShaftClass::full) return {false, false};
  if (impl_->collect_entering(s, out) >= 0) return {true, false};
  return {false, true};
}

ShaftClass Occluders::classify(const Vec3& P, const Vec3& nP, const std::array<Vec3, 3>& tau, const Vec3& nQ,
                               std::span<const Index> among, std::vector<Index>& meeting,
                               VisiblePart* part) const {
  meeting.clear();
  if (part) part->clear();
  Shaft s;
  if (!make_shaft(P, nP, tau, nQ, impl_->margin, s)) return ShaftClass::hidden;
  if (s.grazing) among = {};
  if (among.empty() && !s.straddles) return ShaftClass::full;  // the four plane tests decide
  complete_shaft(s);
  thread_local std::vector<Shadow> shadows;
  shadows.clear();
  impl_->shadows_of(s, among, meeting, shadows);
  if (!std::is_sorted(meeting.begin(), meeting.end())) std::sort(meeting.begin(), meeting.end());
  if (shadows.empty() && !s.straddles) return ShaftClass::full;
  thread_local Pieces pieces, covered;
  const double area = impl_->visible_pieces(s, shadows, pieces, part ? &covered : nullptr);
  if (!(area > s.area_margin)) return ShaftClass::hidden;
  if (part) Impl::write(s, pieces, area, covered, *part);
  return ShaftClass::partial;
}

ShaftClass Occluders::classify(const Vec3& P, const Vec3& nP, const std::array<Vec3, 3>& tau, const Vec3& nQ,
                               std::span<const Index> among, ShadowPlane& plane, VisiblePart* part) const {
  plane.shadows.clear();
  plane.faces.clear();
  plane.seen = false;
  if (part) part->clear();
  Shaft s;
  if (!make_shaft(P, nP, tau, nQ, impl_->margin, s)) return ShaftClass::hidden;
  complete_shaft(s);
  plane.P = s.P;
  plane.nP = s.nP;
  plane.origin = s.t[0];
  plane.u = s.u;
  plane.w = s.w;
  plane.nQ = s.nQ;
  plane.height = s.height;
  plane.seen = true;
  if (s.grazing) among = {};
  if (among.empty() && !s.straddles) return ShaftClass::full;  // the four plane tests decide
  impl_->shadows_of(s, among, plane.faces, plane.shadows);
  for (PlaneShadow& sh : plane.shadows) {
    sh.lo = sh.hi = sh.p[0];
    for (int j = 1; j < sh.n; ++j) {
      sh.lo = sh.lo.cwiseMin(sh.p[j]);
      sh.hi = sh.hi.cwiseMax(sh.p[j]);
    }
    sh.lines = 0;
    for (int j = 0; j < sh.n; ++j) {
      const Vec2 d = sh.p[j + 1 < sh.n ? j + 1 : 0] - sh.p[j];
      const double len = d.norm();
      if (!(len > impl_->margin)) continue;  // as subtract_convex: a degenerate edge bounds nothing
      sh.line_at[sh.lines] = sh.p[j];
      sh.line_in[sh.lines++] = Vec2(-d.y() / len, d.x() / len);
    }
  }
  if (plane.shadows.empty() && !s.straddles) return ShaftClass::full;
  thread_local Pieces pieces, covered;
  const double area = impl_->visible_pieces(s, plane.shadows, pieces, part ? &covered : nullptr);
  if (!(area > s.area_margin)) return ShaftClass::hidden;
  if (part) Impl::write(s, pieces, area, covered, *part);
  return ShaftClass::partial;
}

ShaftClass Occluders::classify_within(const ShadowPlane& plane, const std::array<Vec3, 3>& sub,
                                      std::span<const Index> among, std::vector<Index>& meeting,
                                      VisiblePart* part) const {
  meeting.clear();
  if (part) part->clear();
  if (!plane.seen) return ShaftClass::hidden;
  const double m = impl_->margin;
  // sub in T's frame, counter-clockwise about nQ, and its corners' distances from P's plane. P's
  // height over sub's plane is T's (plane.height > margin, or P strictly in front within the
  // margin, as make_shaft checked; then T has no shadows).
  std::array<Vec2, 3> c;
  std::array<double, 3> tP;
  for (int i = 0; i < 3; ++i) {
    const Vec3 d = sub[i] - plane.origin;
    c[i] = Vec2(d.dot(plane.u), d.dot(plane.w));
    tP[i] = (sub[i] - plane.P).dot(plane.nP);
  }
  const Vec2 e1 = c[1] - c[0], e2 = c[2] - c[0];
  double twice_area = e1.x() * e2.y() - e1.y() * e2.x();
  if (twice_area < 0) {
    std::swap(c[1], c[2]);
    std::swap(tP[1], tP[2]);
    twice_area = -twice_area;
  }
  if (!(twice_area > 0)) return ShaftClass::hidden;  // no area to see
  const double tP_lo = std::min({tP[0], tP[1], tP[2]}), tP_hi = std::max({tP[0], tP[1], tP[2]});
  if (!(tP_hi > m)) return ShaftClass::hidden;  // sub on or behind P's plane: cos theta_P <= 0
  const bool straddles = tP_lo < -m;            // as make_shaft: a corner within the margin is on the plane
  if (among.empty() && !straddles) return ShaftClass::full;
  const double area_margin = kShadowMargin * twice_area / 2;

  // The shadows on sub: those on T clipped to sub's three edge lines (the images of the planes of
  // sub's shaft through P and its edges). On T's part behind P's plane (a straddling T) the
  // shadows were cut away with it; front_part cuts sub there too.
  const Vec2 lo = c[0].cwiseMin(c[1]).cwiseMin(c[2]), hi = c[0].cwiseMax(c[1]).cwiseMax(c[2]);
  std::array<Vec2, 3> inward;  // normals of the edge lines (c[i], c[i+1]) towards sub (unnormalized)
  std::array<double, 3> edge2;      // squared lengths of the edges (c[i], c[i+1])
  std::array<double, 3> enter_tol;  // see clip_to_half_plane
  for (int i = 0; i < 3; ++i) {
    const Vec2 d = c[i + 1 < 3 ? i + 1 : 0] - c[i];
    inward[i] = Vec2(-d.y(), d.x());
    edge2[i] = d.squaredNorm();
    enter_tol[i] = m * std::sqrt(edge2[i]);  // the distance margin in the units of inward[i]
  }
  constexpr double kInf = std::numeric_limits<double>::infinity();
  thread_local std::vector<const PlaneShadow*> shadows;
  shadows.clear();
  for (const Index k : among) {
    if (k < 0 || static_cast<std::size_t>(k) >= plane.shadows.size())
      throw std::invalid_argument("Occluders::classify_within: shadow index " + std::to_string(k) +
                                  " is not in [0, " + std::to_string(plane.shadows.size()) + ")");
    const PlaneShadow& sh = plane.shadows[static_cast<std::size_t>(k)];
    if ((sh.hi.array() <= lo.array()).any() || (sh.lo.array() >= hi.array()).any()) continue;  // no common area
    // sub's corners against the shadow's edge lines: sub on the outer side of one line has no
    // area in common with the shadow; sub inside every line, with the tolerance of subtract_convex,
    // is covered (the subtraction of this shadow leaves nothing, whatever the other shadows).
    bool covered = true, missed = false;
    std::array<double, 3> depth = {kInf, kInf, kInf};  // distance of each corner inside the shadow's lines
    for (int j = 0; j < sh.lines && !missed; ++j) {
      const double d0 = (c[0] - sh.line_at[j]).dot(sh.line_in[j]);
      const double d1 = (c[1] - sh.line_at[j]).dot(sh.line_in[j]);
      const double d2 = (c[2] - sh.line_at[j]).dot(sh.line_in[j]);
      missed = std::max({d0, d1, d2}) <= 0;
      covered = covered && std::min({d0, d1, d2}) >= -m;
      depth = {std::min(depth[0], d0), std::min(depth[1], d1), std::min(depth[2], d2)};
    }
    if (missed) continue;
    if (covered) {
      meeting.clear();
      return ShaftClass::hidden;
    }
    // The shadow meets sub when a corner c_i of sub lies at depth r > margin inside it: the disk
    // of radius r about c_i is in the shadow, so the shadow enters sub farther than the margin
    // past each of sub's edge lines (the rejection of clip_to_half_plane, as may_meet does with
    // the planes of sub's shaft, cannot apply), and with the disk the triangle
    // (c_i, c_i + r' e, c_i + r' e') of sub (e, e' the unit directions of sub's edges at c_i,
    // r' = min(r, their lengths)), of area r'^2 sin(theta_i) / 2 with
    // sin(theta_i) = twice_area / (|edge| |edge'|), which must exceed the area margin.
    bool deep = false;
    for (int i = 0; i < 3 && !deep; ++i) {
      if (!(depth[i] > m)) continue;
      const double la2 = edge2[i], lb2 = edge2[i > 0 ? i - 1 : 2];
      const double r2 = std::min({depth[i] * depth[i], la2, lb2});
      deep = r2 * twice_area > 2 * area_margin * std::sqrt(la2 * lb2);
    }
    if (deep) {
      meeting.push_back(k);
      shadows.push_back(&sh);
      continue;
    }
    // Otherwise: rejected when the shadow enters sub by at most the margin past one of its edge
    // lines (as may_meet for a face within the margin outside a plane of the shaft), else the
    // area of the part inside sub, clipped to sub's edge lines (Sutherland-Hodgman
    // adds at most one corner per line: 8 + 3).
    std::array<Vec2, 12> buf_a, buf_b;
    const Vec2* cur = sh.p.data();
    Vec2* nxt = buf_a.data();
    Vec2* spare = buf_b.data();
    int n = sh.n;
    for (int i = 0; i < 3 && n >= 3; ++i) {
      const int clipped_n = clip_to_half_plane(cur, n, c[i], inward[i], enter_tol[i], nxt);
      if (clipped_n < 0) continue;  // the shadow is on sub's side of this edge line
      n = clipped_n;
      cur = nxt;
      std::swap(nxt, spare);
    }
    if (n < 3) continue;
    const double area_inside = cur == sh.p.data() ? sh.area : polygon_area(cur, n);
    if (!(area_inside > area_margin)) continue;
    meeting.push_back(k);
    shadows.push_back(&sh);
  }
  if (shadows.empty() && !straddles) return ShaftClass::full;
  // sub's front part minus the shadows on T: the same as minus their parts inside sub.
  thread_local Pieces pieces, other;
  front_part(c, tP, straddles, pieces);
  const double min_area = 1e-3 * area_margin;  // as visible_pieces
  if (!part) {
    // Only the class is asked: the fragments of the front part are taken depth first through the
    // shadows (the same fragments as shadow after shadow, each piece being cut independently), and
    // the class is partial as soon as the fragments that survive every shadow exceed the margin.
    const std::size_t S = shadows.size();
    thread_local std::vector<Pieces> stage;  // stage[j]: fragments still to cut by shadow j
    thread_local std::vector<Vec2> fragment;
    if (stage.size() < S + 1) stage.resize(S + 1);
    stage[0].swap(pieces);
    for (std::size_t j = 1; j <= S; ++j) stage[j].clear();
    double visible = 0;
    std::size_t j = 0;
    for (;;) {
      while (stage[j].end.empty() && j > 0) --j;
      Pieces& at = stage[j];
      if (at.end.empty()) break;
      const std::uint32_t end = at.end.back();
      const std::uint32_t begin = at.end.size() > 1 ? at.end[at.end.size() - 2] : 0;
      const double fragment_area = at.area.back();
      fragment.assign(at.pts.begin() + begin, at.pts.begin() + end);
      at.pts.resize(begin);
      at.end.pop_back();
      at.area.pop_back();
      if (j == S) {
        visible += fragment_area;
        if (visible > area_margin) {
          stage[0].swap(pieces);  // keep the buffers' capacity with this thread
          return ShaftClass::partial;
        }
        continue;
      }
      const PlaneShadow& sh = *shadows[j];
      subtract_convex_from_piece(fragment.data(), static_cast<int>(fragment.size()), fragment_area, sh.line_at.data(),
                                 sh.line_in.data(), sh.lines, sh.lo, sh.hi, m, min_area, stage[j + 1]);
      ++j;
    }
    stage[0].swap(pieces);
    meeting.clear();
    return ShaftClass::hidden;
  }
  thread_local Pieces covered;
  covered.clear();
  for (const PlaneShadow* sh : shadows) {
    if (pieces.end.empty()) break;
    subtract_convex(pieces, sh->line_at.data(), sh->line_in.data(), sh->lines, sh->lo, sh->hi, m, min_area, other,
                    &covered);
    pieces.swap(other);
  }
  double area = 0;
  for (const double a : pieces.area) area += a;
  if (!(area > area_margin)) {
    meeting.clear();
    return ShaftClass::hidden;
  }
  Impl::write(plane.origin, plane.u, plane.w, pieces, area, *part);
  part->whole_front = !straddles;
  Impl::write_covered(plane.origin, plane.u, plane.w, covered, *part);
  return ShaftClass::partial;
}

void Occluders::visible_part(const Vec3& P, const Vec3& nP, const std::array<Vec3, 3>& tau, const Vec3& nQ,
                             std::span<const Index> among, VisiblePart& out) const {
  out.clear();
  Shaft s;
  if (!make_shaft(P, nP, tau, nQ, impl_->margin, s)) return;
  if (s.grazing) among = {};
  complete_shaft(s);
  thread_local std::vector<Index> meeting;
  thread_local std::vector<Shadow> shadows;
  meeting.clear();
  shadows.clear();
  impl_->shadows_of(s, among, meeting, shadows);
  if (shadows.empty() && !s.straddles) {
    Impl::write_whole(s, out);
    return;
  }
  thread_local Pieces pieces, covered;
  const double area = impl_->visible_pieces(s, shadows, pieces, &covered);
  if (!(area > s.area_margin)) return;
  Impl::write(s, pieces, area, covered, out);
}

bool Occluders::visible(const Vec3& P, const Vec3& Q) const {
  if (impl_->faces.empty() || P == Q) return true;
  const K::Segment_3 segment(point(P), point(Q));
  Impl::BlockingSearch search{impl_.get(), P, Q};
  impl_->tree.traversal(segment, search);
  return !search.blocked;
}

}  // namespace panelrad::geometry

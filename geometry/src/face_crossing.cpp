// Rule "crossing" of validate_scene (scene_validation.hpp): no two triangles of the scene have a
// point interior to both. Faces may touch along edges or at points, shared or not (a block's
// bottom edges lying inside the triangles of an uncut floor), but a face that passes through
// another has no single side towards it, and the front side of each face is what the radiosity
// equation (1) integrates over.
//
// Candidate pairs: the triangles' bounding boxes (CGAL::box_self_intersection_d, closed boxes, so
// touching boxes are candidates). The decision for a pair (T1, T2) is exact:
// - the sides of T2's vertices relative to the plane of T1 (Epick orientation, exact). When they
//   are not all on the plane and no two are strictly on opposite sides, T2 meets that plane only
//   in the convex hull of its vertices on it (a vertex or an edge of T2, on its boundary): every
//   point of T1 /\ T2, so the midpoint of the intersection, is on T2's boundary, and the pair does
//   not cross. Likewise with T1 and T2 exchanged.
// - coplanar (all of T2 on T1's plane): the interiors meet iff the intersection has positive area,
//   iff no edge line of either triangle weakly separates them (separating axes: the interiors of
//   two convex polygons are disjoint iff the line of an edge of one of them has the other on its
//   closed outer side, since the edges of the Minkowski difference are the edges of the two).
//   Exact orientation predicates in the plane (coplanar_orientation).
// - otherwise each triangle strictly straddles the other's plane: the intersection S is computed
//   with exact constructions (Epeck), a point or a segment; they cross iff the midpoint of S
//   (S itself when a point) lies in the relative interior of both triangles.
// With `overlaps`, coplanar overlaps of two input faces are not refused here but listed: faces in
// contact are resolved once their front sides are known (contact_removal.cpp).
// The crossing point reported is that midpoint, or for a coplanar overlap the mean of the vertices
// of the (convex, positive-area) intersection polygon, an interior point of it.
#include "contact_removal.hpp"
#include "validation_internal.hpp"

#include <CGAL/Bbox_3.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace panelrad::geometry::validation_detail {

namespace {

using ExactKernel = CGAL::Exact_predicates_exact_constructions_kernel;
using ExactPoint = ExactKernel::Point_3;
using ExactTriangle = ExactKernel::Triangle_3;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, Index>;

bool has_index(const Tri& t, Index v) { return t[0] == v || t[1] == v || t[2] == v; }

/// How the vertices of `u` lie relative to the plane of `t`: +1 some strictly on each side, 0 all
/// on the plane, -1 otherwise (all on one closed side, not all on the plane).
int straddles(const std::vector<Point>& p, const Tri& t, const Tri& u) {
  bool pos = false, neg = false;
  for (Index v : u) {
    if (has_index(t, v)) continue;  // a shared vertex is on the plane
    const CGAL::Orientation o = CGAL::orientation(p[at(t[0])], p[at(t[1])], p[at(t[2])], p[at(v)]);
    pos = pos || o == CGAL::POSITIVE;
    neg = neg || o == CGAL::NEGATIVE;
  }
  if (pos && neg) return 1;
  return pos || neg ? -1 : 0;
}

/// Coplanar triangles: true when the line of an edge of `t` has all of `u` on its closed outer side.
bool edge_separates(const std::vector<Point>& p, const Tri& t, const Tri& u) {
  for (int s = 0; s < 3; ++s) {
    const Point& a = p[at(t[at(s)])];
    const Point& b = p[at(t[at((s + 1) % 3)])];
    const Point& c = p[at(t[at((s + 2) % 3)])];  // on the inner side of the line (a, b)
    bool inner = false;
    for (Index v : u) inner = inner || CGAL::coplanar_orientation(a, b, c, p[at(v)]) == CGAL::POSITIVE;
    if (!inner) return true;
  }
  return false;
}

ExactTriangle exact_triangle(const TriangleMesh& mesh, const Tri& t) {
  const auto e = [&](Index v) {
    const Vec3& x = mesh.vertices[at(v)];
    return ExactPoint(x.x(), x.y(), x.z());
  };
  return ExactTriangle(e(t[0]), e(t[1]), e(t[2]));
}

/// m, a point of triangle t, is in its relative interior: on none of its edges.
bool in_relative_interior(const ExactTriangle& t, const ExactPoint& m) {
  return !CGAL::collinear(t[0], t[1], m) && !CGAL::collinear(t[1], t[2], m) && !CGAL::collinear(t[2], t[0], m);
}

Vec3 to_vec(const ExactPoint& x) { return {CGAL::to_double(x.x()), CGAL::to_double(x.y()), CGAL::to_double(x.z())}; }

/// A point of the exact intersection of two triangles: the midpoint of a point or a segment, the
/// mean of the vertices of a triangle or a polygon. Empty when they do not meet.
struct Meeting {
  ExactPoint point;
  bool area = false;  // the intersection has positive area (a triangle or a polygon)
};
std::optional<Meeting> meeting_point(const ExactTriangle& t1, const ExactTriangle& t2) {
  const auto res = CGAL::intersection(t1, t2);
  if (!res) return std::nullopt;
  if (const auto* pt = boost::get<ExactPoint>(&*res)) return Meeting{*pt, false};
  if (const auto* sg = boost::get<ExactKernel::Segment_3>(&*res))
    return Meeting{CGAL::midpoint(sg->source(), sg->target()), false};
  if (const auto* tr = boost::get<ExactTriangle>(&*res)) return Meeting{CGAL::centroid((*tr)[0], (*tr)[1], (*tr)[2]), true};
  if (const auto* poly = boost::get<std::vector<ExactPoint>>(&*res)) {
    if (poly->empty()) return std::nullopt;
    ExactKernel::FT x(0), y(0), z(0);
    for (const ExactPoint& q : *poly) {
      x += q.x();
      y += q.y();
      z += q.z();
    }
    const ExactKernel::FT n(static_cast<double>(poly->size()));
    return Meeting{ExactPoint(x / n, y / n, z / n), true};
  }
  return std::nullopt;
}

/// The crossing point of triangles i and j, or nothing when they only touch or are apart.
/// `coplanar` is set when they overlap in one plane with positive area.
std::optional<Vec3> crossing_point(const TriangleMesh& mesh, const std::vector<Point>& p, Index i, Index j,
                                   bool& coplanar) {
  coplanar = false;
  const Tri& t1 = mesh.triangles[at(i)];
  const Tri& t2 = mesh.triangles[at(j)];
  const int s21 = straddles(p, t1, t2);
  if (s21 < 0) return std::nullopt;
  if (s21 == 0) {  // coplanar
    if (edge_separates(p, t1, t2) || edge_separates(p, t2, t1)) return std::nullopt;
    coplanar = true;
    const ExactTriangle e1 = exact_triangle(mesh, t1), e2 = exact_triangle(mesh, t2);
    const std::optional<Meeting> m = meeting_point(e1, e2);
    // The overlap has positive area, so the exact intersection is a triangle or a polygon; the
    // centroid of t1 is the fallback only should CGAL return a lower-dimensional form.
    return m ? to_vec(m->point) : to_vec(CGAL::centroid(e1[0], e1[1], e1[2]));
  }
  if (straddles(p, t2, t1) < 0) return std::nullopt;  // not 0: t1 is not on t2's plane, as t2 is not on t1's
  const ExactTriangle e1 = exact_triangle(mesh, t1), e2 = exact_triangle(mesh, t2);
  const std::optional<Meeting> m = meeting_point(e1, e2);
  if (!m) return std::nullopt;
  if (m->area || (in_relative_interior(e1, m->point) && in_relative_interior(e2, m->point))) return to_vec(m->point);
  return std::nullopt;
}

/// The distances of u's corners from the plane of t (double precision, plane_distance).
std::array<double, 3> corner_distances(const TriangleMesh& mesh, const Tri& t, const Tri& u) {
  const Vec3 &a = mesh.vertices[at(t[0])], &b = mesh.vertices[at(t[1])], &c = mesh.vertices[at(t[2])];
  return {plane_distance(a, b, c, mesh.vertices[at(u[0])]), plane_distance(a, b, c, mesh.vertices[at(u[1])]),
          plane_distance(a, b, c, mesh.vertices[at(u[2])])};
}

/// How deep u passes through the plane of t: the lesser of its corners' largest distances on
/// either side.
double depth_through(const std::array<double, 3>& d) {
  double pos = 0, neg = 0;
  for (double x : d) {
    pos = std::max(pos, x);
    neg = std::max(neg, -x);
  }
  return std::min(pos, neg);
}

/// Every corner of each of t and u within the tolerance of their faces f, g of the other's plane.
bool within_of(const TriangleMesh& mesh, const Tri& t, const Tri& u, double tol) {
  for (const auto& d : {corner_distances(mesh, t, u), corner_distances(mesh, u, t)})
    for (double x : d)
      if (!(std::abs(x) <= tol)) return false;
  return true;
}

/// All corners of u strictly on one side of the plane of t (exact): apart, not touching it.
bool strictly_one_side(const std::vector<Point>& p, const Tri& t, const Tri& u) {
  bool pos = false, neg = false, on = false;
  for (Index v : u) {
    const CGAL::Orientation o = CGAL::orientation(p[at(t[0])], p[at(t[1])], p[at(t[2])], p[at(v)]);
    pos = pos || o == CGAL::POSITIVE;
    neg = neg || o == CGAL::NEGATIVE;
    on = on || o == CGAL::COPLANAR;
  }
  return pos != neg && !on;
}

Vec3 centroid_of(const TriangleMesh& mesh, const Tri& t) {
  return (mesh.vertices[at(t[0])] + mesh.vertices[at(t[1])] + mesh.vertices[at(t[2])]) / 3.0;
}

/// The ContactTolerance of faces f and g (of triangles t and u) for the size of the two triangles.
double pair_tolerance(const TriangleMesh& mesh, const Tri& t, const Tri& u, const ContactTolerance& tolerance, Index f,
                      Index g) {
  double size = 0;
  for (const Tri* x : {&t, &u})
    for (int s = 0; s < 3; ++s)
      size = std::max(size, (mesh.vertices[at((*x)[at(s)])] - mesh.vertices[at((*x)[at((s + 1) % 3)])]).norm());
  return tolerance.of(f, g, size);
}

}  // namespace

std::optional<Failure> check_no_crossing(const TriangleMesh& mesh, const std::vector<Point>& pts,
                                         std::vector<Overlap>* overlaps, const ContactTolerance* tolerance) {
  const Sz nt = mesh.triangles.size();
  std::vector<Box> boxes;
  boxes.reserve(nt);
  for (Sz t = 0; t < nt; ++t) {
    const Tri& tr = mesh.triangles[t];
    boxes.emplace_back(pts[at(tr[0])].bbox() + pts[at(tr[1])].bbox() + pts[at(tr[2])].bbox(), static_cast<Index>(t));
  }
  std::vector<std::pair<Index, Index>> candidates;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
    const Index i = a.info(), j = b.info();
    if (i != j) candidates.emplace_back(std::min(i, j), std::max(i, j));
  });
  // The first crossing pair in triangle order, so that the message does not depend on the order
  // in which the boxes are reported.
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  for (const auto& [i, j] : candidates) {
    bool coplanar = false;
    const std::optional<Vec3> x = crossing_point(mesh, pts, i, j, coplanar);
    const Index fi = mesh.facet_of_triangle[at(i)], fj = mesh.facet_of_triangle[at(j)];
    if (!x) {
      // Not crossing, but one touching or passing through the other's plane within the rounding
      // of the numbers as written, or folded onto it across a shared edge (strictly apart both
      // ways is a gap: faces_across_a_gap).
      if (tolerance && overlaps && fi != fj) {
        const Tri &ti = mesh.triangles[at(i)], &tj = mesh.triangles[at(j)];
        if (straddles(pts, ti, tj) != 0 && !(strictly_one_side(pts, ti, tj) && strictly_one_side(pts, tj, ti))) {
          const double tol = pair_tolerance(mesh, ti, tj, *tolerance, fi, fj);
          if (within_of(mesh, ti, tj, tol) && projections_overlap(mesh, ti, tj, tol))
            overlaps->push_back({i, j, centroid_of(mesh, ti), false, true});
        }
      }
      continue;
    }
    const Describe d{mesh};
    if (coplanar && overlaps && fi != fj) {  // faces in contact, or given twice: remove_contacts decides
      overlaps->push_back({i, j, *x});
      continue;
    }
    std::string beyond, hint;
    if (!coplanar && tolerance && fi != fj) {
      // Within the rounding of the numbers as written: two faces in one plane (an overlap of
      // faces in contact), or touching (a side standing on a floor, through it by an ulp).
      const Tri &ti = mesh.triangles[at(i)], &tj = mesh.triangles[at(j)];
      const double tol = pair_tolerance(mesh, ti, tj, *tolerance, fi, fj);
      const std::array<double, 3> dij = corner_distances(mesh, ti, tj), dji = corner_distances(mesh, tj, ti);
      if (within_of(mesh, ti, tj, tol)) {
        if (overlaps && projections_overlap(mesh, ti, tj, tol)) overlaps->push_back({i, j, *x, false, true});
        continue;
      }
      const double depth = std::min(depth_through(dij), depth_through(dji));
      if (depth <= tol) continue;
      beyond = ", by " + sci(depth) + ", more than the rounding of their coordinates as written allows (" +
               sci(tol) + ")";
      double size = 0;
      std::vector<Vec3> corners;
      for (const Tri* t : {&ti, &tj})
        for (int s = 0; s < 3; ++s) {
          corners.push_back(mesh.vertices[at((*t)[at(s)])]);
          size = std::max(size, (mesh.vertices[at((*t)[at(s)])] - mesh.vertices[at((*t)[at((s + 1) % 3)])]).norm());
        }
      const double printed = std::max({printed_rounding(corners, size), tolerance->rounding[at(fi)], tolerance->rounding[at(fj)]});
      hint = more_digits_hint(printed, depth, 8, size);
    }
    const std::string faces = fi == fj ? d.face(fi) + " crosses itself" : d.faces(fi, fj) + " cross";
    return Failure{"crossing", faces + " at " + point_text(*x) + beyond + ": " + d.triangle(i) + " and " + d.triangle(j) +
                                   " have interior points in common, so neither lies on one side of the other and "
                                   "their front sides (what emits, reflects and is seen) are not defined there; "
                                   "split the faces along their intersection, or move one so that they only touch" +
                                   hint};
  }
  return std::nullopt;
}

}  // namespace panelrad::geometry::validation_detail

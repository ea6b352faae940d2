// Faces in contact (validate_scene, scene_validation.hpp): two faces that overlap in one plane with
// positive area and opposite front sides, as where a box stands on a floor, leans on a wall or
// touches another box. The front side of each looks into the other's back side: solid matter
// where the other face belongs to a closed piece, the opaque back of a one-sided sheet where it
// belongs to an open one (a block's bottom on a floor given as a sheet). Either way that part sees
// nothing and is seen by nothing: it is not a surface of the scene. It is cut out along the
// contact outline and removed from both faces; the rest of each stays, re-triangulated, with its
// facet id and front side. Two open sheets back to back keep both (a two-sided sheet); an open
// sheet's face that would vanish whole is refused (a window written on a wall). Overlaps with the
// same front side (z-fighting, a face given twice) are refused.
//
// The geometry is exact: the triangles are projected to the coordinate plane that drops the
// dominant axis of their common plane (exact: the two other coordinates are kept), the triangle
// and the triangles covering it are inserted as constraints into CGAL's constrained Delaunay
// triangulation with exact constructions (Epeck, Exact_intersections_tag), and each face of that
// triangulation is kept when its centroid lies inside the triangle and inside none of the covering
// ones (exact predicates: a face of the triangulation lies on one side of every constraint). Kept
// corners that are input vertices keep their index; new corners (where outlines cross) are lifted
// to the triangle's plane exactly and rounded once to double, shared between triangles by value.
// Constraints that cross are computed exactly (Exact_intersections_tag); CGAL's advice to use
// Constrained_triangulation_plus_2 instead is printed on stderr at every crossing, not for users.
#define CGAL_NO_CDT_2_WARNING
#include "contact_removal.hpp"
#include "canonical_diagonals.hpp"
#include "t_junctions.hpp"

#include <CGAL/Bbox_3.h>
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <utility>

namespace panelrad::geometry::validation_detail {

namespace {

using EK = CGAL::Exact_predicates_exact_constructions_kernel;
using EPoint2 = EK::Point_2;
using EPoint3 = EK::Point_3;
/// The input vertex at a triangulation vertex; kNone where outlines cross.
struct InputVertex {
  Index v = kNone;
};
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<InputVertex, EK>;
using FaceBase = CGAL::Constrained_triangulation_face_base_2<EK>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<EK, Tds, CGAL::Exact_intersections_tag>;

EPoint2 project(const Vec3& v, int axis) {
  const int u = (axis + 1) % 3, w = (axis + 2) % 3;
  return EPoint2(v[u], v[w]);
}

/// Orientation of the projected triangle: exact (the projection only drops a coordinate).
CGAL::Orientation projected_orientation(const TriangleMesh& mesh, const Tri& t, int axis) {
  return CGAL::orientation(project(mesh.vertices[at(t[0])], axis), project(mesh.vertices[at(t[1])], axis),
                           project(mesh.vertices[at(t[2])], axis));
}

double triangle_area(const Vec3& a, const Vec3& b, const Vec3& c) { return 0.5 * (b - a).cross(c - a).norm(); }

/// The part of triangle `t` inside none of `covers` (coplanar with it), as triangles of the same
/// orientation, their diagonals canonical (canonical_diagonals.hpp, corners within `tie` of a
/// circle a tie); new corners appended to `vertices` (shared by value through `made`).
std::vector<Tri> remainder(const TriangleMesh& mesh, Index t, const std::vector<Index>& covers, double tie,
                           std::vector<Vec3>& vertices, std::map<std::array<double, 3>, Index>& made) {
  const Tri& tr = mesh.triangles[at(t)];
  const Vec3 &a = mesh.vertices[at(tr[0])], &b = mesh.vertices[at(tr[1])], &c = mesh.vertices[at(tr[2])];
  const Vec3 n = (b - a).cross(c - a);
  int axis = 0;
  n.cwiseAbs().maxCoeff(&axis);
  const auto p2 = [&](Index v) { return project(mesh.vertices[at(v)], axis); };
  CDT cdt;
  const auto insert = [&](Index v) {
    const CDT::Vertex_handle h = cdt.insert(p2(v));
    h->info().v = v;
    return h;
  };
  const auto add_triangle = [&](const Tri& u) {
    const CDT::Vertex_handle h0 = insert(u[0]), h1 = insert(u[1]), h2 = insert(u[2]);
    cdt.insert_constraint(h0, h1);
    cdt.insert_constraint(h1, h2);
    cdt.insert_constraint(h2, h0);
  };
  add_triangle(tr);
  for (Index k : covers) add_triangle(mesh.triangles[at(k)]);
  const EK::Triangle_2 whole(p2(tr[0]), p2(tr[1]), p2(tr[2]));
  const CGAL::Orientation sign = whole.orientation();
  std::vector<EK::Triangle_2> cover_triangles;
  for (Index k : covers) {
    const Tri& u = mesh.triangles[at(k)];
    cover_triangles.emplace_back(p2(u[0]), p2(u[1]), p2(u[2]));
  }
  // The plane of t, exactly, to lift new corners.
  const EPoint3 ea(a.x(), a.y(), a.z()), eb(b.x(), b.y(), b.z()), ec(c.x(), c.y(), c.z());
  const EK::Plane_3 plane(ea, eb, ec);
  const int u_axis = (axis + 1) % 3, w_axis = (axis + 2) % 3;
  // A crossing of two outlines: (x_u, x_w) lifted to the plane, exactly, then rounded once.
  const auto lifted = [&](const CDT::Vertex_handle& h) {
    const EK::FT& xu = h->point().x();
    const EK::FT& xw = h->point().y();
    std::array<EK::FT, 3> coeff = {plane.a(), plane.b(), plane.c()};
    EK::FT rest = plane.d() + coeff[at(u_axis)] * xu + coeff[at(w_axis)] * xw;
    const EK::FT xa = -rest / coeff[at(axis)];
    std::array<double, 3> key{};
    // Rounded from the exact value, not from the lazy kernel's interval, so that the same point
    // reached through two triangles (the crossing of an outline with an edge they share) is the
    // same double, and so the same corner.
    key[at(axis)] = CGAL::to_double(CGAL::exact(xa));
    key[at(u_axis)] = CGAL::to_double(CGAL::exact(xu));
    key[at(w_axis)] = CGAL::to_double(CGAL::exact(xw));
    return key;
  };
  // The diagonals by the plane's own metric, not the projection's (canonical_diagonals.hpp): in the
  // orthonormal frame (u3, w3) of t's plane; ranked by input vertex number, crossings last.
  // Each corner placed once (a crossing's exact lift is costly), before the flips look them up.
  const Vec3 u3 = (b - a).normalized(), w3 = n.normalized().cross(u3);
  std::map<CDT::Vertex_handle, Eigen::Vector2d> places;
  for (auto v = cdt.finite_vertices_begin(); v != cdt.finite_vertices_end(); ++v) {
    Vec3 x;
    if (v->info().v != kNone) {
      x = mesh.vertices[at(v->info().v)];
    } else {
      const std::array<double, 3> key = lifted(v);
      x = Vec3(key[0], key[1], key[2]);
    }
    places.emplace(v, Eigen::Vector2d((x - a).dot(u3), (x - a).dot(w3)));
  }
  // A crossing within the tie of an input corner (an outline through a corner, crossed an ulp off
  // it in a rotated frame) ranks as that corner.
  std::map<CDT::Vertex_handle, std::int64_t> ranks;
  for (const auto& [v, x] : places) {
    std::int64_t r = std::numeric_limits<std::int64_t>::max();
    if (v->info().v != kNone) {
      r = v->info().v;
    } else {
      for (const auto& [w, y] : places)
        if (w->info().v != kNone && (y - x).norm() <= tie) r = std::min<std::int64_t>(r, w->info().v);
    }
    ranks.emplace(v, r);
  }
  const auto place = [&](const CDT::Vertex_handle& h) { return places.at(h); };
  const auto rank = [&](const CDT::Vertex_handle& h) { return ranks.at(h); };
  canonical_diagonals(cdt, place, rank, tie);
  const auto corner = [&](const CDT::Vertex_handle& h) -> Index {
    if (h->info().v != kNone) return h->info().v;  // of t or of a covering triangle (coplanar)
    const std::array<double, 3> key = lifted(h);
    const auto [it, fresh] = made.emplace(key, static_cast<Index>(vertices.size()));
    if (fresh) vertices.emplace_back(key[0], key[1], key[2]);
    return it->second;
  };
  std::vector<Tri> out;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    const EPoint2 m = CGAL::centroid(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point());
    if (whole.bounded_side(m) != CGAL::ON_BOUNDED_SIDE) continue;
    bool covered = false;
    for (const EK::Triangle_2& k : cover_triangles) covered = covered || k.bounded_side(m) == CGAL::ON_BOUNDED_SIDE;
    if (covered) continue;
    Tri piece{corner(f->vertex(0)), corner(f->vertex(1)), corner(f->vertex(2))};
    if (CGAL::orientation(f->vertex(0)->point(), f->vertex(1)->point(), f->vertex(2)->point()) != sign)
      std::swap(piece[1], piece[2]);
    out.push_back(piece);
  }
  return out;
}

/// The corners of input face f (sorted vertex indices of its triangles).
std::vector<Index> polygon_corners(const TriangleMesh& mesh, Index f) {
  std::vector<Index> v;
  for (Sz t = 0; t < mesh.triangles.size(); ++t)
    if (mesh.facet_of_triangle[t] == f) v.insert(v.end(), mesh.triangles[t].begin(), mesh.triangles[t].end());
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

/// Faces f and g are one polygon: the same corners (the readers merge coincident vertices, so a
/// polygon written twice on separate vertices has the same corners too), triangulated either way.
bool same_polygon(const TriangleMesh& mesh, Index f, Index g) { return polygon_corners(mesh, f) == polygon_corners(mesh, g); }

}  // namespace

std::vector<Overlap> copies_of_one_polygon(const TriangleMesh& mesh, double tol) {
  const Sz nf = at(mesh.num_facets);
  std::vector<std::vector<Index>> corners(nf), triangles(nf);
  for (Sz t = 0; t < mesh.triangles.size(); ++t) {
    const Sz f = at(mesh.facet_of_triangle[t]);
    corners[f].insert(corners[f].end(), mesh.triangles[t].begin(), mesh.triangles[t].end());
    triangles[f].push_back(static_cast<Index>(t));
  }
  std::map<std::vector<Index>, std::vector<Index>> faces_on;
  for (Sz f = 0; f < nf; ++f) {
    std::sort(corners[f].begin(), corners[f].end());
    corners[f].erase(std::unique(corners[f].begin(), corners[f].end()), corners[f].end());
    if (!corners[f].empty()) faces_on[corners[f]].push_back(static_cast<Index>(f));
  }
  std::vector<Overlap> out;
  for (const auto& [c, faces] : faces_on)
    for (Sz a = 0; a < faces.size(); ++a)
      for (Sz b = a + 1; b < faces.size(); ++b)
        for (Index ti : triangles[at(faces[a])])
          for (Index tj : triangles[at(faces[b])]) {
            const Tri &x = mesh.triangles[at(ti)], &y = mesh.triangles[at(tj)];
            if (!projections_overlap(mesh, x, y, tol)) continue;
            const Vec3 centre = (mesh.vertices[at(x[0])] + mesh.vertices[at(x[1])] + mesh.vertices[at(x[2])]) / 3.0;
            out.push_back({std::min(ti, tj), std::max(ti, tj), centre, false, true});
          }
  return out;
}

namespace {

/// A mesh whose triangles were cut by cut_covered.
struct CutMesh {
  TriangleMesh mesh;
  std::vector<Index> origin;              ///< per triangle of `mesh`, the triangle it is (part of)
  std::vector<double> removed_of_facet;   ///< per input face, the area removed
  Sz triangles_cut = 0;                   ///< triangles with covers (cut or removed)
};

/// Each triangle t minus the union of covers[t] (triangles coplanar with it), re-triangulated by
/// remainder(), without the pieces no higher than `sliver`; the others kept as they are. Facet ids
/// and orientations kept; vertices no triangle uses any more dropped, the order of the others kept.
CutMesh cut_covered(const TriangleMesh& mesh, const std::vector<std::vector<Index>>& covers, double sliver) {
  CutMesh out;
  out.mesh.num_facets = mesh.num_facets;
  out.mesh.source = mesh.source;
  out.mesh.facet_line = mesh.facet_line;
  out.mesh.facet_group = mesh.facet_group;
  out.removed_of_facet.assign(at(mesh.num_facets), 0.0);
  std::map<std::array<double, 3>, Index> made;
  for (Sz v = 0; v < mesh.vertices.size(); ++v)
    made.emplace(std::array<double, 3>{mesh.vertices[v].x(), mesh.vertices[v].y(), mesh.vertices[v].z()}, static_cast<Index>(v));
  std::vector<Vec3> vertices = mesh.vertices;
  const Sz nt = mesh.triangles.size();
  for (Sz t = 0; t < nt; ++t) {
    const Index f = mesh.facet_of_triangle[t];
    if (covers[t].empty()) {
      out.mesh.triangles.push_back(mesh.triangles[t]);
      out.mesh.facet_of_triangle.push_back(f);
      out.origin.push_back(static_cast<Index>(t));
      continue;
    }
    const std::vector<Tri> rest = remainder(mesh, static_cast<Index>(t), covers[t], sliver, vertices, made);
    const Tri& tr = mesh.triangles[t];
    double kept = 0;
    for (const Tri& r : rest) {
      // Two corners of the exact cut that round to one double, or three that round onto one line:
      // a sliver narrower than the rounding, dropped (no area, nothing to see).
      const auto pt = [&](Index v) { return Point(vertices[at(v)].x(), vertices[at(v)].y(), vertices[at(v)].z()); };
      if (r[0] == r[1] || r[1] == r[2] || r[2] == r[0] || CGAL::collinear(pt(r[0]), pt(r[1]), pt(r[2]))) continue;
      const Vec3 &a = vertices[at(r[0])], &b = vertices[at(r[1])], &c = vertices[at(r[2])];
      const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
      if (2 * triangle_area(a, b, c) <= sliver * longest) continue;  // its height: a slit below the resolution
      kept += triangle_area(vertices[at(r[0])], vertices[at(r[1])], vertices[at(r[2])]);
      out.mesh.triangles.push_back(r);
      out.mesh.facet_of_triangle.push_back(f);
      out.origin.push_back(static_cast<Index>(t));
    }
    const double whole = triangle_area(mesh.vertices[at(tr[0])], mesh.vertices[at(tr[1])], mesh.vertices[at(tr[2])]);
    out.removed_of_facet[at(f)] += std::max(0.0, whole - kept);
    ++out.triangles_cut;
  }
  out.mesh.vertices = std::move(vertices);
  drop_unused_vertices(out.mesh);
  return out;
}

/// Where the vertices of `u` lie relative to the plane of `t` (exact): +1 all on the front side
/// or on the plane (front: opposite to the geometric normal), -1 all behind or on it, 0 mixed or
/// all on it.
int side_of(const std::vector<Point>& p, const Tri& t, const Tri& u) {
  bool front = false, back = false;
  for (Index v : u) {
    const CGAL::Orientation o = CGAL::orientation(p[at(t[0])], p[at(t[1])], p[at(t[2])], p[at(v)]);
    front = front || o == CGAL::NEGATIVE;  // the geometric normal points to the back
    back = back || o == CGAL::POSITIVE;
  }
  return front == back ? 0 : front ? 1 : -1;
}

}  // namespace

/// The projections of t and u along the dominant axis of t's normal overlap by more than `tol`:
/// no edge line of either has all of the other within `tol` on its inner side (separating axes,
/// in double precision: faces meeting along an edge within the rounding of their corners, as
/// two flush sides of a step, only touch).
bool projections_overlap(const TriangleMesh& mesh, const Tri& t, const Tri& u, double tol) {
  const Vec3& a = mesh.vertices[at(t[0])];
  int axis = 0;
  (mesh.vertices[at(t[1])] - a).cross(mesh.vertices[at(t[2])] - a).cwiseAbs().maxCoeff(&axis);
  const int p = (axis + 1) % 3, q = (axis + 2) % 3;
  const auto pt = [&](Index v) { return Eigen::Vector2d(mesh.vertices[at(v)][p], mesh.vertices[at(v)][q]); };
  const auto cross = [](const Eigen::Vector2d& x, const Eigen::Vector2d& y) { return x.x() * y.y() - x.y() * y.x(); };
  const auto separated = [&](const Tri& x, const Tri& y) {
    const double o = cross(pt(x[1]) - pt(x[0]), pt(x[2]) - pt(x[0]));
    if (o == 0) return true;
    for (int s = 0; s < 3; ++s) {
      const Eigen::Vector2d e0 = pt(x[at(s)]), e = pt(x[at((s + 1) % 3)]) - e0;
      const double length = e.norm();
      bool inner = false;
      for (Index v : y) inner = inner || std::copysign(1.0, o) * cross(e, pt(v) - e0) > tol * length;
      if (!inner) return true;
    }
    return false;
  };
  return !separated(t, u) && !separated(u, t);
}

std::vector<std::pair<Index, Index>> nearby_triangle_pairs(const TriangleMesh& mesh, double widen) {
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, Index>;
  std::vector<Box> boxes;
  boxes.reserve(mesh.triangles.size());
  for (Sz t = 0; t < mesh.triangles.size(); ++t) {
    Vec3 lo = mesh.vertices[at(mesh.triangles[t][0])], hi = lo;
    for (Index v : mesh.triangles[t]) {
      lo = lo.cwiseMin(mesh.vertices[at(v)]);
      hi = hi.cwiseMax(mesh.vertices[at(v)]);
    }
    boxes.emplace_back(CGAL::Bbox_3(lo.x() - widen, lo.y() - widen, lo.z() - widen, hi.x() + widen, hi.y() + widen,
                                    hi.z() + widen),
                       static_cast<Index>(t));
  }
  std::vector<std::pair<Index, Index>> pairs;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
    pairs.emplace_back(std::min(a.info(), b.info()), std::max(a.info(), b.info()));
  });
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

bool corners_near_plane(const TriangleMesh& mesh, const Tri& t, const Tri& u, double tol) {
  const Vec3 &a = mesh.vertices[at(t[0])], &b = mesh.vertices[at(t[1])], &c = mesh.vertices[at(t[2])];
  for (Index v : u)
    if (!(std::abs(plane_distance(a, b, c, mesh.vertices[at(v)])) <= tol)) return false;
  return true;
}

double longest_edge(const TriangleMesh& mesh, const Tri& t) {
  double s = 0;
  for (int k = 0; k < 3; ++k) s = std::max(s, (mesh.vertices[at(t[at(k)])] - mesh.vertices[at(t[at((k + 1) % 3)])]).norm());
  return s;
}

std::vector<Overlap> faces_across_a_gap(const TriangleMesh& mesh, const ContactTolerance& tolerance) {
  std::vector<Overlap> out;
  if (!(tolerance.resolution > 0)) return out;
  const std::vector<Point> p = exact_points(mesh);
  // Wide enough for any pair of the scene.
  const std::vector<std::pair<Index, Index>> candidates =
      nearby_triangle_pairs(mesh, largest_tolerance(tolerance, diameter(mesh)));
  for (const auto& [i, j] : candidates) {
    const Tri &ti = mesh.triangles[at(i)], &tj = mesh.triangles[at(j)];
    if (mesh.facet_of_triangle[at(i)] == mesh.facet_of_triangle[at(j)]) continue;
    // Each strictly on one side of the other's plane (an exactly coplanar pair is an overlap of
    // check_no_crossing already). Back to back, neither sees the other anyway; facing each other
    // they are a contact, facing the same way the same surface twice (remove_contacts decides).
    const int si = side_of(p, ti, tj), sj = side_of(p, tj, ti);
    if (si == 0 || sj == 0) continue;
    const Index fi = mesh.facet_of_triangle[at(i)], fj = mesh.facet_of_triangle[at(j)];
    const double size = std::max(longest_edge(mesh, ti), longest_edge(mesh, tj));
    // Back to back, neither sees the other: apart, unless within the rounding of their corners
    // as written (a box's bottom an ulp below the floor it stands on: in contact).
    const bool back_to_back = si == -1 && sj == -1;
    const double tol = back_to_back ? rounding_tolerance(tolerance, fi, fj, size) : tolerance.of(fi, fj, size);
    if (!(tol > 0)) continue;
    if (!corners_near_plane(mesh, ti, tj, tol) || !corners_near_plane(mesh, tj, ti, tol)) continue;
    if (!projections_overlap(mesh, ti, tj, tol)) continue;
    const Vec3 ci = (mesh.vertices[at(ti[0])] + mesh.vertices[at(ti[1])] + mesh.vertices[at(ti[2])]) / 3.0;
    out.push_back({i, j, ci, !back_to_back, back_to_back});
  }
  return out;
}

std::optional<Failure> remove_contacts(TriangleMesh& mesh, const std::vector<Overlap>& overlaps,
                                       const std::vector<char>& in_closed_piece, double resolution,
                                       double sliver, ContactReport& out) {
  out.removed_of_facet.resize(at(mesh.num_facets), 0.0);
  if (overlaps.empty()) return std::nullopt;
  const Describe d{mesh};
  const Sz nt = mesh.triangles.size();
  std::vector<std::vector<Index>> covers(nt);
  for (const Overlap& o : overlaps) {
    const Index i = o.i, j = o.j;
    const Tri &ti = mesh.triangles[at(i)], &tj = mesh.triangles[at(j)];
    int axis = 0;
    ((mesh.vertices[at(ti[1])] - mesh.vertices[at(ti[0])]).cross(mesh.vertices[at(ti[2])] - mesh.vertices[at(ti[0])]))
        .cwiseAbs()
        .maxCoeff(&axis);
    const Index fi = mesh.facet_of_triangle[at(i)], fj = mesh.facet_of_triangle[at(j)];
    const std::string faces = d.faces(fi, fj);
    const std::string triangles = " (" + d.triangle(i) + " and " + d.triangle(j) + ")";
    if (projected_orientation(mesh, ti, axis) == projected_orientation(mesh, tj, axis)) {
      if (same_polygon(mesh, fi, fj))
        return Failure{"crossing", d.face(fj) + " duplicates " + d.face(fi) +
                                       ": the same polygon with the same front side, so which of the two is seen is "
                                       "not defined; remove one of them (a surface seen from both sides is the "
                                       "polygon given twice with opposite windings, away from any solid)"};
      const std::string what =
          o.across_gap ? faces + " lie closer than the visibility's resolution (" + sci(resolution) +
                             ") with the same front side at " + point_text(o.point)
                       : faces + " overlap in one plane with the same front side at " + point_text(o.point);
      return Failure{"crossing", what + triangles +
                                     ": the surface is there twice, so which of the two is seen is not defined; "
                                     "remove one of them, or cut them so that they only touch (an opening in a wall: the "
                                     "wall as polygons around it, the opening a face of its own)"};
    }
    if (!in_closed_piece[at(i)] && !in_closed_piece[at(j)]) {
      if (o.across_gap)
        return Failure{"crossing", faces + " face each other across a gap below the visibility's resolution (" +
                                       sci(resolution) + ") at " + point_text(o.point) + triangles +
                                       ", and neither belongs to a closed piece: they can be told neither apart "
                                       "nor in contact; move them apart by more than that, or make them touch"};
      // Back to back in one plane, neither bounding matter: a two-sided sheet where they overlap.
      // Both stay, each seen from its own front side; neither covers the other.
      out.two_sided.insert(std::minmax(fi, fj));
      continue;
    }
    if (o.across_gap) ++out.across_gap;
    // Opposite front sides, one of them bounding matter: each covers the other. A face against a
    // closed piece's face looks into its solid; a face against an open sheet's back (a block's
    // bottom on a one-sided floor) looks into that opaque back at distance 0, so it sees nothing
    // and nothing sees it: neither is a surface of the scene there.
    covers[at(i)].push_back(j);
    covers[at(j)].push_back(i);
  }
  CutMesh cut = cut_covered(mesh, covers, sliver);
  for (Sz f = 0; f < cut.removed_of_facet.size(); ++f) out.removed_of_facet[f] += cut.removed_of_facet[f];
  out.triangles_cut += cut.triangles_cut;
  // An open piece's face wholly against a solid's face, its front side looking into the matter:
  // none of it would be seen, and dropping it without a word hides what the file says (a window
  // written as a polygon on a wall, a lamp given on the face of a body).
  std::vector<char> kept_facet(at(mesh.num_facets), 0), open_facet(at(mesh.num_facets), 0);
  for (Index f : cut.mesh.facet_of_triangle) kept_facet[at(f)] = 1;
  for (Sz t = 0; t < nt; ++t)
    if (!in_closed_piece[t]) open_facet[at(mesh.facet_of_triangle[t])] = 1;
  for (const Overlap& o : overlaps) {
    for (const auto& [mine, other] : {std::pair{o.i, o.j}, std::pair{o.j, o.i}}) {
      const Index f = mesh.facet_of_triangle[at(mine)], g = mesh.facet_of_triangle[at(other)];
      if (kept_facet[at(f)] || !open_facet[at(f)] || !in_closed_piece[at(other)]) continue;
      return Failure{"crossing",
                     (same_polygon(mesh, f, g) ? d.face(f) + " duplicates " + d.face(g) + ", with the opposite winding,"
                                               : d.face(f) + " lies wholly on " + d.face(g)) +
                         " of a closed surface, its front side looking into that surface's solid matter, so none of "
                         "it would be seen. To cut an opening (a window) into a wall, leave the opening out of the "
                         "wall's polygons (the wall as polygons around the opening) and give the opening as a face "
                         "of its own, its front side facing the room; a face lying on a solid's face facing the "
                         "room is given as part of that face"};
    }
  }
  for (const Overlap& o : overlaps) {
    const auto pair = std::minmax(mesh.facet_of_triangle[at(o.i)], mesh.facet_of_triangle[at(o.j)]);
    if (!out.two_sided.count(pair)) out.pairs.insert(pair);
  }
  mesh = std::move(cut.mesh);
  return std::nullopt;
}

void close_gaps(TriangleMesh& mesh, const std::vector<Overlap>& across_gap) {
  const auto normal = [&](const Tri& t) {
    return Vec3((mesh.vertices[at(t[1])] - mesh.vertices[at(t[0])]).cross(mesh.vertices[at(t[2])] - mesh.vertices[at(t[0])]));
  };
  for (const Overlap& o : across_gap) {
    // The larger triangle's plane is the better determined: its corners' rounding tilts it by
    // about rounding / its size, and the smaller one's corners lie within about their own
    // distance of it. (The plane of a small triangle, extended over a large one, would move the
    // large one's far corners by the rounding times their distance over the small one's size.)
    Index to = o.i, moved = o.j;
    if (normal(mesh.triangles[at(o.j)]).norm() > normal(mesh.triangles[at(o.i)]).norm()) std::swap(to, moved);
    const Tri &ti = mesh.triangles[at(to)], &tj = mesh.triangles[at(moved)];
    int axis = 0;
    const Vec3 n = normal(ti);
    n.cwiseAbs().maxCoeff(&axis);
    if (projected_orientation(mesh, ti, axis) == projected_orientation(mesh, tj, axis)) continue;  // refused later
    // Onto the plane of ti (the larger) along its unit normal; exact for a plane normal to an axis.
    const Vec3 a = mesh.vertices[at(ti[0])];
    const Vec3 u = n.normalized();
    const bool axis_plane = n.cwiseAbs().maxCoeff() == n.norm();
    for (Index v : tj) {
      Vec3& x = mesh.vertices[at(v)];
      if (axis_plane)
        x[axis] = a[axis];
      else
        x -= u.dot(x - a) * u;
    }
  }
}

double ContactReport::area_removed() const {
  double a = 0;
  for (double r : removed_of_facet) a += r;
  return a;
}

std::vector<ContactReport::Touch> ContactReport::touching() const {
  std::vector<Touch> t;
  for (const auto& [a, b] : pairs) t.push_back({a, b, removed_of_facet[at(a)], removed_of_facet[at(b)]});
  return t;
}

bool merge_contacts_into_closed_pieces(TriangleMesh& mesh, std::vector<Overlap>& overlaps, ScenePieces& pieces,
                                       const ContactTolerance& tolerance, ContactReport& out) {
  const Sz nt = mesh.triangles.size();
  // Candidates: overlaps in one plane (or within the rounding, or across a gap below the
  // tolerance) between open pieces as the faces are written, wound either way (a solid wound
  // against the other: its pieces are oriented once joined).
  std::vector<Overlap> candidates = overlaps;
  if (candidates.empty()) return false;
  ScenePieces written;
  {
    TriangleMesh copy = mesh;
    if (orient_scene_pieces(copy, written)) written.in_closed_piece.assign(nt, 0);
  }
  std::erase_if(candidates, [&](const Overlap& o) { return written.in_closed_piece[at(o.i)] || written.in_closed_piece[at(o.j)]; });
  if (candidates.empty()) return false;
  // Contacts: triangles joined by candidate overlaps (union-find).
  std::vector<Index> parent(nt);
  for (Sz t = 0; t < nt; ++t) parent[t] = static_cast<Index>(t);
  const std::function<Index(Index)> root = [&](Index t) {
    while (parent[at(t)] != t) t = parent[at(t)] = parent[at(parent[at(t)])];
    return t;
  };
  for (const Overlap& o : candidates) parent[at(root(o.i))] = root(o.j);
  // The edges of the input triangles, to find the triangles next to a contact.
  std::map<std::pair<Index, Index>, std::vector<Index>> edge_triangles;
  for (Sz t = 0; t < nt; ++t)
    for (int s = 0; s < 3; ++s)
      edge_triangles[std::minmax(mesh.triangles[t][at(s)], mesh.triangles[t][at((s + 1) % 3)])].push_back(
          static_cast<Index>(t));
  // Pieces of a cut no higher than the largest contact tolerance are a slit within the rounding.
  const double sliver = largest_tolerance(tolerance, diameter(mesh));
  std::set<Index> refused;  // contacts (roots) left as they are
  for (;;) {
    std::vector<std::vector<Index>> covers(nt);
    for (const Overlap& o : candidates)
      if (!refused.count(root(o.i))) {
        covers[at(o.i)].push_back(o.j);
        covers[at(o.j)].push_back(o.i);
      }
    CutMesh cut = cut_covered(mesh, covers, sliver);
    join_close_corners(cut.mesh, tolerance.resolution, &cut.origin);
    if (cut.mesh.triangles.empty()) return false;
    // The cut leaves a side of a solid whose edge the other solid's sides now meet in two pieces
    // (a step: the upper box's side and the rest of the lower box's top): split there.
    split_t_junctions(cut.mesh, &cut.origin, largest_tolerance(tolerance, diameter(cut.mesh)));
    ScenePieces trial;
    if (orient_scene_pieces(cut.mesh, trial)) return false;
    // Its rim: what is left of the contact's triangles, and the uncut triangles sharing an edge
    // with them. Two solids in contact join into one closed surface across it; anything else
    // (two sheets back to back, a polygon given twice) leaves no rim, or an open one.
    std::vector<std::set<Index>> next_to(nt);  // per uncut triangle, the contacts it borders
    for (Sz t = 0; t < nt; ++t) {
      if (covers[t].empty()) continue;
      for (int s = 0; s < 3; ++s)
        for (Index u : edge_triangles[std::minmax(mesh.triangles[t][at(s)], mesh.triangles[t][at((s + 1) % 3)])])
          if (covers[at(u)].empty()) next_to[at(u)].insert(root(static_cast<Index>(t)));
    }
    std::map<Index, int> rim_state;  // root -> 1 closed rim, 0 open
    for (Sz t = 0; t < nt; ++t)
      if (!covers[t].empty()) rim_state.emplace(root(static_cast<Index>(t)), 1);
    std::map<Index, bool> has_rim;
    for (Sz k = 0; k < cut.origin.size(); ++k) {
      const Index t = cut.origin[k];
      std::set<Index> groups = next_to[at(t)];
      if (!covers[at(t)].empty()) groups.insert(root(t));
      for (Index r : groups) {
        has_rim[r] = true;
        if (!trial.in_closed_piece[k]) rim_state[r] = 0;
      }
    }
    bool all_closed = true;
    for (const auto& [r, closed] : rim_state)
      if (!closed || !has_rim[r]) {
        refused.insert(r);
        all_closed = false;
      }
    if (!all_closed) continue;
    if (rim_state.empty()) return false;
    // Accepted: the overlaps are found again on the cut mesh (what is left of the contacts' faces
    // meets nothing; other overlaps are renumbered).
    std::vector<Overlap> again;
    if (check_no_crossing(cut.mesh, exact_points(cut.mesh), &again, &tolerance)) return false;
    out.removed_of_facet.resize(at(mesh.num_facets), 0.0);
    for (Sz f = 0; f < cut.removed_of_facet.size(); ++f) out.removed_of_facet[f] += cut.removed_of_facet[f];
    out.triangles_cut += cut.triangles_cut;
    for (const Overlap& o : candidates)
      if (!refused.count(root(o.i))) out.pairs.insert(std::minmax(mesh.facet_of_triangle[at(o.i)], mesh.facet_of_triangle[at(o.j)]));
    mesh = std::move(cut.mesh);
    overlaps = std::move(again);
    pieces = std::move(trial);
    return true;
  }
}

}  // namespace panelrad::geometry::validation_detail

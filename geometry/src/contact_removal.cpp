// Faces in contact (validate_scene, scene_validation.hpp): two faces that overlap in one plane with
// positive area and opposite front sides, as where a box stands on a floor, leans on a wall or
// touches another box. The front side of each looks into the other's back side, so where the
// other face belongs to a closed piece, what it looks into is solid matter: that part is not a
// surface of the scene. It is cut out along the contact outline and removed; the rest of the face
// stays, re-triangulated, with its facet id and front side. Where the other face belongs to an
// open piece (a one-sided sheet, which bounds no matter), nothing is removed: a partition given as
// two coincident sheets back to back keeps both. Overlaps with the same front side (z-fighting,
// a face given twice) are refused.
//
// The geometry is exact: the triangles are projected to the coordinate plane that drops the
// dominant axis of their common plane (exact: the two other coordinates are kept), the triangle
// and the triangles covering it are inserted as constraints into CGAL's constrained Delaunay
// triangulation with exact constructions (Epeck, Exact_intersections_tag), and each face of that
// triangulation is kept when its centroid lies inside the triangle and inside none of the covering
// ones (exact predicates: a face of the triangulation lies on one side of every constraint). Kept
// corners that are input vertices keep their index; new corners (where outlines cross) are lifted
// to the triangle's plane exactly and rounded once to double, shared between triangles by value.
#include "contact_removal.hpp"

#include <CGAL/Bbox_3.h>
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
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
/// orientation; new corners appended to `vertices` (shared by value through `made`).
std::vector<Tri> remainder(const TriangleMesh& mesh, Index t, const std::vector<Index>& covers,
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
  const auto corner = [&](const CDT::Vertex_handle& h) -> Index {
    if (h->info().v != kNone) return h->info().v;  // of t or of a covering triangle (coplanar)
    // A crossing of two outlines: lift (x_u, x_w) to the plane, exactly, then round once.
    const EK::FT& xu = h->point().x();
    const EK::FT& xw = h->point().y();
    std::array<EK::FT, 3> coeff = {plane.a(), plane.b(), plane.c()};
    EK::FT rest = plane.d() + coeff[at(u_axis)] * xu + coeff[at(w_axis)] * xw;
    const EK::FT xa = -rest / coeff[at(axis)];
    std::array<double, 3> key{};
    key[at(axis)] = CGAL::to_double(xa);
    key[at(u_axis)] = CGAL::to_double(xu);
    key[at(w_axis)] = CGAL::to_double(xw);
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

/// The triangles' projections (dropping `axis`) overlap with positive area: no edge line of
/// either weakly separates them (exact 2-D orientations of the projected corners).
bool projections_overlap(const TriangleMesh& mesh, const Tri& t, const Tri& u, int axis) {
  const auto separated = [&](const Tri& a, const Tri& b) {
    const CGAL::Orientation o = projected_orientation(mesh, a, axis);
    for (int s = 0; s < 3; ++s) {
      const EPoint2 p = project(mesh.vertices[at(a[at(s)])], axis), q = project(mesh.vertices[at(a[at((s + 1) % 3)])], axis);
      bool inner = false;
      for (Index v : b) inner = inner || CGAL::orientation(p, q, project(mesh.vertices[at(v)], axis)) == o;
      if (!inner) return true;
    }
    return false;
  };
  return !separated(t, u) && !separated(u, t);
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

std::vector<Overlap> faces_across_a_gap(const TriangleMesh& mesh, double resolution) {
  std::vector<Overlap> out;
  if (!(resolution > 0)) return out;
  const std::vector<Point> p = exact_points(mesh);
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, Index>;
  std::vector<Box> boxes;
  boxes.reserve(mesh.triangles.size());
  for (Sz t = 0; t < mesh.triangles.size(); ++t) {
    const Tri& tr = mesh.triangles[t];
    CGAL::Bbox_3 b = p[at(tr[0])].bbox() + p[at(tr[1])].bbox() + p[at(tr[2])].bbox();
    b = CGAL::Bbox_3(b.xmin() - resolution, b.ymin() - resolution, b.zmin() - resolution, b.xmax() + resolution,
                     b.ymax() + resolution, b.zmax() + resolution);
    boxes.emplace_back(b, static_cast<Index>(t));
  }
  std::vector<std::pair<Index, Index>> candidates;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
    candidates.emplace_back(std::min(a.info(), b.info()), std::max(a.info(), b.info()));
  });
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  const auto near_plane = [&](const Tri& t, const Tri& u) {
    const Vec3 &a = mesh.vertices[at(t[0])], &b = mesh.vertices[at(t[1])], &c = mesh.vertices[at(t[2])];
    for (Index v : u)
      if (!(std::abs(plane_distance(a, b, c, mesh.vertices[at(v)])) <= resolution)) return false;
    return true;
  };
  for (const auto& [i, j] : candidates) {
    const Tri &ti = mesh.triangles[at(i)], &tj = mesh.triangles[at(j)];
    if (mesh.facet_of_triangle[at(i)] == mesh.facet_of_triangle[at(j)]) continue;
    // Each strictly on one side of the other's plane (an exactly coplanar pair is an overlap of
    // check_no_crossing already). Back to back, neither sees the other anyway; facing each other
    // they are a contact, facing the same way the same surface twice (remove_contacts decides).
    const int si = side_of(p, ti, tj), sj = side_of(p, tj, ti);
    if (si == 0 || sj == 0 || (si == -1 && sj == -1)) continue;
    if (!near_plane(ti, tj) || !near_plane(tj, ti)) continue;
    int axis = 0;
    ((mesh.vertices[at(ti[1])] - mesh.vertices[at(ti[0])]).cross(mesh.vertices[at(ti[2])] - mesh.vertices[at(ti[0])]))
        .cwiseAbs()
        .maxCoeff(&axis);
    if (!projections_overlap(mesh, ti, tj, axis)) continue;
    const Vec3 ci = (mesh.vertices[at(ti[0])] + mesh.vertices[at(ti[1])] + mesh.vertices[at(ti[2])]) / 3.0;
    out.push_back({i, j, ci, true});
  }
  return out;
}

std::optional<Failure> remove_contacts(TriangleMesh& mesh, const std::vector<Overlap>& overlaps,
                                       const std::vector<char>& in_closed_piece, double resolution,
                                       ContactReport& out) {
  out.removed_of_facet.resize(at(mesh.num_facets), 0.0);
  if (overlaps.empty()) return std::nullopt;
  const Describe d{mesh};
  const Sz nt = mesh.triangles.size();
  std::vector<std::vector<Index>> covers(nt);
  const auto point_text = [](const Vec3& x) { return "(" + num(x.x()) + ", " + num(x.y()) + ", " + num(x.z()) + ")"; };
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
      std::array<Index, 3> a = ti, b = tj;
      std::sort(a.begin(), a.end());
      std::sort(b.begin(), b.end());
      const std::string what = a == b ? faces + " are the same triangle given twice"
                               : o.across_gap
                                   ? faces + " lie closer than the visibility's resolution (" + sci(resolution) +
                                         ") with the same front side at " + point_text(o.point)
                                   : faces + " overlap in one plane with the same front side at " + point_text(o.point);
      return Failure{"crossing", what + triangles +
                                     ": the surface is there twice, so which of the two is seen is not defined; "
                                     "remove one of them, or cut them so that they only touch"};
    }
    if (!in_closed_piece[at(i)] && !in_closed_piece[at(j)]) {
      if (o.across_gap)
        return Failure{"crossing", faces + " face each other across a gap below the visibility's resolution (" +
                                       sci(resolution) + ") at " + point_text(o.point) + triangles +
                                       ", and neither belongs to a closed piece: they can be told neither apart "
                                       "nor in contact; move them apart by more than that, or make them touch"};
      return Failure{"crossing", faces + " overlap in one plane back to back at " + point_text(o.point) + triangles +
                                     ", and neither belongs to a closed piece, so neither covers the other: two "
                                     "one-sided sheets would stay in one place; give a two-sided wall as a thin "
                                     "closed box, or cut the faces so that they only touch"};
    }
    if (o.across_gap) ++out.across_gap;
    // Opposite front sides: each covers the other where the other's back is solid matter.
    if (in_closed_piece[at(j)]) covers[at(i)].push_back(j);
    if (in_closed_piece[at(i)]) covers[at(j)].push_back(i);
  }
  std::map<std::array<double, 3>, Index> made;
  for (Sz v = 0; v < mesh.vertices.size(); ++v) made.emplace(std::array<double, 3>{mesh.vertices[v].x(), mesh.vertices[v].y(), mesh.vertices[v].z()}, static_cast<Index>(v));
  std::vector<Vec3> vertices = mesh.vertices;
  std::vector<Tri> triangles;
  std::vector<Index> facets;
  triangles.reserve(nt);
  facets.reserve(nt);
  std::vector<double>& removed_of_facet = out.removed_of_facet;
  removed_of_facet.resize(at(mesh.num_facets), 0.0);
  for (Sz t = 0; t < nt; ++t) {
    const Index f = mesh.facet_of_triangle[t];
    if (covers[t].empty()) {
      triangles.push_back(mesh.triangles[t]);
      facets.push_back(f);
      continue;
    }
    const std::vector<Tri> rest = remainder(mesh, static_cast<Index>(t), covers[t], vertices, made);
    const Tri& tr = mesh.triangles[t];
    double kept = 0;
    for (const Tri& r : rest) {
      kept += triangle_area(vertices[at(r[0])], vertices[at(r[1])], vertices[at(r[2])]);
      triangles.push_back(r);
      facets.push_back(f);
    }
    const double whole = triangle_area(mesh.vertices[at(tr[0])], mesh.vertices[at(tr[1])], mesh.vertices[at(tr[2])]);
    removed_of_facet[at(f)] += std::max(0.0, whole - kept);
    ++out.triangles_cut;
  }
  for (const Overlap& o : overlaps) out.pairs.insert(std::minmax(mesh.facet_of_triangle[at(o.i)], mesh.facet_of_triangle[at(o.j)]));
  mesh.vertices = std::move(vertices);
  mesh.triangles = std::move(triangles);
  mesh.facet_of_triangle = std::move(facets);
  // Drop the vertices no triangle uses any more (corners of removed contact faces), keeping the
  // order of the others.
  std::vector<Index> index(mesh.vertices.size(), kNone);
  for (const Tri& tr : mesh.triangles)
    for (Index v : tr) index[at(v)] = 0;
  Index next = 0;
  for (Sz v = 0; v < index.size(); ++v)
    if (index[v] == 0) {
      index[v] = next;
      mesh.vertices[at(next++)] = mesh.vertices[v];
    }
  mesh.vertices.resize(at(next));
  for (Tri& tr : mesh.triangles)
    for (Index& v : tr) v = index[at(v)];
  return std::nullopt;
}

void close_gaps(TriangleMesh& mesh, const std::vector<Overlap>& across_gap) {
  for (const Overlap& o : across_gap) {
    const Tri &ti = mesh.triangles[at(o.i)], &tj = mesh.triangles[at(o.j)];
    int axis = 0;
    const Vec3 n = (mesh.vertices[at(ti[1])] - mesh.vertices[at(ti[0])]).cross(mesh.vertices[at(ti[2])] - mesh.vertices[at(ti[0])]);
    n.cwiseAbs().maxCoeff(&axis);
    if (projected_orientation(mesh, ti, axis) == projected_orientation(mesh, tj, axis)) continue;  // refused later
    // Onto the plane of ti along its unit normal; exact for a plane normal to an axis.
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

bool remove_shared_contact_faces(TriangleMesh& mesh, std::vector<Overlap>& overlaps, ScenePieces& pieces,
                                 ContactReport& out) {
  const Sz nt = mesh.triangles.size();
  const auto sorted = [](Tri t) {
    std::sort(t.begin(), t.end());
    return t;
  };
  std::vector<char> drop(nt, 0);
  std::vector<std::pair<Index, Index>> shared;
  for (const Overlap& o : overlaps) {
    const Tri &ti = mesh.triangles[at(o.i)], &tj = mesh.triangles[at(o.j)];
    if (o.across_gap || drop[at(o.i)] || drop[at(o.j)] || sorted(ti) != sorted(tj)) continue;
    drop[at(o.i)] = drop[at(o.j)] = 1;
    shared.emplace_back(o.i, o.j);
  }
  if (shared.empty()) return false;
  TriangleMesh trial = mesh;
  trial.triangles.clear();
  trial.facet_of_triangle.clear();
  std::vector<Index> renumber(nt, kNone);
  for (Sz t = 0; t < nt; ++t)
    if (!drop[t]) {
      renumber[t] = static_cast<Index>(trial.triangles.size());
      trial.triangles.push_back(mesh.triangles[t]);
      trial.facet_of_triangle.push_back(mesh.facet_of_triangle[t]);
    }
  if (trial.triangles.empty()) return false;
  ScenePieces trial_pieces;
  if (orient_scene_pieces(trial, trial_pieces)) return false;
  // Every triangle of the trial with an edge of a removed triangle must be in a closed piece.
  std::set<std::pair<Index, Index>> contact_edges;
  for (Sz t = 0; t < nt; ++t)
    if (drop[t])
      for (int s = 0; s < 3; ++s)
        contact_edges.insert(std::minmax(mesh.triangles[t][at(s)], mesh.triangles[t][at((s + 1) % 3)]));
  for (Sz t = 0; t < trial.triangles.size(); ++t)
    for (int s = 0; s < 3; ++s)
      if (contact_edges.count(std::minmax(trial.triangles[t][at(s)], trial.triangles[t][at((s + 1) % 3)])) &&
          !trial_pieces.in_closed_piece[t])
        return false;
  out.removed_of_facet.resize(at(mesh.num_facets), 0.0);
  for (const auto& [i, j] : shared) {
    const Tri& t = mesh.triangles[at(i)];
    const double a = triangle_area(mesh.vertices[at(t[0])], mesh.vertices[at(t[1])], mesh.vertices[at(t[2])]);
    const Index fi = mesh.facet_of_triangle[at(i)], fj = mesh.facet_of_triangle[at(j)];
    out.removed_of_facet[at(fi)] += a;
    out.removed_of_facet[at(fj)] += a;
    out.pairs.insert(std::minmax(fi, fj));
    out.triangles_cut += 2;
  }
  std::vector<Overlap> kept;
  for (Overlap o : overlaps)
    if (!drop[at(o.i)] && !drop[at(o.j)]) {
      o.i = renumber[at(o.i)];
      o.j = renumber[at(o.j)];
      kept.push_back(o);
    }
  overlaps = std::move(kept);
  mesh = std::move(trial);
  pieces = std::move(trial_pieces);
  return true;
}

}  // namespace panelrad::geometry::validation_detail

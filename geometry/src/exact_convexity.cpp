// Rule "convex" of validate_closed_convex, decided by exact predicates: an O(F) exact proof for
// convex meshes (local convexity of every edge, an interior point strictly inside every triangle's
// plane, and the solid angles summing to one sphere; see proven_convex), and the exhaustive exact
// O(V F) test of every vertex against every triangle's plane when that proof does not go through.
// coplanar_orientation() is not needed because coplanar neighbours are compared through an
// off-plane witness vertex (Geometry::facing).
#include "validation_internal.hpp"

#include <cmath>
#include <numbers>

namespace panelrad::geometry::validation_detail {

namespace {

/// Sum of the triangles' solid angles seen from `inside`, in units of 4 pi, rounded (the degree
/// of the radial projection when `inside` is strictly inside every triangle's plane).
long solid_angle_degree(const TriangleMesh& mesh, const Vec3& inside) {
  double solid_angle = 0;
  for (const Tri& tr : mesh.triangles) {
    // Van Oosterom-Strackee: tan(Omega/2) = a.(b x c) / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|).
    const Vec3 a = mesh.vertices[at(tr[0])] - inside, b = mesh.vertices[at(tr[1])] - inside,
               c = mesh.vertices[at(tr[2])] - inside;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    solid_angle += 2 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la);
  }
  // The sum is 4 pi times an integer; its rounding error (~1e-15 per triangle) is far below the
  // 2 pi that separates one integer from the next, so rounding decides the degree exactly.
  return std::lround(solid_angle / (4 * std::numbers::pi));
}

}  // namespace

std::vector<Point> exact_points(const TriangleMesh& mesh) {
  std::vector<Point> pts;
  pts.reserve(mesh.vertices.size());
  for (const Vec3& p : mesh.vertices) pts.emplace_back(p.x(), p.y(), p.z());
  return pts;
}

/// An interior point: the mean of four vertices spanning a fat tetrahedron (extreme in x, then
/// farthest from it, from their line, from their plane; chosen in double, checked exactly).
Vec3 interior_point(const TriangleMesh& mesh, const std::vector<Point>& p, const std::array<Index, 4>& fallback) {
  const auto& v = mesh.vertices;
  const Sz n = v.size();
  Sz i0 = 0, i1 = 0, i2 = 0, i3 = 0;
  for (Sz i = 0; i < n; ++i)
    if (v[i].x() < v[i0].x()) i0 = i;
  double best = -1;
  for (Sz i = 0; i < n; ++i)
    if (const double d = (v[i] - v[i0]).squaredNorm(); d > best) best = d, i1 = i;
  const Vec3 axis = (v[i1] - v[i0]).normalized();
  best = -1;
  for (Sz i = 0; i < n; ++i) {
    const Vec3 r = v[i] - v[i0];
    if (const double d = (r - r.dot(axis) * axis).squaredNorm(); d > best) best = d, i2 = i;
  }
  const Vec3 nrm = (v[i1] - v[i0]).cross(v[i2] - v[i0]);
  best = -1;
  for (Sz i = 0; i < n; ++i)
    if (const double d = std::abs((v[i] - v[i0]).dot(nrm)); d > best) best = d, i3 = i;
  std::array<Sz, 4> w{i0, i1, i2, i3};
  if (CGAL::orientation(p[i0], p[i1], p[i2], p[i3]) == CGAL::COPLANAR)
    for (int k = 0; k < 4; ++k) w[at(k)] = at(fallback[at(k)]);
  return (v[w[0]] + v[w[1]] + v[w[2]] + v[w[3]]) / 4.0;
}

/// Sound fast proof of convexity, O(F): (a) every edge is locally convex (the far vertex of each
/// neighbour is not strictly outside the triangle's plane, exact); (b) an interior point O lies
/// strictly on the inner side of every triangle's plane (exact); (c) the triangles' solid angles
/// seen from O sum to 4 pi once (degree 1). (b)+(c) make the radial projection from O a one-sheeted
/// covering of the sphere, so the surface is embedded and star-shaped; with (a) the solid is locally
/// convex everywhere, hence convex (Tietze-Nakajima). Returns false when it cannot prove it.
bool proven_convex(const TriangleMesh& mesh, const Adjacency& adj, const Geometry& g, const Vec3& inside) {
  const Point o(inside.x(), inside.y(), inside.z());
  for (Sz t = 0; t < mesh.triangles.size(); ++t) {
    const Tri& tr = mesh.triangles[t];
    if (CGAL::orientation(g.p[at(tr[0])], g.p[at(tr[1])], g.p[at(tr[2])], o) != CGAL::NEGATIVE) return false;
    for (int s = 0; s < 3; ++s) {
      const Tri& nt = mesh.triangles[at(adj.neighbour[3 * t + at(s)])];
      for (Index v : nt)
        if (v != tr[0] && v != tr[1] && v != tr[2] && g.side(tr, v) == CGAL::POSITIVE) return false;
    }
  }
  return solid_angle_degree(mesh, inside) == 1;
}

/// Triangles with some vertex strictly outside their plane (exact; empty iff convex). The O(F)
/// proof above settles convex meshes; anything else gets the exhaustive O(V F) exact test.
std::vector<Index> unsupported_triangles(const TriangleMesh& mesh, const Adjacency& adj, const Geometry& g,
                                         const Vec3& inside) {
  if (proven_convex(mesh, adj, g, inside)) return {};
  const auto nt = static_cast<long>(mesh.triangles.size());
  const auto nv = static_cast<Index>(mesh.vertices.size());
  std::vector<char> bad(static_cast<Sz>(nt), 0);
#pragma omp parallel for schedule(dynamic, 64)
  for (long t = 0; t < nt; ++t)
    for (Index v = 0; v < nv; ++v)
      if (g.side(mesh.triangles[static_cast<Sz>(t)], v) == CGAL::POSITIVE) {
        bad[static_cast<Sz>(t)] = 1;
        break;
      }
  std::vector<Index> out;
  for (long t = 0; t < nt; ++t)
    if (bad[static_cast<Sz>(t)]) out.push_back(static_cast<Index>(t));
  return out;
}

/// The surface winds once around `inside`, which is strictly on the inner side of every triangle's
/// plane (exact): the radial projection from it is a one-sheeted covering of the sphere.
bool winds_once_around(const TriangleMesh& mesh, const Geometry& g, const Vec3& inside) {
  const Point o(inside.x(), inside.y(), inside.z());
  for (const Tri& tr : mesh.triangles)
    if (CGAL::orientation(g.p[at(tr[0])], g.p[at(tr[1])], g.p[at(tr[2])], o) != CGAL::NEGATIVE) return false;
  return solid_angle_degree(mesh, inside) == 1;
}

}  // namespace panelrad::geometry::validation_detail

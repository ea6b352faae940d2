// Corners closer than the visibility's resolution are one corner (contact_removal.hpp:
// join_close_corners): a scene written with an ulp between two corners meant to coincide (a table
// top's corner and its leg's, computed separately), or a contact whose cut put a new corner an ulp
// from an old one, would otherwise keep triangles thinner than any element the subdivision can
// halve (their midpoints round onto one line), and slits the visibility cannot resolve.
//
// Candidates by a sweep along x over the corners sorted by x; a pair closer than the tolerance in
// every coordinate (so closer than sqrt(3) times it) joins; each class of joined corners becomes its
// lowest-numbered corner, whose coordinates are kept. A triangle left with two equal corners, or
// with three collinear ones (exact), is a sliver of the joined corners and is dropped.
#include "contact_removal.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

namespace panelrad::geometry::validation_detail {

Sz join_close_corners(TriangleMesh& mesh, double tolerance, std::vector<Index>* origin) {
  const Sz nv = mesh.vertices.size();
  if (!(tolerance > 0) || nv < 2) return 0;
  std::vector<Index> order(nv);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](Index a, Index b) { return mesh.vertices[at(a)].x() < mesh.vertices[at(b)].x(); });
  std::vector<Index> parent(nv);
  std::iota(parent.begin(), parent.end(), 0);
  const std::function<Index(Index)> root = [&](Index v) {
    while (parent[at(v)] != v) v = parent[at(v)] = parent[at(parent[at(v)])];
    return v;
  };
  Sz joined = 0;
  for (Sz a = 0; a < nv; ++a)
    for (Sz b = a + 1; b < nv; ++b) {
      const Vec3 &p = mesh.vertices[at(order[a])], &q = mesh.vertices[at(order[b])];
      if (q.x() - p.x() > tolerance) break;
      if ((q - p).cwiseAbs().maxCoeff() > tolerance) continue;
      const Index ra = root(order[a]), rb = root(order[b]);
      if (ra == rb) continue;
      parent[at(std::max(ra, rb))] = std::min(ra, rb);
      ++joined;
    }
  if (joined == 0) return 0;
  const std::vector<Point> p = exact_points(mesh);
  std::vector<std::array<Index, 3>> triangles;
  std::vector<Index> facets, kept_origin;
  for (Sz t = 0; t < mesh.triangles.size(); ++t) {
    Tri tr = mesh.triangles[t];
    for (Index& v : tr) v = root(v);
    if (tr[0] == tr[1] || tr[1] == tr[2] || tr[2] == tr[0]) continue;
    if (CGAL::collinear(p[at(tr[0])], p[at(tr[1])], p[at(tr[2])])) continue;
    triangles.push_back(tr);
    facets.push_back(mesh.facet_of_triangle[t]);
    if (origin) kept_origin.push_back((*origin)[t]);
  }
  if (origin) *origin = std::move(kept_origin);
  mesh.triangles = std::move(triangles);
  mesh.facet_of_triangle = std::move(facets);
  // Drop the corners no triangle uses any more, keeping the order of the others.
  std::vector<Index> index(nv, kNone);
  for (const Tri& tr : mesh.triangles)
    for (Index v : tr) index[at(v)] = 0;
  Index next = 0;
  for (Sz v = 0; v < nv; ++v)
    if (index[v] == 0) {
      index[v] = next;
      mesh.vertices[at(next++)] = mesh.vertices[v];
    }
  mesh.vertices.resize(at(next));
  for (Tri& tr : mesh.triangles)
    for (Index& v : tr) v = index[at(v)];
  return joined;
}

}  // namespace panelrad::geometry::validation_detail

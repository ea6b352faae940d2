// Corners closer than the visibility's resolution are one corner (contact_removal.hpp:
// join_close_corners): a scene written with an ulp between two corners meant to coincide (a table
// top's corner and its leg's, computed separately), or a contact whose cut put a new corner an ulp
// from an old one, would otherwise keep triangles thinner than any element the subdivision can
// halve (their midpoints round onto one line), and slits the visibility cannot resolve.
//
// Candidates by box intersection: a pair closer than the tolerance in every coordinate (so closer
// than sqrt(3) times it) joins; each class of joined corners becomes its
// lowest-numbered corner, whose coordinates are kept. A triangle left with two equal corners, or
// with three collinear ones (exact), is a sliver of the joined corners and is dropped.
#include "contact_removal.hpp"

#include <CGAL/Bbox_3.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

namespace panelrad::geometry::validation_detail {

Sz join_close_corners(TriangleMesh& mesh, double tolerance, std::vector<Index>* origin) {
  const Sz nv = mesh.vertices.size();
  if (!(tolerance > 0) || nv < 2) return 0;
  // Pairs closer than the tolerance in every coordinate: boxes of side `tolerance` around the
  // corners intersect (CGAL::box_self_intersection_d, O(n log n) plus the pairs).
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, Index>;
  std::vector<Box> boxes;
  boxes.reserve(nv);
  const double h = tolerance / 2;
  for (Sz v = 0; v < nv; ++v) {
    const Vec3& x = mesh.vertices[v];
    boxes.emplace_back(CGAL::Bbox_3(x.x() - h, x.y() - h, x.z() - h, x.x() + h, x.y() + h, x.z() + h),
                       static_cast<Index>(v));
  }
  std::vector<std::pair<Index, Index>> close;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
    close.emplace_back(std::min(a.info(), b.info()), std::max(a.info(), b.info()));
  });
  std::sort(close.begin(), close.end());  // the same classes whatever order the pairs come in
  std::vector<Index> parent(nv);
  std::iota(parent.begin(), parent.end(), 0);
  const std::function<Index(Index)> root = [&](Index v) {
    while (parent[at(v)] != v) v = parent[at(v)] = parent[at(parent[at(v)])];
    return v;
  };
  Sz joined = 0;
  for (const auto& [a, b] : close) {
    const Index ra = root(a), rb = root(b);
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
  drop_unused_vertices(mesh);
  return joined;
}

void drop_unused_vertices(TriangleMesh& mesh) {
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
}

}  // namespace panelrad::geometry::validation_detail

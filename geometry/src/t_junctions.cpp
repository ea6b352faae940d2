// T-junctions: vertices strictly inside boundary edges inserted into those edges (t_junctions.hpp).
// Candidates by box intersection (the vertices as points against boxes covering each boundary edge
// in short pieces), decisions by exact predicates on the input coordinates.
#include "t_junctions.hpp"

#include "validation_internal.hpp"

#include <CGAL/Bbox_3.h>
#include <CGAL/box_intersection_d.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace panelrad::geometry::validation_detail {

namespace {

using EdgeBox = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::uint32_t>;
using VertexBox = EdgeBox;  // box_intersection_d takes one box type; the info is the vertex index

/// Slot s of triangle t: the edge tr[s] -> tr[s + 1].
struct Slot {
  Sz t;
  int s;
};

Index corner(const Tri& tr, int k) { return tr[at(k % 3)]; }

std::uint64_t edge_key(Index u, Index v) {
  const auto lo = static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::min(u, v)));
  const auto hi = static_cast<std::uint64_t>(static_cast<std::uint32_t>(std::max(u, v)));
  return lo << 32 | hi;
}

/// The slots whose undirected edge is used by exactly one triangle, in triangle order; also the
/// median length of the undirected edges (0 for an empty mesh).
std::vector<Slot> boundary_slots(const TriangleMesh& mesh, double& median_length) {
  std::vector<std::pair<std::uint64_t, std::uint32_t>> edges;  // (key, 3 t + s)
  edges.reserve(3 * mesh.triangles.size());
  for (Sz t = 0; t < mesh.triangles.size(); ++t)
    for (int s = 0; s < 3; ++s) {
      const Tri& tr = mesh.triangles[t];
      edges.emplace_back(edge_key(corner(tr, s), corner(tr, s + 1)), static_cast<std::uint32_t>(3 * t + at(s)));
    }
  std::sort(edges.begin(), edges.end());
  std::vector<Slot> out;
  std::vector<double> lengths;
  for (Sz i = 0; i < edges.size();) {
    Sz j = i + 1;
    while (j < edges.size() && edges[j].first == edges[i].first) ++j;
    const Index u = static_cast<Index>(edges[i].first >> 32);
    const Index v = static_cast<Index>(edges[i].first & 0xffffffffu);
    lengths.push_back((mesh.vertices[at(u)] - mesh.vertices[at(v)]).norm());
    if (j == i + 1) out.push_back({edges[i].second / 3, static_cast<int>(edges[i].second % 3)});
    i = j;
  }
  std::sort(out.begin(), out.end(), [](const Slot& x, const Slot& y) { return x.t != y.t ? x.t < y.t : x.s < y.s; });
  median_length = 0;
  if (!lengths.empty()) {
    const auto mid = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
    std::nth_element(lengths.begin(), mid, lengths.end());
    median_length = *mid;
  }
  return out;
}

/// Boxes covering the segments (a, b) of the boundary slots: each segment cut at parameters k / K
/// into K pieces of about `piece` length (K at most kMaxPieces), each piece's box enlarged by a
/// bound on the rounding of its computed end points, so that the boxes cover the exact segment.
/// The info of a box is the index of its slot in `slots`.
std::vector<EdgeBox> covering_boxes(const TriangleMesh& mesh, const std::vector<Slot>& slots, double piece) {
  constexpr double kMaxPieces = 256;
  // At most about two pieces per triangle edge in all: a longer piece when the boundary is long.
  double total = 0;
  const auto pieces_of = [&](double length, double p) {
    return p > 0 ? std::clamp(std::ceil(length / p), 1.0, kMaxPieces) : 1.0;
  };
  for (const Slot& sl : slots) {
    const Tri& tr = mesh.triangles[sl.t];
    total += pieces_of((mesh.vertices[at(corner(tr, sl.s))] - mesh.vertices[at(corner(tr, sl.s + 1))]).norm(), piece);
  }
  const double budget = 6.0 * static_cast<double>(mesh.triangles.size()) + 64;
  if (total > budget) piece *= total / budget;

  std::vector<EdgeBox> boxes;
  boxes.reserve(slots.size());
  for (Sz i = 0; i < slots.size(); ++i) {
    const Tri& tr = mesh.triangles[slots[i].t];
    const Vec3& a = mesh.vertices[at(corner(tr, slots[i].s))];
    const Vec3& b = mesh.vertices[at(corner(tr, slots[i].s + 1))];
    const int k_pieces = static_cast<int>(pieces_of((b - a).norm(), piece));
    // |fl(a + (b - a) t) - (a + (b - a) t)| <= 4 eps max(|a|, |b|) per coordinate for t in [0, 1].
    const double scale = std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff());
    const double slack = k_pieces == 1 ? 0.0 : 8 * std::numeric_limits<double>::epsilon() * scale;
    const Vec3 d = b - a;
    Vec3 from = a;
    for (int k = 1; k <= k_pieces; ++k) {
      const Vec3 to = k == k_pieces ? b : Vec3(a + d * (static_cast<double>(k) / k_pieces));
      const Vec3 lo = from.cwiseMin(to).array() - slack;
      const Vec3 hi = from.cwiseMax(to).array() + slack;
      boxes.emplace_back(CGAL::Bbox_3(lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z()), static_cast<std::uint32_t>(i));
      from = to;
    }
  }
  return boxes;
}

/// One round: finds the vertices strictly inside the boundary edges and splits each triangle along
/// the first of its edges that has some. Returns the number of vertices inserted.
Sz split_round(TriangleMesh& mesh, const std::vector<Point>& p, std::vector<Index>* origin, double tolerance) {
  double median = 0;
  std::vector<Slot> slots = boundary_slots(mesh, median);
  // A triangle with collinear corners is left alone: its pieces would be degenerate.
  std::erase_if(slots, [&](const Slot& sl) {
    const Tri& tr = mesh.triangles[sl.t];
    return CGAL::collinear(p[at(tr[0])], p[at(tr[1])], p[at(tr[2])]);
  });
  if (slots.empty()) return 0;

  std::vector<EdgeBox> edge_boxes = covering_boxes(mesh, slots, median);
  std::vector<char> used(mesh.vertices.size(), 0);
  for (const Tri& tr : mesh.triangles)
    for (Index v : tr) used[at(v)] = 1;
  std::vector<VertexBox> vertex_boxes;
  for (Sz v = 0; v < mesh.vertices.size(); ++v)
    if (used[v]) {
      const Vec3& x = mesh.vertices[v];
      vertex_boxes.emplace_back(CGAL::Bbox_3(x.x() - tolerance, x.y() - tolerance, x.z() - tolerance, x.x() + tolerance,
                                             x.y() + tolerance, x.z() + tolerance),
                                static_cast<std::uint32_t>(v));
    }
  std::vector<std::pair<std::uint32_t, Index>> candidates;  // (slot, vertex)
  CGAL::box_intersection_d(edge_boxes.begin(), edge_boxes.end(), vertex_boxes.begin(), vertex_boxes.end(),
                           [&](const EdgeBox& e, const VertexBox& v) {
                             candidates.emplace_back(e.info(), static_cast<Index>(v.info()));
                           });
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());

  // The exact test, and the position along the edge: on the line (a, b) the coordinate of an axis
  // with a_i != b_i is strictly monotone, so it orders the points exactly.
  struct Hit {
    std::uint32_t slot;
    double along;  // the coordinate on the dominant axis of (a, b), signed to grow from a to b
    Index v;
  };
  std::vector<Hit> hits;
  for (const auto& [i, v] : candidates) {
    const Tri& tr = mesh.triangles[slots[i].t];
    const Index ia = corner(tr, slots[i].s), ib = corner(tr, slots[i].s + 1);
    // Not a corner of the triangle itself: its apex within the tolerance of its own base (a
    // sliver) would split it into two triangles with a repeated corner.
    if (v == ia || v == ib || v == corner(tr, slots[i].s + 2)) continue;
    const Point &a = p[at(ia)], &b = p[at(ib)], &x = p[at(v)];
    const Vec3 d = mesh.vertices[at(ib)] - mesh.vertices[at(ia)];
    if ((!CGAL::collinear(a, x, b) || !CGAL::collinear_are_strictly_ordered_along_line(a, x, b)) &&
        !(tolerance > 0 && near_open_segment(mesh.vertices[at(ia)], mesh.vertices[at(ib)], mesh.vertices[at(v)], tolerance)))
      continue;
    int axis = 0;
    d.cwiseAbs().maxCoeff(&axis);
    const double coord = mesh.vertices[at(v)][axis];
    hits.push_back({i, d[axis] > 0 ? coord : -coord, v});
  }
  if (hits.empty()) return 0;
  std::sort(hits.begin(), hits.end(), [](const Hit& x, const Hit& y) {
    if (x.slot != y.slot) return x.slot < y.slot;
    if (x.along != y.along) return x.along < y.along;
    return x.v < y.v;
  });
  // Vertices at the same point (distinct indices, equal coordinates) are inserted once.
  hits.erase(std::unique(hits.begin(), hits.end(),
                         [](const Hit& x, const Hit& y) { return x.slot == y.slot && x.along == y.along; }),
             hits.end());

  // Per triangle, the first slot with hits (slots are in triangle order) and its range of hits.
  constexpr Sz kNoSplit = std::numeric_limits<Sz>::max();
  std::vector<Sz> first_hit(mesh.triangles.size(), kNoSplit);
  std::vector<Sz> hit_end(mesh.triangles.size(), 0);
  for (Sz h = 0; h < hits.size();) {
    Sz e = h + 1;
    while (e < hits.size() && hits[e].slot == hits[h].slot) ++e;
    const Sz t = slots[hits[h].slot].t;
    if (first_hit[t] == kNoSplit) {
      first_hit[t] = h;
      hit_end[t] = e;
    }
    h = e;
  }

  Sz inserted = 0;
  std::vector<Tri> triangles;
  std::vector<Index> facets, from_triangle;
  triangles.reserve(mesh.triangles.size() + hits.size());
  facets.reserve(triangles.capacity());
  for (Sz t = 0; t < mesh.triangles.size(); ++t) {
    const Tri& tr = mesh.triangles[t];
    if (first_hit[t] == kNoSplit) {
      triangles.push_back(tr);
      facets.push_back(mesh.facet_of_triangle[t]);
      if (origin) from_triangle.push_back((*origin)[t]);
      continue;
    }
    // (a, b, c) with v_1, ..., v_k on (a, b): the fan (a, v_1, c), ..., (v_k, b, c) around c.
    const int s = slots[hits[first_hit[t]].slot].s;
    const Index c = corner(tr, s + 2);
    Index from = corner(tr, s);
    // A piece whose corners are collinear (a vertex within the tolerance of the edge but on the
    // line through c and an end) has no area and is left out.
    const auto piece = [&](Index x, Index y) {
      if (CGAL::collinear(p[at(x)], p[at(y)], p[at(c)])) return;
      triangles.push_back({x, y, c});
      facets.push_back(mesh.facet_of_triangle[t]);
      if (origin) from_triangle.push_back((*origin)[t]);
    };
    for (Sz h = first_hit[t]; h < hit_end[t]; ++h) {
      piece(from, hits[h].v);
      from = hits[h].v;
      ++inserted;
    }
    piece(from, corner(tr, s + 1));
  }
  if (origin) *origin = std::move(from_triangle);
  mesh.triangles = std::move(triangles);
  mesh.facet_of_triangle = std::move(facets);
  return inserted;
}

}  // namespace

bool near_open_segment(const Vec3& a, const Vec3& b, const Vec3& x, double tolerance) {
  const Vec3 d = b - a, ax = x - a;
  const double length = d.norm(), along = ax.dot(d) / length;
  return along > tolerance && along < length - tolerance && (ax - along / length * d).norm() <= tolerance;
}

std::size_t split_t_junctions(TriangleMesh& mesh, std::vector<Index>* origin, double tolerance) {
  const std::vector<Point> p = exact_points(mesh);
  Sz inserted = 0;
  for (Sz round = split_round(mesh, p, origin, tolerance); round > 0; round = split_round(mesh, p, origin, tolerance))
    inserted += round;
  return inserted;
}

}  // namespace panelrad::geometry::validation_detail

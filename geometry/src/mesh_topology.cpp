// Rules "closed", "manifold" and "connected" of validate_closed_convex: every edge in exactly two
// triangles, a single fan of triangles around every vertex, no two vertices at the same point, one
// connected piece, and a consistent orientation (the surface is orientable).
#include "validation_internal.hpp"

#include <algorithm>
#include <deque>
#include <numeric>
#include <tuple>
#include <utility>

namespace panelrad::geometry::validation_detail {

namespace {

/// The slot of triangle t whose edge joins u and v (either direction).
int slot_of(const Tri& tr, Index u, Index v) {
  for (int s = 0; s < 3; ++s) {
    const Index a = tr[at(s)], b = tr[at((s + 1) % 3)];
    if ((a == u && b == v) || (a == v && b == u)) return s;
  }
  return -1;
}

/// Vertex manifoldness: the triangles around each vertex form a single fan (one cycle).
std::optional<Failure> check_vertex_fans(const TriangleMesh& mesh, const Adjacency& adj) {
  const Describe d{mesh};
  const Sz nv = mesh.vertices.size();
  std::vector<Index> degree(nv, 0), first(nv, kNone);
  for (Sz t = 0; t < mesh.triangles.size(); ++t)
    for (Index v : mesh.triangles[t]) {
      ++degree[at(v)];
      if (first[at(v)] == kNone) first[at(v)] = static_cast<Index>(t);
    }
  for (Sz v = 0; v < nv; ++v) {
    if (degree[v] == 0)
      return Failure{"manifold", d.vertex(static_cast<Index>(v)) + " belongs to no triangle"};
    // Walk around v: enter a triangle through one of its two edges at v, leave through the other.
    const Index start = first[v];
    Index t = start;
    const Tri& st = mesh.triangles[at(start)];
    const int corner = static_cast<int>(std::find(st.begin(), st.end(), static_cast<Index>(v)) - st.begin());
    int leave = corner;  // slot corner = edge (v, next)
    Index steps = 0;
    while (true) {
      ++steps;
      const Tri& tr = mesh.triangles[at(t)];
      const Index other = tr[at((leave + 1) % 3)] == static_cast<Index>(v) ? tr[at(leave)] : tr[at((leave + 1) % 3)];
      const Index next = adj.neighbour[3 * at(t) + at(leave)];
      if (next == start || steps > degree[v]) break;
      const Tri& nt = mesh.triangles[at(next)];
      const int enter = slot_of(nt, static_cast<Index>(v), other);
      // The other slot of `next` containing v.
      int out = -1;
      for (int s = 0; s < 3; ++s)
        if (s != enter && (nt[at(s)] == static_cast<Index>(v) || nt[at((s + 1) % 3)] == static_cast<Index>(v))) out = s;
      t = next;
      leave = out;
    }
    if (steps != degree[v])
      return Failure{"manifold", "the triangles around " + d.vertex(static_cast<Index>(v)) +
                                     " do not form a single fan (" + std::to_string(steps) + " of its " +
                                     std::to_string(degree[v]) + " triangles are reached around it): "
                                     "a non-manifold vertex"};
  }
  return std::nullopt;
}

std::optional<Failure> check_coincident_vertices(const TriangleMesh& mesh) {
  const Describe d{mesh};
  std::vector<Index> order(mesh.vertices.size());
  std::iota(order.begin(), order.end(), 0);
  const auto key = [&](Index v) {
    const Vec3& p = mesh.vertices[at(v)];
    return std::array<double, 3>{p.x(), p.y(), p.z()};
  };
  std::sort(order.begin(), order.end(), [&](Index a, Index b) { return std::pair(key(a), a) < std::pair(key(b), b); });
  for (Sz i = 1; i < order.size(); ++i)
    if (key(order[i]) == key(order[i - 1]))
      return Failure{"manifold", "vertices " + std::to_string(order[i - 1]) + " and " + std::to_string(order[i]) +
                                     " coincide at " + d.point(order[i]) +
                                     "; a closed convex surface cannot touch itself"};
  return std::nullopt;
}

}  // namespace

/// Closedness (every edge in exactly two triangles) and edge-manifoldness; fills the adjacency.
std::optional<Failure> build_adjacency(const TriangleMesh& mesh, Adjacency& adj) {
  const Describe d{mesh};
  struct Half {
    Index lo, hi, tri, slot;
  };
  const Sz nt = mesh.triangles.size();
  std::vector<Half> halves;
  halves.reserve(3 * nt);
  for (Sz t = 0; t < nt; ++t)
    for (int s = 0; s < 3; ++s) {
      const Index a = mesh.triangles[t][at(s)], b = mesh.triangles[t][at((s + 1) % 3)];
      halves.push_back({std::min(a, b), std::max(a, b), static_cast<Index>(t), s});
    }
  std::sort(halves.begin(), halves.end(), [](const Half& x, const Half& y) {
    return std::tie(x.lo, x.hi, x.tri, x.slot) < std::tie(y.lo, y.hi, y.tri, y.slot);
  });
  adj.neighbour.assign(3 * nt, kNone);
  // First offending edge = the one whose lowest triangle index is smallest.
  Index open_tri = kNone, open_lo = 0, open_hi = 0;
  Sz open_count = 0;
  Index multi_tri = kNone, multi_lo = 0, multi_hi = 0;
  std::vector<Index> multi_tris;
  for (Sz i = 0; i < halves.size();) {
    Sz j = i;
    while (j < halves.size() && halves[j].lo == halves[i].lo && halves[j].hi == halves[i].hi) ++j;
    const Sz n = j - i;
    if (n == 1) {
      ++open_count;
      if (open_tri == kNone || halves[i].tri < open_tri) {
        open_tri = halves[i].tri;
        open_lo = halves[i].lo;
        open_hi = halves[i].hi;
      }
    } else if (n > 2) {
      if (multi_tri == kNone || halves[i].tri < multi_tri) {
        multi_tri = halves[i].tri;
        multi_lo = halves[i].lo;
        multi_hi = halves[i].hi;
        multi_tris.clear();
        for (Sz k = i; k < j; ++k) multi_tris.push_back(halves[k].tri);
      }
    } else {
      adj.neighbour[3 * at(halves[i].tri) + at(halves[i].slot)] = halves[i + 1].tri;
      adj.neighbour[3 * at(halves[i + 1].tri) + at(halves[i + 1].slot)] = halves[i].tri;
    }
    i = j;
  }
  if (open_tri != kNone)
    return Failure{"closed", "the edge from " + d.vertex(open_lo) + " to " + d.vertex(open_hi) + " belongs to " +
                                 d.triangle(open_tri) + " only: the surface has a boundary (" +
                                 std::to_string(open_count) + " boundary edges in all)"};
  if (multi_tri != kNone) {
    std::string list;
    for (Index t : multi_tris) list += (list.empty() ? "" : ", ") + std::to_string(t);
    return Failure{"manifold", "the edge from " + d.vertex(multi_lo) + " to " + d.vertex(multi_hi) +
                                   " is shared by " + std::to_string(multi_tris.size()) + " triangles (" + list +
                                   "); a closed 2-manifold needs exactly 2"};
  }
  return std::nullopt;
}

std::optional<Failure> check_closed_manifold(const TriangleMesh& mesh, Adjacency& adj) {
  if (auto f = build_adjacency(mesh, adj)) return f;
  if (auto f = check_vertex_fans(mesh, adj)) return f;
  return check_coincident_vertices(mesh);
}

/// Breadth-first from each unvisited triangle: a neighbour across an edge keeps the orientation
/// when it runs the shared edge the other way, and is flipped when it runs it the same way.
std::optional<Failure> consistent_orientation(const TriangleMesh& mesh, const Adjacency& adj,
                                              std::vector<signed char>& flip) {
  const Describe d{mesh};
  const Sz nt = mesh.triangles.size();
  flip.assign(nt, -1);
  Sz components = 0;
  Index second_piece = kNone;
  for (Sz seed = 0; seed < nt; ++seed) {
    if (flip[seed] >= 0) continue;
    if (++components == 2) second_piece = static_cast<Index>(seed);
    flip[seed] = 0;
    std::deque<Index> queue{static_cast<Index>(seed)};
    while (!queue.empty()) {
      const Index t = queue.front();
      queue.pop_front();
      const Tri& tr = mesh.triangles[at(t)];
      for (int s = 0; s < 3; ++s) {
        const Index n = adj.neighbour[3 * at(t) + at(s)];
        const Index a = tr[at(s)], b = tr[at((s + 1) % 3)];
        const Tri& ntr = mesh.triangles[at(n)];
        const int ns = slot_of(ntr, a, b);
        const bool same_direction = ntr[at(ns)] == a;  // consistent neighbours run the edge b -> a
        const signed char want = static_cast<signed char>(flip[at(t)] ^ (same_direction ? 1 : 0));
        if (flip[at(n)] < 0) {
          flip[at(n)] = want;
          queue.push_back(n);
        } else if (flip[at(n)] != want) {
          return Failure{"manifold", "the surface is not orientable: " + d.triangle(n) +
                                         " cannot be oriented consistently with its neighbours"};
        }
      }
    }
  }
  if (components > 1)
    return Failure{"connected", "the surface has " + std::to_string(components) + " separate pieces (triangle 0 and " +
                                    std::to_string(second_piece) + " are not connected); a convex polyhedron is one piece"};
  return std::nullopt;
}

}  // namespace panelrad::geometry::validation_detail

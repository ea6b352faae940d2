#pragma once
// Raw input meshes of scenes where the line of sight V(P, Q) of the radiosity equation (1) matters,
// for tests: rooms with bodies inside, a non-convex room, an emitter shadowed by a blocker, a block
// standing on a floor. They are given as a user would give them, before any validation: each input
// polygon is one facet, fan-triangulated from its first corner; open polygons run counter-clockwise
// seen from their front side (the side that emits, reflects and sees); closed boxes are
// consistently oriented (rooms counter-clockwise seen from inside, bodies seen from outside, i.e.
// every polygon counter-clockwise seen from its front side; reversed() gives the other
// orientation). Vertices of one mesh with the same coordinates are shared, as the OBJ/OFF reader
// merges them; append() shares nothing.
#include <panelrad/geometry/mesh.hpp>

#include <array>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace panelrad::testing {

using geometry::Index;
using geometry::TriangleMesh;
using geometry::Vec3;

/// Triangles given one by one, each its own facet, with corners of their own (nothing shared).
inline TriangleMesh triangle_soup(const std::vector<std::array<Vec3, 3>>& tris, std::string source) {
  TriangleMesh m;
  m.source = std::move(source);
  for (const auto& t : tris) {
    const Index base = static_cast<Index>(m.vertices.size());
    m.vertices.insert(m.vertices.end(), t.begin(), t.end());
    m.triangles.push_back({base, base + 1, base + 2});
    m.facet_of_triangle.push_back(m.num_facets++);
  }
  return m;
}

/// The index of a vertex at exactly `p` in `mesh`, appended when there is none.
inline Index shared_vertex(TriangleMesh& mesh, const Vec3& p) {
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    if (mesh.vertices[i] == p) return static_cast<Index>(i);
  mesh.vertices.push_back(p);
  return static_cast<Index>(mesh.vertices.size() - 1);
}

/// Appends the planar polygon `corners` as one new facet, fan-triangulated from corners[0]
/// (triangles (c0, c_k, c_k+1), which keep the polygon's orientation). The fan is a triangulation
/// when every c_k is visible from c0 (a convex polygon, or an L started at its reflex corner).
/// Returns the facet id.
inline Index add_polygon(TriangleMesh& mesh, const std::vector<Vec3>& corners) {
  const Index facet = mesh.num_facets++;
  std::vector<Index> id;
  for (const Vec3& c : corners) id.push_back(shared_vertex(mesh, c));
  for (std::size_t k = 1; k + 1 < id.size(); ++k) {
    mesh.triangles.push_back({id[0], id[k], id[k + 1]});
    mesh.facet_of_triangle.push_back(facet);
  }
  return facet;
}

/// The quadrilateral a, b, c, d (planar, convex, counter-clockwise seen from its front side): one
/// facet, triangles (a, b, c) and (a, c, d).
inline TriangleMesh quad(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d,
                         std::string source = "quad") {
  TriangleMesh mesh;
  mesh.source = std::move(source);
  add_polygon(mesh, {a, b, c, d});
  return mesh;
}

/// Which side of a closed box is its front side.
enum class BoxFront {
  outside,  ///< a body: every face counter-clockwise seen from outside (outward normal)
  inside,   ///< a room: every face counter-clockwise seen from inside
};

/// The faces of the axis-aligned box [lo, hi] (lo < hi componentwise) appended to `mesh` as 6
/// facets of 2 triangles, in the order x = lo.x, x = hi.x, y = lo.y, y = hi.y, z = lo.z, z = hi.z.
inline void add_axis_box(TriangleMesh& mesh, const Vec3& lo, const Vec3& hi, BoxFront front) {
  for (int k = 0; k < 3; ++k) {
    const int u = (k + 1) % 3, v = (k + 2) % 3;  // e_u x e_v = e_k
    for (int side = 0; side < 2; ++side) {
      std::array<Vec3, 4> c;
      const double uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};  // counter-clockwise about e_k
      for (int i = 0; i < 4; ++i) {
        c[i][k] = side == 0 ? lo[k] : hi[k];
        c[i][u] = uv[i][0] == 0 ? lo[u] : hi[u];
        c[i][v] = uv[i][1] == 0 ? lo[v] : hi[v];
      }
      // The order above has normal +e_k: outward on the hi side, inward on the lo side.
      const bool keep = (side == 1) == (front == BoxFront::outside);
      if (keep)
        add_polygon(mesh, {c[0], c[1], c[2], c[3]});
      else
        add_polygon(mesh, {c[0], c[3], c[2], c[1]});
    }
  }
}

/// The closed axis-aligned box [lo, hi]: 6 facets, 12 triangles, 8 shared vertices (facet order as
/// add_axis_box).
inline TriangleMesh axis_box(const Vec3& lo, const Vec3& hi, BoxFront front = BoxFront::outside,
                             std::string source = "box") {
  TriangleMesh mesh;
  mesh.source = std::move(source);
  add_axis_box(mesh, lo, hi, front);
  return mesh;
}

/// `a` followed by `b`, sharing no vertex: b's vertex indices and facet ids are offset by a's
/// counts (facet i of b becomes a.num_facets + i).
inline TriangleMesh append(TriangleMesh a, const TriangleMesh& b) {
  const Index v0 = static_cast<Index>(a.vertices.size());
  const Index f0 = a.num_facets;
  a.vertices.insert(a.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (const auto& t : b.triangles) a.triangles.push_back({t[0] + v0, t[1] + v0, t[2] + v0});
  for (const Index f : b.facet_of_triangle) a.facet_of_triangle.push_back(f + f0);
  a.num_facets += b.num_facets;
  a.source += "+" + b.source;
  return a;
}

/// Every triangle reversed (the other orientation of every facet).
inline TriangleMesh reversed(TriangleMesh mesh) {
  for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  return mesh;
}

/// The closed room [0, 1]^3 (facets 0-5, seen from inside) with closed axis boxes [lo, hi] inside
/// it, seen from outside (6 facets each, in the order given).
inline TriangleMesh room_with_boxes(const std::vector<std::pair<Vec3, Vec3>>& boxes, std::string source) {
  TriangleMesh mesh;
  mesh.source = std::move(source);
  add_axis_box(mesh, Vec3(0, 0, 0), Vec3(1, 1, 1), BoxFront::inside);
  for (const auto& [lo, hi] : boxes) add_axis_box(mesh, lo, hi, BoxFront::outside);
  return mesh;
}

/// The closed room [0, 1]^3 (facets 0-5, seen from inside) with the closed box
/// [0.3, 0.6] x [0.35, 0.7] x [0.2, 0.55] inside it (facets 6-11, seen from outside), at distance
/// >= 0.2 from every wall. 24 triangles.
inline TriangleMesh room_with_box() {
  return room_with_boxes({{Vec3(0.3, 0.35, 0.2), Vec3(0.6, 0.7, 0.55)}}, "room_with_box");
}

/// The closed L-shaped room [0, 2] x [0, 1] x [0, 1]  U  [0, 1] x [1, 2] x [0, 1], seen from
/// inside: floor (facet 0) and ceiling (facet 1) are L-shaped hexagons fanned from the reflex
/// corner (1, 1) (4 triangles each); the six walls are rectangles (facets 2-7: x = 0, y = 0,
/// x = 2, y = 1 for x in [1, 2], x = 1 for y in [1, 2], y = 2). Every edge of a wall is an edge of
/// the floor, the ceiling or the neighbouring wall: no T-junction. 20 triangles, 12 vertices. The
/// room is not convex: the reflex vertical edge x = y = 1 hides parts of the two wings from each
/// other.
inline TriangleMesh l_shaped_room() {
  TriangleMesh mesh;
  mesh.source = "l_shaped_room";
  // The L counter-clockwise about +z, from the reflex corner.
  const double L[6][2] = {{1, 1}, {1, 2}, {0, 2}, {0, 0}, {2, 0}, {2, 1}};
  std::vector<Vec3> floor, ceiling;
  for (int i = 0; i < 6; ++i) {
    floor.emplace_back(L[i][0], L[i][1], 0.0);
    ceiling.emplace_back(L[i][0], L[i][1], 1.0);
  }
  // Seen from inside: the floor faces up (+z, counter-clockwise about +z as listed), the ceiling
  // down (reversed, keeping the reflex corner first).
  add_polygon(mesh, floor);
  std::vector<Vec3> ceiling_down = {ceiling[0]};
  for (int i = 5; i >= 1; --i) ceiling_down.push_back(ceiling[i]);
  add_polygon(mesh, ceiling_down);
  // Walls: for each boundary edge p -> q of the L (counter-clockwise about +z, the room on its
  // left), the rectangle p, p + z, q + z, q runs counter-clockwise seen from the room.
  const double W[6][4] = {{0, 2, 0, 0}, {0, 0, 2, 0}, {2, 0, 2, 1},
                          {2, 1, 1, 1}, {1, 1, 1, 2}, {1, 2, 0, 2}};
  for (const auto& w : W) {
    const Vec3 p(w[0], w[1], 0), q(w[2], w[3], 0), up(0, 0, 1);
    add_polygon(mesh, {p, p + up, q + up, q});
  }
  return mesh;
}

/// The closed room [0, 1]^3 (facets 0-5, seen from inside) with three closed boxes inside, seen
/// from outside, none touching another or the room: [0.1, 0.3] x [0.1, 0.3] x [0.1, 0.4]
/// (facets 6-11), [0.5, 0.8] x [0.2, 0.4] x [0.3, 0.6] (12-17), [0.3, 0.6] x [0.6, 0.9] x
/// [0.55, 0.85] (18-23). 48 triangles.
inline TriangleMesh room_with_floating_boxes() {
  return room_with_boxes({{Vec3(0.1, 0.1, 0.1), Vec3(0.3, 0.3, 0.4)},
                          {Vec3(0.5, 0.2, 0.3), Vec3(0.8, 0.4, 0.6)},
                          {Vec3(0.3, 0.6, 0.55), Vec3(0.6, 0.9, 0.85)}},
                         "room_with_floating_boxes");
}

/// Three parallel open squares, centred on the z axis: facet 0 the emitter [-0.5, 0.5]^2 at z = 1
/// facing down (-z), facet 1 the opaque blocker [-0.25, 0.25]^2 at z = 0.5 facing down, facet 2
/// the receiving floor [-1, 1]^2 at z = 0 facing up (+z). 2 triangles each. Seen from a floor point
/// P = (px, py, 0), the blocker hides the emitter's points in its central projection from P onto
/// z = 1, the square [-0.5 - px, 0.5 - px] x [-0.5 - py, 0.5 - py] (scale factor 1 / 0.5 = 2):
/// configuration_factors.hpp gives the visible factor in closed form.
inline TriangleMesh shadow_scene() {
  TriangleMesh mesh;
  mesh.source = "shadow_scene";
  // Counter-clockwise seen from below: (x, y) order (-,-), (-,+), (+,+), (+,-).
  const double e = 0.5, b = 0.25;
  add_polygon(mesh, {Vec3(-e, -e, 1), Vec3(-e, e, 1), Vec3(e, e, 1), Vec3(e, -e, 1)});
  add_polygon(mesh, {Vec3(-b, -b, 0.5), Vec3(-b, b, 0.5), Vec3(b, b, 0.5), Vec3(b, -b, 0.5)});
  // Counter-clockwise seen from above.
  add_polygon(mesh, {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)});
  return mesh;
}

/// A block [-0.25, 0.25]^2 x [0, 0.5] standing on the floor [-1, 1]^2 at z = 0: facet 0 the floor
/// (one quad facing up, not cut under the block), facets 1-5 the block's top and four sides
/// (x = -0.25, x = 0.25, y = -0.25, y = 0.25), facing outside; the block has no bottom face, its
/// bottom edges lie on the floor. 12 triangles. The block's shadow and the floor's hidden part are
/// what V(P, Q) must account for.
inline TriangleMesh block_on_floor() {
  TriangleMesh mesh;
  mesh.source = "block_on_floor";
  add_polygon(mesh, {Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(1, 1, 0), Vec3(-1, 1, 0)});
  const double b = 0.25, h = 0.5;
  add_polygon(mesh, {Vec3(-b, -b, h), Vec3(b, -b, h), Vec3(b, b, h), Vec3(-b, b, h)});  // top, +z
  add_polygon(mesh, {Vec3(-b, -b, 0), Vec3(-b, -b, h), Vec3(-b, b, h), Vec3(-b, b, 0)});  // -x
  add_polygon(mesh, {Vec3(b, -b, 0), Vec3(b, b, 0), Vec3(b, b, h), Vec3(b, -b, h)});      // +x
  add_polygon(mesh, {Vec3(-b, -b, 0), Vec3(b, -b, 0), Vec3(b, -b, h), Vec3(-b, -b, h)});  // -y
  add_polygon(mesh, {Vec3(-b, b, 0), Vec3(-b, b, h), Vec3(b, b, h), Vec3(b, b, 0)});      // +y
  return mesh;
}

}  // namespace panelrad::testing

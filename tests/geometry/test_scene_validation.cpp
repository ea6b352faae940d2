// validate_scene on scenes built in code: the convex path kept bit for bit, closed rooms with
// objects and solids with cavities (front inward and outward, checked against the known inside of
// each box; the file's winding kept unless the nesting or an open piece in the air forbids it, then
// the reading with the fewest pieces against it, ties to the room), open surfaces
// (front on their counter-clockwise side), touching faces accepted, crossing faces and one-sided
// pieces refused with the faces and a point named, faces flipped to the majority of their piece.
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/scene_validation.hpp>
#include <panelrad/geometry/validation.hpp>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace pg = panelrad::geometry;

namespace {

const std::string kScenes = std::string(PANELRAD_SOURCE_DIR) + "/examples/scenes/";
const std::string kMeshes = std::string(PANELRAD_SOURCE_DIR) + "/examples/meshes/";

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << "message: " << (haystack)

/// A scene assembled from polygons, each one input face (facet), fan-triangulated.
struct SceneBuilder {
  pg::TriangleMesh mesh;
  SceneBuilder() { mesh.source = "test"; }

  pg::Index vertex(const pg::Vec3& p) {
    mesh.vertices.push_back(p);
    return static_cast<pg::Index>(mesh.vertices.size() - 1);
  }
  /// A polygon over existing vertices, listed counter-clockwise as given.
  pg::Index polygon(const std::vector<pg::Index>& v) {
    for (std::size_t k = 1; k + 1 < v.size(); ++k) {
      mesh.triangles.push_back({v[0], v[k], v[k + 1]});
      mesh.facet_of_triangle.push_back(mesh.num_facets);
    }
    return mesh.num_facets++;
  }
  /// A planar polygon over existing vertices, ordered so that it runs counter-clockwise seen from
  /// the side `front` points to (reversed keeping the first vertex, the apex of the fan).
  pg::Index facing(std::vector<pg::Index> v, const pg::Vec3& front) {
    const pg::Vec3& a = mesh.vertices[v[0]];
    if ((mesh.vertices[v[1]] - a).cross(mesh.vertices[v[2]] - a).dot(front) < 0) std::reverse(v.begin() + 1, v.end());
    return polygon(v);
  }
  /// A rectangle with new vertices: corner, two edge vectors; counter-clockwise seen from `front`.
  pg::Index quad(const pg::Vec3& o, const pg::Vec3& u, const pg::Vec3& w, const pg::Vec3& front) {
    return facing({vertex(o), vertex(o + u), vertex(o + u + w), vertex(o + w)}, front);
  }
  /// The axis box [lo, hi] as six quads (12 triangles) over 8 shared vertices, counter-clockwise
  /// seen from outside (outward = true) or from inside; `skip` leaves out faces, named by their
  /// outward normal ("-x", "+x", "-y", "+y", "-z", "+z"). Returns the facet id of each face kept,
  /// in that order (-1 for the skipped ones).
  std::vector<pg::Index> box(const pg::Vec3& lo, const pg::Vec3& hi, bool outward = true,
                             const std::vector<std::string>& skip = {}) {
    pg::Index c[2][2][2];
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        for (int k = 0; k < 2; ++k)
          c[i][j][k] = vertex({i ? hi.x() : lo.x(), j ? hi.y() : lo.y(), k ? hi.z() : lo.z()});
    const double s = outward ? 1.0 : -1.0;
    struct Face {
      std::string name;
      std::vector<pg::Index> v;
      pg::Vec3 normal;
    };
    const std::vector<Face> faces = {
        {"-x", {c[0][0][0], c[0][1][0], c[0][1][1], c[0][0][1]}, {-1, 0, 0}},
        {"+x", {c[1][0][0], c[1][1][0], c[1][1][1], c[1][0][1]}, {1, 0, 0}},
        {"-y", {c[0][0][0], c[1][0][0], c[1][0][1], c[0][0][1]}, {0, -1, 0}},
        {"+y", {c[0][1][0], c[1][1][0], c[1][1][1], c[0][1][1]}, {0, 1, 0}},
        {"-z", {c[0][0][0], c[1][0][0], c[1][1][0], c[0][1][0]}, {0, 0, -1}},
        {"+z", {c[0][0][1], c[1][0][1], c[1][1][1], c[0][1][1]}, {0, 0, 1}},
    };
    std::vector<pg::Index> ids;
    for (const Face& f : faces) {
      if (std::find(skip.begin(), skip.end(), f.name) != skip.end()) {
        ids.push_back(-1);
        continue;
      }
      ids.push_back(facing(f.v, s * f.normal));
    }
    return ids;
  }
  /// An n x n grid of quads on [0, size]^2 at z = 0 with shared vertices, counter-clockwise from +z.
  void grid(int n, double size) {
    std::vector<pg::Index> v;
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) v.push_back(vertex({size * i / n, size * j / n, 0.0}));
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const auto at = [&](int a, int b) { return v[static_cast<std::size_t>(b * (n + 1) + a)]; };
        polygon({at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  }
};

pg::Vec3 centroid(const pg::TriangleMesh& m, std::size_t t) {
  const auto& tr = m.triangles[t];
  return (m.vertices[tr[0]] + m.vertices[tr[1]] + m.vertices[tr[2]]) / 3.0;
}
/// The stored geometric normal (b - a) x (c - a), unit; by the storage convention it points to
/// the back, the front (inner normal n) is its negative.
pg::Vec3 geometric_normal(const pg::TriangleMesh& m, std::size_t t) {
  const auto& tr = m.triangles[t];
  const pg::Vec3& a = m.vertices[tr[0]];
  return (m.vertices[tr[1]] - a).cross(m.vertices[tr[2]] - a).normalized();
}
pg::Vec3 front_normal(const pg::TriangleMesh& m, std::size_t t) { return -geometric_normal(m, t); }
/// (b - a) x (c - a), twice the area in length.
pg::Vec3 geometric_normal_raw(const pg::TriangleMesh& m, std::size_t t) {
  const auto& tr = m.triangles[t];
  const pg::Vec3& a = m.vertices[tr[0]];
  return (m.vertices[tr[1]] - a).cross(m.vertices[tr[2]] - a);
}

bool in_box(const pg::Vec3& p, const pg::Vec3& lo, const pg::Vec3& hi) {
  return (p.array() > lo.array()).all() && (p.array() < hi.array()).all();
}

/// For each triangle in [first, last): a point a little in front of its centroid lies in the
/// region `inside` says, a point a little behind it does not (0.01 is far below every box size
/// used here and far above rounding, so the step never reaches another face).
void expect_front_into(const pg::TriangleMesh& m, std::size_t first, std::size_t last,
                       const std::function<bool(const pg::Vec3&)>& inside, const std::string& what) {
  for (std::size_t t = first; t < last; ++t) {
    const pg::Vec3 c = centroid(m, t), n = front_normal(m, t);
    EXPECT_TRUE(inside(c + 0.01 * n)) << what << ": triangle " << t << " faces away";
    EXPECT_FALSE(inside(c - 0.01 * n)) << what << ": triangle " << t << " faces backwards";
  }
}

/// The point named after " at (" in a crossing message.
pg::Vec3 crossing_point(const std::string& msg) {
  const std::size_t k = msg.find(" at (");
  EXPECT_NE(k, std::string::npos) << msg;
  if (k == std::string::npos) return pg::Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  pg::Vec3 p;
  std::size_t pos = k + 5;
  for (int i = 0; i < 3; ++i) {
    std::size_t used = 0;
    p[i] = std::stod(msg.substr(pos), &used);
    pos += used + 2;  // ", "
  }
  return p;
}

TEST(SceneValidation, BuiltinSolidsStayConvexAndIdenticalToTheConvexPath) {
  for (const std::string name : {"cube", "prism:7", "octahedron"}) {
    pg::TriangleMesh scene = pg::make_builtin(name), convex = scene;
    const pg::ValidationReport cr = pg::validate_closed_convex(convex);
    const pg::SceneValidationReport r = pg::validate_scene(scene);
    ASSERT_TRUE(r.valid) << name << ": " << r.message;
    EXPECT_EQ(r.shape, pg::SceneShape::convex);
    EXPECT_STREQ(pg::to_string(r.shape), "convex");
    EXPECT_EQ(r.pieces, 1u);
    EXPECT_EQ(r.closed_pieces, 1u);
    EXPECT_EQ(scene.vertices, convex.vertices) << name;  // Eigen ==: every coordinate bit for bit
    EXPECT_EQ(scene.triangles, convex.triangles) << name;
    EXPECT_EQ(scene.facet_of_triangle, convex.facet_of_triangle) << name;
    EXPECT_EQ(r.notes, cr.notes);
  }
  // Given inward: the convex path flips every triangle; the scene takes exactly that.
  pg::TriangleMesh scene = pg::make_cube();
  for (auto& t : scene.triangles) std::swap(t[1], t[2]);
  pg::TriangleMesh convex = scene;
  pg::validate_closed_convex(convex);
  const pg::SceneValidationReport r = pg::validate_scene(scene);
  ASSERT_TRUE(r.valid);
  EXPECT_EQ(r.flipped_faces, 12u);
  EXPECT_EQ(scene.triangles, convex.triangles);
}

TEST(SceneValidation, ClosedRoomWithABoxInside) {
  SceneBuilder b;
  const pg::Vec3 rlo(0, 0, 0), rhi(4, 3, 2.5), blo(1, 1, 0.5), bhi(2, 1.5, 1.5);
  b.box(rlo, rhi, /*outward=*/true);   // the usual export: counter-clockwise from outside
  b.box(blo, bhi, /*outward=*/false);  // and the box inward
  pg::SceneValidationReport r = pg::validate_scene(b.mesh);
  ASSERT_TRUE(r.valid) << r.message;
  EXPECT_EQ(r.shape, pg::SceneShape::general);
  EXPECT_STREQ(pg::to_string(r.shape), "general");
  EXPECT_EQ(r.convex_report.rule, "connected");
  EXPECT_EQ(r.pieces, 2u);
  EXPECT_EQ(r.closed_pieces, 2u);
  EXPECT_EQ(r.flipped_faces, 0u);
  ASSERT_EQ(r.notes.size(), 3u);
  EXPECT_CONTAINS(r.notes[0], "not one closed convex surface (connected: the surface has 2 separate pieces");
  EXPECT_CONTAINS(r.notes[0], "the visibility V(P, Q) is computed");
  // Wound so, the file consistently describes a solid (outer surface outward) with a cavity
  // (inward): of the nesting's two readings that one has no piece against the file's winding, the
  // other (a room with a body) two, so the file is kept.
  EXPECT_EQ(r.pieces_against_file, 0u);
  EXPECT_CONTAINS(r.notes[1], "piece 0 (12 triangles, closed): an object, front side outward, as the file winds it");
  EXPECT_CONTAINS(r.notes[1], "0 of them against the file's winding with it as a solid, 2 with it as a room");
  EXPECT_CONTAINS(r.notes[2], "piece 1 (12 triangles, closed): a cavity, front side inward, as the file winds it (inside the object piece 0");
  expect_front_into(b.mesh, 0, 12, [&](const pg::Vec3& p) { return !in_box(p, rlo, rhi); }, "solid");
  expect_front_into(b.mesh, 12, 24, [&](const pg::Vec3& p) { return in_box(p, blo, bhi); }, "cavity");
  // Nested: a box wound outward inside the cavity is a body in the cavity's air, front outward.
  // (A fresh scene: validation stores the triangles clockwise from the front, so the mesh above
  // no longer carries the file's winding.)
  SceneBuilder n;
  n.box(rlo, rhi, true);
  n.box(blo, bhi, false);
  n.box({1.2, 1.1, 0.7}, {1.4, 1.3, 0.9});
  r = pg::validate_scene(n.mesh);
  ASSERT_TRUE(r.valid) << r.message;
  ASSERT_EQ(r.notes.size(), 4u);
  EXPECT_EQ(r.pieces_against_file, 0u);
  EXPECT_CONTAINS(r.notes[3], "piece 2 (12 triangles, closed): an object, front side outward, as the file winds it");
  EXPECT_CONTAINS(r.notes[3], "inside the cavity piece 1");
  // The room with the box as exporters write both (outward): the two readings tie (one piece
  // against the file each), and the outermost piece is taken as the room.
  SceneBuilder e;
  e.box(rlo, rhi, true);
  e.box(blo, bhi, true);
  r = pg::validate_scene(e.mesh);
  ASSERT_TRUE(r.valid) << r.message;
  EXPECT_EQ(r.pieces_against_file, 1u);
  EXPECT_CONTAINS(r.notes[1], "piece 0 (12 triangles, closed): an enclosure, front side inward, against the file's winding (its faces run counter-clockwise seen from outside)");
  EXPECT_CONTAINS(r.notes[1], "1 of them against the file's winding with it as a room, 1 with it as a solid");
  EXPECT_CONTAINS(r.notes[1], "the outermost piece is the room");
  EXPECT_CONTAINS(r.notes[2], "piece 1 (12 triangles, closed): an object, front side outward, as the file winds it (inside the enclosure piece 0");
  expect_front_into(e.mesh, 0, 12, [&](const pg::Vec3& p) { return in_box(p, rlo, rhi); }, "room");
  expect_front_into(e.mesh, 12, 24, [&](const pg::Vec3& p) { return !in_box(p, blo, bhi); }, "box");
}

TEST(SceneValidation, LShapedRoomIsOneClosedNonConvexPiece) {
  // The L = [0,2]x[0,1] u [0,1]x[0,2] extruded over z in [0,1]; caps fanned from the reflex corner.
  SceneBuilder b;
  const std::vector<pg::Vec3> l = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  std::vector<pg::Index> bottom, top;
  for (const auto& p : l) bottom.push_back(b.vertex(p));
  for (const auto& p : l) top.push_back(b.vertex(p + pg::Vec3(0, 0, 1)));
  // Caps as polygons starting at the reflex corner (index 3), so that the fan lies inside the L.
  const auto rot = [](std::vector<pg::Index> v) {
    std::rotate(v.begin(), v.begin() + 3, v.end());
    return v;
  };
  b.facing(rot(bottom), {0, 0, 1});  // counter-clockwise from inside the room (the file's front)
  b.facing(rot(top), {0, 0, -1});
  for (std::size_t i = 0; i < l.size(); ++i) {
    const std::size_t j = (i + 1) % l.size();
    const pg::Vec3 edge = l[j] - l[i];
    b.facing({bottom[i], bottom[j], top[j], top[i]}, pg::Vec3(-edge.y(), edge.x(), 0));  // inward: L is CCW
  }
  const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
  ASSERT_TRUE(r.valid) << r.message;
  EXPECT_EQ(r.shape, pg::SceneShape::general);
  EXPECT_EQ(r.convex_report.rule, "convex");
  EXPECT_EQ(r.pieces, 1u);
  EXPECT_EQ(r.closed_pieces, 1u);
  ASSERT_EQ(b.mesh.triangles.size(), 20u);
  const auto in_l = [](const pg::Vec3& p) {
    return p.z() > 0 && p.z() < 1 && p.x() > 0 && p.y() > 0 && ((p.x() < 2 && p.y() < 1) || (p.x() < 1 && p.y() < 2));
  };
  expect_front_into(b.mesh, 0, 20, in_l, "L room");
}

TEST(SceneValidation, TwoSeparateBoxesFollowTheirWindings) {
  // Neither box is inside the other and no open piece lies in the air around them, so nothing
  // forces either: each is what the file winds it as, the first a body (outward), the second a
  // room (inward). Closed pieces side by side do not constrain each other.
  SceneBuilder b;
  const pg::Vec3 alo(0, 0, 0), ahi(1, 1, 1), blo(2, 0, 0), bhi(3, 1, 1);
  b.box(alo, ahi);
  b.box(blo, bhi, false);
  const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
  ASSERT_TRUE(r.valid) << r.message;
  EXPECT_EQ(r.pieces, 2u);
  EXPECT_EQ(r.closed_pieces, 2u);
  EXPECT_EQ(r.pieces_against_file, 0u);
  ASSERT_EQ(r.notes.size(), 3u);
  EXPECT_CONTAINS(r.notes[1], "piece 0 (12 triangles, closed): an object, front side outward, as the file winds it");
  EXPECT_CONTAINS(r.notes[1], "inside no other closed piece and holding none, so the file's winding decides");
  EXPECT_CONTAINS(r.notes[2], "piece 1 (12 triangles, closed): an enclosure, front side inward, as the file winds it");
  expect_front_into(b.mesh, 0, 12, [&](const pg::Vec3& p) { return !in_box(p, alo, ahi); }, "first box");
  expect_front_into(b.mesh, 12, 24, [&](const pg::Vec3& p) { return in_box(p, blo, bhi); }, "second box");
}

TEST(SceneValidation, TwoSeparateRoomsWoundInwardAreBothEnclosures) {
  SceneBuilder b;
  const pg::Vec3 alo(0, 0, 0), ahi(1, 1, 1), blo(2, 0, 0), bhi(3, 1, 1);
  b.box(alo, ahi, false);
  b.box(blo, bhi, false);
  const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
  ASSERT_TRUE(r.valid) << r.message;
  EXPECT_EQ(r.pieces_against_file, 0u);
  ASSERT_EQ(r.notes.size(), 3u);
  EXPECT_CONTAINS(r.notes[1], "piece 0 (12 triangles, closed): an enclosure, front side inward, as the file winds it");
  EXPECT_CONTAINS(r.notes[2], "piece 1 (12 triangles, closed): an enclosure, front side inward, as the file winds it");
  expect_front_into(b.mesh, 0, 12, [&](const pg::Vec3& p) { return in_box(p, alo, ahi); }, "first room");
  expect_front_into(b.mesh, 12, 24, [&](const pg::Vec3& p) { return in_box(p, blo, bhi); }, "second room");
}

TEST(SceneValidation, LShapedRoomAndABoxInItsNotchWoundInwardAreBothEnclosures) {
  // The L = [0,2]x[0,1] u [0,1]x[0,2] extruded over z in [0,1], wound inward, and the closed box
  // [1.2,1.8]x[1.2,1.8]x[0.2,0.8] in its notch (outside the L, touching nothing), wound inward.
  SceneBuilder b;
  const std::vector<pg::Vec3> l = {{0, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}, {1, 2, 0}, {0, 2, 0}};
  std::vector<pg::Index> bottom, top;
  for (const auto& p : l) bottom.push_back(b.vertex(p));
  for (const auto& p : l) top.push_back(b.vertex(p + pg::Vec3(0, 0, 1)));
  const auto rot = [](std::vector<pg::Index> v) {
    std::rotate(v.begin(), v.begin() + 3, v.end());
    return v;
  };
  b.facing(rot(bottom), {0, 0, 1});
  b.facing(rot(top), {0, 0, -1});
  for (std::size_t i = 0; i < l.size(); ++i) {
    const std::size_t j = (i + 1) % l.size();
    const pg::Vec3 edge = l[j] - l[i];
    b.facing({bottom[i], bottom[j], top[j], top[i]}, pg::Vec3(-edge.y(), edge.x(), 0));
  }
  const pg::Vec3 blo(1.2, 1.2, 0.2), bhi(1.8, 1.8, 0.8);
  b.box(blo, bhi, false);
  const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
  ASSERT_TRUE(r.valid) << r.message;
  EXPECT_EQ(r.closed_pieces, 2u);
  EXPECT_EQ(r.pieces_against_file, 0u);
  ASSERT_EQ(r.notes.size(), 3u);
  EXPECT_CONTAINS(r.notes[1], "piece 0 (20 triangles, closed): an enclosure, front side inward, as the file winds it");
  EXPECT_CONTAINS(r.notes[2], "piece 1 (12 triangles, closed): an enclosure, front side inward, as the file winds it");
  const auto in_l = [](const pg::Vec3& p) {
    return p.z() > 0 && p.z() < 1 && p.x() > 0 && p.y() > 0 && ((p.x() < 2 && p.y() < 1) || (p.x() < 1 && p.y() < 2));
  };
  expect_front_into(b.mesh, 0, 20, in_l, "L room");
  expect_front_into(b.mesh, 20, 32, [&](const pg::Vec3& p) { return in_box(p, blo, bhi); }, "room in the notch");
}

TEST(SceneValidation, LoneHollowSolidIsAnObjectWithACavity) {
  // Outer surface wound outward, the cavity inward, nothing else: a solid with a cavity, as the
  // file winds it (reading it as a room with a body would put both pieces against the file).
  for (const bool outward : {true, false}) {
    SceneBuilder b;
    const pg::Vec3 slo(0, 0, 0), shi(1, 1, 1), clo(0.3, 0.3, 0.3), chi(0.7, 0.7, 0.7);
    b.box(slo, shi, outward);
    b.box(clo, chi, !outward);
    const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
    ASSERT_TRUE(r.valid) << r.message;
    EXPECT_EQ(r.pieces_against_file, 0u);
    ASSERT_EQ(r.notes.size(), 3u);
    if (outward) {
      EXPECT_CONTAINS(r.notes[1], "piece 0 (12 triangles, closed): an object, front side outward, as the file winds it");
      EXPECT_CONTAINS(r.notes[2], "piece 1 (12 triangles, closed): a cavity, front side inward, as the file winds it");
      expect_front_into(b.mesh, 0, 12, [&](const pg::Vec3& p) { return !in_box(p, slo, shi); }, "solid");
      expect_front_into(b.mesh, 12, 24, [&](const pg::Vec3& p) { return in_box(p, clo, chi); }, "cavity");
    } else {  // wound the other way, the same file says a room with a body: so it is
      EXPECT_CONTAINS(r.notes[1], "piece 0 (12 triangles, closed): an enclosure, front side inward, as the file winds it");
      EXPECT_CONTAINS(r.notes[2], "piece 1 (12 triangles, closed): an object, front side outward, as the file winds it");
      expect_front_into(b.mesh, 0, 12, [&](const pg::Vec3& p) { return in_box(p, slo, shi); }, "room");
      expect_front_into(b.mesh, 12, 24, [&](const pg::Vec3& p) { return !in_box(p, clo, chi); }, "body");
    }
  }
}

TEST(SceneValidation, RoomWoundOutwardWithFurnitureIsAnEnclosure) {
  // As exporters write a room: every piece counter-clockwise from outside. With one body the two
  // readings tie (the room or the body against the file), the outermost is the room; with three,
  // reading the room as a solid would put its three cavities against the file, reading it as a
  // room only itself.
  for (const int bodies : {1, 3}) {
    SceneBuilder b;
    const pg::Vec3 rlo(0, 0, 0), rhi(4, 4, 2);
    b.box(rlo, rhi, true);
    std::vector<std::pair<pg::Vec3, pg::Vec3>> boxes = {
        {{0.5, 0.5, 0.5}, {1.5, 1.5, 1.0}}, {{2.5, 0.5, 0.5}, {3.5, 1.5, 1.0}}, {{1.5, 2.5, 0.5}, {2.5, 3.5, 1.5}}};
    boxes.resize(static_cast<std::size_t>(bodies));
    for (const auto& [lo, hi] : boxes) b.box(lo, hi, true);
    const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
    ASSERT_TRUE(r.valid) << r.message;
    EXPECT_EQ(r.pieces_against_file, 1u) << bodies;
    ASSERT_GE(r.notes.size(), 2u);
    EXPECT_CONTAINS(r.notes[1], "piece 0 (12 triangles, closed): an enclosure, front side inward, against the file's winding");
    EXPECT_CONTAINS(r.notes[1], "1 of them against the file's winding with it as a room, " + std::to_string(bodies) +
                                    " with it as a solid");
    if (bodies == 1) {
      EXPECT_CONTAINS(r.notes[1], "the outermost piece is the room");
    }
    expect_front_into(b.mesh, 0, 12, [&](const pg::Vec3& p) { return in_box(p, rlo, rhi); }, "room");
    for (std::size_t k = 0; k < boxes.size(); ++k) {
      EXPECT_CONTAINS(r.notes[2 + k], "an object, front side outward, as the file winds it (inside the enclosure piece 0");
      const auto& [lo, hi] = boxes[k];
      expect_front_into(b.mesh, 12 * (k + 1), 12 * (k + 2), [&](const pg::Vec3& p) { return !in_box(p, lo, hi); }, "box");
    }
  }
}

TEST(SceneValidation, PieceWoundAgainstItsNestingIsOverriddenByThePhysicalRule) {
  // A room wound inward with two bodies wound outward and one wound inward: a closed piece in a
  // room's air is a body, so the third is overridden (reading the room as a solid instead would
  // override three), and its note says which rule.
  SceneBuilder b;
  b.box({0, 0, 0}, {4, 4, 2}, false);
  b.box({0.5, 0.5, 0.5}, {1.5, 1.5, 1.0});
  b.box({2.5, 0.5, 0.5}, {3.5, 1.5, 1.0});
  const pg::Vec3 lo(1.5, 2.5, 0.5), hi(2.5, 3.5, 1.5);
  b.box(lo, hi, false);
  const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
  ASSERT_TRUE(r.valid) << r.message;
  EXPECT_EQ(r.pieces_against_file, 1u);
  ASSERT_EQ(r.notes.size(), 5u);
  EXPECT_CONTAINS(r.notes[1], "piece 0 (12 triangles, closed): an enclosure, front side inward, as the file winds it");
  EXPECT_CONTAINS(r.notes[1], "1 of them against the file's winding with it as a room, 3 with it as a solid");
  EXPECT_CONTAINS(r.notes[4], "piece 3 (12 triangles, closed): an object, front side outward, against the file's winding "
                              "(its faces run counter-clockwise seen from inside) (inside the enclosure piece 0: a closed "
                              "piece in an enclosure's air is an object)");
  expect_front_into(b.mesh, 36, 48, [&](const pg::Vec3& p) { return !in_box(p, lo, hi); }, "overridden box");
}

TEST(SceneValidation, RoomWithALampInsideIsAnEnclosureWhateverItsWinding) {
  // An open lamp inside the room lives in the room's air: the room cannot be a solid.
  for (const bool outward : {true, false}) {
    SceneBuilder b;
    const pg::Vec3 lo(0, 0, 0), hi(2, 2, 2);
    b.box(lo, hi, outward);
    b.quad({0.5, 0.5, 1.8}, {1, 0, 0}, {0, 1, 0}, {0, 0, -1});
    const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
    ASSERT_TRUE(r.valid) << r.message;
    EXPECT_EQ(r.pieces_against_file, outward ? 1u : 0u);
    EXPECT_CONTAINS(r.notes[1], "piece 0 (12 triangles, closed): an enclosure, front side inward");
    EXPECT_CONTAINS(r.notes[1], "open piece 1 lies in the air inside it");
    expect_front_into(b.mesh, 0, 12, [&](const pg::Vec3& p) { return in_box(p, lo, hi); }, "room");
  }
}

TEST(SceneValidation, ClosedPieceWithOpenPiecesInsideAndOutsideFollowsTheFile) {
  // A lamp inside the box and a sheet outside it: the box would need air on both sides, which a
  // closed one-sided surface cannot have, so the file's winding decides and the note says why.
  for (const bool outward : {true, false}) {
    SceneBuilder b;
    const pg::Vec3 lo(0, 0, 0), hi(2, 2, 2);
    b.box(lo, hi, outward);
    b.quad({0.5, 0.5, 1.8}, {1, 0, 0}, {0, 1, 0}, {0, 0, -1});
    b.quad({0, 0, 3}, {2, 0, 0}, {0, 2, 0}, {0, 0, -1});
    const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
    ASSERT_TRUE(r.valid) << r.message;
    EXPECT_EQ(r.pieces_against_file, 0u);
    EXPECT_CONTAINS(r.notes[1], outward ? "an object, front side outward, as the file winds it"
                                        : "an enclosure, front side inward, as the file winds it");
    EXPECT_CONTAINS(r.notes[1], "open piece 1 lies in the air inside it and open piece 2 in the air outside it");
  }
}

TEST(SceneValidation, ClosedCubeUnderALampIsSeenFromOutsideWhateverItsWinding) {
  for (const bool outward : {true, false}) {
    SceneBuilder b;
    const pg::Vec3 lo(0, 0, 0), hi(1, 1, 1);
    b.box(lo, hi, outward);
    b.quad({-1, -1, 3}, {3, 0, 0}, {0, 3, 0}, {0, 0, -1});  // the lamp, facing down
    const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
    ASSERT_TRUE(r.valid) << r.message;
    EXPECT_EQ(r.pieces_against_file, outward ? 0u : 1u);
    EXPECT_CONTAINS(r.notes[1], "an object, front side outward");
    expect_front_into(b.mesh, 0, 12, [&](const pg::Vec3& p) { return !in_box(p, lo, hi); }, "cube");
    for (std::size_t t = 12; t < 14; ++t) EXPECT_LT(front_normal(b.mesh, t).z(), 0.0) << "lamp";
  }
}

TEST(SceneValidation, RoomHoldingEverythingIsReadWithTheFewestPiecesAgainstTheFile) {
  for (const bool outward : {true, false}) {
    SceneBuilder b;
    b.box({0, 0, 0}, {2, 1, 1}, outward);
    b.box({3, 0, 0}, {4, 1, 1}, outward);  // and a second room beside it, inside a third
    b.box({-1, -1, -1}, {5, 2, 2}, outward);
    const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
    ASSERT_TRUE(r.valid) << r.message;
    EXPECT_EQ(r.pieces_against_file, 1u);
    if (outward) {
      // The outer box holds the other two: read as a room, only it is against the file's winding
      // (the two inside are bodies as wound); read as a solid, its two cavities would be.
      expect_front_into(b.mesh, 24, 36, [&](const pg::Vec3& p) { return in_box(p, {-1, -1, -1}, {5, 2, 2}); }, "outer");
      expect_front_into(b.mesh, 0, 12, [&](const pg::Vec3& p) { return !in_box(p, {0, 0, 0}, {2, 1, 1}); }, "inner");
      EXPECT_CONTAINS(r.notes[3], "piece 2 (12 triangles, closed): an enclosure, front side inward, against the file's winding");
      EXPECT_CONTAINS(r.notes[3], "1 of them against the file's winding with it as a room, 2 with it as a solid");
    } else {
      // All three wound as rooms: two rooms cannot float in a room's air (a closed piece there is
      // a body), so one reading overrides the two inside, the other only the outer box, which
      // becomes a solid with two cavities, as the two inner pieces are wound.
      expect_front_into(b.mesh, 24, 36, [&](const pg::Vec3& p) { return !in_box(p, {-1, -1, -1}, {5, 2, 2}); }, "outer");
      expect_front_into(b.mesh, 0, 12, [&](const pg::Vec3& p) { return in_box(p, {0, 0, 0}, {2, 1, 1}); }, "inner");
      EXPECT_CONTAINS(r.notes[3], "piece 2 (12 triangles, closed): an object, front side outward, against the file's winding");
      EXPECT_CONTAINS(r.notes[3], "1 of them against the file's winding with it as a solid, 2 with it as a room");
      EXPECT_CONTAINS(r.notes[1], "piece 0 (12 triangles, closed): a cavity, front side inward, as the file winds it");
    }
  }
}

TEST(SceneValidation, CavityInsideAnObjectInsideARoomAlternates) {
  // Room (front inward), a thick shell (front outward), its closed cavity (front inward) and a
  // ball in the cavity (front outward), each given with the wrong winding: the nesting still
  // alternates, and the file's own alternation is the reading with no piece against it (a solid,
  // a cavity in it, a body in the cavity, a cavity in the body). One piece wound against an
  // otherwise consistent nesting is overridden, and its note names the rule.
  const pg::Vec3 rlo(0, 0, 0), rhi(4, 4, 4), slo(1, 1, 1), shi(3, 3, 3), clo(1.5, 1.5, 1.5), chi(2.5, 2.5, 2.5),
      blo(1.8, 1.8, 1.8), bhi(2.2, 2.2, 2.2);
  {
    SceneBuilder b;
    b.box(rlo, rhi, true);
    b.box(slo, shi, false);
    b.box(clo, chi, true);
    b.box(blo, bhi, false);
    const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
    ASSERT_TRUE(r.valid) << r.message;
    EXPECT_EQ(r.pieces_against_file, 0u);
    expect_front_into(b.mesh, 0, 12, [&](const pg::Vec3& p) { return !in_box(p, rlo, rhi); }, "solid");
    expect_front_into(b.mesh, 12, 24, [&](const pg::Vec3& p) { return in_box(p, slo, shi); }, "its cavity");
    expect_front_into(b.mesh, 24, 36, [&](const pg::Vec3& p) { return !in_box(p, clo, chi); }, "body in the cavity");
    expect_front_into(b.mesh, 36, 48, [&](const pg::Vec3& p) { return in_box(p, blo, bhi); }, "its cavity");
    EXPECT_CONTAINS(r.notes[1], "0 of them against the file's winding with it as a solid, 4 with it as a room");
    EXPECT_CONTAINS(r.notes[3], "piece 2 (12 triangles, closed): an object, front side outward");
    EXPECT_CONTAINS(r.notes[3], "inside the cavity piece 1");
    EXPECT_CONTAINS(r.notes[4], "a cavity, front side inward");
    EXPECT_CONTAINS(r.notes[4], "inside the object piece 2");
  }
  SceneBuilder b;
  b.box(rlo, rhi, false);
  b.box(slo, shi, false);  // the one against the nesting
  b.box(clo, chi, false);
  b.box(blo, bhi, true);
  const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
  ASSERT_TRUE(r.valid) << r.message;
  EXPECT_EQ(r.pieces_against_file, 1u);
  expect_front_into(b.mesh, 0, 12, [&](const pg::Vec3& p) { return in_box(p, rlo, rhi); }, "room");
  expect_front_into(b.mesh, 12, 24, [&](const pg::Vec3& p) { return !in_box(p, slo, shi); }, "shell");
  expect_front_into(b.mesh, 24, 36, [&](const pg::Vec3& p) { return in_box(p, clo, chi); }, "cavity");
  expect_front_into(b.mesh, 36, 48, [&](const pg::Vec3& p) { return !in_box(p, blo, bhi); }, "ball");
  EXPECT_CONTAINS(r.notes[2], "piece 1 (12 triangles, closed): an object, front side outward, against the file's "
                              "winding (its faces run counter-clockwise seen from inside) (inside the enclosure piece 0: "
                              "a closed piece in an enclosure's air is an object)");
  EXPECT_CONTAINS(r.notes[3], "piece 2 (12 triangles, closed): a cavity, front side inward");
  EXPECT_CONTAINS(r.notes[3], "inside the object piece 1: a closed piece in an object's solid is a cavity");
  EXPECT_CONTAINS(r.notes[4], "an object, front side outward");
  EXPECT_CONTAINS(r.notes[4], "inside the cavity piece 2: a closed piece in a cavity's air is an object");
}

TEST(SceneValidation, HollowObjectUnderALampIsAnObjectWhateverItsWinding) {
  // A shell with a cavity and a lamp outside: the lamp hangs in the air around the shell, so the
  // shell is a solid seen from outside and its cavity a cavity, whatever the winding; wound the
  // other way both are overridden, and the notes name the lamp.
  for (const bool outward : {true, false}) {
    SceneBuilder b;
    const pg::Vec3 slo(1, 1, 1), shi(3, 3, 3), clo(1.5, 1.5, 1.5), chi(2.5, 2.5, 2.5);
    b.box(slo, shi, outward);
    b.box(clo, chi, !outward);
    b.quad({0, 0, 5}, {4, 0, 0}, {0, 4, 0}, {0, 0, -1});
    const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
    ASSERT_TRUE(r.valid) << r.message;
    EXPECT_CONTAINS(r.notes[1], "open piece 2 lies in the air outside it");
    EXPECT_EQ(r.pieces_against_file, outward ? 0u : 2u);
    EXPECT_CONTAINS(r.notes[1], "an object, front side outward");
    EXPECT_CONTAINS(r.notes[2], "a cavity, front side inward");
    expect_front_into(b.mesh, 0, 12, [&](const pg::Vec3& p) { return !in_box(p, slo, shi); }, "shell");
    expect_front_into(b.mesh, 12, 24, [&](const pg::Vec3& p) { return in_box(p, clo, chi); }, "cavity");
  }
}

TEST(SceneValidation, RoomWithATJunctionIsClosedAndItsBoxAnObject) {
  // The unit room wound inward, its ceiling given as two halves: the walls y = 0 and y = 1 run
  // whole along the top, so the halves' corners (0.5, 0, 1) and (0.5, 1, 1) lie inside those edges.
  SceneBuilder b;
  std::vector<pg::Index> v;
  const auto at = [&](double x, double y, double z) {
    for (std::size_t i = 0; i < b.mesh.vertices.size(); ++i)
      if (b.mesh.vertices[i] == pg::Vec3(x, y, z)) return static_cast<pg::Index>(i);
    return b.vertex({x, y, z});
  };
  const pg::Vec3 in(0.5, 0.5, 0.5);
  const auto face = [&](std::vector<pg::Index> c) {
    pg::Vec3 m = pg::Vec3::Zero();
    for (pg::Index i : c) m += b.mesh.vertices[static_cast<std::size_t>(i)];
    m /= static_cast<double>(c.size());
    b.facing(std::move(c), in - m);
  };
  face({at(0, 0, 0), at(1, 0, 0), at(1, 1, 0), at(0, 1, 0)});
  face({at(0, 0, 1), at(0.5, 0, 1), at(0.5, 1, 1), at(0, 1, 1)});
  face({at(0.5, 0, 1), at(1, 0, 1), at(1, 1, 1), at(0.5, 1, 1)});
  face({at(0, 0, 0), at(1, 0, 0), at(1, 0, 1), at(0, 0, 1)});
  face({at(0, 1, 0), at(1, 1, 0), at(1, 1, 1), at(0, 1, 1)});
  face({at(0, 0, 0), at(0, 1, 0), at(0, 1, 1), at(0, 0, 1)});
  face({at(1, 0, 0), at(1, 1, 0), at(1, 1, 1), at(1, 0, 1)});
  const std::size_t room_triangles = b.mesh.triangles.size();
  const pg::Vec3 blo(0.3, 0.3, 0.2), bhi(0.6, 0.6, 0.5);
  b.box(blo, bhi, false);
  const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
  ASSERT_TRUE(r.valid) << r.message;
  EXPECT_EQ(r.t_junctions_split, 2u);
  EXPECT_EQ(r.closed_pieces, 2u);
  // The split walls have one more triangle each; the room's fronts inward, the box's outward.
  ASSERT_EQ(b.mesh.triangles.size(), room_triangles + 2 + 12);
  expect_front_into(b.mesh, 0, room_triangles + 2, [&](const pg::Vec3& p) { return in_box(p, {0, 0, 0}, {1, 1, 1}); }, "room");
  expect_front_into(b.mesh, room_triangles + 2, b.mesh.triangles.size(), [&](const pg::Vec3& p) { return !in_box(p, blo, bhi); }, "box");
}

/// The total area of the triangles of facet f.
double facet_area(const pg::TriangleMesh& m, pg::Index f) {
  double a = 0;
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    if (m.facet_of_triangle[t] == f) a += 0.5 * geometric_normal_raw(m, t).norm();
  return a;
}

TEST(SceneValidation, BoxRestingOnTheFloorLosesItsContactFaces) {
  // The unit room with a box standing on its floor: the floor under the box and the box's bottom
  // face are inside solid matter and removed; the rest stays with its front sides.
  SceneBuilder b;
  const std::vector<pg::Index> room = b.box({0, 0, 0}, {1, 1, 1}, false);
  const pg::Vec3 blo(0.25, 0.375, 0), bhi(0.625, 0.75, 0.3);
  const std::vector<pg::Index> box = b.box(blo, bhi, true);
  const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
  ASSERT_TRUE(r.valid) << r.message;
  const double footprint = (bhi.x() - blo.x()) * (bhi.y() - blo.y());
  ASSERT_EQ(r.contacts.size(), 1u);
  EXPECT_EQ(r.contacts[0].face_a, room[4]);
  EXPECT_EQ(r.contacts[0].face_b, box[4]);
  EXPECT_NEAR(r.contacts[0].removed_a, footprint, 1e-15);
  EXPECT_NEAR(r.contacts[0].removed_b, footprint, 1e-15);
  EXPECT_NEAR(r.contact_area_removed, 2 * footprint, 1e-15);
  EXPECT_NEAR(facet_area(b.mesh, room[4]), 1 - footprint, 1e-15);
  EXPECT_EQ(facet_area(b.mesh, box[4]), 0.0);
  bool noted = false;
  for (const std::string& n : r.notes) noted = noted || n.find("touch with their front sides against each other") != std::string::npos;
  EXPECT_TRUE(noted);
  for (std::size_t t = 0; t < b.mesh.triangles.size(); ++t) {
    const pg::Vec3 c = centroid(b.mesh, t);
    if (b.mesh.facet_of_triangle[t] == room[4]) {
      EXPECT_FALSE(c.x() > blo.x() && c.x() < bhi.x() && c.y() > blo.y() && c.y() < bhi.y()) << "floor under the box";
      EXPECT_GT(front_normal(b.mesh, t).z(), 0.99);
    }
  }
  // No vertex is left that no triangle uses.
  std::vector<char> used(b.mesh.vertices.size(), 0);
  for (const auto& tr : b.mesh.triangles)
    for (pg::Index v : tr) used[static_cast<std::size_t>(v)] = 1;
  EXPECT_EQ(std::count(used.begin(), used.end(), 0), 0);
}

// Whether light stays on front sides (closed), in the scene (enclosed), or leaves it. A box standing
// on the floor loses its bottom and the floor under it, which leaves no hole: every ray from a
// front side still ends on a front side, as in the room with a floating box.
TEST(SceneValidation, RoomWithABoxStandingOnItsFloorIsClosed) {
  for (const double lift : {0.0, 0.25}) {
    SceneBuilder b;
    b.box({0, 0, 0}, {1, 1, 1}, false);
    b.box({0.25, 0.375, lift}, {0.625, 0.75, lift + 0.3});
    const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
    ASSERT_TRUE(r.valid) << r.message;
    EXPECT_EQ(r.contacts.size(), lift == 0 ? 1u : 0u);
    EXPECT_TRUE(r.enclosed) << "lift " << lift;
    EXPECT_TRUE(r.closed) << "lift " << lift;
  }
  // The convex path: one closed surface seen from inside.
  pg::TriangleMesh cube = pg::make_cube();
  const pg::SceneValidationReport convex = pg::validate_scene(cube);
  EXPECT_EQ(convex.shape, pg::SceneShape::convex);
  EXPECT_TRUE(convex.enclosed && convex.closed);
}

// A one-sided sheet in a closed room: no light leaves the room, but the sheet's back side takes
// what falls on it (it neither reflects nor emits), so the room is enclosed, not closed.
TEST(SceneValidation, OneSidedSheetInARoomIsEnclosedButNotClosed) {
  for (const double z : {-1.0, 1.0}) {
    SceneBuilder b;
    b.box({0, 0, 0}, {1, 1, 1}, false);
    b.quad({0.25, 0.25, 0.5}, {0.5, 0, 0}, {0, 0.5, 0}, {0, 0, z});
    const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
    ASSERT_TRUE(r.valid) << r.message;
    EXPECT_TRUE(r.enclosed) << "sheet facing z = " << z;
    EXPECT_FALSE(r.closed) << "sheet facing z = " << z;
  }
}

// Light leaves a room without its front wall, and a cube under a lamp (nothing around them).
TEST(SceneValidation, OpenRoomAndCubeUnderALampAreNeitherClosedNorEnclosed) {
  SceneBuilder open_room;
  open_room.box({0, 0, 0}, {1, 1, 1}, false, {"-y"});
  SceneBuilder lamp;
  lamp.box({0, 0, 0}, {1, 1, 1});
  lamp.quad({-1, -1, 3}, {3, 0, 0}, {0, 3, 0}, {0, 0, -1});
  for (SceneBuilder* b : {&open_room, &lamp}) {
    const pg::SceneValidationReport r = pg::validate_scene(b->mesh);
    ASSERT_TRUE(r.valid) << r.message;
    EXPECT_FALSE(r.enclosed);
    EXPECT_FALSE(r.closed);
  }
}

TEST(SceneValidation, BoxesFaceToFaceLoseTheOverlapOnly) {
  // Two boxes touching in the plane x = 0.4 over [0.3, 0.4] x [0.25, 0.4] (a partial overlap).
  SceneBuilder b;
  b.box({0, 0, 0}, {1, 1, 1}, false);
  const std::vector<pg::Index> a = b.box({0.2, 0.2, 0.2}, {0.4, 0.4, 0.4});
  const std::vector<pg::Index> c = b.box({0.4, 0.3, 0.25}, {0.6, 0.5, 0.45});
  const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
  ASSERT_TRUE(r.valid) << r.message;
  ASSERT_EQ(r.contacts.size(), 1u);
  const double overlap = 0.1 * 0.15;
  EXPECT_NEAR(r.contacts[0].removed_a, overlap, 1e-15);
  EXPECT_NEAR(r.contacts[0].removed_b, overlap, 1e-15);
  EXPECT_NEAR(facet_area(b.mesh, a[1]), 0.04 - overlap, 1e-15);
  EXPECT_NEAR(facet_area(b.mesh, c[0]), 0.04 - overlap, 1e-15);
  // Each face keeps its front side: +x for the first box's face, -x for the second's.
  for (std::size_t t = 0; t < b.mesh.triangles.size(); ++t) {
    if (b.mesh.facet_of_triangle[t] == a[1]) {
      EXPECT_GT(front_normal(b.mesh, t).x(), 0.99);
    }
    if (b.mesh.facet_of_triangle[t] == c[0]) {
      EXPECT_LT(front_normal(b.mesh, t).x(), -0.99);
    }
  }
}

TEST(SceneValidation, FaceGivenTwiceIsRefusedByName) {
  SceneBuilder b;
  b.box({0, 0, 0}, {1, 1, 1}, false);
  b.quad({0.2, 0.2, 0.5}, {0.2, 0, 0}, {0, 0.2, 0}, {0, 0, 1});
  b.quad({0.2, 0.2, 0.5}, {0.2, 0, 0}, {0, 0.2, 0}, {0, 0, 1});
  const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
  ASSERT_FALSE(r.valid);
  EXPECT_EQ(r.rule, "crossing");
  EXPECT_CONTAINS(r.message, "input face 7 duplicates input face 6: the same polygon with the same front side");
  EXPECT_CONTAINS(r.message, "remove one of them");
}

TEST(SceneValidation, OpenRoomKeepsTheCounterClockwiseSideAsFront) {
  // The unit room without its front wall (y = 0), counter-clockwise seen from inside.
  SceneBuilder b;
  b.box({0, 0, 0}, {1, 1, 1}, /*outward=*/false, {"-y"});
  const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
  ASSERT_TRUE(r.valid) << r.message;
  EXPECT_EQ(r.convex_report.rule, "closed");
  EXPECT_EQ(r.pieces, 1u);
  EXPECT_EQ(r.closed_pieces, 0u);
  EXPECT_EQ(r.flipped_faces, 0u);
  ASSERT_EQ(r.notes.size(), 2u);
  EXPECT_CONTAINS(r.notes[1], "piece 0 (10 triangles, open): an open surface, front side where its faces run counter-clockwise");
  const pg::Vec3 centre(0.5, 0.5, 0.5);
  for (std::size_t t = 0; t < b.mesh.triangles.size(); ++t)  // stored normal to the back: outward
    EXPECT_GT(geometric_normal(b.mesh, t).dot(centroid(b.mesh, t) - centre), 0.0) << "triangle " << t;
}

TEST(SceneValidation, BlockWithoutBottomStandsOnAnUncutFloor) {
  // The block's bottom edges lie inside the floor's two triangles and cross its diagonal
  // (T-junctions): touching, not crossing.
  SceneBuilder b;
  b.quad({0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 1});
  b.box({1, 1.5, 0}, {2, 2.5, 1}, true, {"-z"});
  const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
  ASSERT_TRUE(r.valid) << r.message;
  EXPECT_EQ(r.shape, pg::SceneShape::general);
  EXPECT_EQ(r.pieces, 2u);
  EXPECT_EQ(r.closed_pieces, 0u);
  // The floor's front is up (+z), stored with its geometric normal down; the block's front outward.
  for (std::size_t t = 0; t < 2; ++t) EXPECT_LT(geometric_normal(b.mesh, t).z(), 0.0);
  for (std::size_t t = 2; t < b.mesh.triangles.size(); ++t)
    EXPECT_LT(geometric_normal(b.mesh, t).dot(centroid(b.mesh, t) - pg::Vec3(1.5, 2, 0.5)), 0.0);
  // A block sunk into the floor by 0.25 is refused: its walls cut through it.
  SceneBuilder sunk;
  sunk.quad({0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {0, 0, 1});
  sunk.box({1, 1.5, -0.25}, {2, 2.5, 1}, true, {"-z"});
  EXPECT_EQ(pg::validate_scene(sunk.mesh).rule, "crossing");
}

TEST(SceneValidation, WallPiercingAFaceIsRefusedWithBothFacesAndAPoint) {
  // A closed box, and a quad in the plane y = 0.5 from x = 0.5 to 1.5: it cuts the wall x = 1
  // along x = 1, y = 0.5, z in [0.25, 0.75].
  SceneBuilder b;
  const std::vector<pg::Index> faces = b.box({0, 0, 0}, {1, 1, 1});
  const pg::Index quad = b.quad({0.5, 0.5, 0.25}, {1, 0, 0}, {0, 0, 0.5}, {0, 1, 0});
  pg::TriangleMesh input = b.mesh;
  const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
  ASSERT_FALSE(r.valid);
  EXPECT_EQ(r.rule, "crossing");
  EXPECT_CONTAINS(r.message, "crossing: input faces " + std::to_string(faces[1]) + " and " + std::to_string(quad) + " cross at (");
  EXPECT_CONTAINS(r.message, "(input face " + std::to_string(faces[1]) + "; vertices");
  EXPECT_CONTAINS(r.message, "(input face " + std::to_string(quad) + "; vertices");
  EXPECT_CONTAINS(r.message, "split the faces along their intersection, or move one so that they only touch");
  const pg::Vec3 x = crossing_point(r.message);
  EXPECT_EQ(x.x(), 1.0);  // exact constructions, printed round-trip: the values on the segment exactly
  EXPECT_EQ(x.y(), 0.5);
  EXPECT_GT(x.z(), 0.25);
  EXPECT_LT(x.z(), 0.75);
  EXPECT_EQ(b.mesh.triangles, input.triangles);  // unchanged when refused
}

TEST(SceneValidation, CoplanarOverlapOfTwoSheetsBackToBackIsTwoSided) {
  // Two open quads overlapping back to back: neither bounds matter, so neither covers the other;
  // where they overlap the sheet is seen from both sides, each face from its own front side.
  SceneBuilder b;
  b.quad({0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 1});
  b.quad({1, 1, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, -1});
  const pg::TriangleMesh input = b.mesh;
  pg::SceneValidationReport r = pg::validate_scene(b.mesh);
  ASSERT_TRUE(r.valid) << r.message;
  EXPECT_TRUE(r.contacts.empty());
  EXPECT_EQ(b.mesh.triangles.size(), input.triangles.size());  // nothing removed
  bool noted = false;
  for (const std::string& n : r.notes) noted = noted || n.find("input faces 0 and 1 lie back to back") != std::string::npos;
  EXPECT_TRUE(noted);
  // Facing the same way: the same surface twice.
  SceneBuilder same;
  same.quad({0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 1});
  same.quad({1, 1, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 1});
  r = pg::validate_scene(same.mesh);
  ASSERT_FALSE(r.valid);
  EXPECT_CONTAINS(r.message, "input faces 0 and 1 overlap in one plane with the same front side at (");
}

TEST(SceneValidation, CoplanarQuadsSharingAnEdgeWithSeparateVerticesTouch) {
  SceneBuilder b;
  b.quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  b.quad({1, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  // And one touching the first at a corner only, and one whose corner lies on the first's edge.
  b.quad({-1, -1, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  b.quad({-1, 0.5, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
  ASSERT_TRUE(r.valid) << r.message;
  // The first quad's corner (0, 1, 0) lies inside the last one's edge and the last one's corner
  // (0, 0.5, 0) inside the first one's: both edges are split there (T-junctions), the two quads
  // then share the edge from (0, 0.5, 0) to (0, 1, 0) and are one piece.
  // The second quad's corners at the first's are one corner with them (corners closer than the
  // visibility's resolution are joined), so the two share the edge and are one piece with the last.
  EXPECT_EQ(r.t_junctions_split, 2u);
  EXPECT_EQ(r.pieces, 2u);
  // A duplicate of the first triangle over the same vertices, reversed: back to back, a two-sided
  // piece of sheet; the same triangle twice with one winding is refused.
  SceneBuilder d;
  d.quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  d.mesh.triangles.push_back({d.mesh.triangles[0][0], d.mesh.triangles[0][2], d.mesh.triangles[0][1]});
  d.mesh.facet_of_triangle.push_back(d.mesh.num_facets++);
  EXPECT_TRUE(pg::validate_scene(d.mesh).valid);
  SceneBuilder e;
  e.quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  e.mesh.triangles.push_back(e.mesh.triangles[0]);
  e.mesh.facet_of_triangle.push_back(e.mesh.num_facets++);
  EXPECT_EQ(pg::validate_scene(e.mesh).rule, "crossing");
}

TEST(SceneValidation, SingleQuadIsAGeneralScene) {
  SceneBuilder b;
  b.quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
  ASSERT_TRUE(r.valid) << r.message;
  EXPECT_EQ(r.shape, pg::SceneShape::general);
  EXPECT_EQ(r.convex_report.rule, "closed");
  EXPECT_EQ(r.pieces, 1u);
  for (std::size_t t = 0; t < 2; ++t) EXPECT_EQ(geometric_normal(b.mesh, t), pg::Vec3(0, 0, -1));  // front +z
  // A triangle and its reverse over the same vertices: refused by the convex path as enclosing no
  // volume; on the general path the two are folded flat onto each other across every edge, so no
  // edge joins them: two open pieces back to back, a two-sided sheet.
  SceneBuilder two;
  two.polygon({two.vertex({0, 0, 0}), two.vertex({1, 0, 0}), two.vertex({0, 1, 0})});
  two.polygon({0, 2, 1});
  const pg::SceneValidationReport f = pg::validate_scene(two.mesh);
  EXPECT_EQ(f.convex_report.rule, "non-degenerate");
  EXPECT_CONTAINS(f.convex_report.message, "all vertices are coplanar");
  ASSERT_TRUE(f.valid) << f.message;
  EXPECT_EQ(f.pieces, 2u);
  EXPECT_EQ(f.closed_pieces, 0u);
}

TEST(SceneValidation, MoebiusStripIsRefusedAsNotOrientable) {
  // Centre circle of radius 2, half-width 0.5, turning by pi once around: 16 quads; the last one
  // joins the end to the start with the sides exchanged.
  SceneBuilder b;
  const int n = 16;
  std::vector<pg::Index> in, out;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * std::numbers::pi * i / n;
    const pg::Vec3 c(2 * std::cos(t), 2 * std::sin(t), 0), radial(std::cos(t), std::sin(t), 0);
    const pg::Vec3 w = 0.5 * (std::cos(t / 2) * radial + std::sin(t / 2) * pg::Vec3(0, 0, 1));
    in.push_back(b.vertex(c - w));
    out.push_back(b.vertex(c + w));
  }
  for (int i = 0; i + 1 < n; ++i) b.polygon({in[i], in[i + 1], out[i + 1], out[i]});
  b.polygon({in[n - 1], out[0], in[0], out[n - 1]});  // at t = 2 pi, c + w is the start's c - w
  const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
  ASSERT_FALSE(r.valid);
  EXPECT_EQ(r.rule, "orientable") << r.message;
  EXPECT_CONTAINS(r.message, "orientable: the piece of the surface containing triangle 0 is one-sided");
  EXPECT_CONTAINS(r.message, "cannot be oriented consistently with its neighbours");
  // The same strip without the twist (an annulus) is fine.
  SceneBuilder a;
  std::vector<pg::Index> ai, ao;
  for (int i = 0; i < n; ++i) {
    const double t = 2 * std::numbers::pi * i / n;
    ai.push_back(a.vertex({1.5 * std::cos(t), 1.5 * std::sin(t), 0}));
    ao.push_back(a.vertex({2.5 * std::cos(t), 2.5 * std::sin(t), 0}));
  }
  for (int i = 0; i < n; ++i) a.polygon({ai[i], ai[(i + 1) % n], ao[(i + 1) % n], ao[i]});
  EXPECT_TRUE(pg::validate_scene(a.mesh).valid);
}

TEST(SceneValidation, InconsistentTrianglesOfAnOpenPieceFollowTheMajority) {
  SceneBuilder b;
  b.grid(3, 3.0);  // 18 triangles counter-clockwise from +z
  std::swap(b.mesh.triangles[4][1], b.mesh.triangles[4][2]);
  std::swap(b.mesh.triangles[11][1], b.mesh.triangles[11][2]);
  const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
  ASSERT_TRUE(r.valid) << r.message;
  EXPECT_EQ(r.flipped_faces, 2u);
  ASSERT_EQ(r.notes.size(), 2u);
  EXPECT_CONTAINS(r.notes[1], "piece 0 (18 triangles, open)");
  EXPECT_CONTAINS(r.notes[1], "2 triangles flipped to agree with most of its area");
  for (std::size_t t = 0; t < 18; ++t) EXPECT_LT(geometric_normal(b.mesh, t).z(), 0.0) << t;  // front +z
}

TEST(SceneValidation, ManyPiecesAreSummarized) {
  SceneBuilder b;
  for (int i = 0; i < 10; ++i) b.quad({2.0 * i, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  b.box({0, 3, 0}, {1, 4, 1});
  const pg::SceneValidationReport r = pg::validate_scene(b.mesh);
  ASSERT_TRUE(r.valid) << r.message;
  EXPECT_EQ(r.pieces, 11u);
  ASSERT_EQ(r.notes.size(), 3u);
  EXPECT_CONTAINS(r.notes[1], "11 pieces: 0 enclosures");
  EXPECT_CONTAINS(r.notes[1], "1 objects");
  EXPECT_CONTAINS(r.notes[2], "piece 10 (12 triangles, closed): an object, front side outward");
  EXPECT_CONTAINS(r.notes[1], "10 open");
}

TEST(SceneValidation, BadInputIsRefusedAsOnTheConvexPath) {
  SceneBuilder nan;
  nan.quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  nan.mesh.vertices[2].y() = std::numeric_limits<double>::quiet_NaN();
  pg::SceneValidationReport r = pg::validate_scene(nan.mesh);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.rule, "finite");
  EXPECT_CONTAINS(r.message, "vertex 2");
  SceneBuilder flat;
  flat.quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  const pg::Index v = flat.vertex({2, 0, 0});  // collinear with vertices 0 and 1
  flat.polygon({0, 1, v});
  r = pg::validate_scene(flat.mesh);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.rule, "non-degenerate");
  EXPECT_CONTAINS(r.message, "triangle 2");
  EXPECT_CONTAINS(r.message, "zero area");
  pg::TriangleMesh empty;
  EXPECT_EQ(pg::validate_scene(empty).rule, "non-empty");
}

TEST(SceneValidation, LoadSceneMesh) {
  std::vector<std::string> notes;
  const pg::ValidatedMesh cube_scene = pg::load_scene_mesh("builtin:cube", &notes);
  const pg::TriangleMesh& cube = cube_scene.mesh();
  EXPECT_EQ(cube_scene.shape(), pg::SceneShape::convex);
  EXPECT_EQ(cube.triangles, pg::load_closed_convex("builtin:cube").triangles);
  // A convex file: the convex path, as load_closed_convex, notes included.
  std::vector<std::string> scene_notes, convex_notes;
  const pg::ValidatedMesh box_scene = pg::load_scene_mesh(kMeshes + "cube.off", &scene_notes);
  const pg::TriangleMesh& box = box_scene.mesh();
  const pg::TriangleMesh same = pg::load_closed_convex(kMeshes + "cube.off", &convex_notes);
  EXPECT_EQ(box_scene.shape(), pg::SceneShape::convex);
  EXPECT_EQ(box.vertices, same.vertices);
  EXPECT_EQ(box.triangles, same.triangles);
  EXPECT_EQ(scene_notes, convex_notes);
  // The measured Cornell box (file comments): open at the front, closed blocks standing on the
  // floor, which is cut around their footprints; floor front up (+y), the light (face 7) front
  // down. 52 triangles as read; the floor's 2 become 14 around the two footprints, and the
  // blocks' bottoms (4, against the opaque back of the floor, a one-sided sheet) leave: 60.
  notes.clear();
  const pg::ValidatedMesh cornell_scene = pg::load_scene_mesh(kScenes + "cornell_box.obj", &notes);
  const pg::TriangleMesh& cornell = cornell_scene.mesh();
  EXPECT_EQ(cornell_scene.shape(), pg::SceneShape::general);
  ASSERT_EQ(cornell.triangles.size(), 60u);
  ASSERT_FALSE(notes.empty());
  bool piece_noted = false;
  for (const std::string& n : notes) piece_noted = piece_noted || n.find("cornell_box.obj: piece") != std::string::npos;
  EXPECT_TRUE(piece_noted);
  EXPECT_CONTAINS(notes.back(), "cornell_box.obj: contacts: 2 pairs of faces touch");
  for (std::size_t t = 0; t < cornell.triangles.size(); ++t) {
    // Floor (y = 0) and light (y = 548.8) are horizontal: their unit fronts are (0, +-1, 0) up to
    // rounding of the normalization, far inside 0.99.
    if (cornell.facet_of_triangle[t] == 0) {
      EXPECT_GT(front_normal(cornell, t).y(), 0.99) << "floor " << t;
    }
    if (cornell.facet_of_triangle[t] == 7) {
      EXPECT_LT(front_normal(cornell, t).y(), -0.99) << "light " << t;
    }
  }
  for (const std::string mesh : {"l_block.off", "open_box.off"}) {
    EXPECT_EQ(pg::load_scene_mesh(kMeshes + mesh).shape(), pg::SceneShape::general) << mesh;
  }
  // Two crossing squares: refused, naming both faces and a point of x = 0.5, z = 0, y in [0.2, 0.8].
  try {
    pg::load_scene_mesh(std::string(PANELRAD_SOURCE_DIR) + "/tests/data/meshes/crossing_faces.off");
    ADD_FAILURE() << "crossing faces accepted";
  } catch (const pg::MeshError& e) {
    const std::string msg = e.what();
    EXPECT_CONTAINS(msg, "crossing_faces.off: invalid scene: crossing: input faces 0 (line 14) and 1 (line 15) cross at (");
    const pg::Vec3 x = crossing_point(msg);
    EXPECT_EQ(x.x(), 0.5);
    EXPECT_EQ(x.z(), 0.0);
    EXPECT_TRUE(x.y() >= 0.2 && x.y() <= 0.8) << msg;
  }
  try {
    pg::load_scene_mesh("builtin:nothing");
    ADD_FAILURE() << "unknown built-in accepted";
  } catch (const pg::MeshError&) {
  }
}

}  // namespace

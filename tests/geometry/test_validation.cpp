// Exact validation: every rule rejected by a purpose-made bad mesh, re-orientation with the right
// flip count, exact hull re-triangulation of rounded polygons, and verdicts that survive
// translation by 1e6 and scaling by 1e-6.
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/mesh_io.hpp>
#include <panelrad/geometry/validation.hpp>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <numbers>
#include <set>
#include <sstream>

namespace pg = panelrad::geometry;

namespace {

const std::string kMeshes = std::string(PANELRAD_SOURCE_DIR) + "/examples/meshes/";

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << "message: " << (haystack)

pg::ValidationReport validate(pg::TriangleMesh m) { return pg::validate_closed_convex(m); }

pg::TriangleMesh from_off(const std::string& text) {
  std::istringstream in(text);
  return pg::read_off(in, "test.off");
}

pg::TriangleMesh make(std::vector<pg::Vec3> v, std::vector<std::array<pg::Index, 3>> t) {
  pg::TriangleMesh m;
  m.vertices = std::move(v);
  m.triangles = std::move(t);
  for (std::size_t i = 0; i < m.triangles.size(); ++i) m.facet_of_triangle.push_back(static_cast<pg::Index>(i));
  m.num_facets = static_cast<pg::Index>(m.triangles.size());
  m.source = "test";
  return m;
}

/// Appends a copy of `b` (vertices renumbered) to `a`.
pg::TriangleMesh join(pg::TriangleMesh a, const pg::TriangleMesh& b) {
  const auto off = static_cast<pg::Index>(a.vertices.size());
  for (const auto& v : b.vertices) a.vertices.push_back(v);
  for (const auto& t : b.triangles) {
    a.triangles.push_back({t[0] + off, t[1] + off, t[2] + off});
    a.facet_of_triangle.push_back(a.num_facets++);
  }
  return a;
}

pg::TriangleMesh shifted(pg::TriangleMesh m, const pg::Vec3& d) {
  for (auto& v : m.vertices) v += d;
  return m;
}

/// Two tetrahedra glued along one edge: that edge is in four triangles.
pg::TriangleMesh edge_bowtie() {
  pg::TriangleMesh a = pg::make_tetrahedron();  // (1,0,0),(0,1,0),(0,0,1),(1,1,1)
  // b: a rotated by pi about the line of its edge (0,0,1)-(1,1,1), so both share that edge.
  pg::TriangleMesh b = a;
  const pg::Vec3 p = a.vertices[2], q = a.vertices[3];
  const Eigen::AngleAxisd rot(std::numbers::pi, (q - p).normalized());
  for (auto& v : b.vertices) v = p + rot * (v - p);
  b.vertices[2] = p;  // exact copies of the shared edge's end points
  b.vertices[3] = q;
  pg::TriangleMesh m = join(a, b);
  // Use the shared vertices of a for the edge.
  for (std::size_t t = 4; t < 8; ++t)
    for (auto& v : m.triangles[t]) {
      if (v == 6) v = 2;
      if (v == 7) v = 3;
    }
  m.vertices.erase(m.vertices.begin() + 6, m.vertices.end());
  return m;
}

/// Two tetrahedra sharing one vertex (and nothing else).
pg::TriangleMesh vertex_bowtie() {
  pg::TriangleMesh a = pg::make_tetrahedron();
  pg::TriangleMesh b = a;
  for (auto& v : b.vertices) v = pg::Vec3(2, 2, 2) - v;  // (1,1,1) stays; the rest move away
  pg::TriangleMesh m = join(a, b);
  for (std::size_t t = 4; t < 8; ++t)
    for (auto& v : m.triangles[t])
      if (v == 7) v = 3;
  m.vertices.pop_back();
  return m;
}

/// The real projective plane (hemi-icosahedron, 6 vertices, 10 triangles): closed, every edge in
/// two triangles, every vertex a single fan, but not orientable.
pg::TriangleMesh projective_plane() {
  std::vector<pg::Vec3> v = {{0, 0, 0}, {1, 0.1, 0.2}, {0.3, 1, 0.1}, {0.2, 0.3, 1}, {1.1, 1.2, 0.4}, {0.5, 0.9, 1.3}};
  return make(v, {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {0, 5, 1},
                  {1, 2, 4}, {2, 3, 5}, {3, 4, 1}, {4, 5, 2}, {5, 1, 3}});
}

/// A bipyramid whose apex axis misses its equator triangle (the origin lies outside the triangle
/// (1,0), (-0.5,0.8), (0.3,-0.4)): non-convex though every vertex is extreme; each triangle is its own
/// facet and the exact hull has the edge between the two apexes, which share no input face.
pg::TriangleMesh dented_bipyramid() {
  std::vector<pg::Vec3> v = {{0, 0, 1}, {0, 0, -1}, {1, 0, 0}, {-0.5, 0.8, 0}, {0.3, -0.4, 0}};
  return make(v, {{0, 2, 3}, {0, 3, 4}, {0, 4, 2}, {1, 3, 2}, {1, 4, 3}, {1, 2, 4}});
}

pg::Vec3 tri_normal(const pg::TriangleMesh& m, std::size_t t) {
  const auto& tr = m.triangles[t];
  const pg::Vec3& a = m.vertices[static_cast<std::size_t>(tr[0])];
  return (m.vertices[static_cast<std::size_t>(tr[1])] - a).cross(m.vertices[static_cast<std::size_t>(tr[2])] - a);
}

void expect_outward(const pg::TriangleMesh& m) {
  pg::Vec3 inside = pg::Vec3::Zero();
  for (const auto& v : m.vertices) inside += v;
  inside /= static_cast<double>(m.vertices.size());
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    pg::Vec3 c = pg::Vec3::Zero();
    for (auto v : m.triangles[t]) c += m.vertices[static_cast<std::size_t>(v)];
    EXPECT_GT(tri_normal(m, t).dot(c / 3.0 - inside), 0.0) << "triangle " << t;
  }
}

struct Case {
  std::string name;
  std::function<pg::TriangleMesh()> make;
  std::string rule;  // "" when valid
};

std::vector<Case> cases() {
  return {
      {"cube", [] { return pg::make_cube(); }, ""},
      {"prism:6", [] { return pg::make_prism(6); }, ""},
      {"prism:5 r=2.5 h=0.25", [] { return pg::make_prism(5, 2.5, 0.25); }, ""},
      {"tetrahedron", [] { return pg::make_tetrahedron(); }, ""},
      {"octahedron", [] { return pg::make_octahedron(); }, ""},
      {"cube.off", [] { return pg::read_mesh(kMeshes + "cube.off"); }, ""},
      {"hexagonal_prism.off", [] { return pg::read_mesh(kMeshes + "hexagonal_prism.off"); }, ""},
      {"triangular_prism.obj", [] { return pg::read_mesh(kMeshes + "triangular_prism.obj"); }, ""},
      {"dodecahedron.off", [] { return pg::read_mesh(kMeshes + "dodecahedron.off"); }, ""},
      {"l_block.off", [] { return pg::read_mesh(kMeshes + "l_block.off"); }, "convex"},
      {"open_box.off", [] { return pg::read_mesh(kMeshes + "open_box.off"); }, "closed"},
      {"edge bowtie", edge_bowtie, "manifold"},
      {"vertex bowtie", vertex_bowtie, "manifold"},
      {"projective plane", projective_plane, "manifold"},
      {"two cubes", [] { return join(pg::make_cube(), shifted(pg::make_cube(), pg::Vec3(3, 0, 0))); }, "connected"},
      {"dented bipyramid", dented_bipyramid, "convex"},
      {"zero-area triangle",
       [] {
         pg::TriangleMesh m = pg::make_cube();
         m.vertices.emplace_back(0.5, 0, 0);  // on the edge from (0,0,0) to (1,0,0)
         m.triangles.push_back({0, 8, 1});
         m.facet_of_triangle.push_back(m.num_facets++);
         return m;
       },
       "non-degenerate"},
      {"flat double triangle", [] { return make({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}, {0, 2, 1}}); },
       "non-degenerate"},
      {"nan vertex",
       [] {
         pg::TriangleMesh m = pg::make_cube();
         m.vertices[5].y() = std::numeric_limits<double>::quiet_NaN();
         return m;
       },
       "finite"},
  };
}

}  // namespace

TEST(Validation, VerdictsOfPurposeMadeMeshes) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    const pg::ValidationReport r = validate(c.make());
    EXPECT_EQ(r.valid, c.rule.empty()) << r.message;
    EXPECT_EQ(r.rule, c.rule) << r.message;
    if (!c.rule.empty()) {
      EXPECT_EQ(r.message.rfind(c.rule + ": ", 0), 0u) << r.message;  // names the rule
    }
  }
}

TEST(Validation, MessagesNameTheOffendingFaceOrVertex) {
  EXPECT_CONTAINS(validate(pg::read_mesh(kMeshes + "open_box.off")).message,
                  "belongs to triangle 0 (input face 0 (line 13); vertices 0 (0, 0, 0), 4 (0, 0, 1), 6 (0, 1, 1)) only");
  const pg::ValidationReport l = validate(pg::read_mesh(kMeshes + "l_block.off"));
  EXPECT_CONTAINS(l.message, "vertex 4 (1, 2, 0) lies outside the plane of triangle 12 (input face 4 (line 21);");
  EXPECT_CONTAINS(l.message, "by 1.00e+00");
  // The reflex edge x = 1 / y = 1 at (1,1): vertices at y = 2 lie 1 outside the plane y = 1, and the
  // diameter is |(2,0,0) - (0,2,1)| = 3.
  EXPECT_NEAR(l.worst_convexity_violation, 1.0 / 3.0, 1e-15);
  EXPECT_CONTAINS(l.message, "not a vertex of the exact convex hull");
  EXPECT_CONTAINS(validate(edge_bowtie()).message, "is shared by 4 triangles");
  EXPECT_CONTAINS(validate(vertex_bowtie()).message, "vertex 3 (1, 1, 1) do not form a single fan");
  EXPECT_CONTAINS(validate(projective_plane()).message, "not orientable");
  const auto cases_list = cases();
  EXPECT_CONTAINS(validate(cases_list[16].make()).message, "triangle 12 (input face 6; vertices 0 (0, 0, 0), 8 (0.5, 0, 0), 1 (1, 0, 0)) has zero area");
  EXPECT_CONTAINS(validate(cases_list[18].make()).message, "vertex 5 (1, nan, 1) has a non-finite coordinate");
  EXPECT_CONTAINS(validate(cases_list[17].make()).message, "encloses no volume");
  EXPECT_CONTAINS(validate(dented_bipyramid()).message, "joins vertices of different input faces");
  // Unused and coincident vertices, empty and broken structure.
  pg::TriangleMesh unused = pg::make_cube();
  unused.vertices.emplace_back(0.5, 0.5, 0.5);
  EXPECT_CONTAINS(validate(unused).message, "manifold: vertex 8 (0.5, 0.5, 0.5) belongs to no triangle");
  pg::TriangleMesh coincident = join(pg::make_tetrahedron(), shifted(pg::make_tetrahedron(), pg::Vec3(0, 1, 1)));
  const pg::ValidationReport rc = validate(coincident);
  EXPECT_EQ(rc.rule, "manifold");
  EXPECT_CONTAINS(rc.message, "coincide at (1, 1, 1)");  // vertex (1,0,0)+(0,1,1) meets (1,1,1)
  EXPECT_EQ(validate(pg::TriangleMesh{}).rule, "non-empty");
  pg::TriangleMesh broken = pg::make_cube();
  broken.triangles[3][1] = 42;
  EXPECT_EQ(validate(broken).rule, "structure");
  broken = pg::make_cube();
  broken.facet_of_triangle.pop_back();
  EXPECT_EQ(validate(broken).rule, "structure");
}

TEST(Validation, InconsistentOrientationIsFixedWithTheRightFlipCount) {
  pg::TriangleMesh cube = pg::make_cube();
  const auto outward = cube.triangles;
  for (std::size_t t : {0u, 3u, 7u}) std::swap(cube.triangles[t][1], cube.triangles[t][2]);
  pg::ValidationReport r = pg::validate_closed_convex(cube);
  ASSERT_TRUE(r.valid) << r.message;
  EXPECT_EQ(r.flipped_faces, 3u);
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_CONTAINS(r.notes[0], "re-oriented 3 of 12 triangles (3 input faces)");
  EXPECT_EQ(cube.triangles, outward);
  expect_outward(cube);

  // Six of eight inward: the geometry decides which side is out, so those six are flipped.
  pg::TriangleMesh most = pg::make_octahedron();
  for (std::size_t t = 2; t < 8; ++t) std::swap(most.triangles[t][1], most.triangles[t][2]);
  r = pg::validate_closed_convex(most);
  ASSERT_TRUE(r.valid);
  EXPECT_EQ(r.flipped_faces, 6u);
  expect_outward(most);

  // Consistent but inward everywhere.
  pg::TriangleMesh inward = pg::make_prism(7);
  for (auto& t : inward.triangles) std::swap(t[0], t[1]);
  r = pg::validate_closed_convex(inward);
  ASSERT_TRUE(r.valid);
  EXPECT_EQ(r.flipped_faces, inward.triangles.size());
  EXPECT_CONTAINS(r.notes[0], "front side inward, as the file winds it");
  expect_outward(inward);

  // A whole polygon face of a file written clockwise.
  std::string text = "OFF\n8 6 12\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n0 0 1\n1 0 1\n0 1 1\n1 1 1\n"
                     "4 0 4 6 2\n4 1 3 7 5\n4 0 1 5 4\n4 2 6 7 3\n4 1 3 2 0\n4 4 5 7 6\n";
  pg::TriangleMesh file = from_off(text);
  r = pg::validate_closed_convex(file);
  ASSERT_TRUE(r.valid);
  EXPECT_EQ(r.flipped_faces, 2u);
  EXPECT_CONTAINS(r.notes[0], "(1 input faces)");
  expect_outward(file);
}

TEST(Validation, RoundedDodecahedronIsRetriangulatedFromTheExactHull) {
  pg::TriangleMesh m = pg::read_mesh(kMeshes + "dodecahedron.off");
  const pg::TriangleMesh input = m;
  const pg::ValidationReport r = pg::validate_closed_convex(m);
  ASSERT_TRUE(r.valid) << r.message;
  EXPECT_TRUE(r.retriangulated_from_hull);
  EXPECT_CONTAINS(r.notes.back(), "exact convex hull");
  EXPECT_EQ(m.triangles.size(), 36u);
  EXPECT_EQ(m.num_facets, 12);
  // Each facet keeps its id: 3 triangles on exactly the 5 vertices of that input pentagon.
  for (pg::Index f = 0; f < 12; ++f) {
    std::set<pg::Index> in_vertices, out_vertices;
    int count = 0;
    for (std::size_t t = 0; t < input.triangles.size(); ++t)
      if (input.facet_of_triangle[t] == f) in_vertices.insert(input.triangles[t].begin(), input.triangles[t].end());
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
      if (m.facet_of_triangle[t] == f) {
        ++count;
        out_vertices.insert(m.triangles[t].begin(), m.triangles[t].end());
      }
    EXPECT_EQ(count, 3);
    EXPECT_EQ(in_vertices, out_vertices);
  }
  expect_outward(m);
  // Regular dodecahedron of circumradius sqrt 3: edge 2/phi, area 3 sqrt(25 + 10 sqrt 5) a^2. The
  // file's six decimals perturb coordinates by up to 5e-7 (relative 3e-7); 2e-6 covers it.
  const double phi = (1 + std::sqrt(5.0)) / 2, a = 2 / phi;
  const double area = 3 * std::sqrt(25 + 10 * std::sqrt(5.0)) * a * a;
  EXPECT_NEAR(pg::surface_area(m), area, 2e-6 * area);
  // Validating again changes nothing.
  const auto once = m.triangles;
  const pg::ValidationReport again = pg::validate_closed_convex(m);
  EXPECT_TRUE(again.valid);
  EXPECT_FALSE(again.retriangulated_from_hull);
  EXPECT_EQ(m.triangles, once);
}

TEST(Validation, RoundedPolygonWithAVertexInsideIsRejected) {
  // Move dodecahedron vertex 0 just below the plane of its three neighbours: it is no longer
  // extreme. (Exactly onto that plane would still be a valid, flat-vertex convex polyhedron.)
  pg::TriangleMesh m = pg::read_mesh(kMeshes + "dodecahedron.off");
  std::set<pg::Index> nbrs;
  for (const auto& t : m.triangles)
    for (int i = 0; i < 3; ++i)
      if (t[static_cast<std::size_t>(i)] == 0) {
        // Neighbours along polygon edges only: collect, then keep the three nearest.
        nbrs.insert(t[static_cast<std::size_t>((i + 1) % 3)]);
        nbrs.insert(t[static_cast<std::size_t>((i + 2) % 3)]);
      }
  std::vector<std::pair<double, pg::Index>> by_distance;
  for (pg::Index n : nbrs) by_distance.emplace_back((m.vertices[static_cast<std::size_t>(n)] - m.vertices[0]).norm(), n);
  std::sort(by_distance.begin(), by_distance.end());
  pg::Vec3 mean = pg::Vec3::Zero();
  for (int k = 0; k < 3; ++k) mean += m.vertices[static_cast<std::size_t>(by_distance[static_cast<std::size_t>(k)].second)];
  m.vertices[0] = 0.99 * mean / 3.0;  // the solid's centre is the origin
  const pg::ValidationReport r = pg::validate_closed_convex(m);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.rule, "convex");
  EXPECT_CONTAINS(r.message, "the exact convex hull cannot replace the triangulation");
  EXPECT_GT(r.worst_convexity_violation, 0.0);
}

// A convex shape must not depend on where it sits or how big it is: the exact predicates give the
// same verdicts after translation by 1e6 and scaling by 1e-6 (and both).
TEST(Validation, SameVerdictsAfterTranslationAndScaling) {
  const std::vector<std::pair<std::string, std::function<pg::Vec3(const pg::Vec3&)>>> maps = {
      {"translate 1e6", [](const pg::Vec3& p) { return (p.array() + 1e6).matrix().eval(); }},
      {"scale 1e-6", [](const pg::Vec3& p) { return (p * 1e-6).eval(); }},
      {"translate 1e6 then scale 1e-6", [](const pg::Vec3& p) { return ((p.array() + 1e6) * 1e-6).matrix().eval(); }},
  };
  for (const Case& c : cases()) {
    const pg::ValidationReport ref = validate(c.make());
    for (const auto& [name, map] : maps) {
      SCOPED_TRACE(c.name + ", " + name);
      pg::TriangleMesh m = c.make();
      for (auto& v : m.vertices) v = map(v);
      const pg::ValidationReport r = pg::validate_closed_convex(m);
      EXPECT_EQ(r.valid, ref.valid) << r.message;
      EXPECT_EQ(r.rule, ref.rule) << r.message;
      EXPECT_EQ(r.flipped_faces, ref.flipped_faces);
      if (ref.rule == "convex") {
        EXPECT_NEAR(r.worst_convexity_violation, ref.worst_convexity_violation, 1e-6);
      }
    }
  }
}

TEST(Validation, PlanarFacetCount) {
  EXPECT_EQ(pg::count_planar_facets(pg::make_cube()), 6u);
  EXPECT_EQ(pg::count_planar_facets(pg::make_octahedron()), 8u);
  EXPECT_EQ(pg::count_planar_facets(pg::read_mesh(kMeshes + "l_block.off")), 8u);
  // The rounded dodecahedron's pentagons are not exactly planar, but within the rounding of its
  // six-decimal coordinates: its 36 fan triangles make the dodecahedron's 12 faces.
  EXPECT_EQ(pg::count_planar_facets(pg::read_mesh(kMeshes + "dodecahedron.off")), 12u);
}

TEST(Validation, LoadClosedConvex) {
  std::vector<std::string> notes;
  const pg::TriangleMesh cube = pg::load_closed_convex("builtin:cube", &notes);
  EXPECT_EQ(cube.triangles.size(), 12u);
  EXPECT_TRUE(notes.empty());
  const pg::TriangleMesh d = pg::load_closed_convex(kMeshes + "dodecahedron.off", &notes);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_CONTAINS(notes[0], "dodecahedron.off: the fan triangulation was not exactly convex");
  try {
    pg::load_closed_convex(kMeshes + "l_block.off");
    ADD_FAILURE() << "l_block accepted";
  } catch (const pg::MeshError& e) {
    EXPECT_CONTAINS(e.what(), "l_block.off: invalid mesh: convex: vertex 4 (1, 2, 0)");
  }
  EXPECT_THROW(pg::load_closed_convex("builtin:sphere"), pg::MeshError);
  EXPECT_THROW(pg::load_closed_convex(kMeshes + "missing.off"), pg::MeshError);
}

// Large meshes: a UV sphere of ~20k triangles (quads between rings are cyclic trapezoids, planar in
// exact arithmetic but not after rounding) and a 5000-gon prism (~20k triangles). The time is
// printed, not asserted.
TEST(Validation, LargeConvexMeshes) {
  const int rings = 100, sectors = 100;
  pg::TriangleMesh s;
  s.source = "uv sphere";
  s.vertices.emplace_back(0, 0, 1);
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      const double th = std::numbers::pi * i / rings, ph = 2 * std::numbers::pi * j / sectors;
      s.vertices.emplace_back(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
    }
  s.vertices.emplace_back(0, 0, -1);
  const auto ring = [&](int i, int j) { return static_cast<pg::Index>(1 + (i - 1) * sectors + (j % sectors)); };
  const auto south = static_cast<pg::Index>(s.vertices.size() - 1);
  for (int j = 0; j < sectors; ++j) {
    s.triangles.push_back({0, ring(1, j), ring(1, j + 1)});
    s.facet_of_triangle.push_back(s.num_facets++);
  }
  for (int i = 1; i + 1 < rings; ++i)
    for (int j = 0; j < sectors; ++j) {
      s.triangles.push_back({ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
      s.triangles.push_back({ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
      s.facet_of_triangle.push_back(s.num_facets);
      s.facet_of_triangle.push_back(s.num_facets++);
    }
  for (int j = 0; j < sectors; ++j) {
    s.triangles.push_back({south, ring(rings - 1, j + 1), ring(rings - 1, j)});
    s.facet_of_triangle.push_back(s.num_facets++);
  }
  for (pg::TriangleMesh m : {s, pg::make_prism(5000)}) {
    const auto start = std::chrono::steady_clock::now();
    const pg::ValidationReport r = pg::validate_closed_convex(m);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << "[ info ] " << m.source << ": " << m.triangles.size() << " triangles validated in " << secs
              << " s" << (r.retriangulated_from_hull ? " (re-triangulated from the hull)" : "") << "\n";
    EXPECT_TRUE(r.valid) << r.message;
  }
}

// split_t_junctions: a unit cube room with T-junctions (top split into two quads, one wall into two)
// closed by the split, with the area, the facets and every triangle's orientation kept; several
// vertices on one edge inserted in order along it (also on a sheared, non-axis edge and with the
// edge running either way); vertices only near the edge, beyond its ends, at an end point's
// coordinates or used by no triangle left out; a closed mesh without T-junctions unchanged; a
// grid of 10^5 triangles with random refinement closed up to its outer boundary.
#include "../../geometry/src/t_junctions.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cstdint>
#include <map>
#include <random>
#include <utility>
#include <vector>

namespace pg = panelrad::geometry;
using panelrad::geometry::validation_detail::split_t_junctions;

namespace {

/// Polygons over vertices merged by coordinates (as the readers do), each polygon one facet,
/// fan-triangulated from its first vertex in the order given.
struct Builder {
  pg::TriangleMesh mesh;
  std::map<std::array<double, 3>, pg::Index> index;

  pg::Index vertex(const pg::Vec3& p) {
    const auto [it, added] = index.try_emplace({p.x(), p.y(), p.z()}, static_cast<pg::Index>(mesh.vertices.size()));
    if (added) mesh.vertices.push_back(p);
    return it->second;
  }
  void polygon(const std::vector<pg::Vec3>& corners) {
    std::vector<pg::Index> v;
    for (const pg::Vec3& p : corners) v.push_back(vertex(p));
    for (std::size_t k = 1; k + 1 < v.size(); ++k) {
      mesh.triangles.push_back({v[0], v[k], v[k + 1]});
      mesh.facet_of_triangle.push_back(mesh.num_facets);
    }
    ++mesh.num_facets;
  }
};

using Edge = std::pair<pg::Index, pg::Index>;

/// How many triangles use each undirected edge.
std::map<Edge, int> edge_uses(const pg::TriangleMesh& m) {
  std::map<Edge, int> uses;
  for (const auto& t : m.triangles)
    for (int s = 0; s < 3; ++s) {
      const pg::Index a = t[static_cast<std::size_t>(s)], b = t[static_cast<std::size_t>((s + 1) % 3)];
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  return uses;
}

bool closed(const pg::TriangleMesh& m) {
  const auto uses = edge_uses(m);
  return std::all_of(uses.begin(), uses.end(), [](const auto& e) { return e.second == 2; });
}

pg::Vec3 normal(const pg::TriangleMesh& m, const std::array<pg::Index, 3>& t) {
  const pg::Vec3& a = m.vertices[static_cast<std::size_t>(t[0])];
  return (m.vertices[static_cast<std::size_t>(t[1])] - a).cross(m.vertices[static_cast<std::size_t>(t[2])] - a);
}

/// Per facet, the sum of the triangles' normals (twice the vector area): unchanged by a split into
/// pieces of the same orientation.
std::vector<pg::Vec3> facet_vector_areas(const pg::TriangleMesh& m) {
  std::vector<pg::Vec3> s(static_cast<std::size_t>(m.num_facets), pg::Vec3::Zero());
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    s[static_cast<std::size_t>(m.facet_of_triangle[t])] += normal(m, m.triangles[t]);
  return s;
}

double twice_area(const pg::TriangleMesh& m) {
  double a = 0;
  for (const auto& t : m.triangles) a += normal(m, t).norm();
  return a;
}

/// The unit cube [0, 1]^3 as a room, counter-clockwise seen from outside. With `t_junctions` the
/// top is two quads split at x = 1/2 and the wall x = 0 two quads split at z = 1/2, while the walls
/// y = 0 and y = 1 keep their whole edges: four vertices lie at the middle of those walls' edges.
pg::TriangleMesh cube_room(bool t_junctions) {
  Builder b;
  const auto P = [](double x, double y, double z) { return pg::Vec3(x, y, z); };
  b.polygon({P(0, 0, 0), P(0, 1, 0), P(1, 1, 0), P(1, 0, 0)});  // floor, z = 0
  b.polygon({P(0, 0, 0), P(1, 0, 0), P(1, 0, 1), P(0, 0, 1)});  // y = 0
  b.polygon({P(0, 1, 0), P(0, 1, 1), P(1, 1, 1), P(1, 1, 0)});  // y = 1
  b.polygon({P(1, 0, 0), P(1, 1, 0), P(1, 1, 1), P(1, 0, 1)});  // x = 1
  if (t_junctions) {
    b.polygon({P(0, 0, 0), P(0, 0, 0.5), P(0, 1, 0.5), P(0, 1, 0)});  // x = 0, lower half
    b.polygon({P(0, 0, 0.5), P(0, 0, 1), P(0, 1, 1), P(0, 1, 0.5)});  // x = 0, upper half
    b.polygon({P(0, 0, 1), P(0.5, 0, 1), P(0.5, 1, 1), P(0, 1, 1)});  // top, x <= 1/2
    b.polygon({P(0.5, 0, 1), P(1, 0, 1), P(1, 1, 1), P(0.5, 1, 1)});  // top, x >= 1/2
  } else {
    b.polygon({P(0, 0, 0), P(0, 0, 1), P(0, 1, 1), P(0, 1, 0)});  // x = 0
    b.polygon({P(0, 0, 1), P(1, 0, 1), P(1, 1, 1), P(0, 1, 1)});  // top
  }
  b.mesh.source = "cube room";
  return b.mesh;
}

TEST(TJunctions, CubeRoomBecomesClosedWithAreaFacetsAndOrientationsKept) {
  pg::TriangleMesh m = cube_room(true);
  ASSERT_FALSE(closed(m));
  const std::size_t vertices = m.vertices.size();
  const std::vector<pg::Vec3> before = facet_vector_areas(m);
  const double area = twice_area(m);
  const pg::Index facets = m.num_facets;

  // (1/2, 0, 1) and (1/2, 1, 1) on the top edges of y = 0 and y = 1, (0, 0, 1/2) and (0, 1, 1/2)
  // on their edges at x = 0; the triangle of y = 0 holding both of its edges needs two rounds.
  EXPECT_EQ(split_t_junctions(m), 4u);
  EXPECT_TRUE(closed(m));
  EXPECT_EQ(m.vertices.size(), vertices);
  EXPECT_EQ(m.num_facets, facets);
  ASSERT_EQ(m.facet_of_triangle.size(), m.triangles.size());
  // Dyadic coordinates and axis-aligned faces: every cross product and norm is exact in double.
  EXPECT_EQ(twice_area(m), area);
  EXPECT_EQ(facet_vector_areas(m), before);
  // Each piece faces as its facet did (the facets are planar: one normal direction each).
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const pg::Vec3 n = normal(m, m.triangles[t]);
    const pg::Vec3& f = before[static_cast<std::size_t>(m.facet_of_triangle[t])];
    EXPECT_GT(n.dot(f), 0) << "triangle " << t;
    EXPECT_EQ(n.cross(f), pg::Vec3::Zero()) << "triangle " << t;
  }
  // Nothing left to split.
  const pg::TriangleMesh after = m;
  EXPECT_EQ(split_t_junctions(m), 0u);
  EXPECT_EQ(m.triangles, after.triangles);
}

TEST(TJunctions, ClosedMeshWithoutTJunctionsIsUnchanged) {
  pg::TriangleMesh m = cube_room(false);
  ASSERT_TRUE(closed(m));
  const pg::TriangleMesh before = m;
  EXPECT_EQ(split_t_junctions(m), 0u);
  EXPECT_EQ(m.triangles, before.triangles);
  EXPECT_EQ(m.facet_of_triangle, before.facet_of_triangle);
}

/// An open strip: the triangle (0, 0, 0), (4, 0, 0), (2, 2, 0) above four unit squares whose top
/// vertices (1, 0, 0), (2, 0, 0), (3, 0, 0) lie inside its edge on y = 0, mapped by `shear` (dyadic
/// entries, so the mapped points stay exactly collinear). The vertices are numbered out of their
/// order along the edge; `reversed` lists every triangle clockwise instead.
struct Strip {
  pg::TriangleMesh mesh;
  pg::Index big_facet = 0;
};

Strip strip(const Eigen::Matrix3d& shear, bool reversed) {
  Builder b;
  const auto P = [&](double x, double y) { return pg::Vec3(shear * pg::Vec3(x, y, 0)); };
  for (double x : {3.0, 1.0, 4.0, 0.0, 2.0}) b.vertex(P(x, 0));  // indices not in edge order
  const auto polygon = [&](std::vector<pg::Vec3> c) {
    if (reversed) std::reverse(c.begin() + 1, c.end());
    b.polygon(c);
  };
  Strip s;
  s.big_facet = b.mesh.num_facets;
  polygon({P(0, 0), P(4, 0), P(2, 2)});
  for (int i = 0; i < 4; ++i) polygon({P(i, 0), P(i, -1), P(i + 1, -1), P(i + 1, 0)});
  s.mesh = b.mesh;
  return s;
}

/// The edges on the line y = 0 of the strip's plane (before the shear): all between consecutive
/// points x = i, i + 1 after the split.
void expect_strip_split(const Strip& s, const std::vector<pg::Vec3>& vector_areas, const Eigen::Matrix3d& shear,
                        bool reversed) {
  const pg::TriangleMesh& m = s.mesh;
  const auto id = [&](double x) {
    const pg::Vec3 p = shear * pg::Vec3(x, 0, 0);
    for (std::size_t v = 0; v < m.vertices.size(); ++v)
      if (m.vertices[v] == p) return static_cast<pg::Index>(v);
    return pg::Index{-1};
  };
  const auto uses = edge_uses(m);
  for (int i = 0; i < 4; ++i) {
    const pg::Index a = id(i), b = id(i + 1);
    const auto it = uses.find({std::min(a, b), std::max(a, b)});
    ASSERT_NE(it, uses.end()) << "edge x = " << i << " .. " << i + 1;
    EXPECT_EQ(it->second, 2) << "edge x = " << i << " .. " << i + 1;
  }
  EXPECT_EQ(uses.count({std::min(id(0), id(4)), std::max(id(0), id(4))}), 0u);
  // The big triangle's pieces: a fan around its apex, in order along the edge, oriented alike.
  const pg::Index apex = [&] {
    const pg::Vec3 p = shear * pg::Vec3(2, 2, 0);
    for (std::size_t v = 0; v < m.vertices.size(); ++v)
      if (m.vertices[v] == p) return static_cast<pg::Index>(v);
    return pg::Index{-1};
  }();
  std::vector<std::array<pg::Index, 3>> pieces;
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    if (m.facet_of_triangle[t] == s.big_facet) pieces.push_back(m.triangles[t]);
  ASSERT_EQ(pieces.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    // Pieces follow the edge from its first vertex: x = 0 -> 4 counter-clockwise, 4 -> 0 reversed.
    const int lo = reversed ? 4 - i : i, hi = reversed ? 3 - i : i + 1;
    const std::array<pg::Index, 3> expected = {id(lo), id(hi), apex};
    std::array<pg::Index, 3> got = pieces[static_cast<std::size_t>(i)];
    std::rotate(got.begin(), std::find(got.begin(), got.end(), id(lo)), got.end());
    EXPECT_EQ(got, expected) << "piece " << i;
    const pg::Vec3& facet_normal = vector_areas[static_cast<std::size_t>(s.big_facet)];
    EXPECT_GT(normal(m, pieces[static_cast<std::size_t>(i)]).dot(facet_normal), 0) << "piece " << i;
  }
}

TEST(TJunctions, SeveralVerticesOnOneEdgeInsertedInOrder) {
  Eigen::Matrix3d shears[2];
  shears[0].setIdentity();
  shears[1] << 1, 0.5, 0, 0.5, 1, 0, 0.25, -0.75, 1;  // the edge along (1, 1/2, 1/4): no axis
  for (const Eigen::Matrix3d& shear : shears)
    for (bool reversed : {false, true}) {
      SCOPED_TRACE(reversed ? "clockwise" : "counter-clockwise");
      Strip s = strip(shear, reversed);
      const std::vector<pg::Vec3> before = facet_vector_areas(s.mesh);
      EXPECT_EQ(split_t_junctions(s.mesh), 3u);
      expect_strip_split(s, before, shear, reversed);
      EXPECT_EQ(facet_vector_areas(s.mesh), before);
    }
}

TEST(TJunctions, VerticesNearBeyondOrAtTheEndsAreNotInside) {
  // The triangle (0, 0, 0), (4, 0, 0), (2, 2, 0) alone, and below its edge y = 0 separate
  // triangles with a vertex at: 1e-12 off the edge, on its line beyond (4, 0, 0), and a second
  // vertex at the coordinates of (0, 0, 0) (a coincident copy, as code may build).
  pg::TriangleMesh m;
  m.vertices = {{0, 0, 0}, {4, 0, 0}, {2, 2, 0},                 // the triangle
                {2, 1e-12, 0}, {1.5, -1, 0}, {2.5, -1, 0},      // near the edge, not on it
                {5, 0, 0}, {5, -1, 0}, {6, -1, 0},              // beyond its end
                {0, 0, 0}, {-1, -1, 0}, {0.5, -1, 0},           // at its end point
                {1, -2e-12, 0}, {3, 1e-300, 0}};                 // used by no triangle / off by 1e-300
  m.triangles = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}, {9, 10, 11}, {13, 4, 5}};
  m.facet_of_triangle = {0, 1, 2, 3, 4};
  m.num_facets = 5;
  const pg::TriangleMesh before = m;
  EXPECT_EQ(split_t_junctions(m), 0u);
  EXPECT_EQ(m.triangles, before.triangles);

  // The same vertex exactly on the edge is inserted; an exactly collinear vertex that no triangle
  // uses is not.
  m.vertices[3] = {2, 0, 0};
  m.vertices[12] = {1, 0, 0};
  EXPECT_EQ(split_t_junctions(m), 1u);
  ASSERT_EQ(m.triangles.size(), before.triangles.size() + 1);
  EXPECT_EQ(m.triangles[0], (std::array<pg::Index, 3>{0, 3, 2}));
  EXPECT_EQ(m.triangles[1], (std::array<pg::Index, 3>{3, 1, 2}));
  EXPECT_EQ(m.facet_of_triangle[0], 0);
  EXPECT_EQ(m.facet_of_triangle[1], 0);
}

/// A K x K grid of unit cells in the plane z = 0 (sheared), each cell randomly kept as two
/// triangles or refined into 2 x 2 half cells (eight triangles): every side shared by a kept and a
/// refined cell has the refined cell's mid-side vertex inside the kept cell's edge.
struct Grid {
  pg::TriangleMesh mesh;
  std::size_t junctions = 0;       // sides shared by a kept and a refined cell
  std::size_t outer_edges = 0;     // edges on the grid's outer boundary once conforming
};

Grid random_grid(int k, unsigned seed) {
  std::mt19937 rng(seed);
  std::bernoulli_distribution refine(0.5);
  std::vector<char> fine(static_cast<std::size_t>(k * k));
  for (char& f : fine) f = refine(rng) ? 1 : 0;
  const auto is_fine = [&](int i, int j) { return fine[static_cast<std::size_t>(i * k + j)] != 0; };
  Grid g;
  // Lattice of half-unit points, numbered as first used (no vertex that no triangle uses).
  std::vector<pg::Index> id(static_cast<std::size_t>((2 * k + 1) * (2 * k + 1)), -1);
  const auto v = [&](int x2, int y2) {
    pg::Index& slot = id[static_cast<std::size_t>(x2 * (2 * k + 1) + y2)];
    if (slot < 0) {
      slot = static_cast<pg::Index>(g.mesh.vertices.size());
      g.mesh.vertices.emplace_back(0.5 * x2 + 0.25 * y2, 0.5 * y2, 0.125 * x2);
    }
    return slot;
  };
  const auto quad = [&](int x2, int y2, int step) {
    const pg::Index a = v(x2, y2), b = v(x2 + step, y2), c = v(x2 + step, y2 + step), d = v(x2, y2 + step);
    g.mesh.triangles.push_back({a, b, c});
    g.mesh.triangles.push_back({a, c, d});
  };
  for (int i = 0; i < k; ++i)
    for (int j = 0; j < k; ++j) {
      if (is_fine(i, j)) {
        for (int di = 0; di < 2; ++di)
          for (int dj = 0; dj < 2; ++dj) quad(2 * i + di, 2 * j + dj, 1);
      } else {
        quad(2 * i, 2 * j, 2);
      }
      if (i + 1 < k && is_fine(i, j) != is_fine(i + 1, j)) ++g.junctions;
      if (j + 1 < k && is_fine(i, j) != is_fine(i, j + 1)) ++g.junctions;
      const int sides_out = (i == 0) + (i == k - 1) + (j == 0) + (j == k - 1);
      g.outer_edges += static_cast<std::size_t>(sides_out * (is_fine(i, j) ? 2 : 1));
    }
  g.mesh.facet_of_triangle.assign(g.mesh.triangles.size(), 0);
  g.mesh.num_facets = 1;
  return g;
}

TEST(TJunctions, LargeRandomGridBecomesConformingUpToItsBoundary) {
  // About 10^5 triangles (k = 160: 25,600 cells, half of them refined into 8 triangles).
  Grid g = random_grid(160, 12345);
  ASSERT_GT(g.mesh.triangles.size(), 100000u);
  ASSERT_GT(g.junctions, 1000u);
  const std::vector<pg::Vec3> before = facet_vector_areas(g.mesh);
  EXPECT_EQ(split_t_junctions(g.mesh), g.junctions);
  const auto uses = edge_uses(g.mesh);
  std::size_t single = 0, other = 0;
  for (const auto& [edge, count] : uses) {
    single += count == 1;
    other += count != 1 && count != 2;
  }
  EXPECT_EQ(single, g.outer_edges);
  EXPECT_EQ(other, 0u);
  // Dyadic coordinates with few bits: every cross product exact, sums of integers in 1/64.
  EXPECT_EQ(facet_vector_areas(g.mesh), before);
}

}  // namespace

// A sliver whose apex lies within the tolerance of its own base: the apex is a corner of the
// triangle, not a vertex inside the edge, so nothing is split (splitting there would give two
// triangles with a repeated corner). A foreign vertex as close to the base is still inserted, and
// no piece has collinear corners.
TEST(TJunctions, ASliversOwnApexIsNotInsideItsBase) {
  Builder b;
  b.polygon({{0, 0, 0}, {1, 0, 0}, {0.5, 1e-9, 0}});
  pg::TriangleMesh alone = b.mesh;
  EXPECT_EQ(split_t_junctions(alone, nullptr, 1e-6), 0u);
  EXPECT_EQ(alone.triangles, b.mesh.triangles);

  b.polygon({{0.25, -1e-9, 0}, {0.3, -1, 0}, {0.2, -1, 0}});  // a corner 1e-9 below the base
  pg::TriangleMesh with_foreign = b.mesh;
  EXPECT_EQ(split_t_junctions(with_foreign, nullptr, 1e-6), 1u);
  for (const auto& t : with_foreign.triangles) {
    EXPECT_TRUE(t[0] != t[1] && t[1] != t[2] && t[2] != t[0]);
    const pg::Vec3 &p = with_foreign.vertices[static_cast<std::size_t>(t[0])],
                   &q = with_foreign.vertices[static_cast<std::size_t>(t[1])],
                   &r = with_foreign.vertices[static_cast<std::size_t>(t[2])];
    EXPECT_GT((q - p).cross(r - p).norm(), 0);
  }
}

// STL input (read_stl, read_mesh on .stl) and the objects a file names (TriangleMesh::facet_group):
// ASCII with several solids (names, lines, merged corners), binary (float32 corners, no names), the
// same triangles either way; refusals naming the file: empty, truncated binary, a non-finite binary
// corner, bytes that are neither text nor binary STL, text that does not parse, above the size
// limit; OBJ `o` and `g` names per face.
#include <panelrad/geometry/mesh_io.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace pg = panelrad::geometry;

/// Two triangles in solid "floor" and one in solid "wall", ASCII.
const char* kAscii =
    "solid floor\n"
    " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 1 1 0\n  endloop\n endfacet\n"
    " facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 1 0\n   vertex 0 1 0\n  endloop\n endfacet\n"
    "endsolid floor\n"
    "solid wall\n"
    " facet normal 0 1 0\n  outer loop\n   vertex 0 0 0\n   vertex 0 0 1\n   vertex 1 0 0\n  endloop\n endfacet\n"
    "endsolid wall\n";

/// The same three triangles as a binary STL, corners as float32 (0.25 in place of each 1 when
/// `quarter`, to see the float32 values come through).
std::string binary(const std::vector<std::array<float, 9>>& triangles) {
  std::string b(80, ' ');
  const auto n = static_cast<std::uint32_t>(triangles.size());
  b.append(reinterpret_cast<const char*>(&n), 4);
  for (const auto& t : triangles) {
    const float normal[3] = {0, 0, 0};
    b.append(reinterpret_cast<const char*>(normal), 12);
    b.append(reinterpret_cast<const char*>(t.data()), 36);
    b.append(2, '\0');
  }
  return b;
}

const std::vector<std::array<float, 9>> kTriangles = {
    {0, 0, 0, 1, 0, 0, 1, 1, 0}, {0, 0, 0, 1, 1, 0, 0, 1, 0}, {0, 0, 0, 0, 0, 1, 1, 0, 0}};

pg::TriangleMesh read(const std::string& bytes, std::vector<std::string>* notes = nullptr) {
  std::istringstream in(bytes);
  return pg::read_stl(in, "t.stl", notes);
}

void expect_refused(const std::string& bytes, const std::string& part) {
  try {
    (void)read(bytes);
    ADD_FAILURE() << "accepted; expected a refusal with '" << part << "'";
  } catch (const pg::MeshError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("t.stl: ", 0), 0u) << what;
    EXPECT_NE(what.find(part), std::string::npos) << what << " (expected: " << part << ")";
  }
}

TEST(StlIo, AsciiSolidsNameTheirFacets) {
  std::vector<std::string> notes;
  const pg::TriangleMesh m = read(kAscii, &notes);
  ASSERT_EQ(m.triangles.size(), 3u);
  EXPECT_EQ(m.num_facets, 3);
  EXPECT_EQ(m.vertices.size(), 5u);  // corners with identical coordinates merged
  EXPECT_EQ(m.facet_group, (std::vector<std::string>{"floor", "floor", "wall"}));
  EXPECT_EQ(m.facet_line, (std::vector<long>{2, 9, 18}));
  EXPECT_EQ(m.facet_of_triangle, (std::vector<pg::Index>{0, 1, 2}));
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("ASCII STL, 3 facets, 5 distinct corners"), std::string::npos) << notes[0];
  // Each triangle's corners in the file's order.
  const auto& t = m.triangles[2];
  EXPECT_EQ(m.vertices[static_cast<std::size_t>(t[1])], pg::Vec3(0, 0, 1));
}

TEST(StlIo, BinaryGivesTheSameTrianglesWithoutNames) {
  const pg::TriangleMesh a = read(kAscii), b = read(binary(kTriangles));
  ASSERT_EQ(b.triangles.size(), a.triangles.size());
  EXPECT_TRUE(b.facet_group.empty());
  EXPECT_TRUE(b.facet_line.empty());
  for (std::size_t t = 0; t < a.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(a.vertices[static_cast<std::size_t>(a.triangles[t][static_cast<std::size_t>(k)])],
                b.vertices[static_cast<std::size_t>(b.triangles[t][static_cast<std::size_t>(k)])]);
  // float32 corners come through as the float's value.
  const pg::TriangleMesh c = read(binary({{0.1f, 0, 0, 1, 0, 0, 1, 1, 0}}));
  EXPECT_EQ(c.vertices[static_cast<std::size_t>(c.triangles[0][0])].x(), static_cast<double>(0.1f));
  // A binary header may start with "solid" (some exporters write it): still binary.
  std::string solid_header = binary(kTriangles);
  solid_header.replace(0, 11, "solid thing");
  EXPECT_EQ(read(solid_header).triangles.size(), 3u);
}

TEST(StlIo, RefusalsNameTheFile) {
  expect_refused("", "empty file");
  std::string truncated = binary(kTriangles);
  truncated.resize(truncated.size() - 7);
  expect_refused(truncated, "is not text");  // not 84 + 50 N bytes, and binary bytes
  std::string nan = binary(kTriangles);
  const float q = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(nan.data() + 84 + 50 + 12 + 4, &q, 4);  // facet 1, corner 0, y
  expect_refused(nan, "binary STL facet 1 has a non-finite coordinate (corner 0)");
  std::string inf = binary(kTriangles);
  const float i = std::numeric_limits<float>::infinity();
  std::memcpy(inf.data() + 84 + 2 * 50 + 12 + 32, &i, 4);  // facet 2, corner 2, z
  expect_refused(inf, "binary STL facet 2 has a non-finite coordinate (corner 2)");
  expect_refused("solid a\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 nan\n", "not a readable ASCII STL");
  expect_refused("hello world\n", "no `solid`");
  expect_refused("solid a\nendsolid a\n", "no facet");
  std::istringstream big(kAscii);
  panelrad::TextReadOptions small;
  small.max_bytes = 64;
  EXPECT_THROW((void)pg::read_stl(big, "t.stl", nullptr, small), pg::MeshError);
}

TEST(StlIo, ReadMeshTakesStlByExtension) {
  const auto dir = std::filesystem::temp_directory_path() / "panelrad_stl_io";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "two_solids.STL").string();
  std::ofstream(path) << kAscii;
  const pg::TriangleMesh m = pg::read_mesh(path);
  EXPECT_EQ(m.source, path);
  EXPECT_EQ(m.facet_group.size(), 3u);
  pg::ObjMaterialUse materials;
  EXPECT_THROW((void)pg::read_obj_with_materials(path, materials), pg::MeshError);
  std::filesystem::remove_all(dir);
}

TEST(ObjGroups, ObjectAndGroupNamesPerFace) {
  std::istringstream in(
      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
      "f 1 2 3\n"           // before any name: ""
      "o table\nf 1 3 4\n"  // o
      "g top surface\nf 2 3 4\n"  // g, its whole name
      "s off\nf 1 2 4\n");  // s changes nothing
  const pg::TriangleMesh m = pg::read_obj(in, "t.obj");
  EXPECT_EQ(m.facet_group, (std::vector<std::string>{"", "table", "top surface", "top surface"}));
  std::istringstream plain("v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n");
  EXPECT_TRUE(pg::read_obj(plain, "t.obj").facet_group.empty());
}

}  // namespace

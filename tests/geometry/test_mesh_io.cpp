// Mesh input: OFF and OBJ readers, their error messages, and robustness against garbage.
#include <panelrad/geometry/mesh_io.hpp>
#include <panelrad/geometry/oracles/openmesh_reader.hpp>
#include <panelrad/geometry/validation.hpp>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <sstream>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

namespace pg = panelrad::geometry;

namespace {

const std::string kMeshes = std::string(PANELRAD_SOURCE_DIR) + "/examples/meshes/";

pg::TriangleMesh off(const std::string& text, std::vector<std::string>* notes = nullptr) {
  std::istringstream in(text);
  return pg::read_off(in, "test.off", notes);
}

pg::TriangleMesh obj(const std::string& text, std::vector<std::string>* notes = nullptr) {
  std::istringstream in(text);
  return pg::read_obj(in, "test.obj", notes);
}

/// The MeshError message thrown by f, or "" when nothing is thrown.
template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const pg::MeshError& e) {
    return e.what();
  }
  return "";
}

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << "message: " << (haystack)

const std::string kTetraOff =
    "OFF\n"
    "4 4 6\n"
    "1 0 0\n0 1 0\n0 0 1\n1 1 1\n"
    "3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";

}  // namespace

TEST(MeshIo, ReadsShippedCube) {
  const pg::TriangleMesh m = pg::read_mesh(kMeshes + "cube.off");
  EXPECT_EQ(m.vertices.size(), 8u);
  EXPECT_EQ(m.triangles.size(), 12u);
  EXPECT_EQ(m.num_facets, 6);
  EXPECT_EQ(m.facet_of_triangle.size(), 12u);
  EXPECT_DOUBLE_EQ(pg::surface_area(m), 6.0);  // six unit squares, exact in double
  EXPECT_EQ(m.source, kMeshes + "cube.off");
}

TEST(MeshIo, PolygonFacesAreFanTriangulatedAndKeepTheirFacetId) {
  const pg::TriangleMesh m = off("OFF\n5 1 0\n0 0 0\n1 0 0\n2 1 0\n1 2 0\n0 1 0\n5 0 1 2 3 4\n");
  ASSERT_EQ(m.triangles.size(), 3u);
  const std::array<pg::Index, 3> expected[3] = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}};
  for (int t = 0; t < 3; ++t) {
    EXPECT_EQ(m.triangles[t], expected[t]);
    EXPECT_EQ(m.facet_of_triangle[t], 0);
  }
}

TEST(MeshIo, OffWithCommentsColoursAndVariants) {
  const std::string text =
      "# exported by some tool\n"
      "COFF # vertex colours follow the coordinates\n"
      "\n"
      "4 4 6   # counts\n"
      "1 0 0 255 0 0 255\n"
      "0 1 0 0 255 0 255   # a comment after a vertex\n"
      "0 0 1 0 0 255 255\n"
      "1 1 1 0.5 0.5 0.5 1\n"
      "# faces with per-face colours\n"
      "3 0 2 1 255 0 0\n"
      "3 0 1 3 0.1 0.2 0.3 0.4\n"
      "3 1 2 3 7\n"
      "3 0 3 2\n";
  const pg::TriangleMesh m = off(text);
  EXPECT_EQ(m.vertices.size(), 4u);
  EXPECT_EQ(m.triangles.size(), 4u);
  EXPECT_EQ(m.vertices[3], pg::Vec3(1, 1, 1));
  // Counts on the header line, NOFF normals, CRLF line ends.
  const pg::TriangleMesh n = off(
      "NOFF 4 4 6\r\n1 0 0 1 0 0\r\n0 1 0 0 1 0\r\n0 0 1 0 0 1\r\n1 1 1 1 1 1\r\n"
      "3 0 2 1\r\n3 0 1 3\r\n3 1 2 3\r\n3 0 3 2\r\n");
  EXPECT_EQ(n.triangles.size(), 4u);
  // No header keyword at all (some exporters omit it).
  EXPECT_EQ(off(kTetraOff.substr(4)).triangles.size(), 4u);
}

TEST(MeshIo, OffErrorsNameLineAndProblem) {
  EXPECT_CONTAINS(error_of([] { off(""); }), "test.off: empty file");
  EXPECT_CONTAINS(error_of([] { off("# only a comment\n\n   \n"); }), "empty file");
  EXPECT_CONTAINS(error_of([] { off("OFF\n0 0 0\n"); }), "declares 0 vertices");
  EXPECT_CONTAINS(error_of([] { off("OFF\n4 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n"); }), "declares 0 faces");
  // Truncated: fewer vertices or faces than the header says.
  const std::string cut_vertices = "OFF\n4 4 6\n1 0 0\n0 1 0\n";
  EXPECT_CONTAINS(error_of([&] { off(cut_vertices); }), "test.off:4: truncated file");
  EXPECT_CONTAINS(error_of([&] { off(cut_vertices); }), "declares 4 vertices, the file ends after 2");
  const std::string cut_faces = kTetraOff.substr(0, kTetraOff.rfind("3 0 3 2"));
  EXPECT_CONTAINS(error_of([&] { off(cut_faces); }), "declares 4 faces, the file ends after 3");
  // Truncated in the middle of a line.
  EXPECT_CONTAINS(error_of([&] { off(kTetraOff.substr(0, kTetraOff.size() - 3)); }), "test.off:10: input face 3 (line 10) declares 3 vertices but lists 2");
  // Bad numbers and garbage.
  EXPECT_CONTAINS(error_of([] { off("OFF\n4 4 6\n1 0 0\n0 1x 0\n"); }), "test.off:4: bad number '1x' in vertex 1");
  EXPECT_CONTAINS(error_of([] { off("OFF\nfour 4 6\n"); }), "test.off:2: bad count 'four'");
  EXPECT_CONTAINS(error_of([] { off("hello world\n"); }), "test.off:1: not an OFF file");
  EXPECT_CONTAINS(error_of([] { off(std::string("OFF\n4 4 6\n1 0 \x01\x02\n")); }), "test.off:3: unexpected byte 0x1");
  EXPECT_CONTAINS(error_of([] { off(std::string("OFF\n4 4 6\n1 0 0\0\n", 17)); }), "test.off:3: NUL byte at byte offset 15 (column 6)");
  EXPECT_CONTAINS(error_of([] { off("OFF BINARY\n"); }), "binary OFF is not supported");
  EXPECT_CONTAINS(error_of([] { off("4OFF\n"); }), "not supported");
  // Faces: index out of range, too few vertices, bad index, too many trailing values.
  std::string bad = kTetraOff;
  bad.replace(bad.find("3 1 2 3"), 7, "3 1 2 4");
  EXPECT_CONTAINS(error_of([&] { off(bad); }), "test.off:9: input face 2 (line 9): vertex index 4 out of range [0, 3]");
  bad = kTetraOff;
  bad.replace(bad.find("3 1 2 3"), 7, "2 1 2  ");
  EXPECT_CONTAINS(error_of([&] { off(bad); }), "test.off:9: input face 2 (line 9) has 2 vertices; a face needs at least 3");
  bad = kTetraOff;
  bad.replace(bad.find("3 1 2 3"), 7, "3 1 -2 3");
  EXPECT_CONTAINS(error_of([&] { off(bad); }), "vertex index -2 out of range");
  bad = kTetraOff;
  bad.replace(bad.find("3 1 2 3"), 7, "3 1 2 3 1 2 3 4 5");
  EXPECT_CONTAINS(error_of([&] { off(bad); }), "input face 2 (line 9) has 5 values after its indices");
  EXPECT_CONTAINS(error_of([&] { off(kTetraOff + "3 0 1 2\n"); }), "test.off:11: unexpected data after the last face");
}

TEST(MeshIo, NonFiniteCoordinatesAreRefused) {
  for (const char* bad : {"nan", "NaN", "inf", "-inf", "infinity", "1e400"}) {
    std::string text = kTetraOff;
    text.replace(text.find("0 0 1\n"), 1, bad);
    EXPECT_CONTAINS(error_of([&] { off(text); }), "test.off:5: non-finite coordinate");
  }
}

TEST(MeshIo, ObjWithTextureNormalRefsAndNegativeIndices) {
  const std::string text =
      "# a tetrahedron\n"
      "mtllib scene.mtl\n"
      "o tetra\n"
      "v 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1 1.0\n"
      "vt 0 0\nvt 1 0\nvt 0 1\n"
      "vn 0 0 1\n"
      "g part\ns 1\nusemtl red\n"
      "f 1/1 3/2 2/3\n"
      "f 1//1 2//1 4//1\n"
      "f -3/1/1 -2/2/1 \\\n"
      "  -1/3/1\n"
      "f -4 -1 -2\n";
  const pg::TriangleMesh m = obj(text);
  ASSERT_EQ(m.triangles.size(), 4u);
  EXPECT_EQ(m.triangles[0], (std::array<pg::Index, 3>{0, 2, 1}));
  EXPECT_EQ(m.triangles[1], (std::array<pg::Index, 3>{0, 1, 3}));
  EXPECT_EQ(m.triangles[2], (std::array<pg::Index, 3>{1, 2, 3}));
  EXPECT_EQ(m.triangles[3], (std::array<pg::Index, 3>{0, 3, 2}));
  EXPECT_EQ(m.num_facets, 4);
  pg::TriangleMesh copy = m;
  EXPECT_TRUE(pg::validate_closed_convex(copy).valid);
}

TEST(MeshIo, ObjErrors) {
  EXPECT_CONTAINS(error_of([] { obj(""); }), "test.obj: empty file");
  EXPECT_CONTAINS(error_of([] { obj("v 0 0 0\nv 1 0 0\nv 0 1 0\n"); }), "no faces");
  EXPECT_CONTAINS(error_of([] { obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n"); }), "test.obj:4: input face 0 (line 4): bad vertex reference '0'");
  EXPECT_CONTAINS(error_of([] { obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"); }), "test.obj:4: vertex index 4 out of range [1, 3]");
  EXPECT_CONTAINS(error_of([] { obj("v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n"); }),
                  "test.obj:3: input face 0 (line 3): relative vertex index -3 but only 2 vertices");
  EXPECT_CONTAINS(error_of([] { obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n"); }), "test.obj:4: input face 0 (line 4) has 2 vertices");
  EXPECT_CONTAINS(error_of([] { obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/x 2 3\n"); }), "bad vertex reference '1/x'");
  EXPECT_CONTAINS(error_of([] { obj("v 0 0\n"); }), "test.obj:1: vertex 1 has 2 values");
  EXPECT_CONTAINS(error_of([] { obj("v 0 0 nan\n"); }), "test.obj:1: non-finite coordinate 'nan'");
  EXPECT_CONTAINS(error_of([] { obj("v 0 0 0\ncurv 0 1 1 2\n"); }), "test.obj:2: unsupported OBJ statement 'curv' (free-form");
  EXPECT_CONTAINS(error_of([] { obj("\x7f\x45LF\x02\x01"); }), "test.obj:1: unexpected byte 0x7f");
}

TEST(MeshIo, TriangleSoupIsMergedAndUnusedVerticesDropped) {
  // A tetrahedron as a triangle soup: 12 vertices, each triangle with its own copies, plus one
  // vertex that no face uses.
  const std::string soup =
      "v 1 0 0\nv 0 0 1\nv 0 1 0\n"
      "v 1 0 0\nv 0 1 0\nv 1 1 1\n"
      "v 0 1 0\nv 0 0 1\nv 1 1 1\n"
      "v 1 0 0\nv 1 1 1\nv 0 0 1\n"
      "v 5 5 5\n"
      "f 1 2 3\nf 4 5 6\nf 7 8 9\nf 10 11 12\n";
  std::vector<std::string> notes;
  pg::TriangleMesh m = obj(soup, &notes);
  EXPECT_EQ(m.vertices.size(), 4u);
  EXPECT_EQ(m.triangles.size(), 4u);
  ASSERT_EQ(notes.size(), 2u);
  EXPECT_CONTAINS(notes[0], "merged 8 vertices");
  EXPECT_CONTAINS(notes[1], "dropped 1 vertices used by no face");
  EXPECT_TRUE(pg::validate_closed_convex(m).valid);
  // -0.0 and 0.0 are the same point.
  EXPECT_EQ(obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv -0.0 0 0\nf 1 2 3\nf 4 3 2\n").vertices.size(), 3u);
}

TEST(MeshIo, ReadMeshByExtensionAndFileErrors) {
  const auto dir = std::filesystem::temp_directory_path() / ("panelrad_mesh_io_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name, std::ios::binary) << text;
    return (dir / name).string();
  };
  EXPECT_EQ(pg::read_mesh(write("upper.OFF", kTetraOff)).triangles.size(), 4u);
  const std::string stl = write("mesh.stl", "solid x\nendsolid x\n");  // STL is read (test_stl_io): no facet here
  EXPECT_CONTAINS(error_of([&] { pg::read_mesh(stl); }), stl + ": no facet");
  EXPECT_CONTAINS(error_of([&] { pg::read_mesh(write("mesh.ply", kTetraOff)); }),
                  "unknown mesh format '.ply': expected .off, .obj or .stl");
  EXPECT_CONTAINS(error_of([&] { pg::read_mesh(write("noext", kTetraOff)); }), "unknown mesh format '(no extension)'");
  EXPECT_CONTAINS(error_of([&] { pg::read_mesh((dir / "missing.off").string()); }), "missing.off: cannot open: no such file");
  std::filesystem::create_directories(dir / "dir.off");
  EXPECT_CONTAINS(error_of([&] { pg::read_mesh((dir / "dir.off").string()); }), "is a directory");
  const std::string empty = write("empty.obj", "");
  EXPECT_CONTAINS(error_of([&] { pg::read_mesh(empty); }), empty + ": empty file");
  // An OFF file given the .obj extension is read as OBJ and refused with the line.
  EXPECT_CONTAINS(error_of([&] { pg::read_mesh(write("wrong.obj", kTetraOff)); }), "wrong.obj:1: unknown OBJ statement 'OFF'");
  std::filesystem::remove_all(dir);
}

// Files that are not regular, too large or binary are refused by the bounded reader, named by the
// mesh reader's MeshError, without blocking (FIFO) or reading without end (/dev/zero).
TEST(MeshIo, BoundedReadingOfMeshFiles) {
  const auto dir = std::filesystem::temp_directory_path() / ("panelrad_mesh_io_bounded_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string fifo = (dir / "pipe.off").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_CONTAINS(error_of([&] { pg::read_mesh(fifo); }), fifo + ": cannot read: is a FIFO (named pipe)");
  const auto zero = dir / "zero.obj";
  std::filesystem::create_symlink("/dev/zero", zero);
  EXPECT_CONTAINS(error_of([&] { pg::read_mesh(zero.string()); }), "zero.obj: cannot read: is a character device");
  const std::string tetra = (dir / "tetra.off").string();
  std::ofstream(tetra, std::ios::binary) << kTetraOff;
  panelrad::TextReadOptions small;
  small.max_bytes = kTetraOff.size() - 1;
  EXPECT_CONTAINS(error_of([&] { pg::read_mesh(tetra, nullptr, small); }),
                  "tetra.off: cannot read: the file is " + std::to_string(kTetraOff.size()) + " bytes");
  small.max_bytes = kTetraOff.size();
  EXPECT_EQ(pg::read_mesh(tetra, nullptr, small).num_facets, 4);
  std::istringstream in(kTetraOff);
  small.max_bytes = 10;
  EXPECT_CONTAINS(error_of([&] { pg::read_off(in, "s.off", nullptr, small); }), "s.off: grew while being read");
  // A sparse 1 GiB file of NUL bytes: refused at its first byte.
  const auto zeros = dir / "zeros.obj";
  std::ofstream(zeros, std::ios::binary).put('\0');
  std::filesystem::resize_file(zeros, std::uintmax_t{1} << 30);
  EXPECT_CONTAINS(error_of([&] { pg::read_mesh(zeros.string()); }), "zeros.obj:1: NUL byte at byte offset 0");
  std::filesystem::remove_all(dir);
}

// A leading UTF-8 byte-order mark (written by some Windows editors) is not part of the content:
// OFF and OBJ read the same with and without it, from files and from streams; the same bytes
// anywhere else are refused with their line.
TEST(MeshIo, Utf8ByteOrderMarkIsAccepted) {
  const std::string bom = "\xEF\xBB\xBF";
  const std::string tetra_obj = "v 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n";
  const pg::TriangleMesh plain_off = off(kTetraOff);
  const pg::TriangleMesh bom_off = off(bom + kTetraOff);
  EXPECT_EQ(bom_off.vertices, plain_off.vertices);
  EXPECT_EQ(bom_off.triangles, plain_off.triangles);
  EXPECT_EQ(obj(bom + tetra_obj).triangles, obj(tetra_obj).triangles);
  EXPECT_EQ(off(bom + "# comment first\n" + kTetraOff).num_facets, 4);
  const auto dir = std::filesystem::temp_directory_path() / ("panelrad_mesh_io_bom_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "bom.off", std::ios::binary) << bom << kTetraOff;
  std::ofstream(dir / "bom.obj", std::ios::binary) << bom << tetra_obj;
  EXPECT_EQ(pg::read_mesh((dir / "bom.off").string()).triangles, plain_off.triangles);
  EXPECT_EQ(pg::read_mesh((dir / "bom.obj").string()).num_facets, 4);
  std::filesystem::remove_all(dir);
  EXPECT_CONTAINS(error_of([&] { obj("v 0 0 0\n" + bom + "v 1 0 0\n"); }), "test.obj:2: unexpected byte 0xef at column 1");
}

// OBJ statements are case-sensitive: `V` or `F` read as `v`/`f` or skipped would both be guesses.
TEST(MeshIo, MiscasedObjStatementsAreErrors) {
  EXPECT_CONTAINS(error_of([] { obj("v 0 0 0\nV 1 0 0\n"); }),
                  "test.obj:2: unknown OBJ statement 'V' (OBJ statements are case-sensitive: did you mean 'v'?)");
  EXPECT_CONTAINS(error_of([] { obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nF 1 2 3\n"); }), "test.obj:4: unknown OBJ statement 'F'");
  EXPECT_CONTAINS(error_of([] { obj("v 0 0 0\nUSEMTL a\n"); }), "did you mean 'usemtl'?");
  EXPECT_CONTAINS(error_of([] { obj("v 0 0 0\nfoo 1\n"); }), "test.obj:2: unknown OBJ statement 'foo'");
}

// The OBJ reader records the material statements it skips for geometry: mtllib files and, per
// face, the usemtl in force, with the faces counted exactly as the mesh's facets (continued and
// commented-out lines included).
TEST(MeshIo, ObjMaterialStatementsPerFace) {
  const auto dir = std::filesystem::temp_directory_path() / ("panelrad_mesh_io_mtl_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "t.obj").string();
  std::ofstream(path) << "mtllib a.mtl b.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                         "f 1 2 3  # before any usemtl\nusemtl red paint\nf 1 2 \\\n 4\n# f 1 3 4\n"
                         "usemtl white\nf 1 4 3\nf 2 3 4\nmtllib c.mtl\n";
  pg::ObjMaterialUse use;
  const pg::TriangleMesh m = pg::read_obj_with_materials(path, use);
  ASSERT_EQ(m.num_facets, 4);
  EXPECT_EQ(use.face_material, (std::vector<std::string>{"", "red paint", "white", "white"}));
  EXPECT_EQ(use.face_line, (std::vector<long>{6, 8, 12, 13}));
  EXPECT_EQ(use.usemtl_line, (std::vector<long>{0, 7, 11, 11}));
  EXPECT_EQ(m.facet_line, use.face_line);  // a continued face: the line where it starts
  ASSERT_EQ(use.libraries.size(), 3u);
  EXPECT_EQ(use.libraries[1].file, "b.mtl");
  EXPECT_EQ(use.libraries[2].line, 14);
  std::ofstream(path) << "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl\nf 1 2 3\n";
  EXPECT_CONTAINS(error_of([&] { pg::read_obj_with_materials(path, use); }), "t.obj:4: usemtl without a material name");
  EXPECT_EQ(pg::read_mesh(path).num_facets, 1);  // geometry alone ignores material statements
  std::filesystem::remove_all(dir);
}

TEST(MeshIo, ShippedMeshesAllRead) {
  for (const char* name : {"cube.off", "hexagonal_prism.off", "triangular_prism.obj", "dodecahedron.off",
                           "l_block.off", "open_box.off"}) {
    SCOPED_TRACE(name);
    const pg::TriangleMesh m = pg::read_mesh(kMeshes + name);
    EXPECT_GT(m.triangles.size(), 0u);
    EXPECT_EQ(m.facet_of_triangle.size(), m.triangles.size());
  }
  EXPECT_EQ(pg::read_mesh(kMeshes + "dodecahedron.off").num_facets, 12);
  EXPECT_EQ(pg::read_mesh(kMeshes + "triangular_prism.obj").triangles.size(), 8u);
}

// Two independent readers agree on every well-formed shipped file (meshes and scenes): the same
// vertices (to OpenMesh's single-precision parsing), the same faces and the same fan triangulation (OpenMesh's reader as the
// truth for ours; ours merges nothing here since these files have no duplicate vertices).
// OpenMesh's OFF reader does not know '#' comments (it reads such a file as an empty mesh without
// an error) nor colours after a face's indices (it stops after the first face, silently): the
// reasons panelrad has its own reader. It gets the files without comment lines here.
TEST(MeshIo, AgreesWithOpenMeshReader) {
  const std::string scenes = std::string(PANELRAD_SOURCE_DIR) + "/examples/scenes/";
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("panelrad_openmesh_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  for (const std::string& path : {kMeshes + "cube.off", kMeshes + "hexagonal_prism.off", kMeshes + "triangular_prism.obj",
                                  kMeshes + "l_block.off", kMeshes + "open_box.off", scenes + "convex_box.obj",
                                  scenes + "prism_lamp.off", scenes + "cornell_box.obj"}) {
    SCOPED_TRACE(path);
    const std::string plain = (dir / std::filesystem::path(path).filename()).string();
    {
      std::ifstream in(path);
      std::ofstream out(plain);
      for (std::string line; std::getline(in, line);)
        if (line.find_first_not_of(" \t") != std::string::npos && line[line.find_first_not_of(" \t")] != '#')
          out << line << "\n";
    }
    const pg::TriangleMesh ours = pg::read_mesh(path);
    const pg::TriangleMesh theirs = pg::read_mesh_with_openmesh(plain);
    ASSERT_EQ(ours.vertices.size(), theirs.vertices.size());
    // OpenMesh's readers parse coordinates in single precision even into double points (measured
    // differences up to 2.8e-8 on these files): agreement to float rounding, 2^-24 relative per
    // coordinate. Ours parse correctly rounded doubles (std::from_chars).
    for (std::size_t v = 0; v < ours.vertices.size(); ++v)
      for (int k = 0; k < 3; ++k)
        EXPECT_LE(std::abs(ours.vertices[v][k] - theirs.vertices[v][k]), 0x1p-24 * std::abs(ours.vertices[v][k]))
            << "vertex " << v;
    EXPECT_EQ(ours.num_facets, theirs.num_facets);
    EXPECT_EQ(ours.triangles, theirs.triangles);
    EXPECT_EQ(ours.facet_of_triangle, theirs.facet_of_triangle);
  }
  EXPECT_THROW(pg::read_mesh_with_openmesh(kMeshes + "cube.off"), pg::MeshError);  // comments: read as empty
  // Per-face colours after the indices (dodecahedron.off): OpenMesh stops after the first face,
  // silently; ours reads all 12.
  {
    const std::string plain = (dir / "dodecahedron.off").string();
    std::ifstream in(kMeshes + "dodecahedron.off");
    std::ofstream out(plain);
    for (std::string line; std::getline(in, line);)
      if (!line.empty() && line[0] != '#') out << line << "\n";
    out.close();
    EXPECT_EQ(pg::read_mesh_with_openmesh(plain).num_facets, 1);
    EXPECT_EQ(pg::read_mesh(kMeshes + "dodecahedron.off").num_facets, 12);
    // Without the colours OpenMesh reads all 12 pentagons: the same fan triangulation (the rounded
    // pentagons are planar within the rounding of their 7 digits, and convex).
    std::ifstream again(kMeshes + "dodecahedron.off");
    std::ofstream bare(plain);
    for (std::string line; std::getline(again, line);) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream tokens(line);
      std::vector<std::string> t{std::istream_iterator<std::string>(tokens), std::istream_iterator<std::string>()};
      // Header, counts and vertices have at most 3 values; a face "k i_1 .. i_k r g b" loses its colour.
      if (t.size() > 3 && std::stoul(t[0]) + 1 < t.size()) t.resize(std::stoul(t[0]) + 1);
      for (std::size_t k = 0; k < t.size(); ++k) bare << (k ? " " : "") << t[k];
      bare << "\n";
    }
    bare.close();
    const pg::TriangleMesh theirs = pg::read_mesh_with_openmesh(plain);
    const pg::TriangleMesh ours = pg::read_mesh(kMeshes + "dodecahedron.off");
    EXPECT_EQ(theirs.num_facets, 12);
    EXPECT_EQ(ours.triangles, theirs.triangles);
    EXPECT_EQ(ours.facet_of_triangle, theirs.facet_of_triangle);
  }
  EXPECT_THROW(pg::read_mesh_with_openmesh(kMeshes + "missing.off"), pg::MeshError);
  std::filesystem::remove_all(dir);
}

// Random byte mutations of real files: every outcome is a mesh or a MeshError, never a crash or
// another exception; a mesh that is read is then validated, which must not crash either.
TEST(MeshIo, MutatedFilesNeverCrash) {
  std::mt19937 rng(12345);
  for (const char* name : {"cube.off", "dodecahedron.off", "triangular_prism.obj"}) {
    std::ifstream in(kMeshes + name, std::ios::binary);
    const std::string original((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const bool is_obj = std::string(name).ends_with(".obj");
    int read_ok = 0, refused = 0;
    for (int trial = 0; trial < 1500; ++trial) {
      std::string text = original;
      const int edits = 1 + static_cast<int>(rng() % 4);
      for (int e = 0; e < edits; ++e) {
        const std::size_t pos = rng() % text.size();
        switch (rng() % 4) {
          case 0: text[pos] = static_cast<char>(rng() % 256); break;
          case 1: text.erase(pos, 1 + rng() % 8); break;
          case 2: text.insert(pos, 1, "0123456789 -.#\n/e"[rng() % 17]); break;
          default: text.resize(pos); break;
        }
        if (text.empty()) text.push_back('x');
      }
      try {
        std::istringstream s(text);
        pg::TriangleMesh m = is_obj ? pg::read_obj(s, name) : pg::read_off(s, name);
        ++read_ok;
        const pg::ValidationReport r = pg::validate_closed_convex(m);
        EXPECT_EQ(r.valid, r.rule.empty());
      } catch (const pg::MeshError&) {
        ++refused;
      }
    }
    EXPECT_GT(refused, 0);
    EXPECT_GT(read_ok, 0);
  }
}

// ---- polygonal faces: triangulated on their own corners, or refused naming face and line --------

namespace {

using Poly2 = std::vector<std::array<double, 2>>;

/// An L-shaped and a U-shaped room wall (area 3 and 5), counter-clockwise in their (x, y) plane.
const Poly2 kL = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
const Poly2 kU = {{0, 0}, {3, 0}, {3, 2}, {2, 2}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};

/// The polygon starting at corner `shift`, reversed when asked, placed on the plane z = x + y
/// (area factor sqrt(3); the coordinates stay integers, exact).
std::vector<pg::Vec3> placed(const Poly2& p, std::size_t shift, bool reversed) {
  std::vector<pg::Vec3> out;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const auto& q = p[(shift + k) % p.size()];
    out.emplace_back(q[0], q[1], q[0] + q[1]);
  }
  if (reversed) std::reverse(out.begin(), out.end());
  return out;
}

/// The polygon as the only face of an OBJ (after a comment line) and of an OFF text.
std::string obj_text(const std::vector<pg::Vec3>& p, int digits = 17) {
  std::ostringstream s;
  s.precision(digits);
  s << "# one polygon\n";
  for (const auto& v : p) s << "v " << v.x() << " " << v.y() << " " << v.z() << "\n";
  s << "f";
  for (std::size_t k = 1; k <= p.size(); ++k) s << " " << k;
  s << "\n";
  return s.str();
}

std::string off_text(const std::vector<pg::Vec3>& p, int digits = 17) {
  std::ostringstream s;
  s.precision(digits);
  s << "OFF\n" << p.size() << " 1 0\n";
  for (const auto& v : p) s << v.x() << " " << v.y() << " " << v.z() << "\n";
  s << p.size();
  for (std::size_t k = 0; k < p.size(); ++k) s << " " << k;
  s << "\n";
  return s.str();
}

/// Twice the vector area of a polygon (Newell's formula).
pg::Vec3 newell(const std::vector<pg::Vec3>& p) {
  pg::Vec3 n = pg::Vec3::Zero();
  for (std::size_t k = 0; k < p.size(); ++k) n += p[k].cross(p[(k + 1) % p.size()]);
  return n;
}

/// One facet read from a polygon: n - 2 triangles, each of positive area and facing the polygon's
/// Newell normal, whose area vectors sum to the polygon's (area and orientation of the polygon).
void expect_triangulates(const pg::TriangleMesh& m, const std::vector<pg::Vec3>& polygon) {
  const pg::Vec3 n = newell(polygon);
  ASSERT_EQ(m.triangles.size(), polygon.size() - 2);
  EXPECT_EQ(m.num_facets, 1);
  pg::Vec3 sum = pg::Vec3::Zero();
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    EXPECT_EQ(m.facet_of_triangle[t], 0);
    const auto& tr = m.triangles[t];
    const pg::Vec3 a = m.vertices[tr[0]], b = m.vertices[tr[1]], c = m.vertices[tr[2]];
    const pg::Vec3 area = (b - a).cross(c - a);
    EXPECT_GT(area.dot(n), 1e-9 * n.squaredNorm()) << "triangle " << t << " is degenerate or faces away";
    sum += area;
  }
  EXPECT_LE((sum - n).norm(), 1e-12 * n.norm()) << "sum of triangle areas " << sum.transpose() << ", polygon " << n.transpose();
  EXPECT_NEAR(pg::surface_area(m), 0.5 * n.norm(), 1e-12 * n.norm());
}

}  // namespace

// L- and U-shaped walls written as one polygon, from every starting corner and in both directions,
// as OBJ and as OFF: the exact area, in the direction the file gives (the fan from the first corner
// overlaps itself from most starting corners).
TEST(MeshIo, NonConvexPolygonsTriangulateToTheirAreaAndOrientation) {
  for (const Poly2* shape : {&kL, &kU})
    for (std::size_t shift = 0; shift < shape->size(); ++shift)
      for (bool reversed : {false, true}) {
        SCOPED_TRACE("corners " + std::to_string(shape->size()) + ", shift " + std::to_string(shift) +
                     (reversed ? ", reversed" : ""));
        const std::vector<pg::Vec3> p = placed(*shape, shift, reversed);
        const pg::TriangleMesh a = obj(obj_text(p));
        expect_triangulates(a, p);
        EXPECT_EQ(a.facet_line, std::vector<long>{static_cast<long>(p.size()) + 2});
        const pg::TriangleMesh b = off(off_text(p));
        expect_triangulates(b, p);
        EXPECT_EQ(b.facet_line, std::vector<long>{static_cast<long>(p.size()) + 3});
        EXPECT_NEAR(pg::surface_area(a), (shape == &kL ? 3 : 5) * std::sqrt(3.0), 1e-12);
      }
}

// A polygon whose first three corners are collinear (a rectangle with a corner in the middle of
// its first side): the fan's first triangle would have zero area; read with its area, the middle
// corner a corner of the triangles.
TEST(MeshIo, PolygonWithCollinearFirstCornersIsAccepted) {
  const std::vector<pg::Vec3> p = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {0, 1, 0}};
  for (const pg::TriangleMesh& m : {obj(obj_text(p)), off(off_text(p))}) {
    expect_triangulates(m, p);
    EXPECT_DOUBLE_EQ(pg::surface_area(m), 2.0);
  }
}

// Convex polygons keep the fan from their first corner, also with corners on a straight side when
// the fan stays non-degenerate (the Cornell box's ceiling hexagon).
TEST(MeshIo, ConvexPolygonsKeepTheFan) {
  const pg::TriangleMesh m = obj(
      "v 556 548.8 0\nv 556 548.8 559.2\nv 343 548.8 559.2\nv 343 548.8 332\nv 343 548.8 227\nv 343 548.8 0\n"
      "f 1 2 3 4 5 6\n");
  const std::vector<std::array<pg::Index, 3>> fan = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}};
  EXPECT_EQ(m.triangles, fan);
}

// A bow-tie (its two lobes of equal area: a zero vector area) and an unequal one are refused,
// naming the file, the face (0-based, the facet id) and its line.
TEST(MeshIo, SelfCrossingPolygonsAreRefusedWithFaceAndLine) {
  const std::string head = "v 0 0 0\nv 1 0 0\nv 0 1 0\n# a bow-tie\nv 0 0 1\nv 1 1 1\nv 1 0 1\nv 0 1 1\nf 1 2 3\n";
  EXPECT_CONTAINS(error_of([&] { obj(head + "\nf 4 5 6 7\n"); }), "test.obj:11: input face 1 (line 11) ");
  EXPECT_CONTAINS(error_of([&] { obj(head + "\nf 4 5 6 7\n"); }), "crosses itself");
  const std::string uneven = "v 0 0 5\nv 2 2 5\nv 2 0 5\nv 0 1 5\nf 1 2 3 4\n";
  EXPECT_CONTAINS(error_of([&] { obj(uneven); }), "test.obj:5: input face 0 (line 5) crosses or touches itself: its side");
  EXPECT_CONTAINS(error_of([&] { off("OFF\n4 2 0\n0 0 5\n2 2 5\n2 0 5\n0 1 5\n3 0 2 3\n# next\n4 0 1 2 3\n"); }),
                  "test.off:9: input face 1 (line 9) crosses or touches itself");
  // A corner on another side (touching), a repeated corner, all corners on a line.
  EXPECT_CONTAINS(error_of([] { obj("v 0 0 0\nv 4 0 0\nv 4 4 0\nv 3 4 0\nv 2 0 0\nv 1 4 0\nv 0 4 0\nf 1 2 3 4 5 6 7\n"); }),
                  "input face 0 (line 8) crosses or touches itself: its side from its 1st vertex (0, 0, 0) to its 2nd "
                  "vertex (4, 0, 0) meets its side from its 4th vertex (3, 4, 0) to its 5th vertex (2, 0, 0)");
  EXPECT_CONTAINS(error_of([] { obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 2 4\n"); }),
                  "input face 0 (line 5) lists one vertex twice: its 2nd and 4th vertices are both (1, 0, 0)");
  EXPECT_CONTAINS(error_of([] { obj("v 0 0 0\nv 1 1 1\nv 2 2 2\nv 3 3 3\nf 1 2 3 4\n"); }),
                  "input face 0 (line 5) has zero area: its 4 vertices lie on one straight line");
}

// A unit square with one corner lifted by 1e-2 is not one planar facet: refused with what to do.
// Lifted by 1e-5 (its corners 2.5e-6 from the Newell plane) it is within 4 x the rounding of
// coordinates written with at most 6 digits (eta = 5e-6 here): accepted.
TEST(MeshIo, NonPlanarPolygonIsRefusedWithFaceAndLine) {
  const std::string lifted = "v 0 0 0\nv 1 0 0\nv 1 1 0.01\nv 0 1 0\n\nf 1 2 3 4\n";
  const std::string msg = error_of([&] { obj(lifted); });
  EXPECT_CONTAINS(msg, "test.obj:6: input face 0 (line 6) is not planar: its ");
  EXPECT_CONTAINS(msg, "lies 2.50e-03 from the plane");
  EXPECT_CONTAINS(msg, "split it into planar polygons or triangles");
  EXPECT_CONTAINS(error_of([] { off("OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0.01\n0 1 0\n4 0 1 2 3\n"); }),
                  "test.off:7: input face 0 (line 7) is not planar");
  EXPECT_EQ(obj("v 0 0 0\nv 1 0 0\nv 1 1 0.00001\nv 0 1 0\nf 1 2 3 4\n").triangles.size(), 2u);
}

// The U-shaped wall 4e6 wide on a tilted plane at 1e8 from the origin, written with 6 significant
// digits: rounding moves its corners off the plane by hundreds of units (far above 1e-9 of its
// size), within 4 x the rounding of 6-digit coordinates of that magnitude: accepted, with its area.
TEST(MeshIo, PlanarPolygonWithSixDigitsFarFromTheOriginIsAccepted) {
  const pg::Vec3 origin(1e8, 1.1e8, 0.9e8);
  const pg::Vec3 u = pg::Vec3(2, -1, 0).normalized(), v = pg::Vec3(1, 2, -5).normalized();  // orthonormal
  std::vector<pg::Vec3> exact;
  for (const auto& q : kU) exact.push_back(origin + 1e6 * (q[0] * u + q[1] * v));
  // The corners as read back from 6 digits, and their largest distance from their Newell plane.
  std::vector<pg::Vec3> rounded;
  for (const auto& p : exact) {
    pg::Vec3 r;
    for (int k = 0; k < 3; ++k) {
      std::ostringstream s;
      s.precision(6);
      s << p[k];
      r[k] = std::stod(s.str());
    }
    rounded.push_back(r);
  }
  pg::Vec3 centroid = pg::Vec3::Zero();
  for (const auto& r : rounded) centroid += r / static_cast<double>(rounded.size());
  const pg::Vec3 n = newell(rounded).normalized();
  double off_plane = 0;
  for (const auto& r : rounded) off_plane = std::max(off_plane, std::abs((r - centroid).dot(n)));
  ASSERT_GT(off_plane, 1e-9 * 3e6 * 10) << "the rounding must put the corners off the plane";

  for (const pg::TriangleMesh& m : {obj(obj_text(exact, 6)), off(off_text(exact, 6))}) {
    EXPECT_EQ(m.vertices.size(), rounded.size());
    for (std::size_t k = 0; k < rounded.size(); ++k) EXPECT_EQ(m.vertices[k], rounded[k]);
    ASSERT_EQ(m.triangles.size(), rounded.size() - 2);
    pg::Vec3 sum = pg::Vec3::Zero();
    for (const auto& tr : m.triangles) {
      const pg::Vec3 area = (m.vertices[tr[1]] - m.vertices[tr[0]]).cross(m.vertices[tr[2]] - m.vertices[tr[0]]);
      EXPECT_GT(area.dot(n), 0);
      sum += area;
    }
    EXPECT_NEAR(0.5 * sum.norm(), 5e12, 5e12 * 1e-3);  // the U's area 5 at scale 1e6, to the rounding
    EXPECT_LE((sum - newell(rounded)).norm(), 1e-6 * sum.norm());
  }
}

// Validation names a triangle's face as the reader does: "input face F (line L)", F from 0. A mesh
// built in code has no lines.
TEST(MeshIo, ValidationMessagesNameInputFaceAndLine) {
  // A tetrahedron whose third face has zero area (its corners on a line).
  const std::string text =
      "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\n"
      "# faces\n"
      "f 1 2 4\n"
      "f 2 3 4\n"
      "\n"
      "f 1 3 2\n"
      "f 1 4 3\n";
  pg::TriangleMesh m = obj(text);
  EXPECT_EQ(m.facet_line, (std::vector<long>{6, 7, 9, 10}));
  const pg::ValidationReport r = pg::validate_closed_convex(m);
  EXPECT_CONTAINS(r.message, "triangle 2 (input face 2 (line 9); vertices 0 (0, 0, 0), 2 (2, 0, 0), 1 (1, 0, 0))");
  pg::TriangleMesh built = m;
  built.facet_line.clear();
  EXPECT_CONTAINS(pg::validate_closed_convex(built).message, "triangle 2 (input face 2; vertices");
}

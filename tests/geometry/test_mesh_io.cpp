// Mesh input: OFF and OBJ readers, their error messages, and robustness against garbage.
#include <panelrad/geometry/mesh_io.hpp>
#include <panelrad/geometry/oracles/openmesh_reader.hpp>
#include <panelrad/geometry/validation.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
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
  EXPECT_CONTAINS(error_of([&] { off(kTetraOff.substr(0, kTetraOff.size() - 3)); }), "face 3 declares 3 vertices but lists 2");
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
  EXPECT_CONTAINS(error_of([&] { off(bad); }), "test.off:9: face 2: vertex index 4 out of range [0, 3]");
  bad = kTetraOff;
  bad.replace(bad.find("3 1 2 3"), 7, "2 1 2  ");
  EXPECT_CONTAINS(error_of([&] { off(bad); }), "test.off:9: face 2 has 2 vertices; a face needs at least 3");
  bad = kTetraOff;
  bad.replace(bad.find("3 1 2 3"), 7, "3 1 -2 3");
  EXPECT_CONTAINS(error_of([&] { off(bad); }), "vertex index -2 out of range");
  bad = kTetraOff;
  bad.replace(bad.find("3 1 2 3"), 7, "3 1 2 3 1 2 3 4 5");
  EXPECT_CONTAINS(error_of([&] { off(bad); }), "face 2 has 5 values after its indices");
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
  EXPECT_CONTAINS(error_of([] { obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 0\n"); }), "test.obj:4: face 1: bad vertex reference '0'");
  EXPECT_CONTAINS(error_of([] { obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n"); }), "test.obj:4: vertex index 4 out of range [1, 3]");
  EXPECT_CONTAINS(error_of([] { obj("v 0 0 0\nv 1 0 0\nf -1 -2 -3\nv 0 1 0\n"); }),
                  "test.obj:3: face 1: relative vertex index -3 but only 2 vertices");
  EXPECT_CONTAINS(error_of([] { obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n"); }), "face 1 has 2 vertices");
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
  const std::string stl = write("mesh.stl", "solid x\nendsolid x\n");
  EXPECT_CONTAINS(error_of([&] { pg::read_mesh(stl); }), stl + ": unknown mesh format '.stl'");
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
  pg::TextReadOptions small;
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
                                  scenes + "prism_lamp.off"}) {
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

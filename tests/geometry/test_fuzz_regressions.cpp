// Regression inputs of the mesh-reader fuzzer (fuzz/): every file under tests/data/fuzz
// (also the fuzzer's seeds) goes through the fuzz target's checks, read as OFF, OBJ and STL: the
// only failure allowed is a geometry::MeshError with a message; what parses is a consistent mesh,
// and a mesh that validates either gives a finite cluster tree or is refused with a MeshError.
// The hand-made adversarial inputs (header counts near INT_MAX, index overflow, extreme
// coordinates) and the fuzzer's findings (sliver_apex_on_its_base.off: a face whose apex lies
// within the contact tolerance of its own base, once split at its own corner) kept as a regression.
#include <panelrad/geometry/cluster_tree.hpp>
#include <panelrad/geometry/mesh_io.hpp>
#include <panelrad/geometry/scene_validation.hpp>
#include <panelrad/geometry/validation.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace panelrad::geometry;
namespace fs = std::filesystem;

const fs::path kDir = fs::path(PANELRAD_SOURCE_DIR) / "tests" / "data" / "fuzz";

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<fs::path> inputs() {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(kDir))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

// What the fuzz target checks (fuzz/fuzz_mesh_reader.cpp), as test assertions.
enum class Format { off, obj, stl };

void check_text(const std::string& text, Format format, const std::string& what) {
  std::istringstream in(text);
  TriangleMesh mesh;
  try {
    mesh = format == Format::obj ? read_obj(in, what) : format == Format::off ? read_off(in, what) : read_stl(in, what);
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << "the message names the file: " << e.what();
    return;
  }  // any other exception fails the test (gtest reports it)
  ASSERT_EQ(mesh.facet_of_triangle.size(), mesh.triangles.size()) << what;
  for (const auto& t : mesh.triangles)
    for (Index v : t) ASSERT_TRUE(v >= 0 && static_cast<std::size_t>(v) < mesh.vertices.size()) << what;
  for (const auto& p : mesh.vertices) ASSERT_TRUE(p.allFinite()) << what;
  // As a scene (the convex check, then the general rules: joined corners, split T-junctions,
  // faces moved onto common planes, contacts): a verdict that names its rule, no exception other
  // than MeshError, and what is accepted has no triangle without area.
  TriangleMesh scene = mesh;
  try {
    const SceneValidationReport scene_report = validate_scene(scene);
    EXPECT_EQ(scene_report.valid, scene_report.rule.empty()) << what;
    if (scene_report.valid)
      for (const auto& t : scene.triangles) {
        const Vec3 &a = scene.vertices[static_cast<std::size_t>(t[0])], &b = scene.vertices[static_cast<std::size_t>(t[1])],
                   &c = scene.vertices[static_cast<std::size_t>(t[2])];
        EXPECT_GT((b - a).cross(c - a).norm(), 0) << what;
      }
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << "the message names the file: " << e.what();
  }
  const ValidationReport report = validate_closed_convex(mesh);
  EXPECT_EQ(report.valid, report.rule.empty()) << what;
  if (!report.valid) return;
  try {
    const ClusterTree tree(mesh, 1);
    for (const auto& c : tree.elements())
      EXPECT_TRUE(c.centre.allFinite() && c.normal.allFinite() && std::isfinite(c.radius) && c.area > 0) << what;
  } catch (const MeshError& e) {
    std::cout << "[fuzz regression] " << what << ": valid, tree refused: " << e.what() << "\n";
  }
}

TEST(FuzzRegressions, EveryInputIsReadOrRefusedWithAMeshError) {
  const auto files = inputs();
  ASSERT_GE(files.size(), 10u) << kDir;
  for (const auto& f : files) {
    const std::string text = slurp(f);
    check_text(text, Format::off, f.filename().string() + " as OFF");
    check_text(text, Format::obj, f.filename().string() + " as OBJ");
    check_text(text, Format::stl, f.filename().string() + " as STL");
  }
}

// A header count of 2e9 vertices in a 25-byte file must be refused from the data (truncated),
// not by trying to reserve gigabytes (the fuzzer runs with -malloc_limit_mb=1024).
TEST(FuzzRegressions, HugeHeaderCountsAreNotALicenceToAllocate) {
  for (const char* name : {"header_count_2e9.off", "face_count_int_max.off"}) {
    std::istringstream in(slurp(kDir / name));
    EXPECT_THROW(read_off(in, name), MeshError) << name;
  }
}

// The bounded reader's decisions on fuzzer-style inputs: a leading UTF-8 byte-order mark is not
// content (the tetrahedron reads as without it); a NUL byte is binary data even inside a comment
// (the reader once skipped it there with the comment), refused with its line and byte offset.
TEST(FuzzRegressions, ByteOrderMarkIsSkippedAndNulIsBinaryEverywhere) {
  std::istringstream bom(slurp(kDir / "bom_tetrahedron.off"));
  TriangleMesh m = read_off(bom, "bom_tetrahedron.off");
  EXPECT_EQ(m.num_facets, 4);
  EXPECT_TRUE(validate_closed_convex(m).valid);
  std::istringstream nul(slurp(kDir / "nul_in_comment.obj"));
  try {
    read_obj(nul, "nul_in_comment.obj");
    ADD_FAILURE() << "a NUL byte in a comment was read";
  } catch (const MeshError& e) {
    // "v 1 0 0\n" x 4 = 32 bytes, then "# a comment " (12 bytes): offset 44 on line 5, column 13.
    EXPECT_NE(std::string(e.what()).find("nul_in_comment.obj:5: NUL byte at byte offset 44 (column 13)"), std::string::npos)
        << e.what();
  }
}

// Coordinates near the ends of the double range: the exact predicates accept these tetrahedra, but
// their areas and normals do not exist in double precision (area -nan for 1e308, 0 for 1e-300),
// and the exact convexity proof was fed an interior point that overflowed to inf (a CGAL assertion
// "Creating an Mpzf from infinity or NaN" in builds with assertions, silently undefined without).
// `panelrad check` printed "valid" with "surface area: -nan". Validation must refuse them under
// the "finite" rule, naming the vertex or triangle.
TEST(FuzzRegressions, CoordinatesOutsideTheDoubleRangeAreRefused) {
  for (const char* name : {"coordinates_1e308.obj", "coordinates_1e-300.obj", "coordinates_denormal.obj"}) {
    std::istringstream in(slurp(kDir / name));
    TriangleMesh mesh = read_obj(in, name);
    const ValidationReport report = validate_closed_convex(mesh);
    EXPECT_FALSE(report.valid) << name;
    EXPECT_EQ(report.rule, "finite") << name << ": " << report.message;
    EXPECT_TRUE(report.message.find("vertex") != std::string::npos ||
                report.message.find("triangle") != std::string::npos)
        << report.message;
    std::cout << "[fuzz regression] " << name << ": " << report.message << "\n";
  }
  // The range is lengths from 1e-75 to 1e75: tetrahedra with legs 1e74 and 1e-74 are valid and
  // have a finite positive area in double; legs 1e76 and 1e-76 are refused.
  for (double s : {1e74, 1e-74, 1e76, 1e-76}) {
    TriangleMesh mesh;
    mesh.vertices = {Vec3(0, 0, 0), Vec3(s, 0, 0), Vec3(0, s, 0), Vec3(0, 0, s)};
    mesh.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
    mesh.facet_of_triangle = {0, 1, 2, 3};
    mesh.num_facets = 4;
    const ValidationReport report = validate_closed_convex(mesh);
    if (s > 1e75 || s < 1e-75) {
      EXPECT_EQ(report.rule, "finite") << s << ": " << report.message;
      continue;
    }
    EXPECT_TRUE(report.valid) << s << ": " << report.message;
    const double area = surface_area(mesh);
    EXPECT_TRUE(std::isfinite(area) && area > 0) << s << ": area " << area;
  }
}

}  // namespace

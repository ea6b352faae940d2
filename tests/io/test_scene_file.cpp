// Scene files: OBJ + MTL and OFF + JSON sidecar loading, and every error message.
#include "test_support.hpp"
#include <panelrad/io/scene_file.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include <sys/stat.h>
#include <unistd.h>

namespace fs = std::filesystem;
using panelrad::Scene;
using panelrad::load_scene;
using panelrad::LoadOptions;

namespace {
/// load_scene with a materials path and read limits, as the scene-file tests give them.
panelrad::Scene load_channel_scene(const std::string& path, const std::string& materials = "",
                                   const panelrad::TextReadOptions& read = {}) {
  LoadOptions options;
  options.materials_path = materials;
  options.read = read;
  return load_scene(path, options);
}
}  // namespace
using panelrad::SceneFileError;

namespace {

const std::string kScenes = std::string(PANELRAD_SOURCE_DIR) + "/examples/scenes/";
const std::string kMeshes = std::string(PANELRAD_SOURCE_DIR) + "/examples/meshes/";

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << "message: " << (haystack)

// Unit cube, outward quads: 0 bottom z=0, 1 top z=1, 2 front y=0, 3 right x=1, 4 back y=1, 5 left x=0.
const std::string kCubeVertices =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";
const char* const kCubeFaces[6] = {"f 1 4 3 2", "f 5 6 7 8", "f 1 2 6 5",
                                   "f 2 3 7 6", "f 3 4 8 7", "f 4 1 5 8"};
const std::string kCubeOff =
    "OFF\n8 6 12\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
    "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n";

const std::string kGoodMtl =
    "# test materials\n"
    "newmtl white\nKa 0.1 0.1 0.1\nKd 0.7 0.7 0.7\nKs 0 0 0\nNs 10\nillum 1\nd 1\n"
    "newmtl red\nKd 0.6 0.05 0.04   # a comment\nmap_Kd red.png\n"
    "newmtl green\nKd 0.1 0.45 0.09\n"
    "newmtl light\nKd 0.5 0.5 0.5\nKe 4 3 1.5\n"
    "newmtl unused\nKd 0.2 0.2 0.2\n";

/// A fresh directory per test, removed afterwards.
class SceneFile : public panelrad::testing::TempDirTest {
 protected:
  SceneFile() : TempDirTest("panelrad_scene_file") {}
  /// The cube OBJ with `mtllib cube.mtl`, "usemtl" before each face from `materials` (empty: none).
  std::string cube_obj(const std::vector<std::string>& materials, const std::string& head = "mtllib cube.mtl\n") {
    std::string text = head + kCubeVertices;
    for (int f = 0; f < 6; ++f) {
      if (!materials[f].empty()) text += "usemtl " + materials[f] + "\n";
      text += std::string(kCubeFaces[f]) + "\n";
    }
    return write("cube.obj", text);
  }
  /// The cube OFF with sidecar cube.json.
  std::string cube_off(const std::string& json) {
    write("cube.json", json);
    return write("cube.off", kCubeOff);
  }
};

/// The SceneFileError message thrown by loading, or "" when nothing is thrown.
std::string error_of(const std::string& path, const std::string& materials = "") {
  try {
    load_channel_scene(path, materials);
  } catch (const SceneFileError& e) {
    return e.what();
  }
  return "";
}

/// Does every triangle of `facet` lie in the plane coordinate[axis] == value?
bool facet_on_plane(const Scene& s, int facet, int axis, double value) {
  int triangles = 0;
  for (std::size_t t = 0; t < s.mesh().triangles.size(); ++t) {
    if (s.mesh().facet_of_triangle[t] != facet) continue;
    ++triangles;
    for (auto v : s.mesh().triangles[t])
      if (s.mesh().vertices[static_cast<std::size_t>(v)][axis] != value) return false;
  }
  return triangles > 0;
}

}  // namespace

// ---- good scenes ----------------------------------------------------------------------------

TEST_F(SceneFile, ObjMtlCubeHasPerFacetMaterials) {
  write("cube.mtl", kGoodMtl);
  // Comments, a continued face line and a commented-out face must not shift the face count.
  const std::string obj = write("cube.obj",
                                "# cube\nmtllib cube.mtl\n" + kCubeVertices +
                                    "usemtl white\nf 1 4 3 2\n"
                                    "# f 1 2 3\n"
                                    "usemtl light\nf 5 6 \\\n  7 8\n"
                                    "usemtl white\nf 1 2 6 5\n"
                                    "usemtl green\nf 2 3 7 6\n"
                                    "usemtl white\nf 3 4 8 7\n"
                                    "usemtl red\nf 4 1 5 8\n");
  const Scene s = load_channel_scene(obj);
  ASSERT_EQ(s.mesh().num_facets, 6);
  ASSERT_EQ(s.num_channels(), 3u);
  EXPECT_EQ(s.channels(), (std::vector<std::string>{"R", "G", "B"}));
  EXPECT_EQ(s.facet_material(),
            (std::vector<std::string>{"white", "light", "white", "green", "white", "red"}));
  ASSERT_EQ(s.num_channels(), 3u);
  ASSERT_EQ(s.channels().size(), 3u);
  const double red[3] = {0.6, 0.05, 0.04};
  const double green[3] = {0.1, 0.45, 0.09};
  const double light_e[3] = {4, 3, 1.5};
  for (int c = 0; c < 3; ++c) {
    ASSERT_EQ(s.facet_reflectivity(c).size(), 6u);
    EXPECT_EQ(s.facet_reflectivity(c)[0], 0.7);
    EXPECT_EQ(s.facet_reflectivity(c)[1], 0.5);
    EXPECT_EQ(s.facet_reflectivity(c)[3], green[c]);
    EXPECT_EQ(s.facet_reflectivity(c)[5], red[c]);
    EXPECT_EQ(s.facet_emissivity(c)[1], light_e[c]);
    for (int f : {0, 2, 3, 4, 5}) EXPECT_EQ(s.facet_emissivity(c)[f], 0.0) << "facet " << f;
  }
  // Facet ids survive validation: the green facet is still the face x = 1, the red one x = 0.
  EXPECT_TRUE(facet_on_plane(s, 3, 0, 1.0));
  EXPECT_TRUE(facet_on_plane(s, 5, 0, 0.0));
  EXPECT_TRUE(facet_on_plane(s, 1, 2, 1.0));
  bool noted = false;
  for (const auto& n : s.notes()) noted = noted || n.find("materials: 5 from cube.mtl") != std::string::npos;
  EXPECT_TRUE(noted);
}

TEST_F(SceneFile, ObjSeveralMtlLibrariesAndUppercaseExtension) {
  write("a.mtl", "newmtl wall\nKd 0.25 0.5 0.75\n");
  write("b.mtl", "newmtl lamp\nKd 0.1 0.2 0.3\nKe 1 2 3\n");
  std::string text = "mtllib a.mtl b.mtl\n" + kCubeVertices;
  for (int f = 0; f < 6; ++f) text += std::string(f == 4 ? "usemtl lamp\n" : "usemtl wall\n") + kCubeFaces[f] + "\n";
  const Scene s = load_channel_scene(write("CUBE.OBJ", text));
  EXPECT_EQ(s.facet_material()[4], "lamp");
  EXPECT_EQ(s.facet_reflectivity(2)[0], 0.75);
  EXPECT_EQ(s.facet_reflectivity(1)[4], 0.2);
  EXPECT_EQ(s.facet_emissivity(2)[4], 3.0);
  EXPECT_EQ(s.facet_emissivity(2)[5], 0.0);
}

TEST_F(SceneFile, OffJsonDefaultsIdsAndChannelArrays) {
  const std::string off = cube_off(R"({
    "channels": ["R", "G", "B"],
    "default": { "rho": 0.5, "E": 0 },
    "facets": [ { "id": 1, "rho": 0.7, "E": [1, 0.9, 0.8] },
                { "ids": [2, 4], "rho": [0.2, 0.6, 0.1] },
                { "id": 5, "E": 2 } ] })");
  const Scene s = load_channel_scene(off);
  ASSERT_EQ(s.num_channels(), 3u);
  EXPECT_EQ(s.channels(), (std::vector<std::string>{"R", "G", "B"}));
  EXPECT_EQ(s.facet_material(), std::vector<std::string>(6, ""));
  const double e1[3] = {1, 0.9, 0.8};
  const double rho24[3] = {0.2, 0.6, 0.1};
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(s.facet_reflectivity(c)[0], 0.5);  // default
    EXPECT_EQ(s.facet_emissivity(c)[0], 0.0);
    EXPECT_EQ(s.facet_reflectivity(c)[1], 0.7);  // scalar for all channels
    EXPECT_EQ(s.facet_emissivity(c)[1], e1[c]);
    EXPECT_EQ(s.facet_reflectivity(c)[2], rho24[c]);
    EXPECT_EQ(s.facet_reflectivity(c)[4], rho24[c]);
    EXPECT_EQ(s.facet_emissivity(c)[4], 0.0);  // E from the default
    EXPECT_EQ(s.facet_reflectivity(c)[3], 0.5);
    EXPECT_EQ(s.facet_reflectivity(c)[5], 0.5);  // rho from the default, E given
    EXPECT_EQ(s.facet_emissivity(c)[5], 2.0);
  }
}

TEST_F(SceneFile, OffJsonEnvironmentPerChannelOrForAll) {
  const Scene all = load_channel_scene(cube_off(R"({"channels": ["R", "G"], "default": {"rho": 0.5, "E": 1},
    "environment": 0.25})"));
  EXPECT_EQ(all.environment(0), 0.25);
  EXPECT_EQ(all.environment(1), 0.25);
  const Scene each = load_channel_scene(cube_off(R"({"channels": ["R", "G"], "default": {"rho": 0.5, "E": 1},
    "environment": [0.5, 2]})"));
  EXPECT_EQ(each.environment(0), 0.5);
  EXPECT_EQ(each.environment(1), 2.0);
  const Scene none = load_channel_scene(cube_off(R"({"default": {"rho": 0.5, "E": 1}})"));
  EXPECT_EQ(none.environment(0), 0.0);
  // A negative value, or the wrong count, names the file, the line and the channel.
  const std::string negative = error_of(cube_off("{\"channels\": [\"R\", \"G\"],\n\"default\": {\"rho\": 0.5, \"E\": 1},\n"
                                                 "\"environment\": [1, -2]}"));
  EXPECT_NE(negative.find("cube.json:3:"), std::string::npos) << negative;
  EXPECT_NE(negative.find("channel G"), std::string::npos) << negative;
  const std::string count = error_of(cube_off(R"({"channels": ["R", "G"], "default": {"rho": 0.5, "E": 1},
    "environment": [1, 2, 3]})"));
  EXPECT_NE(count.find("environment has 3 values, expected 2"), std::string::npos) << count;
}

TEST_F(SceneFile, OffJsonOneChannelByDefaultAndExplicitSidecar) {
  write("cube.off", kCubeOff);
  std::string facets;
  for (int f = 0; f < 6; ++f)
    facets += std::string(f ? "," : "") + R"({"id": )" + std::to_string(f) + R"(, "rho": 0.)" +
              std::to_string(f + 1) + R"(, "E": )" + std::to_string(f) + "}";
  const std::string json = write("data.json", R"({"facets": [)" + facets + "]}");
  const Scene s = load_channel_scene((dir_ / "cube.off").string(), json);
  EXPECT_EQ(s.channels(), (std::vector<std::string>{"value"}));
  for (int f = 0; f < 6; ++f) {
    EXPECT_DOUBLE_EQ(s.facet_reflectivity(0)[f], 0.1 * (f + 1));
    EXPECT_EQ(s.facet_emissivity(0)[f], f);
  }
}

TEST_F(SceneFile, ShippedCornellBoxLoads) {
  const Scene s = load_channel_scene(kScenes + "convex_box.obj");
  ASSERT_EQ(s.num_channels(), 3u);
  ASSERT_EQ(s.mesh().num_facets, 14);
  int lights = 0;
  for (int f = 0; f < 14; ++f) {
    const bool light = s.facet_emissivity(0)[f] > 0;
    lights += light;
    if (light) {
      EXPECT_EQ(s.facet_material()[f], "light");
      EXPECT_EQ(s.facet_emissivity(0)[f], 17.0);
      EXPECT_EQ(s.facet_emissivity(1)[f], 12.0);
      EXPECT_EQ(s.facet_emissivity(2)[f], 4.0);
    }
  }
  EXPECT_EQ(lights, 1);
  // The red wall is x = 0, the green one x = 1.
  for (int f = 0; f < 14; ++f) {
    if (s.facet_material()[f] == "red") {
      EXPECT_TRUE(facet_on_plane(s, f, 0, 0.0)) << "facet " << f;
    } else if (s.facet_material()[f] == "green") {
      EXPECT_TRUE(facet_on_plane(s, f, 0, 1.0)) << "facet " << f;
    } else if (s.facet_material()[f] == "light") {
      EXPECT_TRUE(facet_on_plane(s, f, 2, 1.0)) << "facet " << f;
    }
  }
  EXPECT_EQ(s.facet_reflectivity(0)[13], 0.63);  // the last face is the red left wall
}

TEST_F(SceneFile, ShippedPrismLampLoads) {
  const Scene s = load_channel_scene(kScenes + "prism_lamp.off");
  ASSERT_EQ(s.num_channels(), 1u);
  ASSERT_EQ(s.mesh().num_facets, 8);
  for (int f = 0; f < 8; ++f) {
    EXPECT_EQ(s.facet_reflectivity(0)[f], f >= 6 ? 0.3 : 0.6) << "facet " << f;
    EXPECT_EQ(s.facet_emissivity(0)[f], f == 0 ? 1.0 : 0.0) << "facet " << f;
  }
}

// ---- mesh errors ------------------------------------------------------------------------------

// A non-convex closed body and an open surface load as general scenes; faces that cross are
// refused, naming the file, both faces and a point.
TEST_F(SceneFile, NonConvexAndOpenMeshesAreGeneralScenes) {
  std::ifstream in(kMeshes + "l_block.off");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  write("l_block.json", R"({"default": {"rho": 0.5, "E": 1}})");
  const Scene l = load_channel_scene(write("l_block.off", text));
  EXPECT_EQ(l.shape(), panelrad::geometry::SceneShape::general);
  EXPECT_TRUE(l.closed());
  // The cube without its top face.
  std::string open_text = "mtllib cube.mtl\nusemtl white\n" + kCubeVertices;
  for (int f = 0; f < 6; ++f)
    if (f != 1) open_text += std::string(kCubeFaces[f]) + "\n";
  write("cube.mtl", kGoodMtl);
  const Scene open = load_channel_scene(write("open.obj", open_text));
  EXPECT_EQ(open.shape(), panelrad::geometry::SceneShape::general);
  EXPECT_FALSE(open.closed());
}

TEST_F(SceneFile, CrossingFacesAreRejected) {
  std::ifstream in(std::string(PANELRAD_SOURCE_DIR) + "/tests/data/meshes/crossing_faces.off");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  write("crossing.json", R"({"default": {"rho": 0.5, "E": 1}})");
  const std::string msg = error_of(write("crossing.off", text));
  EXPECT_CONTAINS(msg, "crossing.off");
  EXPECT_CONTAINS(msg, "crossing: input faces 0 (line 14) and 1 (line 15) cross at");
}

TEST_F(SceneFile, MeshSyntaxErrorNamesFileAndLine) {
  write("cube.mtl", kGoodMtl);
  const std::string msg = error_of(write("bad.obj", "mtllib cube.mtl\nv 0 0 0\nv 1 x 0\n"));
  EXPECT_CONTAINS(msg, "bad.obj:3");
}

TEST_F(SceneFile, UnknownExtensionIsRejected) {
  const std::string msg = error_of(write("cube.stl", "solid"));
  EXPECT_CONTAINS(msg, "cube.stl");
  EXPECT_CONTAINS(msg, ".stl");
}

// ---- OBJ + MTL errors ------------------------------------------------------------------------

TEST_F(SceneFile, MtlRhoOneIsRejected) {
  write("cube.mtl", "newmtl white\nKd 0.7 0.7 0.7\n\nnewmtl bright\nKd 0.5 1.0 0.5\n");
  const std::string msg = error_of(cube_obj({"white", "white", "bright", "white", "white", "white"}));
  EXPECT_CONTAINS(msg, "cube.mtl:5");
  EXPECT_CONTAINS(msg, "'bright'");
  EXPECT_CONTAINS(msg, "facet 2");
  EXPECT_CONTAINS(msg, "cube.obj:15");  // the face line: mtllib, 8 v, 3 x (usemtl, f)
}

TEST_F(SceneFile, MtlNegativeRhoIsRejected) {
  write("cube.mtl", "newmtl white\nKd 0.7 -0.01 0.7\n");
  const std::string msg = error_of(cube_obj({"white", "", "", "", "", ""}));
  EXPECT_CONTAINS(msg, "cube.mtl:2");
  EXPECT_CONTAINS(msg, "facet 0");
  EXPECT_CONTAINS(msg, "[0, 1)");
}

TEST_F(SceneFile, MtlNanIsRejected) {
  write("cube.mtl", "newmtl white\nKd 0.7 0.7 0.7\nnewmtl light\nKd 0.5 0.5 0.5\nKe 1 nan 1\n");
  const std::string msg = error_of(cube_obj({"white", "light", "white", "", "", ""}));
  EXPECT_CONTAINS(msg, "cube.mtl:5");
  EXPECT_CONTAINS(msg, "'nan'");
  EXPECT_CONTAINS(msg, "finite");
}

TEST_F(SceneFile, MtlGarbageNumberAndGreyKdAreRejected) {
  write("cube.mtl", "newmtl white\nKd 0.7 abc 0.7\n");
  std::string msg = error_of(cube_obj({"white", "", "", "", "", ""}));
  EXPECT_CONTAINS(msg, "cube.mtl:2");
  EXPECT_CONTAINS(msg, "'abc'");
  write("cube.mtl", "# grey\nnewmtl white\nKd 0.7\n");
  msg = error_of(cube_obj({"white", "", "", "", "", ""}));
  EXPECT_CONTAINS(msg, "cube.mtl:3");
  EXPECT_CONTAINS(msg, "three numbers");
}

TEST_F(SceneFile, MtlNegativeEmissionIsRejected) {
  write("cube.mtl", "newmtl white\nKd 0.7 0.7 0.7\nnewmtl light\nKd 0.5 0.5 0.5\nKe 1 1 -2\n");
  const std::string msg = error_of(cube_obj({"white", "white", "white", "light", "white", "light"}));
  EXPECT_CONTAINS(msg, "cube.mtl:5");
  EXPECT_CONTAINS(msg, "'light'");
  EXPECT_CONTAINS(msg, "facet 3");
  EXPECT_CONTAINS(msg, "negative");
}

TEST_F(SceneFile, MaterialWithoutKdIsRejected) {
  write("cube.mtl", "newmtl white\nKd 0.7 0.7 0.7\nnewmtl dull\nKs 0.5 0.5 0.5\n");
  const std::string msg = error_of(cube_obj({"white", "", "", "", "dull", ""}));
  EXPECT_CONTAINS(msg, "cube.mtl:3");
  EXPECT_CONTAINS(msg, "'dull'");
  EXPECT_CONTAINS(msg, "no Kd");
  EXPECT_CONTAINS(msg, "facet 4");
}

TEST_F(SceneFile, UnusedBadMaterialIsFine) {
  write("cube.mtl", "newmtl white\nKd 0.7 0.7 0.7\nnewmtl mirror\nKd 1 1 1\nnewmtl nokd\nKs 1 1 1\n");
  const Scene s = load_channel_scene(cube_obj({"white", "", "", "", "", ""}));
  EXPECT_EQ(s.facet_reflectivity(1)[5], 0.7);
}

TEST_F(SceneFile, MissingMtlIsRejected) {
  const std::string msg = error_of(cube_obj({"white", "", "", "", "", ""}, "# cube\nmtllib nowhere.mtl\n"));
  EXPECT_CONTAINS(msg, "nowhere.mtl");
  EXPECT_CONTAINS(msg, "cube.obj:2");
}

TEST_F(SceneFile, NoMtllibIsRejected) {
  const std::string msg = error_of(cube_obj({"white", "", "", "", "", ""}, ""));
  EXPECT_CONTAINS(msg, "cube.obj");
  EXPECT_CONTAINS(msg, "mtllib");
}

TEST_F(SceneFile, UnknownMaterialIsRejected) {
  write("cube.mtl", kGoodMtl);
  const std::string msg = error_of(cube_obj({"white", "", "", "bogus", "", ""}));
  EXPECT_CONTAINS(msg, "cube.obj:14");  // the usemtl line: mtllib, 8 v, usemtl, 3 f
  EXPECT_CONTAINS(msg, "'bogus'");
  EXPECT_CONTAINS(msg, "facet 3");
}

TEST_F(SceneFile, FaceBeforeUsemtlIsRejected) {
  write("cube.mtl", kGoodMtl);
  const std::string msg = error_of(cube_obj({"", "white", "", "", "", ""}));
  EXPECT_CONTAINS(msg, "cube.obj:10");
  EXPECT_CONTAINS(msg, "facet 0");
  EXPECT_CONTAINS(msg, "usemtl");
}

TEST_F(SceneFile, MaterialsPathWithObjIsRejected) {
  write("cube.mtl", kGoodMtl);
  const std::string msg = error_of(cube_obj({"white", "", "", "", "", ""}), "x.json");
  EXPECT_CONTAINS(msg, "cube.obj");
  EXPECT_CONTAINS(msg, "x.json");
}

// ---- OFF + JSON errors -----------------------------------------------------------------------

TEST_F(SceneFile, JsonRhoOneIsRejected) {
  const std::string msg = error_of(cube_off(R"({"default": {"rho": 0.5, "E": 0},
      "facets": [{"id": 0, "rho": 0.2}, {"id": 3, "rho": 1}]})"));
  EXPECT_CONTAINS(msg, "cube.json");
  EXPECT_CONTAINS(msg, "facet 3");
  EXPECT_CONTAINS(msg, "[0, 1)");
}

TEST_F(SceneFile, JsonNegativeRhoIsRejected) {
  const std::string msg = error_of(cube_off(R"({"channels": ["R", "G", "B"], "default": {"E": 0},
      "facets": [{"ids": [0, 1, 2, 3, 4], "rho": 0.5}, {"id": 5, "rho": [0.5, -0.1, 0.5]}]})"));
  EXPECT_CONTAINS(msg, "cube.json");
  EXPECT_CONTAINS(msg, "facet 5");
  EXPECT_CONTAINS(msg, "channel G");
}

TEST_F(SceneFile, JsonDefaultOutOfRangeIsRejected) {
  const std::string msg = error_of(cube_off(R"({"default": {"rho": 0.5, "E": -1}})"));
  EXPECT_CONTAINS(msg, "cube.json");
  EXPECT_CONTAINS(msg, "default");
}

TEST_F(SceneFile, JsonNonNumberIsRejected) {
  std::string msg = error_of(cube_off(R"({"default": {"rho": 0.5, "E": 0}, "facets": [{"id": 2, "rho": "nan"}]})"));
  EXPECT_CONTAINS(msg, "cube.json");
  EXPECT_CONTAINS(msg, "facet 2");
  EXPECT_CONTAINS(msg, "\"nan\"");
  msg = error_of(cube_off(R"({"channels": ["a", "b"], "default": {"rho": 0.5, "E": 0},
      "facets": [{"id": 4, "E": [0, null]}]})"));
  EXPECT_CONTAINS(msg, "cube.json");
  EXPECT_CONTAINS(msg, "facet 4");
  EXPECT_CONTAINS(msg, "null");
}

TEST_F(SceneFile, JsonOverflowIsRejected) {
  // The parser refuses a number beyond the range of double (it never becomes inf).
  const std::string msg = error_of(cube_off(R"({"default": {"rho": 0.5, "E": 0}, "facets": [{"id": 1, "E": 1e999}]})"));
  EXPECT_CONTAINS(msg, "cube.json");
  EXPECT_CONTAINS(msg, "1e999");
}

TEST_F(SceneFile, MissingSidecarIsRejected) {
  const std::string off = write("cube.off", kCubeOff);
  std::string msg = error_of(off);
  EXPECT_CONTAINS(msg, "cube.json");
  EXPECT_CONTAINS(msg, "cube.off");
  msg = error_of(off, (dir_ / "other.json").string());
  EXPECT_CONTAINS(msg, "other.json");
}

TEST_F(SceneFile, BadJsonIsRejected) {
  const std::string msg = error_of(cube_off("{\n  \"default\": {\"rho\": 0.5,}\n}\n"));
  EXPECT_CONTAINS(msg, "cube.json");
  EXPECT_CONTAINS(msg, "byte ");
  EXPECT_CONTAINS(msg, "line 2");  // the '}' after the trailing comma
}

TEST_F(SceneFile, FacetWithoutValueIsRejected) {
  std::string msg = error_of(cube_off(R"({"facets": [{"ids": [0, 1, 2, 3, 5], "rho": 0.5, "E": 0}]})"));
  EXPECT_CONTAINS(msg, "cube.json");
  EXPECT_CONTAINS(msg, "facet 4");
  EXPECT_CONTAINS(msg, "not listed");
  // rho given, no E anywhere.
  msg = error_of(cube_off(R"({"default": {"rho": 0.5}, "facets": [{"id": 2, "rho": 0.1}]})"));
  EXPECT_CONTAINS(msg, "facet 0 has no E");
}

TEST_F(SceneFile, IdOutOfRangeIsRejected) {
  std::string msg = error_of(cube_off(R"({"default": {"rho": 0.5, "E": 0}, "facets": [{"ids": [1, 6], "E": 1}]})"));
  EXPECT_CONTAINS(msg, "cube.json");
  EXPECT_CONTAINS(msg, "facet 6");
  EXPECT_CONTAINS(msg, "out of range");
  msg = error_of(cube_off(R"({"default": {"rho": 0.5, "E": 0}, "facets": [{"id": -1, "E": 1}]})"));
  EXPECT_CONTAINS(msg, "facet -1");
  msg = error_of(cube_off(R"({"default": {"rho": 0.5, "E": 0}, "facets": [{"id": 1.5, "E": 1}]})"));
  EXPECT_CONTAINS(msg, "1.5");
}

TEST_F(SceneFile, DuplicateIdIsRejected) {
  const std::string msg = error_of(cube_off(R"({"default": {"rho": 0.5, "E": 0},
      "facets": [{"ids": [0, 2], "E": 1}, {"id": 1, "E": 1}, {"id": 2, "rho": 0.3}]})"));
  EXPECT_CONTAINS(msg, "cube.json");
  EXPECT_CONTAINS(msg, "facets[2]");
  EXPECT_CONTAINS(msg, "facet 2");
  EXPECT_CONTAINS(msg, "facets[0]");
}

TEST_F(SceneFile, WrongArrayLengthIsRejected) {
  const std::string msg = error_of(cube_off(R"({"channels": ["R", "G", "B"], "default": {"rho": 0.5, "E": 0},
      "facets": [{"id": 3, "rho": [0.1, 0.2]}]})"));
  EXPECT_CONTAINS(msg, "cube.json");
  EXPECT_CONTAINS(msg, "facet 3");
  EXPECT_CONTAINS(msg, "2 values, expected 3");
}

TEST_F(SceneFile, UnknownKeyIsRejected) {
  std::string msg = error_of(cube_off(R"({"default": {"rho": 0.5, "E": 0}, "facet": []})"));
  EXPECT_CONTAINS(msg, "cube.json");
  EXPECT_CONTAINS(msg, "'facet'");
  msg = error_of(cube_off(R"({"default": {"rho": 0.5, "E": 0}, "facets": [{"id": 1, "Rho": 0.3}]})"));
  EXPECT_CONTAINS(msg, "facets[0]");
  EXPECT_CONTAINS(msg, "'Rho'");
  msg = error_of(cube_off(R"({"default": {"rho": 0.5, "e": 0}})"));
  EXPECT_CONTAINS(msg, "'e'");
}

// ---- bounded reading and strict MTL / JSON -------------------------------------------------------

TEST_F(SceneFile, MtlAndJsonAreReadByTheBoundedReader) {
  // An MTL that is a FIFO (no writer: opening it for reading would block) and a JSON sidecar that
  // is /dev/zero (endless) are refused, naming the file and what it is for.
  const std::string fifo = (dir_ / "cube.mtl").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string msg = error_of(cube_obj({"white", "white", "white", "white", "white", "white"}));
  EXPECT_CONTAINS(msg, "cube.mtl: cannot read MTL file named by ");
  EXPECT_CONTAINS(msg, "cube.obj:1: is a FIFO (named pipe), not a regular file");
  fs::create_symlink("/dev/zero", dir_ / "zero.json");
  msg = error_of(write("cube.off", kCubeOff), (dir_ / "zero.json").string());
  EXPECT_CONTAINS(msg, "zero.json: cannot read JSON sidecar of ");
  EXPECT_CONTAINS(msg, "is a character device");
  // A NUL byte in an MTL file: its line and byte offset.
  fs::remove(fifo);
  write("cube.mtl", std::string("newmtl white\nKd 0.7 0.7 0.7\n\0", 29));
  EXPECT_CONTAINS(error_of(cube_obj({"white", "white", "white", "white", "white", "white"})),
                  "cube.mtl:3: NUL byte at byte offset 28 (column 1)");
}

TEST_F(SceneFile, SizeLimitAppliesToMeshMtlAndJson) {
  write("cube.mtl", kGoodMtl);
  const std::string obj = cube_obj({"white", "white", "white", "white", "white", "white"});
  const std::string off = cube_off(R"({"default": {"rho": 0.5, "E": 0}})");
  panelrad::TextReadOptions limit;
  // The OBJ (about 180 bytes) fits, the MTL (about 240 bytes) does not.
  limit.max_bytes = fs::file_size(obj);
  ASSERT_LT(limit.max_bytes, fs::file_size(dir_ / "cube.mtl"));
  try {
    load_channel_scene(obj, "", limit);
    ADD_FAILURE() << "the MTL file above the limit was read";
  } catch (const SceneFileError& e) {
    EXPECT_CONTAINS(e.what(), "cube.mtl: cannot read MTL file named by ");
    EXPECT_CONTAINS(e.what(), "above the limit of " + std::to_string(limit.max_bytes) + " bytes");
  }
  limit.max_bytes = 20;  // the OFF itself is above it
  try {
    load_channel_scene(off, "", limit);
    ADD_FAILURE() << "the OFF file above the limit was read";
  } catch (const SceneFileError& e) {
    EXPECT_CONTAINS(e.what(), "cube.off: cannot read: the file is ");
  }
  limit.max_bytes = fs::file_size(off);  // the OFF fits, the JSON is smaller: both read
  EXPECT_EQ(load_channel_scene(off, "", limit).mesh().num_facets, 6);
  write("cube.json", R"({"default": {"rho": 0.5, "E": 0}, "facets": [)" + std::string(300, ' ') + "]}");
  try {
    load_channel_scene(off, "", limit);
    ADD_FAILURE() << "the JSON file above the limit was read";
  } catch (const SceneFileError& e) {
    EXPECT_CONTAINS(e.what(), "cube.json: cannot read JSON sidecar of ");
  }
}

TEST_F(SceneFile, ByteOrderMarkIsAcceptedInObjMtlOffAndJson) {
  const std::string bom = "\xEF\xBB\xBF";
  write("cube.mtl", bom + "newmtl white\nKd 0.7 0.6 0.5\n");
  std::string text = bom + "mtllib cube.mtl\n" + kCubeVertices;
  for (int f = 0; f < 6; ++f) text += std::string("usemtl white\n") + kCubeFaces[f] + "\n";
  const Scene s = load_channel_scene(write("cube.obj", text));
  EXPECT_EQ(s.facet_reflectivity(1)[3], 0.6);
  write("cube.json", bom + R"({"default": {"rho": 0.25, "E": 1}})");
  const Scene t = load_channel_scene(write("cube.off", bom + kCubeOff));
  EXPECT_EQ(t.facet_reflectivity(0)[5], 0.25);
  EXPECT_EQ(t.facet_emissivity(0)[0], 1.0);
}

TEST_F(SceneFile, MtlStatementGivenTwiceInOneMaterialIsRejected) {
  write("cube.mtl", "newmtl white\nKd 0.7 0.7 0.7\nNs 10\nKd 0.2 0.2 0.2\n");
  std::string msg = error_of(cube_obj({"white", "white", "white", "white", "white", "white"}));
  EXPECT_CONTAINS(msg, "cube.mtl:4: Kd given twice in material 'white' (lines 2 and 4)");
  write("cube.mtl", "newmtl lamp\nKd 0.5 0.5 0.5\nKe 1 1 1\n\nKe 2 2 2\n");
  msg = error_of(cube_obj({"lamp", "lamp", "lamp", "lamp", "lamp", "lamp"}));
  EXPECT_CONTAINS(msg, "cube.mtl:5: Ke given twice in material 'lamp' (lines 3 and 5)");
  // The same statement in two materials is fine.
  write("cube.mtl", "newmtl a\nKd 0.1 0.1 0.1\nnewmtl b\nKd 0.2 0.2 0.2\n");
  EXPECT_EQ(load_channel_scene(cube_obj({"a", "b", "a", "b", "a", "b"})).facet_reflectivity(0)[1], 0.2);
}

// `ke 4 4 4` read as nothing would leave E = 0: a lamp silently dark. Miscased Kd/Ke/newmtl are
// errors naming the line and the statement meant.
TEST_F(SceneFile, MiscasedMtlStatementsAreRejected) {
  const std::vector<std::string> lamp(6, "lamp");
  write("cube.mtl", "newmtl lamp\nKd 0.5 0.5 0.5\nke 4 4 4\n");
  EXPECT_CONTAINS(error_of(cube_obj(lamp)),
                  "cube.mtl:3: unknown MTL statement 'ke': MTL statements are case-sensitive; write 'Ke' (the emission E)");
  write("cube.mtl", "newmtl lamp\nKD 0.5 0.5 0.5\n");
  EXPECT_CONTAINS(error_of(cube_obj(lamp)), "cube.mtl:2: unknown MTL statement 'KD'");
  EXPECT_CONTAINS(error_of(cube_obj(lamp)), "write 'Kd' (the reflectivity rho)");
  write("cube.mtl", "NewMtl lamp\nKd 0.5 0.5 0.5\n");
  EXPECT_CONTAINS(error_of(cube_obj(lamp)), "cube.mtl:1: unknown MTL statement 'NewMtl'");
  write("cube.mtl", "newmtl lamp\nKd 0.5 0.5 0.5\nglow 1\n");
  EXPECT_CONTAINS(error_of(cube_obj(lamp)), "cube.mtl:3: unknown MTL statement 'glow' (read: newmtl, Kd, Ke;");
}

// Statements that do not enter diffuse radiosity are read over; a note names the line where that
// changes what the file means.
TEST_F(SceneFile, IgnoredMtlStatementsAndTheirNotes) {
  write("cube.mtl",
        "newmtl white\nKa 0.1 0.1 0.1\nKd 0.7 0.7 0.7\nKs 0.5 0.5 0.5\nNs 96\nNi 1.45\nd 1\nTr 0\nillum 2\n"
        "Tf 1 1 1\nPr 0.5\nPm 0\nmap_Bump n.png\nbump n.png\nmap_Ks s.png\n"
        "newmtl glass\nKd 0.2 0.2 0.2\nd 0.5\nmap_Kd glass.png\nns 10\nmap_Ke glow.png\n");
  const Scene s = load_channel_scene(cube_obj({"white", "white", "glass", "white", "white", "white"}));
  EXPECT_EQ(s.facet_reflectivity(0)[2], 0.2);
  EXPECT_EQ(s.facet_reflectivity(0)[0], 0.7);
  std::vector<std::string> mtl_notes;
  for (const auto& n : s.notes())
    if (n.find("cube.mtl:") != std::string::npos) mtl_notes.push_back(n);
  ASSERT_EQ(mtl_notes.size(), 4u) << ::testing::PrintToString(s.notes());
  EXPECT_CONTAINS(mtl_notes[0], "cube.mtl:18: d 0.5 ignored: material 'glass' is read as opaque");
  EXPECT_CONTAINS(mtl_notes[1], "cube.mtl:19: map_Kd ignored: a texture is not applied; rho is the constant Kd");
  EXPECT_CONTAINS(mtl_notes[2], "cube.mtl:20: 'ns' read as 'Ns' and ignored");
  EXPECT_CONTAINS(mtl_notes[3], "cube.mtl:21: map_Ke ignored: a texture is not applied; E is the constant Ke");
}

TEST_F(SceneFile, DuplicateJsonKeysAreRejectedWithTheirLines) {
  std::string msg = error_of(cube_off("{\n  \"default\": {\"rho\": 0.5, \"E\": 0},\n  \"facets\": [\n"
                                      "    {\"id\": 1, \"E\": 2,\n     \"E\": 3}\n  ]\n}\n"));
  EXPECT_CONTAINS(msg, "cube.json:5: duplicate key 'E' in facets[0] (lines 4 and 5)");
  msg = error_of(cube_off("{\"default\": {\"rho\": 0.5, \"E\": 0},\n \"default\": {\"rho\": 0.2, \"E\": 0}}"));
  EXPECT_CONTAINS(msg, "cube.json:2: duplicate key 'default' at the top level (lines 1 and 2)");
  msg = error_of(cube_off("{\"default\": {\"rho\": 0.5,\n\n \"rho\": 0.4, \"E\": 0}}"));
  EXPECT_CONTAINS(msg, "cube.json:3: duplicate key 'rho' in default (lines 1 and 3)");
  // The same key in different objects is fine.
  EXPECT_EQ(load_channel_scene(cube_off(R"({"default": {"rho": 0.5, "E": 0},
      "facets": [{"id": 1, "E": 2}, {"id": 2, "E": 3}]})"))
                .facet_emissivity(0)[2],
            3.0);
}

TEST_F(SceneFile, JsonErrorsNameTheLine) {
  std::string msg = error_of(cube_off("{\n  \"default\": {\"rho\": 0.5, \"E\": 0},\n  \"facets\": [\n"
                                      "    {\"id\": 1, \"E\": 2},\n    {\"id\": 2,\n     \"rho\": 1.5}\n  ]\n}\n"));
  EXPECT_CONTAINS(msg, "cube.json:6: facets[1] (facet 2): rho (channel value) = 1.5 is outside [0, 1)");
  msg = error_of(cube_off("{\n  \"default\": {\"rho\": 0.5, \"E\": 0},\n  \"facets\": [\n    {\"id\": 9, \"E\": 2}\n  ]\n}\n"));
  EXPECT_CONTAINS(msg, "cube.json:4: facets[0]: facet 9 is out of range");
  msg = error_of(cube_off("{\"default\": {\"rho\": 0.5, \"E\": 0},\n\n \"extra\": 1}"));
  EXPECT_CONTAINS(msg, "cube.json:3: unknown key 'extra'");
  // A number ends where the next character starts: the line is the number's, not the next one's.
  msg = error_of(cube_off("{\"default\": {\"rho\": 0.5, \"E\": -1\n}}"));
  EXPECT_CONTAINS(msg, "cube.json:1: default: E (channel value) = -1 is negative");
  msg = error_of(cube_off("{\"facets\": [{\"id\": 1, \"rho\": 0.5, \"E\": 0}]}"));
  EXPECT_CONTAINS(msg, "cube.json: facet 0 has no rho (not listed)");
}

// E must be 0 or in [1e-100, 1e100] (scene_file.hpp: kMinPositiveEmission, kMaxEmission): a
// subnormal E has lost precision already; beyond the range the solve's squares and area
// products would underflow or overflow. rho may not be subnormal either.
TEST_F(SceneFile, SubnormalAndOverflowingEmissionIsRejected) {
  EXPECT_EQ(panelrad::kMaxEmission, 1e100);
  EXPECT_EQ(panelrad::kMinPositiveEmission, 1e-100);
  const auto json_e = [&](const std::string& e) {
    return error_of(cube_off(R"({"default": {"rho": 0.5, "E": 0}, "facets": [{"id": 3, "E": )" + e + "}]}"));
  };
  std::string msg = json_e("1e-310");
  EXPECT_CONTAINS(msg, "cube.json:1: facets[0] (facet 3): E (channel value) = 1e-310 is subnormal (below DBL_MIN");
  msg = json_e("1e-101");
  EXPECT_CONTAINS(msg, "= 1e-101 is below 1e-100, the smallest non-zero E accepted");
  msg = json_e("1.5e100");
  EXPECT_CONTAINS(msg, "= 1.5e+100 is above 1e+100, the largest E accepted");
  EXPECT_EQ(json_e("1e100"), "");
  EXPECT_EQ(json_e("1e-100"), "");
  EXPECT_EQ(json_e("-0.0"), "");
  // MTL: the material, its line and the facet.
  write("cube.mtl", "newmtl white\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0.5 0.5 0.5\nKe 1 4e-320 1\n");
  msg = error_of(cube_obj({"white", "lamp", "white", "white", "white", "white"}));
  EXPECT_CONTAINS(msg, "cube.mtl:5: material 'lamp': E = Ke G = 4e-320 is subnormal");
  EXPECT_CONTAINS(msg, "facet 1");
  write("cube.mtl", "newmtl white\nKd 0.5 0.5 0.5\nnewmtl lamp\nKd 0.5 0.5 0.5\nKe 1e200 1 1\n");
  EXPECT_CONTAINS(error_of(cube_obj({"white", "lamp", "white", "white", "white", "white"})),
                  "cube.mtl:5: material 'lamp': E = Ke R = 1e+200 is above 1e+100");
  write("cube.mtl", "newmtl white\nKd 0.5 1e-310 0.5\n");
  EXPECT_CONTAINS(error_of(cube_obj(std::vector<std::string>(6, "white"))),
                  "cube.mtl:2: material 'white': rho = Kd G = 1e-310 is subnormal");
  // The checks themselves, at the edges.
  EXPECT_EQ(panelrad::emission_problem(0.0), "");
  EXPECT_EQ(panelrad::emission_problem(1.0), "");
  EXPECT_NE(panelrad::emission_problem(std::nextafter(1e100, 2e100)), "");
  EXPECT_NE(panelrad::emission_problem(std::numeric_limits<double>::denorm_min()), "");
  EXPECT_NE(panelrad::emission_problem(std::numeric_limits<double>::infinity()), "");
  EXPECT_NE(panelrad::emission_problem(std::nan("")), "");
  EXPECT_EQ(panelrad::reflectivity_problem(std::numeric_limits<double>::min()), "");
  EXPECT_NE(panelrad::reflectivity_problem(std::numeric_limits<double>::min() / 2), "");
}

// write_outputs: a solved scene's files as one set, each byte for byte what the single-format
// writers give (scene_output.hpp), all or none; and load_scene's routes (builtin, geometry only,
// OBJ + MTL), each validated.
#include <panelrad/io/outputs.hpp>
#include <panelrad/io/scene_file.hpp>
#include <panelrad/io/scene_output.hpp>
#include <panelrad/scene/errors.hpp>
#include <panelrad/solve/scene_solver.hpp>

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace {

namespace fs = std::filesystem;
using namespace panelrad;

const std::string kSource = PANELRAD_SOURCE_DIR;

std::string contents(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class Outputs : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("panelrad_test_outputs_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  static SceneSolution solved_box() {
    const Scene scene = load_scene(kSource + "/examples/scenes/convex_box.obj");
    SolveOptions o;
    o.level = 1;
    return solve_scene(scene, o);
  }
  fs::path dir_;
};

TEST_F(Outputs, EachFileIsWhatItsWriterGives) {
  const SceneSolution s = solved_box();
  s.require_converged();
  OutputOptions view;
  view.view_direction = geometry::Vec3(-1, -1.7, 1.2);
  view.up = geometry::Vec3::UnitZ();
  const std::string prefix = (dir_ / "box").string();
  const std::vector<std::string> written = write_outputs(s, prefix, {"png", "csv", "vtk", "ply"}, view);
  ASSERT_EQ(written, (std::vector<std::string>{prefix + ".csv", prefix + ".ply", prefix + ".vtk", prefix + ".png"}));
  EXPECT_EQ(contents(prefix + ".csv"), radiosity_csv(s.field));
  EXPECT_EQ(contents(prefix + ".ply"), radiosity_ply(s.field));
  EXPECT_EQ(contents(prefix + ".vtk"), radiosity_vtk(s.field));
  RenderOptions render;
  render.view_direction = *view.view_direction;
  render.up = *view.up;
  EXPECT_EQ(contents(prefix + ".png"), radiosity_png(s.field, render));
}

TEST_F(Outputs, BadFormatListsAreRefusedBeforeAnyFile) {
  const SceneSolution s = solved_box();
  const std::string prefix = (dir_ / "box").string();
  EXPECT_THROW(write_outputs(s, prefix, {}), std::invalid_argument);
  EXPECT_THROW(write_outputs(s, prefix, {"csv", "obj"}), std::invalid_argument);
  EXPECT_THROW(write_outputs(s, prefix, {"csv", "csv"}), std::invalid_argument);
  EXPECT_TRUE(fs::is_empty(dir_));
}

TEST_F(Outputs, AllOrNone) {
  const SceneSolution s = solved_box();
  // The PNG's path is a directory: nothing is written, and the CSV's previous file stays.
  const std::string prefix = (dir_ / "box").string();
  { std::ofstream(prefix + ".csv") << "previous"; }
  fs::create_directories(prefix + ".png");
  EXPECT_THROW(write_outputs(s, prefix, {"csv", "png"}), std::runtime_error);
  EXPECT_EQ(contents(prefix + ".csv"), "previous");
}

TEST(LoadScene, EveryRouteIsValidated) {
  const Scene cube = load_scene("builtin:cube");
  EXPECT_EQ(cube.shape(), geometry::SceneShape::convex);
  EXPECT_EQ(cube.channels(), std::vector<std::string>{"value"});
  LoadOptions geometry_only;
  geometry_only.geometry_only = true;
  const Scene l = load_scene(kSource + "/examples/meshes/l_block.off", geometry_only);
  EXPECT_EQ(l.shape(), geometry::SceneShape::general);  // not convex: V is computed
  EXPECT_EQ(l.facet_reflectivity(0), std::vector<double>(static_cast<std::size_t>(l.num_facets()), 0.0));
  const Scene cornell = load_scene(kSource + "/examples/scenes/cornell_box.obj");
  EXPECT_EQ(cornell.shape(), geometry::SceneShape::general);
  EXPECT_EQ(cornell.num_channels(), 3u);
  // An OFF without its sidecar is refused unless read as geometry only; a sidecar with geometry
  // only is a contradiction, refused by name.
  EXPECT_THROW(load_scene(kSource + "/examples/meshes/l_block.off"), SceneFileError);
  geometry_only.materials_path = "x.json";
  EXPECT_THROW(load_scene(kSource + "/examples/meshes/l_block.off", geometry_only), SceneFileError);
  EXPECT_THROW(load_scene("builtin:nothing"), MeshError);
}

}  // namespace

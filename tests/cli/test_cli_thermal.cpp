// `panelrad thermal`: the shipped example end to end (a heated floor, a cool ceiling, adiabatic
// walls and box: the two rates cancel and every adiabatic group's rate is 0), a plate under the
// sky against q = eps sigma (T^4 - T_env^4), the files' layout, and refusals that name the file,
// the line and the group (exit 1, nothing written; usage errors exit 2).
#include "cli_run.hpp"

#include <panelrad/thermal/blackbody.hpp>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
using panelrad::testing::CliRun;
using panelrad::testing::read_csv;

const std::string kSource = PANELRAD_SOURCE_DIR;

CliRun run(const std::string& args, const std::string& redirect = "2>&1") {
  return panelrad::testing::run_cli(args, redirect);
}

class CliThermal : public panelrad::testing::CliDirectoryTest {
 protected:
  CliThermal() : CliDirectoryTest("cli_thermal") {}
};

TEST_F(CliThermal, ShippedRoomBalancesAndAdiabaticWallsCarryNoHeat) {
  const CliRun r = run("thermal " + kSource + "/examples/meshes/room_with_box.obj --bc " + kSource +
                           "/examples/thermal/room_with_box.json --levels 3 --out " + path("room") + " --quiet",
                       "2>/dev/null");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_CONTAINS(r.output, "energy balance: the scene is enclosed, so the net rates sum to 0");
  const auto groups = read_csv(path("room_groups.csv"));
  ASSERT_EQ(groups.size(), 14u);  // header, 12 groups, environment
  EXPECT_EQ(groups[0], (std::vector<std::string>{"group", "area_m2", "T_K", "q_W_m2", "Q_W"}));
  double floor = 0, ceiling = 0;
  for (std::size_t k = 1; k < 13; ++k) {
    const std::string& name = groups[k][0];
    const double T = std::stod(groups[k][2]), Q = std::stod(groups[k][4]);
    if (name == "room_z0") {
      floor = Q;
      EXPECT_DOUBLE_EQ(T, 308.15);
    } else if (name == "room_z1") {
      ceiling = Q;
      EXPECT_DOUBLE_EQ(T, 291.15);
    } else {
      EXPECT_LT(std::abs(Q), 1e-9) << name;  // adiabatic
      EXPECT_GT(T, 291.15) << name;          // between the two given temperatures
      EXPECT_LT(T, 308.15) << name;
    }
  }
  EXPECT_GT(floor, 10);
  EXPECT_LT(std::abs(floor + ceiling), 2e-2 * floor);  // the discretization's defect (level 3)
  EXPECT_EQ(groups[13][0], "environment");  // enclosed: no rate (the empty fields end the row)
  EXPECT_TRUE(groups[13].size() < 5 || groups[13][4].empty());
  const auto elements = read_csv(path("room.csv"));
  ASSERT_EQ(elements.size(), 1u + 24 * 64);
  EXPECT_EQ(elements[0], (std::vector<std::string>{"element", "facet", "group", "x", "y", "z", "area_m2", "J_W_m2",
                                                   "H_W_m2", "q_W_m2", "T_K"}));
  EXPECT_TRUE(fs::exists(path("room.vtk")));
  std::ifstream png(path("room.png"), std::ios::binary);
  char magic[8] = {};
  png.read(magic, 8);
  EXPECT_EQ(std::string(magic, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // The PLY carries the same temperatures, face by face, bit for bit.
  std::ifstream ply(path("room.ply"));
  std::string line;
  std::size_t faces = 0, vertices = 0;
  bool has_T = false;
  while (std::getline(ply, line) && line != "end_header") {
    if (line.rfind("element vertex ", 0) == 0) vertices = std::stoul(line.substr(15));
    if (line.rfind("element face ", 0) == 0) faces = std::stoul(line.substr(13));
    if (line == "property double T_K") has_T = true;
  }
  ASSERT_EQ(faces, 24u * 64);
  EXPECT_TRUE(has_T);
  for (std::size_t k = 0; k < vertices; ++k) std::getline(ply, line);
  for (std::size_t i = 0; i < faces; ++i) {
    ASSERT_TRUE(std::getline(ply, line));
    std::istringstream fields(line);
    std::vector<std::string> f;
    for (std::string x; fields >> x;) f.push_back(x);
    ASSERT_EQ(f.size(), 4u + 1 + 6) << line;  // corners, facet, group, area, J, H, q, T
    EXPECT_EQ(f.back(), elements[i + 1].back()) << "element " << i;
  }
}

// A 2 m x 1 m plate facing a sky at 250 K: q = eps sigma (T^4 - T_env^4) on every element.
TEST_F(CliThermal, PlateUnderTheSky) {
  write("plate.obj", "o plate\nv 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nf 1 2 3 4\n");
  write("sky.json", R"({"groups": {"plate": {"T": 320, "emissivity": 0.7}}, "environment": {"T": 250}})");
  const CliRun r = run("thermal " + path("plate.obj") + " --bc " + path("sky.json") + " --levels 1 --out " +
                       path("p") + " --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  const double sigma = 5.670374419e-8, q = 0.7 * sigma * (std::pow(320.0, 4) - std::pow(250.0, 4));
  const auto groups = read_csv(path("p_groups.csv"));
  ASSERT_EQ(groups.size(), 3u);
  EXPECT_NEAR(std::stod(groups[1][3]), q, 1e-12 * q);
  EXPECT_NEAR(std::stod(groups[1][4]), 2 * q, 1e-12 * q);
  EXPECT_NEAR(std::stod(groups[2][4]), -2 * q, 1e-12 * q);  // the environment receives it
}

// The same plate with an emissivity per band under a sky at 250 K: q = sum_k eps_k sigma (F_k(T)
// T^4 - F_k(T_env) T_env^4), the blackbody's band fractions F_k, on every element.
TEST_F(CliThermal, PlateUnderTheSkyWithBands) {
  write("plate.obj", "o plate\nv 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nf 1 2 3 4\n");
  write("sky.json", R"({"band_edges_um": [3, 8], "groups": {"plate": {"T": 900, "emissivity": [0.9, 0.2, 0.6]}},
                        "environment": {"T": 250}})");
  const CliRun r = run("thermal " + path("plate.obj") + " --bc " + path("sky.json") + " --levels 1 --out " +
                       path("p") + " --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_CONTAINS(r.output, "bands: 3 (edges 3 8 um)");
  const std::vector<double> eps = {0.9, 0.2, 0.6};
  const double q = panelrad::band_emission({3, 8}, eps, 900) - panelrad::band_emission({3, 8}, eps, 250);
  const auto groups = read_csv(path("p_groups.csv"));
  ASSERT_EQ(groups.size(), 3u);
  EXPECT_NEAR(std::stod(groups[1][3]), q, 1e-12 * q);
  EXPECT_NEAR(std::stod(groups[2][4]), -2 * q, 1e-12 * q);
}

TEST_F(CliThermal, RefusalsNameTheFileTheLineAndTheGroup) {
  write("plate.obj", "o plate\nv 0 0 0\nv 2 0 0\nv 2 1 0\nv 0 1 0\nf 1 2 3 4\n");
  const auto refused = [&](const std::string& json, const std::string& message) {
    write("bc.json", json);
    const CliRun r = run("thermal " + path("plate.obj") + " --bc " + path("bc.json") + " --levels 0 --out " +
                         path("x") + " --quiet");
    EXPECT_EQ(r.status, 1) << json << "\n" << r.output;
    EXPECT_CONTAINS(r.output, message);
    EXPECT_FALSE(fs::exists(path("x_groups.csv")));
  };
  refused(R"({"groups": {}})", "group 'plate' has no condition");
  refused("{\"groups\": {\"plate\": {\"T\": 300, \"emissivity\": 1},\n \"roof\": {\"q\": 0}}}",
          "bc.json:2: group 'roof' is not a group of the scene ('plate')");
  refused(R"({"groups": {"plate": {"T": 300}}, "environment": {"T": 280}})", "a temperature needs an \"emissivity\"");
  refused(R"({"groups": {"plate": {"T": 300, "q": 1, "emissivity": 1}}})", "exactly one of \"T\"");
  refused(R"({"groups": {"plate": {"T": -3, "emissivity": 1}}, "environment": {"T": 280}})", "finite and > 0");
  refused(R"({"groups": {"plate": {"T": 300, "emissivity": [0.5, 0.6]}}, "environment": {"T": 280}})",
          "\"emissivity\" is an array (one per wavelength band), but the file gives no \"band_edges_um\"");
  refused(R"({"band_edges_um": [3, 8], "groups": {"plate": {"T": 300, "emissivity": [0.5, 0.6]}}, "environment": {"T": 280}})",
          "\"emissivity\" has 2 values for 3 bands");
  refused(R"({"band_edges_um": [8, 3], "groups": {"plate": {"T": 300, "emissivity": 1}}, "environment": {"T": 280}})",
          "edge 2 is 3: the edges must be finite, > 0 and increasing");
  refused(R"({"band_edges_um": [3], "groups": {"plate": {"T": 300, "emissivity": [0, 0]}}, "environment": {"T": 280}})",
          "every band emissivity is 0");
  refused(R"({"groups": {"plate": {"T": 300, "emissivity": 1.5}}, "environment": {"T": 280}})", "in (0, 1]");
  refused(R"({"groups": {"plate": {"T": 300, "emissivity": 1}}})", "the scene is open");
  refused(R"({"groups": {"plate": {"T": 300, "emissivity": 1}}, "sky": 3})", "unknown key 'sky'");
  EXPECT_EQ(run("thermal " + path("plate.obj")).status, 2);  // no --bc
  EXPECT_EQ(run("thermal --bc " + path("bc.json")).status, 2);  // no scene
}

}  // namespace

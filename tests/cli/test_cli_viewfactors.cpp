// `panelrad viewfactors`: the view factors of a scene's groups end to end: the unit cube's faces
// against their closed forms (Howell C-11, C-14), groups by material from an OBJ's usemtl, the
// CSV's layout (names as header, area, closure column), the .npy read back bit for bit, exit
// statuses (1 invalid input, nothing written; 2 usage error).
#include "cli_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

using panelrad::testing::CliRun;
CliRun run(const std::string& args, const std::string& redirect = "2>&1") {
  return panelrad::testing::run_cli(args, redirect);
}

using panelrad::testing::read_csv;

class CliViewFactors : public panelrad::testing::CliDirectoryTest {
 protected:
  CliViewFactors() : CliDirectoryTest("cli_viewfactors") {}
  // The unit cube seen from inside as an OBJ, faces x=0, x=1, y=0, y=1, z=0, z=1 with the given
  // materials (and an MTL giving each a Kd).
  void write_cube(const std::vector<std::string>& materials) const {
    std::ostringstream os, mtl;
    os << "mtllib cube.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";
    const char* faces[6] = {"1 4 8 5", "2 6 7 3", "1 5 6 2", "4 3 7 8", "1 2 3 4", "5 8 7 6"};  // inner normals
    for (int f = 0; f < 6; ++f) os << "usemtl " << materials[static_cast<std::size_t>(f)] << "\nf " << faces[f] << "\n";
    std::set<std::string> defined;
    for (const std::string& m : materials)
      if (defined.insert(m).second) mtl << "newmtl " << m << "\nKd 0.5 0.5 0.5\n";
    write("cube.obj", os.str());
    write("cube.mtl", mtl.str());
  }
};

// Each face of the unit cube a group: the opposite face 0.199825, each adjacent one 0.200044
// (closed forms), within the written error estimate; the closure column, the header, the .npy.
TEST_F(CliViewFactors, CubeFacesMatchTheClosedForms) {
  write_cube({"a", "b", "c", "d", "e", "f"});
  const CliRun r = run("viewfactors " + path("cube.obj") + " --levels 3 --out " + path("cube") + " --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("groups: 6 (facet)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("closure: the scene is enclosed"), std::string::npos) << r.output;
  const auto F = read_csv(path("cube.csv")), E = read_csv(path("cube_error.csv"));
  ASSERT_EQ(F.size(), 7u);
  ASSERT_EQ(F[0].size(), 9u);
  EXPECT_EQ(F[0][0], "group");
  EXPECT_EQ(F[0][2], "facet 0");
  EXPECT_EQ(F[0][8], "closure_defect");
  const double opposite = 0.19982489569838732, adjacent = 0.20004377607540316;
  for (int I = 0; I < 6; ++I) {
    EXPECT_EQ(F[static_cast<std::size_t>(I) + 1][0], "facet " + std::to_string(I));
    EXPECT_NEAR(std::stod(F[static_cast<std::size_t>(I) + 1][1]), 1.0, 1e-15);
    for (int J = 0; J < 6; ++J) {
      const double f = std::stod(F[static_cast<std::size_t>(I) + 1][static_cast<std::size_t>(J) + 2]);
      const double e = std::stod(E[static_cast<std::size_t>(I) + 1][static_cast<std::size_t>(J) + 2]);
      const double exact = I == J ? 0 : I / 2 == J / 2 ? opposite : adjacent;
      EXPECT_LE(std::abs(f - exact), e + 1e-12) << I << " " << J;
    }
  }
  // The .npy: the header, then the 36 doubles of the CSV's matrix, bit for bit.
  std::ifstream npy(path("cube.npy"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(npy)), std::istreambuf_iterator<char>());
  ASSERT_GE(bytes.size(), 10u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x93NUMPY\x01\x00", 8));
  const std::size_t header = static_cast<unsigned char>(bytes[8]) | static_cast<std::size_t>(static_cast<unsigned char>(bytes[9])) << 8;
  EXPECT_EQ((10 + header) % 64, 0u);
  EXPECT_NE(bytes.find("'shape': (6, 6)"), std::string::npos);
  ASSERT_EQ(bytes.size(), 10 + header + 36 * sizeof(double));
  for (int k = 0; k < 36; ++k) {
    double x;
    std::memcpy(&x, bytes.data() + 10 + header + static_cast<std::size_t>(k) * sizeof(double), sizeof x);
    EXPECT_EQ(x, std::stod(F[static_cast<std::size_t>(k / 6) + 1][static_cast<std::size_t>(k % 6) + 2])) << k;
  }
}

// Groups by material: the floor and the ceiling one group each, the four walls one; names from
// usemtl in the order of first use. Rows of a closed scene sum to 1 up to the closure column.
TEST_F(CliViewFactors, GroupsByMaterial) {
  write_cube({"wall", "wall", "wall", "wall", "floor", "ceiling"});
  const CliRun r = run("viewfactors " + path("cube.obj") + " --groups material --levels 2 --no-estimate --out " +
                       path("m") + " --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_FALSE(fs::exists(path("m_error.csv")));
  const auto F = read_csv(path("m.csv"));
  ASSERT_EQ(F.size(), 4u);
  EXPECT_EQ(F[0], (std::vector<std::string>{"group", "area", "wall", "floor", "ceiling", "closure_defect"}));
  EXPECT_NEAR(std::stod(F[2][1]), 1.0, 1e-15);   // the floor's area
  EXPECT_NEAR(std::stod(F[1][1]), 4.0, 1e-15);   // the walls'
  EXPECT_NEAR(std::stod(F[2][4]), 0.19982489569838732, 5e-3);  // floor -> ceiling
  for (std::size_t I = 1; I <= 3; ++I) {
    double sum = 0;
    for (std::size_t J = 2; J <= 5; ++J) sum += std::stod(F[I][J]);
    EXPECT_NEAR(sum, 1.0, 1e-12) << I;  // the closure column completes each row exactly
  }
}

// An ASCII STL grouped by its solids: the floor one group, the other five faces another.
TEST_F(CliViewFactors, StlGroupedBySolid) {
  const char* corners[6][4] = {{"0 0 0", "0 1 0", "0 1 1", "0 0 1"}, {"1 0 0", "1 0 1", "1 1 1", "1 1 0"},
                               {"0 0 0", "0 0 1", "1 0 1", "1 0 0"}, {"0 1 0", "1 1 0", "1 1 1", "0 1 1"},
                               {"0 0 0", "1 0 0", "1 1 0", "0 1 0"}, {"0 0 1", "0 1 1", "1 1 1", "1 0 1"}};
  std::ostringstream stl;
  for (int f = 0; f < 6; ++f) {
    if (f == 0 || f == 4) stl << (f ? "endsolid walls\n" : "") << "solid " << (f == 4 ? "floor" : "walls") << "\n";
    const char* const* c = corners[f];
    for (const auto& t : {std::array<int, 3>{0, 1, 2}, std::array<int, 3>{0, 2, 3}})
      stl << "facet normal 0 0 0\nouter loop\nvertex " << c[t[0]] << "\nvertex " << c[t[1]] << "\nvertex " << c[t[2]]
          << "\nendloop\nendfacet\n";
    if (f == 4) stl << "endsolid floor\nsolid walls\n";
  }
  stl << "endsolid walls\n";
  write("cube.stl", stl.str());
  const CliRun r = run("viewfactors " + path("cube.stl") + " --groups object --levels 2 --no-estimate --elements-to floor "
                       "--out " + path("s") + " --quiet");
  ASSERT_EQ(r.status, 0) << r.output;
  // Every element's sky view factor: 12 triangles x 16 elements, 0 up to the far field in this
  // closed cube; and its factor to the floor: 0 on the floor, the rest of the hemisphere's share
  // elsewhere.
  const auto elements = read_csv(path("s_elements.csv"));
  ASSERT_EQ(elements.size(), 1u + 12 * 16);
  EXPECT_EQ(elements[0],
            (std::vector<std::string>{"element", "facet", "group", "x", "y", "z", "area", "sky", "F_floor"}));
  for (std::size_t i = 1; i < elements.size(); ++i) {
    EXPECT_LT(std::abs(std::stod(elements[i][7])), 1e-6) << i;
    const double to_floor = std::stod(elements[i][8]);
    if (elements[i][2] == "floor") EXPECT_EQ(to_floor, 0.0) << i;
    else EXPECT_GT(to_floor, 0.0) << i;
  }
  EXPECT_TRUE(fs::exists(path("s_elements.vtk")));
  EXPECT_NE(r.output.find("wrote " + path("s_elements.vtk")), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("wrote " + path("s_elements.ply")), std::string::npos) << r.output;
  std::ifstream ply(path("s_elements.ply"));
  std::vector<std::string> header;
  for (std::string line; std::getline(ply, line) && line != "end_header";) header.push_back(line);
  EXPECT_NE(std::find(header.begin(), header.end(), "element face " + std::to_string(elements.size() - 1)),
            header.end());
  EXPECT_NE(std::find(header.begin(), header.end(), "property double sky"), header.end());
  EXPECT_NE(std::find(header.begin(), header.end(), "property double F_floor"), header.end());
  const CliRun bad = run("viewfactors " + path("cube.stl") + " --groups object --levels 1 --elements-to roof --out " +
                         path("b") + " --quiet");
  EXPECT_EQ(bad.status, 1) << bad.output;
  EXPECT_NE(bad.output.find("element target 'roof' is not a group"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(path("b.csv")));
  const auto F = read_csv(path("s.csv"));
  ASSERT_EQ(F.size(), 3u);
  EXPECT_EQ(F[0], (std::vector<std::string>{"group", "area", "walls", "floor", "closure_defect"}));
  EXPECT_NEAR(std::stod(F[2][1]), 1.0, 1e-15);  // the floor's area
  EXPECT_NEAR(std::stod(F[2][2]), 1.0, 1e-12);  // the floor sees only the other faces
  EXPECT_EQ(std::stod(F[2][3]), 0.0);           // and not itself
}

// A fin across the middle of a floor, given as one sheet: --two-sided adds its back as the group
// 'fin (back)', seen from the floor's other half as the front is from its own.
TEST_F(CliViewFactors, TwoSidedSheetRadiatesFromBothSides) {
  write("fin.obj",
        "o floor\nv -1 0 0\nv 0 0 0\nv 0 1 0\nv -1 1 0\nv 1 0 0\nv 1 1 0\nf 1 2 3 4\nf 2 5 6 3\n"
        "o fin\nv 0 0 1\nv 0 1 1\nf 2 3 8 7\n");
  const CliRun one = run("viewfactors " + path("fin.obj") + " --groups object --levels 3 --no-estimate --out " +
                         path("one") + " --quiet");
  ASSERT_EQ(one.status, 0) << one.output;
  const CliRun two = run("viewfactors " + path("fin.obj") + " --groups object --levels 3 --no-estimate --two-sided fin "
                         "--out " + path("two") + " --quiet");
  ASSERT_EQ(two.status, 0) << two.output;
  const auto F1 = read_csv(path("one.csv")), F2 = read_csv(path("two.csv"));
  ASSERT_EQ(F2[0], (std::vector<std::string>{"group", "area", "floor", "fin", "fin (back)", "sky"}));
  ASSERT_EQ(F2.size(), 4u);
  // The floor sees both sides alike (the fin stands in its middle), each as the one-sided fin.
  EXPECT_NEAR(std::stod(F2[1][3]), std::stod(F1[1][3]), 1e-12);
  EXPECT_NEAR(std::stod(F2[1][4]), std::stod(F2[1][3]), 1e-12);
  EXPECT_GT(std::stod(F2[1][3]), 0.09);
  const CliRun bad = run("viewfactors " + path("fin.obj") + " --groups object --two-sided roof --out " + path("b"));
  EXPECT_EQ(bad.status, 1) << bad.output;
  EXPECT_NE(bad.output.find("'roof' is not a group"), std::string::npos) << bad.output;
}

// Bad input: nothing written, exit 1 with the reason; usage errors exit 2.
TEST_F(CliViewFactors, RefusalsWriteNothing) {
  write("broken.obj", "v 0 0 0\nv 1 0 0\nf 1 2 3\n");
  CliRun r = run("viewfactors " + path("broken.obj") + " --out " + path("x") + " --quiet");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_EQ(files(), 1u);  // the input alone
  write_cube({"a", "b", "c", "d", "e", "f"});
  fs::remove(path("cube.mtl"));
  r = run("viewfactors " + path("cube.obj") + " --groups material --out " + path("y") + " --quiet");
  EXPECT_EQ(r.status, 1) << r.output;  // the materials cannot be read
  EXPECT_FALSE(fs::exists(path("y.csv")));
  r = run("viewfactors " + path("cube.obj") + " --groups object --out " + path("z") + " --quiet");
  EXPECT_EQ(r.status, 1) << r.output;  // the OBJ names no object (o, g)
  EXPECT_NE(r.output.find("names no object"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("z.csv")));
  r = run("viewfactors " + path("cube.obj") + " --groups solid");
  EXPECT_EQ(r.status, 2) << r.output;
  r = run("viewfactors");
  EXPECT_EQ(r.status, 2) << r.output;
  r = run("viewfactors " + path("cube.obj") + " --levels 1 --max-elements 10");
  EXPECT_EQ(r.status, 2) << r.output;
  r = run("viewfactors " + path("cube.obj") + " --eta 0.3");  // manual parameters need a method
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("need --method dense or fast"), std::string::npos) << r.output;
  r = run("viewfactors " + path("cube.obj") + " --out " + path(".hidden"));
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_FALSE(fs::exists(path(".hidden.csv")));
}

}  // namespace

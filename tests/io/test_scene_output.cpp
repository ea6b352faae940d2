// Outputs of a solved scene: CSV round trip, PLY and VTK structure, the PNG picture (decoded with
// libpng), colour rules, and refusal of invalid fields without leaving files behind.
#include <panelrad/io/scene_output.hpp>
#include <panelrad/io/text_output.hpp>

#include "unit_cube_elements.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <png.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <csignal>
#include <map>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using panelrad::ElementField;
using panelrad::geometry::Vec3;
using Rgb = std::array<unsigned char, 3>;

namespace {

/// The `count` vertex lines of an ASCII PLY's body, from lines[first].
std::vector<Vec3> ply_vertices(const std::vector<std::string>& lines, std::size_t first, std::size_t count) {
  std::vector<Vec3> vertices;
  for (std::size_t k = 0; k < count; ++k) {
    std::istringstream in(lines[first + k]);
    Vec3 p;
    in >> p.x() >> p.y() >> p.z();
    vertices.push_back(p);
  }
  return vertices;
}

/// The unit cube, each face split into m x m squares of two triangles, counter-clockwise seen
/// from outside. Facets: 0 x=0, 1 x=1, 2 y=0, 3 y=1, 4 z=0, 5 z=1. Channel values are given per
/// facet: value(facet, channel) for radiosity, emit(facet, channel) for emission.
template <class U, class E>
ElementField cube(int m, std::vector<std::string> channels, U value, E emit) {
  ElementField f;
  f.channels = channels;
  std::vector<std::vector<double>> u(channels.size()), e(channels.size()), rho(channels.size());
  panelrad::testing::for_each_unit_cube_triangle(m, [&](int facet, const Vec3& outward, const std::array<Vec3, 3>& tri) {
    f.triangle.push_back(tri);
    f.inner_normal.push_back(-outward);
    f.centroid.push_back((tri[0] + tri[1] + tri[2]) / 3.0);
    f.area.push_back(0.5 / (m * m));
    f.facet.push_back(facet);
    for (std::size_t c = 0; c < channels.size(); ++c) {
      u[c].push_back(value(facet, c));
      e[c].push_back(emit(facet, c));
      rho[c].push_back(0.1 * (facet + 1) + 0.01 * static_cast<double>(c));
    }
  });
  for (std::size_t c = 0; c < channels.size(); ++c) {
    f.radiosity.push_back(Eigen::Map<Eigen::VectorXd>(u[c].data(), static_cast<Eigen::Index>(u[c].size())));
    f.emission.push_back(Eigen::Map<Eigen::VectorXd>(e[c].data(), static_cast<Eigen::Index>(e[c].size())));
    f.rho.push_back(Eigen::Map<Eigen::VectorXd>(rho[c].data(), static_cast<Eigen::Index>(rho[c].size())));
  }
  return f;
}

/// RGB cube for the default view (-1, -1.7, 1.2): the far walls x=1 (red), y=1 (grey) and the
/// floor z=0 (beige) are drawn; the near walls x=0 and y=0 are pure blue and the ceiling z=1 is an
/// emitting white light, colours that must not show up in the picture.
ElementField rgb_cube(int m = 1) {
  const double colours[6][3] = {{0.0, 0.0, 0.6}, {0.8, 0.1, 0.1}, {0.0, 0.0, 0.6},
                                {0.5, 0.5, 0.5}, {0.4, 0.4, 0.3}, {2.0, 2.0, 2.0}};
  return cube(
      m, {"R", "G", "B"}, [&](int f, std::size_t c) { return colours[f][c] + 1e-3 * f; },
      [](int f, std::size_t) { return f == 5 ? 1.0 : 0.0; });
}

/// Single-channel cube, the radiosity being the facet number plus a little.
ElementField scalar_cube(int m = 1) {
  return cube(
      m, {"u"}, [](int f, std::size_t) { return f + 0.25; },
      [](int f, std::size_t) { return f == 5 ? 1.0 : 0.0; });
}

struct Image {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
  Rgb at(int x, int y) const {
    const std::size_t k = 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                               static_cast<std::size_t>(x));
    return {rgb[k], rgb[k + 1], rgb[k + 2]};
  }
  std::size_t count(const Rgb& c) const {
    std::size_t n = 0;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) n += at(x, y) == c;
    return n;
  }
};

Image read_png(const std::string& path) {
  png_image img;
  std::memset(&img, 0, sizeof img);
  img.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&img, path.c_str())) throw std::runtime_error(img.message);
  img.format = PNG_FORMAT_RGB;
  Image out;
  out.width = static_cast<int>(img.width);
  out.height = static_cast<int>(img.height);
  out.rgb.resize(PNG_IMAGE_SIZE(img));
  if (!png_image_finish_read(&img, nullptr, out.rgb.data(), 0, nullptr))
    throw std::runtime_error(img.message);
  return out;
}

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> parts;
  std::stringstream ss(s);
  for (std::string p; std::getline(ss, p, sep);) parts.push_back(p);
  return parts;
}

std::string str(const Rgb& c) {
  return "(" + std::to_string(c[0]) + "," + std::to_string(c[1]) + "," + std::to_string(c[2]) + ")";
}

const Rgb kBackground = {32, 32, 32};

class SceneOutput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("panelrad_test_scene_output_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  bool dir_is_empty() const { return fs::is_empty(dir_); }
  fs::path dir_;
};

TEST_F(SceneOutput, CsvRoundTripsExactly) {
  ElementField f = rgb_cube(2);
  f.radiosity[1][3] = 0.1 + 0.2;  // a value that needs 17 digits
  f.centroid[5].x() = 1.0 / 3.0;
  panelrad::write_radiosity_csv(path("r.csv"), f);
  const auto lines = lines_of(path("r.csv"));
  ASSERT_EQ(lines.size(), f.size() + 1);
  EXPECT_EQ(lines[0], "element,facet,x,y,z,area,rho_R,E_R,u_R,rho_G,E_G,u_G,rho_B,E_B,u_B");
  for (std::size_t i = 0; i < f.size(); ++i) {
    const auto v = split(lines[i + 1], ',');
    ASSERT_EQ(v.size(), 15u) << lines[i + 1];
    EXPECT_EQ(std::stoul(v[0]), i);
    EXPECT_EQ(std::stoi(v[1]), f.facet[i]);
    for (int k = 0; k < 3; ++k) EXPECT_EQ(std::strtod(v[2 + k].c_str(), nullptr), f.centroid[i][k]);
    EXPECT_EQ(std::strtod(v[5].c_str(), nullptr), f.area[i]);
    for (std::size_t c = 0; c < 3; ++c) {
      const auto j = static_cast<Eigen::Index>(i);
      EXPECT_EQ(std::strtod(v[6 + 3 * c].c_str(), nullptr), f.rho[c][j]);
      EXPECT_EQ(std::strtod(v[7 + 3 * c].c_str(), nullptr), f.emission[c][j]);
      EXPECT_EQ(std::strtod(v[8 + 3 * c].c_str(), nullptr), f.radiosity[c][j]);
    }
  }
}

TEST_F(SceneOutput, CsvSingleChannelHeader) {
  panelrad::write_radiosity_csv(path("s.csv"), scalar_cube());
  const auto lines = lines_of(path("s.csv"));
  ASSERT_EQ(lines.size(), 13u);
  EXPECT_EQ(lines[0], "element,facet,x,y,z,area,rho,E,u");
}

TEST_F(SceneOutput, PlyDeduplicatesVerticesAndCarriesColours) {
  const ElementField f = rgb_cube();
  panelrad::write_radiosity_ply(path("r.ply"), f);
  const auto lines = lines_of(path("r.ply"));
  const auto end = std::find(lines.begin(), lines.end(), "end_header");
  ASSERT_NE(end, lines.end());
  const std::vector<std::string> header(lines.begin(), end);
  EXPECT_EQ(header[0], "ply");
  EXPECT_EQ(header[1], "format ascii 1.0");
  const auto has = [&](const std::string& l) {
    return std::find(header.begin(), header.end(), l) != header.end();
  };
  EXPECT_TRUE(has("element vertex 8"));
  EXPECT_TRUE(has("element face 12"));
  EXPECT_TRUE(has("property list uchar int vertex_indices"));
  EXPECT_TRUE(has("property uchar red"));
  EXPECT_TRUE(has("property uchar green"));
  EXPECT_TRUE(has("property uchar blue"));
  EXPECT_TRUE(has("property float u_R"));
  EXPECT_TRUE(has("property float u_B"));
  const std::size_t body = static_cast<std::size_t>(end - lines.begin()) + 1;
  ASSERT_EQ(lines.size(), body + 8 + 12);
  const std::vector<Vec3> vertices = ply_vertices(lines, body, 8);
  const auto colours = panelrad::element_colours(f);
  for (std::size_t i = 0; i < 12; ++i) {
    std::istringstream in(lines[body + 8 + i]);
    int count, a[3], rgb[3];
    float u[3];
    in >> count >> a[0] >> a[1] >> a[2] >> rgb[0] >> rgb[1] >> rgb[2] >> u[0] >> u[1] >> u[2];
    ASSERT_FALSE(in.fail()) << lines[body + 8 + i];
    EXPECT_EQ(count, 3);
    for (int k = 0; k < 3; ++k) {
      ASSERT_GE(a[k], 0);
      ASSERT_LT(a[k], 8);
      EXPECT_EQ(vertices[static_cast<std::size_t>(a[k])], f.triangle[i][static_cast<std::size_t>(k)]);
      EXPECT_EQ(rgb[k], colours[i][static_cast<std::size_t>(k)]);
      EXPECT_FLOAT_EQ(u[k], static_cast<float>(f.radiosity[static_cast<std::size_t>(k)][static_cast<Eigen::Index>(i)]));
    }
  }
}

TEST_F(SceneOutput, CellsPlyCarriesEveryValueExactly) {
  // Any per-element values (a thermal solve's, view factors'): one face per triangle with its
  // facet and each value, read back bit for bit; a name that is not one token is made one.
  const ElementField f = rgb_cube();
  std::vector<panelrad::CellValues> cells{
      {"T_K", [](std::size_t i) { return 300.0 + 1.0 / (3.0 + static_cast<double>(i)); }},
      {"F to floor", [](std::size_t i) { return std::ldexp(1.0, -static_cast<int>(i)) / 7; }}};
  const std::string text = panelrad::cells_ply("panelrad test", f.triangle, f.facet, cells);
  std::istringstream in(text);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  const auto end = std::find(lines.begin(), lines.end(), "end_header");
  ASSERT_NE(end, lines.end());
  const std::vector<std::string> header(lines.begin(), end);
  const std::vector<std::string> expected{"ply",
                                          "format ascii 1.0",
                                          "comment panelrad test",
                                          "element vertex 8",
                                          "property double x",
                                          "property double y",
                                          "property double z",
                                          "element face 12",
                                          "property list uchar int vertex_indices",
                                          "property int facet",
                                          "property double T_K",
                                          "property double F_to_floor"};
  EXPECT_EQ(header, expected);
  const std::size_t body = static_cast<std::size_t>(end - lines.begin()) + 1;
  ASSERT_EQ(lines.size(), body + 8 + 12);
  const std::vector<Vec3> vertices = ply_vertices(lines, body, 8);
  for (std::size_t i = 0; i < 12; ++i) {
    std::istringstream face(lines[body + 8 + i]);
    int count, a[3], facet;
    std::string t, F;
    face >> count >> a[0] >> a[1] >> a[2] >> facet >> t >> F;
    ASSERT_FALSE(face.fail()) << lines[body + 8 + i];
    EXPECT_EQ(count, 3);
    for (int k = 0; k < 3; ++k) {
      ASSERT_GE(a[k], 0);
      ASSERT_LT(a[k], 8);
      EXPECT_EQ(vertices[static_cast<std::size_t>(a[k])], f.triangle[i][static_cast<std::size_t>(k)]);
    }
    EXPECT_EQ(facet, f.facet[i]);
    EXPECT_EQ(std::strtod(t.c_str(), nullptr), cells[0].value(i));
    EXPECT_EQ(std::strtod(F.c_str(), nullptr), cells[1].value(i));
  }
}

TEST_F(SceneOutput, VtkCounts) {
  const ElementField f = rgb_cube(2);  // 48 elements; 3^3 - 1 = 26 surface vertices
  panelrad::write_radiosity_vtk(path("r.vtk"), f);
  const auto lines = lines_of(path("r.vtk"));
  ASSERT_GE(lines.size(), 4u);
  EXPECT_EQ(lines[0], "# vtk DataFile Version 3.0");
  EXPECT_EQ(lines[2], "ASCII");
  EXPECT_EQ(lines[3], "DATASET POLYDATA");
  const auto index = [&](const std::string& l) {
    return std::find(lines.begin(), lines.end(), l) - lines.begin();
  };
  const auto points = index("POINTS 26 double"), polys = index("POLYGONS 48 192"),
             cells = index("CELL_DATA 48");
  ASSERT_LT(static_cast<std::size_t>(cells), lines.size());
  EXPECT_EQ(polys, points + 27);
  EXPECT_EQ(cells, polys + 49);
  const std::size_t scalars = static_cast<std::size_t>(
      std::count_if(lines.begin(), lines.end(), [](const std::string& l) { return l.rfind("SCALARS ", 0) == 0; }));
  EXPECT_EQ(scalars, 2u + 3u * 3u);  // facet, area, rho/E/u per channel
  EXPECT_NE(index("SCALARS u_G double 1"), static_cast<std::ptrdiff_t>(lines.size()));
  const auto colour = index("COLOR_SCALARS colour 3");
  ASSERT_LT(static_cast<std::size_t>(colour), lines.size());
  EXPECT_EQ(lines.size(), static_cast<std::size_t>(colour) + 1 + 48);
  const auto colours = panelrad::element_colours(f);
  std::istringstream in(lines[static_cast<std::size_t>(colour) + 1]);
  double r, g, b;
  in >> r >> g >> b;
  EXPECT_NEAR(r * 255.0, colours[0][0], 1e-3);
  EXPECT_NEAR(b * 255.0, colours[0][2], 1e-3);

  panelrad::write_radiosity_vtk(path("s.vtk"), scalar_cube());
  const auto s = lines_of(path("s.vtk"));
  EXPECT_NE(std::find(s.begin(), s.end(), "SCALARS u double 1"), s.end());
  EXPECT_EQ(std::find(s.begin(), s.end(), "COLOR_SCALARS colour 3"), s.end());
}

TEST_F(SceneOutput, ColourRules) {
  const auto c = panelrad::element_colours(rgb_cube());
  // The light saturates, the brightest wall channel (red, the 95th percentile) reaches 255.
  EXPECT_EQ(c[10], (Rgb{255, 255, 255})) << str(c[10]);
  EXPECT_EQ(c[2][0], 255) << str(c[2]);
  EXPECT_LT(c[2][1], 128) << str(c[2]);
  EXPECT_EQ(c[0][0], 0);
  EXPECT_GT(c[0][2], 200);  // near walls: blue

  // Scalar: the colour map runs from dark violet (minimum) to yellow (maximum).
  const auto s = panelrad::element_colours(scalar_cube());
  EXPECT_LT(s[0][0] + s[0][1] + s[0][2], 200) << str(s[0]);
  EXPECT_GT(s[10][0], 200) << str(s[10]);
  EXPECT_GT(s[10][1], 200) << str(s[10]);
  ElementField flat = scalar_cube();
  flat.radiosity[0].setConstant(3.0);
  const auto m = panelrad::element_colours(flat);
  for (const Rgb& x : m) EXPECT_EQ(x, m[0]);
  EXPECT_NE(m[0], s[0]);
  EXPECT_NE(m[0], s[10]);
}

TEST_F(SceneOutput, PngShowsFarWallsOnly) {
  const ElementField f = rgb_cube(2);
  panelrad::RenderOptions o;
  o.width = 320;
  o.height = 240;
  panelrad::write_radiosity_png(path("r.png"), f, o);
  const Image img = read_png(path("r.png"));
  ASSERT_EQ(img.width, 320);
  ASSERT_EQ(img.height, 240);
  EXPECT_EQ(img.at(0, 0), kBackground);
  EXPECT_EQ(img.at(319, 239), kBackground);
  const auto colours = panelrad::element_colours(f);
  const Rgb red = colours[8], grey = colours[24], floor = colours[32], blue = colours[0],
            light = colours[40];
  ASSERT_EQ(f.facet[8], 1);
  ASSERT_EQ(f.facet[24], 3);
  ASSERT_EQ(f.facet[32], 4);
  ASSERT_EQ(f.facet[40], 5);
  EXPECT_GT(img.count(red), 1000u);
  EXPECT_GT(img.count(grey), 1000u);
  EXPECT_GT(img.count(floor), 1000u);
  EXPECT_EQ(img.count(blue), 0u);
  EXPECT_EQ(img.count(light), 0u);
  // Nothing bluish at all: blends of the far walls with the background are never blue.
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const Rgb p = img.at(x, y);
      ASSERT_LE(p[2], std::max(p[0], p[1])) << x << "," << y << " " << str(p);
    }
  if (const char* keep = std::getenv("PANELRAD_KEEP_PNG")) fs::copy_file(path("r.png"), keep, fs::copy_options::overwrite_existing);
}

TEST_F(SceneOutput, PngTopViewHasNoCracks) {
  // Looking down z (the screen basis falls back to +y as up): only the floor is drawn, filling a
  // square; its 32 triangles must cover it without cracks.
  ElementField f = scalar_cube(4);
  panelrad::RenderOptions o;
  o.width = 101;
  o.height = 101;
  o.view_direction = Vec3(0.0, 0.0, 2.0);
  panelrad::write_radiosity_png(path("top.png"), f, o);
  const Image img = read_png(path("top.png"));
  const Rgb floor = panelrad::element_colours(f)[4 * 32];
  ASSERT_EQ(f.facet[4 * 32], 4);
  // The square fills 90% of the plot area's smaller side, centred on it.
  const int plot_w = 101 - std::max(12, 101 / 8);
  const int side = static_cast<int>(0.9 * plot_w);
  const int x0 = (plot_w - side) / 2 + 1, y0 = (101 - side) / 2 + 1;
  for (int y = y0; y < y0 + side - 2; ++y)
    for (int x = x0; x < x0 + side - 2; ++x) ASSERT_EQ(img.at(x, y), floor) << x << "," << y;
  EXPECT_EQ(img.at(x0 - 3, 50), kBackground);
  EXPECT_EQ(img.at(50, y0 - 3), kBackground);
}

TEST_F(SceneOutput, PngScalarSceneHasColourBar) {
  panelrad::RenderOptions o;
  o.width = 200;
  o.height = 150;
  panelrad::write_radiosity_png(path("s.png"), scalar_cube(), o);
  const Image img = read_png(path("s.png"));
  ASSERT_EQ(img.width, 200);
  EXPECT_EQ(img.at(0, 0), kBackground);
  // The right margin (x > 180) has a bar: non-background in the middle, bright (yellow) at the top
  // and dark at the bottom.
  int bar = 0;
  for (int x = 180; x < 200; ++x) bar += img.at(x, 75) != kBackground;
  EXPECT_GE(bar, 5);
  int bx = 180;
  while (bx < 200 && img.at(bx, 75) == kBackground) ++bx;
  const Rgb top = img.at(bx + 2, 20), bottom = img.at(bx + 2, 130);
  EXPECT_GT(top[0] + top[1], bottom[0] + bottom[1]) << str(top) << " " << str(bottom);

  // RGB scenes have no bar.
  panelrad::write_radiosity_png(path("r.png"), rgb_cube(), o);
  const Image r = read_png(path("r.png"));
  for (int x = 192; x < 200; ++x) EXPECT_EQ(r.at(x, 75), kBackground);  // inside the 5% margin
}

// The viewpoint that shows the light: a lit facet (inner normal n) is visible when n . d > 0, so
// the chosen direction must look at it; each of the six facets lit in turn.
TEST_F(SceneOutput, BrightestViewLooksAtTheLight) {
  for (int lit = 0; lit < 6; ++lit) {
    const ElementField f = cube(
        2, {"u"}, [lit](int facet, std::size_t) { return facet == lit ? 10.0 : 1.0; },
        [lit](int facet, std::size_t) { return facet == lit ? 9.0 : 0.0; });
    const Vec3 d = brightest_view_direction(f);
    Vec3 inner = Vec3::Zero();
    inner[lit / 2] = lit % 2 == 0 ? 1.0 : -1.0;  // facet x=0 has inner normal +x, and so on
    EXPECT_GT(inner.dot(d), 0) << "lit facet " << lit << ", view " << d.transpose();
  }
}

TEST_F(SceneOutput, InvalidFieldsThrowAndLeaveNoFile) {
  std::vector<ElementField> bad;
  ElementField f = rgb_cube();
  f.area.pop_back();
  bad.push_back(f);
  f = rgb_cube();
  f.radiosity[1][4] = std::numeric_limits<double>::quiet_NaN();
  bad.push_back(f);
  f = rgb_cube();
  f.triangle[3][1].y() = std::numeric_limits<double>::infinity();
  bad.push_back(f);
  f = rgb_cube();
  f.emission.pop_back();
  bad.push_back(f);
  f = rgb_cube();
  f.rho[2].resize(5);
  bad.push_back(f);
  f = rgb_cube();
  f.channels[1] = "G B";
  bad.push_back(f);
  bad.push_back(ElementField{});
  for (std::size_t k = 0; k < bad.size(); ++k) {
    EXPECT_THROW(panelrad::write_radiosity_csv(path("x.csv"), bad[k]), std::invalid_argument) << k;
    EXPECT_THROW(panelrad::write_radiosity_ply(path("x.ply"), bad[k]), std::invalid_argument) << k;
    EXPECT_THROW(panelrad::write_radiosity_vtk(path("x.vtk"), bad[k]), std::invalid_argument) << k;
    EXPECT_THROW(panelrad::write_radiosity_png(path("x.png"), bad[k]), std::invalid_argument) << k;
    EXPECT_THROW(panelrad::element_colours(bad[k]), std::invalid_argument) << k;
    EXPECT_TRUE(dir_is_empty()) << k;
  }
  try {
    panelrad::write_radiosity_csv(path("x.csv"), bad[1]);
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("not finite"), std::string::npos) << e.what();
  }
  panelrad::RenderOptions o;
  o.width = 0;
  EXPECT_THROW(panelrad::write_radiosity_png(path("x.png"), rgb_cube(), o), std::invalid_argument);
  o = {};
  o.view_direction = Vec3::Zero();
  EXPECT_THROW(panelrad::write_radiosity_png(path("x.png"), rgb_cube(), o), std::invalid_argument);
  EXPECT_TRUE(dir_is_empty());
}

TEST_F(SceneOutput, MissingDirectoryThrowsAndLeavesNothing) {
  const std::string missing = path("missing");
  const ElementField f = rgb_cube();
  EXPECT_THROW(panelrad::write_radiosity_csv(missing + "/x.csv", f), std::runtime_error);
  EXPECT_THROW(panelrad::write_radiosity_ply(missing + "/x.ply", f), std::runtime_error);
  EXPECT_THROW(panelrad::write_radiosity_vtk(missing + "/x.vtk", f), std::runtime_error);
  try {
    panelrad::write_radiosity_png(missing + "/x.png", f);
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing + "/x.png"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(missing));
  EXPECT_TRUE(dir_is_empty());
}

TEST_F(SceneOutput, RewritingReplacesTheFile) {
  panelrad::write_radiosity_csv(path("r.csv"), rgb_cube(2));
  panelrad::write_radiosity_csv(path("r.csv"), rgb_cube(1));
  EXPECT_EQ(lines_of(path("r.csv")).size(), 13u);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir_), fs::directory_iterator{}), 1);
}

// ---------------------------------------------------------------------------------------------
// Outputs as a set: all written, or the previous ones untouched.

std::string contents_of(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

/// Every entry of the directory: name -> contents ("<dir>" for a directory).
std::map<std::string, std::string> listing(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::directory_iterator(dir))
    out[e.path().filename().string()] = e.is_directory() ? "<dir>" : contents_of(e.path());
  return out;
}

void put(const fs::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

TEST_F(SceneOutput, OutputSetReplacesAllFilesAndLeavesNothingElse) {
  put(path("a.csv"), "old csv");
  put(path("a.ply"), "old ply");
  {
    panelrad::OutputSet set;
    set.add(path("a.csv"), "new csv");
    set.add(path("a.ply"), "new ply");
    set.add(path("a.vtk"), "new vtk");
    EXPECT_THROW(set.add(path("a.ply"), "twice"), std::invalid_argument);
    set.commit();
  }
  EXPECT_EQ(listing(dir_), (std::map<std::string, std::string>{
                               {"a.csv", "new csv"}, {"a.ply", "new ply"}, {"a.vtk", "new vtk"}}));
  {  // a set that is not committed leaves no temporary and changes nothing
    panelrad::OutputSet set;
    set.add(path("a.csv"), "newer csv");
    EXPECT_EQ(listing(dir_).size(), 4u);  // the temporary exists while the set is open
  }
  EXPECT_EQ(listing(dir_), (std::map<std::string, std::string>{
                               {"a.csv", "new csv"}, {"a.ply", "new ply"}, {"a.vtk", "new vtk"}}));
}

// A write that fails on the third file (the file size limit makes write() fail with EFBIG, as a
// full disk fails it with ENOSPC, also for root): the first two temporaries are removed and the
// previous files are unchanged. In a child process, so the limit does not reach the test runner.
TEST_F(SceneOutput, OutputSetWriteFailureKeepsThePreviousSet) {
  const std::map<std::string, std::string> before = {
      {"a.csv", "old csv"}, {"a.ply", "old ply"}, {"a.vtk", "old vtk"}};
  for (const auto& [name, text] : before) put(path(name), text);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const rlimit limit{4096, 4096};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    std::signal(SIGXFSZ, SIG_IGN);
    int code = 4;  // no exception
    try {
      panelrad::OutputSet set;
      set.add(path("a.csv"), std::string(1000, 'c'));
      set.add(path("a.ply"), std::string(1000, 'p'));
      set.add(path("a.vtk"), std::string(10000, 'v'));  // beyond the limit
      set.commit();
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      code = what.find(path("a.vtk")) != std::string::npos &&
                     what.find(std::strerror(EFBIG)) != std::string::npos
                 ? 0
                 : 3;
    }
    ::_exit(code);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status)) << status;
  EXPECT_EQ(WEXITSTATUS(status), 0) << "3: the message does not name a.vtk and EFBIG; 4: no error";
  EXPECT_EQ(listing(dir_), before);
}

// A rename that fails part-way (the third target is a directory): the file already replaced gets
// its previous contents back, a new one is removed again, the rest is untouched.
TEST_F(SceneOutput, OutputSetFailedRenameRestoresThePreviousFiles) {
  put(path("a.csv"), "old csv");
  put(path("a.ply"), "old ply");
  fs::create_directory(path("a.vtk"));
  put(path("a.vtk") + "/inside", "x");
  const auto before = listing(dir_);
  panelrad::OutputSet set;
  set.add(path("a.csv"), "new csv");
  set.add(path("a.png"), "new png");  // no previous file
  set.add(path("a.vtk"), "new vtk");
  set.add(path("a.ply"), "new ply");
  try {
    set.commit();
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path("a.vtk")), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("previous files are unchanged"), std::string::npos) << e.what();
  }
  EXPECT_EQ(listing(dir_), before);
  EXPECT_EQ(contents_of(path("a.vtk") + "/inside"), "x");
}

// SIGTERM or SIGINT while the temporaries exist: the handler removes them, the previous files
// stay, and the process ends by that signal (a shell shows 128 + signal).
TEST_F(SceneOutput, SignalWhileWritingRemovesTheTemporaries) {
  for (const int sig : {SIGTERM, SIGINT}) {
    const std::map<std::string, std::string> before = {{"a.csv", "old csv"}, {"a.ply", "old ply"}};
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    for (const auto& [name, text] : before) put(path(name), text);
    int ready[2];
    ASSERT_EQ(::pipe(ready), 0);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      ::close(ready[0]);
      // As in a foreground program: the signal neither ignored nor blocked (a test runner started
      // in the background of a script inherits SIGINT ignored).
      std::signal(sig, SIG_DFL);
      sigset_t unblock;
      sigemptyset(&unblock);
      sigaddset(&unblock, sig);
      ::sigprocmask(SIG_UNBLOCK, &unblock, nullptr);
      panelrad::install_output_signal_handlers();
      panelrad::OutputSet set;
      set.add(path("a.csv"), "new csv");
      set.add(path("a.ply"), "new ply");
      set.add(path("a.vtk"), "new vtk");
      const char byte = 'r';
      if (::write(ready[1], &byte, 1) != 1) ::_exit(5);
      for (;;) ::pause();
    }
    ::close(ready[1]);
    char byte = 0;
    const bool got = ::read(ready[0], &byte, 1) == 1;
    ::close(ready[0]);
    const std::size_t entries_while_writing = listing(dir_).size();
    ::kill(child, sig);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    ASSERT_TRUE(got) << "the child did not reach its pause, status " << status;
    EXPECT_EQ(entries_while_writing, 5u) << "2 previous files + 3 temporaries";
    ASSERT_TRUE(WIFSIGNALED(status)) << "signal " << sig << ", status " << status;
    EXPECT_EQ(WTERMSIG(status), sig);
    EXPECT_EQ(listing(dir_), before) << "signal " << sig;
  }
}

// The write check uses a uniquely named temporary: a user's PREFIX.probe (and a file with the
// temporary naming of older versions, PATH.tmp.PID) are not touched.
TEST_F(SceneOutput, CheckOutputPathTouchesNoExistingFile) {
  put(path("p.csv.probe"), "user's probe");
  put(path("p.csv.tmp." + std::to_string(::getpid())), "user's file");
  const auto before = listing(dir_);
  EXPECT_NO_THROW(panelrad::check_output_path(path("p.csv")));
  EXPECT_EQ(listing(dir_), before);
  panelrad::write_file_atomically(path("p.csv"), "written");
  auto after = before;
  after["p.csv"] = "written";
  EXPECT_EQ(listing(dir_), after);

  fs::create_directory(path("d.csv"));
  try {
    panelrad::check_output_path(path("d.csv"));
    ADD_FAILURE() << "a directory accepted as an output";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path("d.csv")), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("directory"), std::string::npos) << e.what();
  }
  try {
    panelrad::check_output_path(path("missing/x.csv"));
    ADD_FAILURE() << "a missing directory accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path("missing/x.csv")), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(path("missing")));
  after["d.csv"] = "<dir>";
  EXPECT_EQ(listing(dir_), after);
}

TEST_F(SceneOutput, ChannelNamesAreCheckedOnTheirOwn) {
  EXPECT_NO_THROW(panelrad::check_channel_names({"R", "G", "B"}));
  EXPECT_NO_THROW(panelrad::check_channel_names({"value"}));
  EXPECT_THROW(panelrad::check_channel_names({}), std::invalid_argument);
  EXPECT_THROW(panelrad::check_channel_names({"R", "G B"}), std::invalid_argument);
  EXPECT_THROW(panelrad::check_channel_names({"R", ""}), std::invalid_argument);
  EXPECT_THROW(panelrad::check_channel_names({"a", "a"}), std::invalid_argument);
  EXPECT_THROW(panelrad::check_channel_names({"u,v"}), std::invalid_argument);  // a CSV separator
}

// PLY: a channel with a value float32 cannot hold (above FLT_MAX it would be inf, below FLT_MIN
// subnormal or 0) is written as double with 17 digits (round trip, compared exactly); the other
// channels stay float.
TEST_F(SceneOutput, PlyValuesBeyondFloatAreWrittenAsDouble) {
  ElementField f = rgb_cube();
  f.radiosity[0][2] = 1e300;   // > FLT_MAX = 3.4e38
  f.radiosity[1][5] = 1e-40;   // < FLT_MIN = 1.2e-38: subnormal as a float
  panelrad::write_radiosity_ply(path("r.ply"), f);
  const auto lines = lines_of(path("r.ply"));
  const auto end = std::find(lines.begin(), lines.end(), "end_header");
  ASSERT_NE(end, lines.end());
  const std::vector<std::string> header(lines.begin(), end);
  const auto has = [&](const std::string& l) {
    return std::find(header.begin(), header.end(), l) != header.end();
  };
  EXPECT_TRUE(has("property double u_R"));
  EXPECT_TRUE(has("property double u_G"));
  EXPECT_TRUE(has("property float u_B"));
  const std::size_t body = static_cast<std::size_t>(end - lines.begin()) + 1 + 8;
  ASSERT_EQ(lines.size(), body + 12);
  for (std::size_t i = 0; i < 12; ++i) {
    EXPECT_EQ(lines[body + i].find("inf"), std::string::npos) << lines[body + i];
    const auto v = split(lines[body + i], ' ');
    ASSERT_EQ(v.size(), 10u) << lines[body + i];
    const auto j = static_cast<Eigen::Index>(i);
    EXPECT_EQ(std::strtod(v[7].c_str(), nullptr), f.radiosity[0][j]) << i;
    EXPECT_EQ(std::strtod(v[8].c_str(), nullptr), f.radiosity[1][j]) << i;
    EXPECT_EQ(std::strtof(v[9].c_str(), nullptr), static_cast<float>(f.radiosity[2][j])) << i;
  }
  // A field whose values all fit keeps float (0 fits: it is exact in float).
  f = scalar_cube();
  f.radiosity[0][0] = 0.0;
  panelrad::write_radiosity_ply(path("s.ply"), f);
  const auto s = lines_of(path("s.ply"));
  EXPECT_NE(std::find(s.begin(), s.end(), "property float u"), s.end());
}

}  // namespace

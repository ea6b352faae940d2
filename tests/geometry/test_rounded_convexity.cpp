// Rounded convex input is convex: every shipped example mesh and scene, rotated (in double) about
// several axes and written with 17, 15 and 6 significant digits, keeps its verdict (convex ones
// accepted, with the same facets; the L-block still refused with its dent); a cube whose top is a
// 2 x 2 grid with the centre 1e-15 .. 1e-10 off the plane is accepted as within the rounding of its
// coordinates; dents from 1e-6 to 1e-1 of the diameter are refused at 17 and 15 digits (and above
// the 6-digit rounding at 6 digits); a refusal never reports a violation of 0.
#include <panelrad/geometry/mesh_io.hpp>
#include <panelrad/geometry/planar_facets.hpp>
#include <panelrad/geometry/validation.hpp>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace pg = panelrad::geometry;

namespace {

const std::string kSource = PANELRAD_SOURCE_DIR;

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << "message: " << (haystack)

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string format(double x, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, x);
  return buf;
}

/// The text of an OFF or OBJ file with every vertex position mapped by `map` and printed with
/// %.{digits}g; everything else (faces, comments, materials, extra vertex values) unchanged.
std::string map_vertices(const std::string& text, bool obj, const std::function<pg::Vec3(const pg::Vec3&)>& map,
                         int digits) {
  std::istringstream in(text);
  std::ostringstream out;
  std::string line;
  long header = 0, vertices_left = -1;  // OFF: "OFF", then the counts, then the vertex lines
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string first;
    ls >> first;
    const bool comment = first.empty() || first[0] == '#';
    bool is_vertex = false;
    if (obj) {
      is_vertex = first == "v";
      if (is_vertex) ls.str(line.substr(line.find('v') + 1)), ls.clear();
    } else if (!comment) {
      if (header == 0) {
        header = 1;
      } else if (header == 1) {
        vertices_left = std::stol(first);
        header = 2;
      } else if (vertices_left > 0) {
        is_vertex = true;
        --vertices_left;
        ls.str(line), ls.clear();
      }
    }
    if (!is_vertex) {
      out << line << '\n';
      continue;
    }
    pg::Vec3 p;
    ls >> p.x() >> p.y() >> p.z();
    std::string rest;
    std::getline(ls, rest);
    const pg::Vec3 q = map(p);
    out << (obj ? "v " : "") << format(q.x(), digits) << ' ' << format(q.y(), digits) << ' ' << format(q.z(), digits)
        << rest << '\n';
  }
  return out.str();
}

pg::TriangleMesh read_text_mesh(const std::string& text, bool obj, const std::string& name) {
  std::istringstream in(text);
  return obj ? pg::read_obj(in, name) : pg::read_off(in, name);
}

struct Shipped {
  std::string path;  // relative to the source directory
  std::string rule;  // verdict of the file as shipped: "" valid
};

const std::vector<Shipped>& shipped() {
  static const std::vector<Shipped> files = {
      {"examples/meshes/cube.off", ""},
      {"examples/meshes/dodecahedron.off", ""},
      {"examples/meshes/hexagonal_prism.off", ""},
      {"examples/meshes/triangular_prism.obj", ""},
      {"examples/meshes/l_block.off", "convex"},
      {"examples/meshes/open_box.off", "closed"},
      {"examples/scenes/convex_box.obj", ""},
      {"examples/scenes/prism_lamp.off", ""},
  };
  return files;
}

/// Largest signed distance of a vertex outside a triangle's plane, by a direct loop in long double
/// (an independent measurement of what the validator reports; rounding error ~1e-19 relative).
// The number of distinct supporting planes of the facets (facet_planes).
std::size_t distinct_planes(const pg::TriangleMesh& m) {
  const std::vector<pg::Index> plane = pg::facet_planes(m);
  return std::set<pg::Index>(plane.begin(), plane.end()).size();
}

double worst_outside_distance(const pg::TriangleMesh& m) {
  long double worst = 0;
  for (const auto& t : m.triangles) {
    using V = Eigen::Matrix<long double, 3, 1>;
    const auto at = [&](pg::Index i) { return m.vertices[static_cast<std::size_t>(i)].cast<long double>().eval(); };
    const V a = at(t[0]), n = (at(t[1]) - a).cross(at(t[2]) - a).normalized();
    for (std::size_t v = 0; v < m.vertices.size(); ++v)
      worst = std::max(worst, (m.vertices[v].cast<long double>() - a).dot(n));
  }
  return static_cast<double>(worst);
}

double diameter(const pg::TriangleMesh& m) {
  double d = 0;
  for (const auto& p : m.vertices)
    for (const auto& q : m.vertices) d = std::max(d, (p - q).norm());
  return d;
}

/// A refusal must name a positive violation: no distance printed as 0.
void expect_no_zero_violation(const pg::ValidationReport& r) {
  EXPECT_GT(r.worst_convexity_violation, 0.0);
  EXPECT_EQ(r.message.find("0.00e+00"), std::string::npos) << r.message;
}

const std::vector<std::pair<std::string, pg::Vec3>>& axes() {
  static const std::vector<std::pair<std::string, pg::Vec3>> a = {
      {"z", pg::Vec3::UnitZ()}, {"x", pg::Vec3::UnitX()}, {"y", pg::Vec3::UnitY()},
      {"(1,2,3)", pg::Vec3(1, 2, 3).normalized()}};
  return a;
}
const std::vector<double> kAngles = {30, 45, 90, 117.3};
const std::vector<int> kDigits = {17, 15, 6};

/// Unit cube [0,1]^3 whose top (z = 1) is a 2 x 2 grid of quads around the centre vertex
/// (0.5, 0.5, z_centre); the four side walls are pentagons through the top edges' midpoints.
/// Input faces: 0 bottom, 1-4 the top quads, 5-8 the walls.
std::string grid_top_cube(double z_centre, int digits) {
  std::ostringstream s;
  s << "OFF\n13 9 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n";
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i)  // top grid: vertex 4 + 3 j + i at (i/2, j/2, 1)
      s << 0.5 * i << ' ' << 0.5 * j << ' ' << (i == 1 && j == 1 ? format(z_centre, digits) : "1") << '\n';
  s << "4 0 3 2 1\n"                                      // bottom
       "4 4 5 8 7\n4 5 6 9 8\n4 7 8 11 10\n4 8 9 12 11\n"  // top quads
       "5 0 1 6 5 4\n5 1 2 12 9 6\n5 2 3 10 11 12\n5 3 0 4 7 10\n";  // walls y=0, x=1, y=1, x=0
  return s.str();
}

}  // namespace

TEST(RoundedConvexity, InputRoundingIsInferredFromTheCoordinates) {
  // Integers: 1 digit, taken as a 6-digit export at the coarsest.
  const pg::InputRounding ints = pg::input_rounding(pg::read_mesh(kSource + "/examples/meshes/cube.off"));
  EXPECT_EQ(ints.digits, 1);
  EXPECT_TRUE(ints.decimal);
  EXPECT_EQ(ints.assumed_digits, 6);
  EXPECT_EQ(ints.magnitude, 1.0);
  // rho_6 + 16 u with u = 2^-53.
  EXPECT_DOUBLE_EQ(ints.per_coordinate, 5e-6 + 16 * std::ldexp(1.0, -53));
  const auto rotated = [](double angle) {
    return [angle](const pg::Vec3& p) { return (Eigen::AngleAxisd(angle, pg::Vec3(1, 2, 3).normalized()) * p).eval(); };
  };
  const std::string cornell = read_text(kSource + "/examples/scenes/convex_box.obj");
  for (int d : {6, 9, 15}) {
    const pg::InputRounding r =
        pg::input_rounding(read_text_mesh(map_vertices(cornell, true, rotated(0.5), d), true, "cornell"));
    EXPECT_EQ(r.digits, d);  // a generic rotation uses every digit somewhere
    EXPECT_EQ(r.assumed_digits, d);
    EXPECT_NEAR(r.relative, 0.5 * std::pow(10.0, 1 - d), 1e-14);
  }
  const pg::InputRounding full =
      pg::input_rounding(read_text_mesh(map_vertices(cornell, true, rotated(0.5), 17), true, "cornell"));
  EXPECT_EQ(full.digits, 17);
  EXPECT_FALSE(full.decimal);
  EXPECT_DOUBLE_EQ(full.relative, 16 * std::ldexp(1.0, -53));
}

// The reported failures: the shipped Cornell box rotated 30 degrees about z at 17, 15, 6 digits.
TEST(RoundedConvexity, RotatedCornellBoxIsAcceptedWithANote) {
  const std::string text = read_text(kSource + "/examples/scenes/convex_box.obj");
  const Eigen::AngleAxisd rot(std::numbers::pi / 6, pg::Vec3::UnitZ());
  for (int d : kDigits) {
    SCOPED_TRACE("digits " + std::to_string(d));
    pg::TriangleMesh m = read_text_mesh(map_vertices(text, true, [&](const pg::Vec3& p) { return (rot * p).eval(); }, d),
                                        true, "convex_box_rotated.obj");
    const double measured = worst_outside_distance(m) / diameter(m);
    const pg::ValidationReport r = pg::validate_closed_convex(m);
    ASSERT_TRUE(r.valid) << r.message;
    EXPECT_TRUE(r.convex_within_rounding);
    EXPECT_LE(r.worst_rounding_ratio, 1.0);
    ASSERT_FALSE(r.notes.empty());
    EXPECT_CONTAINS(r.notes.back(), "convex within the rounding of the input");
    EXPECT_CONTAINS(r.notes.back(), "of the diameter");
    EXPECT_CONTAINS(r.notes.back(), d == 17 ? "double-precision coordinates" : std::to_string(d) + " significant digits");
    // The reported worst violation is the measured one (long double loop above; at 17 and 15 digits
    // the violations are a few ulps, where long double carries 11 more bits: 1e-3 relative).
    EXPECT_NEAR(r.worst_convexity_violation, measured, 1e-3 * measured);
    EXPECT_GT(r.worst_convexity_violation, 0.0);
    // Facets: the 14 input faces stay; the planar facets are the box's 6 sides (ceiling grid one).
    EXPECT_EQ(m.num_facets, 14);
    EXPECT_EQ(pg::count_planar_facets(m), 6u);
    EXPECT_EQ(distinct_planes(m), 6u);  // the ceiling grid's 9 facets in one supporting plane
    EXPECT_NEAR(pg::surface_area(m), 6.0, d == 6 ? 1e-4 : 1e-12);  // 6 unit squares
  }
}

TEST(RoundedConvexity, EveryShippedMeshKeepsItsVerdictWhenRotatedAndRounded) {
  for (const Shipped& f : shipped()) {
    const bool obj = f.path.ends_with(".obj");
    const std::string text = read_text(kSource + "/" + f.path);
    pg::TriangleMesh original = read_text_mesh(text, obj, f.path);
    const pg::ValidationReport ref = pg::validate_closed_convex(original);
    ASSERT_EQ(ref.rule, f.rule) << f.path << ": " << ref.message;
    const std::size_t planar = ref.valid ? pg::count_planar_facets(original) : 0;
    const double area = pg::surface_area(original);
    for (const auto& [axis_name, axis] : axes())
      for (double degrees : kAngles)
        for (int d : kDigits) {
          SCOPED_TRACE(f.path + " rotated " + format(degrees, 6) + " deg about " + axis_name + ", " +
                       std::to_string(d) + " digits");
          const Eigen::Matrix3d rot = Eigen::AngleAxisd(degrees * std::numbers::pi / 180, axis).toRotationMatrix();
          pg::TriangleMesh m =
              read_text_mesh(map_vertices(text, obj, [&](const pg::Vec3& p) { return (rot * p).eval(); }, d), obj, f.path);
          const pg::Index faces = m.num_facets;
          const pg::ValidationReport r = pg::validate_closed_convex(m);
          EXPECT_EQ(r.rule, f.rule) << r.message;
          if (f.rule.empty()) {
            ASSERT_TRUE(r.valid) << r.message;
            if (r.convex_within_rounding) {
              EXPECT_LE(r.worst_rounding_ratio, 1.0);
              EXPECT_LE(r.worst_convexity_violation, pg::kMaxRoundingViolation);
              EXPECT_CONTAINS(r.notes.back(), "convex within the rounding of the input");
            }
            EXPECT_EQ(m.num_facets, faces);  // input faces kept
            if (r.retriangulated_from_hull) {
              // The dodecahedron's six-decimal pentagons are non-planar by ~3e-7; rotated and
              // written with 15 or 17 digits its coordinates no longer show that coarse rounding,
              // so its fan triangles are not coplanar within the rounding the digits imply (the
              // exact hull still proves it convex). Written with 6 digits they are again.
              EXPECT_GE(pg::count_planar_facets(m), planar);
              EXPECT_LE(pg::count_planar_facets(m), m.triangles.size());
            } else {
              EXPECT_EQ(pg::count_planar_facets(m), planar);  // the planar facet structure kept
              EXPECT_EQ(distinct_planes(m), planar);          // coplanar facets of a convex solid touch
            }
            // Rotation keeps the area; 6 digits move coordinates by up to 5e-6 relative.
            EXPECT_NEAR(pg::surface_area(m), area, (d == 6 ? 1e-4 : 1e-12) * area);
          }
          if (f.rule == "convex") {
            expect_no_zero_violation(r);
            // The L-block's reflex edge: vertices 1 outside the plane y = 1, diameter 3.
            EXPECT_NEAR(r.worst_convexity_violation, 1.0 / 3.0, d == 6 ? 1e-5 : 1e-12);
            EXPECT_CONTAINS(r.message, "lies outside the plane of");
          }
        }
  }
}

// Off-plane centres of a grid face, 1e-15 to 1e-10 in either direction, at the precision the file
// carries (the shortest decimal form of z = 1 -/+ delta has -log10(delta) digits): within the
// rounding of such coordinates, so accepted, with the top still one planar facet.
TEST(RoundedConvexity, GridFaceWithOffPlaneCentreIsAccepted) {
  for (int k = 15; k >= 10; --k)
    for (double sign : {-1.0, 1.0}) {
      const double z = 1 + sign * std::pow(10.0, -k), delta = std::abs(z - 1);  // the offset as rounded
      SCOPED_TRACE("centre off the plane by " + format(z - 1, 3));
      pg::TriangleMesh m = read_text_mesh(grid_top_cube(z, 17), false, "grid_top_cube.off");
      const double measured = worst_outside_distance(m) / diameter(m);
      const pg::ValidationReport r = pg::validate_closed_convex(m);
      ASSERT_TRUE(r.valid) << r.message;
      EXPECT_TRUE(r.convex_within_rounding);
      EXPECT_FALSE(r.retriangulated_from_hull);
      ASSERT_FALSE(r.notes.empty());
      EXPECT_CONTAINS(r.notes.back(), "convex within the rounding of the input");
      // The fan triangles through the centre tilt by delta over half a side: boundary vertices lie
      // up to a few delta outside them. Measured independently above (1e-3: the long double loop
      // resolves delta = 1e-15 to ~1e-4 of itself).
      EXPECT_NEAR(r.worst_convexity_violation, measured, 1e-3 * measured);
      EXPECT_GE(r.worst_convexity_violation, delta / std::sqrt(3.0));
      EXPECT_LE(r.worst_convexity_violation, 4 * delta / std::sqrt(3.0));
      EXPECT_EQ(m.num_facets, 9);
      EXPECT_EQ(pg::count_planar_facets(m), 6u);  // the four top quads are one facet
      EXPECT_EQ(distinct_planes(m), 6u);          // and one supporting plane
    }
}

// The same grid cube rotated in double and written with 17 digits: its coordinates now carry full
// double precision, so an offset is rounding only up to a few ulps: 1e-15 accepted, 1e-12 and
// 1e-10 (thousands of ulps) refused, as real dents, with a nonzero violation.
TEST(RoundedConvexity, OffPlaneCentreOfAFullPrecisionMeshIsRoundingOnlyAtUlpLevel) {
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(0.7, pg::Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const auto rotated = [&](double delta) {
    const std::string text = map_vertices(grid_top_cube(1 - delta, 17), false,
                                          [&](const pg::Vec3& p) { return (rot * p).eval(); }, 17);
    return read_text_mesh(text, false, "grid_top_cube_rotated.off");
  };
  pg::TriangleMesh near = rotated(1e-15);
  pg::ValidationReport r = pg::validate_closed_convex(near);
  EXPECT_TRUE(r.valid) << r.message;
  EXPECT_TRUE(r.convex_within_rounding);
  EXPECT_EQ(pg::count_planar_facets(near), 6u);
  for (double delta : {1e-12, 1e-10}) {
    pg::TriangleMesh far = rotated(delta);
    r = pg::validate_closed_convex(far);
    EXPECT_FALSE(r.valid);
    EXPECT_EQ(r.rule, "convex");
    EXPECT_CONTAINS(r.message, "more than the rounding of the input explains");
    expect_no_zero_violation(r);
  }
}

// Dents of depth delta * diameter (the grid centre pushed in), rotated about several axes: refused
// with today's message at 17 and 15 digits for delta = 1e-6 .. 1e-1; at 6 digits for delta >= 1e-3
// (a 6-digit file rounds coordinates of magnitude ~1.4 by up to 7e-6, beyond a 1e-6 dent: that one
// is accepted, within its rounding).
TEST(RoundedConvexity, DentsAreRefused) {
  const double diam = std::sqrt(3.0);
  for (int k = 6; k >= 1; --k) {
    const double delta = std::pow(10.0, -k);
    const std::string text = grid_top_cube(1 - delta * diam, 17);
    for (const auto& [axis_name, axis] : axes())
      for (double degrees : {0.0, 30.0, 117.3})
        for (int d : kDigits) {
          SCOPED_TRACE("dent " + format(delta, 2) + " of the diameter, rotated " + format(degrees, 6) +
                       " deg about " + axis_name + ", " + std::to_string(d) + " digits");
          const Eigen::Matrix3d rot = Eigen::AngleAxisd(degrees * std::numbers::pi / 180, axis).toRotationMatrix();
          pg::TriangleMesh m;
          try {
            m = read_text_mesh(map_vertices(text, false, [&](const pg::Vec3& p) { return (rot * p).eval(); }, d),
                               false, "dent.off");
          } catch (const pg::MeshError& e) {
            // A dent deeper than 1e-4 of a grid polygon's size makes that polygon non-planar
            // beyond what the reader triangulates (mesh_io.hpp): refused there, by name.
            EXPECT_CONTAINS(e.what(), "is not planar");
            EXPECT_GE(delta, 1e-4);
            continue;
          }
          const double measured = worst_outside_distance(m) / diameter(m);
          const pg::ValidationReport r = pg::validate_closed_convex(m);
          if (d == 6 && k > 3) {
            if (k == 6) {
              EXPECT_TRUE(r.valid) << r.message;
              EXPECT_TRUE(r.convex_within_rounding);
            }
            continue;  // 1e-5, 1e-4: at the 6-digit rounding bound itself; either verdict is honest
          }
          EXPECT_FALSE(r.valid);
          EXPECT_EQ(r.rule, "convex");
          EXPECT_EQ(r.message.rfind("convex: vertex ", 0), 0u) << r.message;
          EXPECT_CONTAINS(r.message, "lies outside the plane of triangle");
          EXPECT_CONTAINS(r.message, "of the mesh diameter); worst violation");
          expect_no_zero_violation(r);
          // At least the dent's tilt: boundary vertices 2 to 3 delta outside the tilted top
          // triangles; equal to the independent measurement (1e-6 relative: long double loop).
          EXPECT_NEAR(r.worst_convexity_violation, measured, 1e-6 * measured);
          EXPECT_GE(r.worst_convexity_violation, 1.9 * delta * (1 - 4 * delta));
        }
  }
}

// Before, the first non-convex triangle's violation was a double rounding to 0 and printed as
// "by 0.00e+00" while the worst was elsewhere. Rotated Cornell box (ulp-level violations on its
// walls) with a real dent in the ceiling: the refusal prints the first violation as a positive
// number.
TEST(RoundedConvexity, RefusalNeverPrintsAZeroViolation) {
  const std::string text = read_text(kSource + "/examples/scenes/convex_box.obj");
  const Eigen::AngleAxisd rot(std::numbers::pi / 6, pg::Vec3::UnitZ());
  pg::TriangleMesh m = read_text_mesh(map_vertices(text, true, [&](const pg::Vec3& p) { return (rot * p).eval(); }, 17),
                                      true, "convex_box_dented.obj");
  m.vertices[9].z() -= 1e-3;  // ceiling grid vertex (1/3, 1/3, 1) pushed down
  const pg::ValidationReport r = pg::validate_closed_convex(m);
  ASSERT_FALSE(r.valid);
  EXPECT_EQ(r.rule, "convex");
  expect_no_zero_violation(r);
  // "... by X (Y of the mesh diameter)": both positive.
  const auto by = r.message.find(" by ");
  ASSERT_NE(by, std::string::npos);
  EXPECT_GT(std::stod(r.message.substr(by + 4)), 0.0) << r.message;
  const auto open = r.message.find('(', by);
  EXPECT_GT(std::stod(r.message.substr(open + 1)), 0.0) << r.message;
}

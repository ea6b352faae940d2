// View factors between groups of surfaces (viewfactors/view_factors.hpp) against closed forms:
// the faces of the unit cube and of a 2 x 1 x 1 box seen from inside (Hottel's parallel and
// perpendicular rectangles, Howell's catalog C-11 and C-14), a convex body inside a room
// (F_body,room = 1, F_body,body = 0), closure and reciprocity in closed scenes; the error estimate
// (one level coarser) bounds the measured error; the block size changes nothing; bad groups refused.
#include "occluded_scenes.hpp"

#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/mesh_io.hpp>
#include <panelrad/io/view_factor_output.hpp>
#include <panelrad/quadrature/exact_integrals.hpp>
#include <panelrad/viewfactors/view_factors.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

namespace panelrad {
namespace {

using testing::BoxFront;

/// Directly opposed parallel rectangles a x b at distance c (Howell C-11).
double parallel_rectangles(double a, double b, double c) {
  const double X = a / c, Y = b / c, sx = std::sqrt(1 + X * X), sy = std::sqrt(1 + Y * Y);
  return 2 / (std::numbers::pi * X * Y) *
         (0.5 * std::log((1 + X * X) * (1 + Y * Y) / (1 + X * X + Y * Y)) + X * sy * std::atan(X / sy) +
          Y * sx * std::atan(Y / sx) - X * std::atan(X) - Y * std::atan(Y));
}

/// From a rectangle of width w to a perpendicular one of height h sharing its edge of length l
/// (Howell C-14).
double perpendicular_rectangles(double l, double w, double h) {
  const double W = w / l, H = h / l, W2 = W * W, H2 = H * H, R = std::sqrt(W2 + H2);
  const double log_term = std::log((1 + W2) * (1 + H2) / (1 + W2 + H2)) +
                          W2 * std::log(W2 * (1 + W2 + H2) / ((1 + W2) * (W2 + H2))) +
                          H2 * std::log(H2 * (1 + H2 + W2) / ((1 + H2) * (H2 + W2)));
  return (W * std::atan(1 / W) + H * std::atan(1 / H) - R * std::atan(1 / R) + 0.25 * log_term) / (std::numbers::pi * W);
}

/// The exact factor between facets I and J of the axis box [0, d]^3 seen from inside (facets in
/// add_axis_box's order: x = 0, x = d_x, y = 0, y = d_y, z = 0, z = d_z).
double box_factor(const Vec3& d, int I, int J) {
  const int a = I / 2, b = J / 2;  // the axes normal to I and J
  if (a == b) {
    if (I == J) return 0;
    const int u = (a + 1) % 3, v = (a + 2) % 3;
    return parallel_rectangles(d[u], d[v], d[a]);
  }
  const int common = 3 - a - b;  // the axis of the shared edge
  return perpendicular_rectangles(d[common], d[b], d[a]);  // I spans (common, b), J spans (common, a)
}

ViewFactorOptions at_level(int level, OperatorMethod method = OperatorMethod::automatic) {
  ViewFactorOptions o;
  o.solve.level = level;
  o.solve.op.method = method;
  return o;
}

// The cube and a 2 x 1 x 1 box seen from inside, each face a group: every factor within the
// error estimate (level 4 against 3) of its closed form, and the estimate below 1e-3 (the
// factors converge at second order here: the estimate is about 3 times the error); closure
// (uncovered) within its estimate.
TEST(ViewFactors, BoxFacesMatchTheClosedForms) {
  for (const Vec3& d : {Vec3(1, 1, 1), Vec3(2, 1, 1)}) {
    const Scene scene(testing::axis_box(Vec3::Zero(), d, BoxFront::inside, "room"));
    const ViewFactors v = compute_view_factors(scene, groups_by_facet(scene), at_level(4));
    ASSERT_EQ(v.F.rows(), 6);
    ASSERT_EQ(v.error.rows(), 6);
    EXPECT_TRUE(v.enclosed);
    double worst = 0, worst_estimate = 0;
    for (int I = 0; I < 6; ++I) {
      EXPECT_NEAR(v.area[I], d.prod() / d[I / 2], 1e-14);
      for (int J = 0; J < 6; ++J) {
        const double exact = box_factor(d, I, J), error = std::abs(v.F(I, J) - exact);
        EXPECT_LE(error, v.error(I, J) + 1e-12) << "d " << d.transpose() << " F(" << I << ", " << J << ") = " << v.F(I, J)
                                                << ", exact " << exact;
        worst = std::max(worst, error);
        worst_estimate = std::max(worst_estimate, v.error(I, J));
      }
      EXPECT_LE(std::abs(v.uncovered[I]), v.uncovered_error[I] + 1e-12) << I;
    }
    EXPECT_LT(worst_estimate, 1e-3);
    EXPECT_LT(v.reciprocity_defect, 1e-2);
    std::printf("box %g x %g x %g, n = %d: largest error %.3g, largest estimate %.3g, reciprocity %.3g\n", d.x(), d.y(),
                d.z(), static_cast<int>(v.n), worst, worst_estimate, v.reciprocity_defect);
  }
}

// A convex body inside a closed room: all it sees is the room (F_box,room = 1 up to the
// discretization, its own faces never: exactly 0), and the room sees it by reciprocity,
// F_room,box = A_box / A_room exactly, within the estimates at level 3. (At level 2 the room's
// factor, partly hidden by the box, is off by 1.0e-3 with an estimate of 8.6e-4: the difference
// of two levels is an estimate, not a bound, before the convergence settles.)
TEST(ViewFactors, ConvexBodyInsideARoomSeesOnlyTheRoom) {
  const Scene scene(testing::room_with_box());
  SurfaceGroups g;
  g.names = {"room", "box"};
  for (Index f = 0; f < scene.num_facets(); ++f) g.of_facet.push_back(f < 6 ? 0 : 1);
  const ViewFactors v = compute_view_factors(scene, g, at_level(3));
  EXPECT_EQ(v.F(1, 1), 0.0);
  EXPECT_NEAR(v.F(1, 0), 1.0, std::max(v.error(1, 0), 1e-6));
  EXPECT_NEAR(v.area[0], 6.0, 1e-13);
  EXPECT_NEAR(v.area[1], 2 * (0.3 * 0.35 + 0.3 * 0.35 + 0.35 * 0.35), 1e-13);
  EXPECT_NEAR(v.F(0, 1), v.area[1] / v.area[0], v.error(0, 1));
  EXPECT_NEAR(v.F(0, 1), v.area[1] / v.area[0] * v.F(1, 0), v.error(0, 1) + v.error(1, 0));
  EXPECT_NEAR(v.F(0, 0) + v.F(0, 1), 1.0, v.uncovered_error[0] + 1e-12);
}

// The factors do not depend on how many group columns go through H at once: a column of a block
// product is that column's product, bit for bit.
TEST(ViewFactors, BlockSizeChangesNothing) {
  const Scene scene(testing::room_with_box());
  ViewFactorOptions one = at_level(1, OperatorMethod::fast), many = one;
  one.block_columns = 1;
  many.block_columns = 5;
  one.estimate_error = many.estimate_error = false;
  one.solve.op.eta = many.solve.op.eta = 0.5;
  one.solve.op.degree = many.solve.op.degree = 4;
  const ViewFactors a = compute_view_factors(scene, groups_by_facet(scene), one);
  const ViewFactors b = compute_view_factors(scene, groups_by_facet(scene), many);
  EXPECT_EQ(a.F, b.F);
  EXPECT_EQ(a.error.size(), 0);
}

/// `mesh`'s triangles, each its own face, in order, as an OBJ (`o` before each object's first
/// face), an ASCII STL (one solid per object) and a binary STL (float32 corners, no names); the
/// object of triangle t is objects[t].
struct Writings {
  std::string obj, ascii, binary;
};
Writings write_triangles(const geometry::TriangleMesh& mesh, const std::vector<std::string>& objects) {
  Writings w;
  std::ostringstream obj, stl;
  obj.precision(17);
  stl.precision(17);
  for (const Vec3& v : mesh.vertices) obj << "v " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
  w.binary.assign(80, ' ');
  const auto count = static_cast<std::uint32_t>(mesh.triangles.size());
  w.binary.append(reinterpret_cast<const char*>(&count), 4);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tr = mesh.triangles[t];
    if (t == 0 || objects[t] != objects[t - 1]) {
      obj << "o " << objects[t] << '\n';
      if (t > 0) stl << "endsolid " << objects[t - 1] << '\n';
      stl << "solid " << objects[t] << '\n';
    }
    obj << "f " << tr[0] + 1 << ' ' << tr[1] + 1 << ' ' << tr[2] + 1 << '\n';
    stl << "facet normal 0 0 0\nouter loop\n";
    float record[12] = {};
    for (int k = 0; k < 3; ++k) {
      const Vec3& v = mesh.vertices[static_cast<std::size_t>(tr[static_cast<std::size_t>(k)])];
      stl << "vertex " << v.x() << ' ' << v.y() << ' ' << v.z() << '\n';
      for (int c = 0; c < 3; ++c) record[3 + 3 * k + c] = static_cast<float>(v[c]);
    }
    stl << "endloop\nendfacet\n";
    w.binary.append(reinterpret_cast<const char*>(record), sizeof record);
    w.binary.append(2, '\0');
  }
  stl << "endsolid " << objects.back() << '\n';
  w.obj = obj.str();
  w.ascii = stl.str();
  return w;
}

// The room with a box written as OBJ, ASCII STL and binary STL, grouped by object (the OBJ's o, the
// STL's solids; the binary STL's groups named per facet): OBJ and ASCII STL give the same triangles
// and so the same matrix bit for bit, welded against unwelded (the OBJ's corners are shared, the
// STL's written per triangle and welded on reading); the binary STL's float32 corners move the box by up to 1e-8,
// and its factors by less than 1e-6.
TEST(ViewFactors, TheSameMatrixFromObjAndStl) {
  const geometry::TriangleMesh mesh = testing::room_with_box();
  std::vector<std::string> objects;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) objects.push_back(mesh.facet_of_triangle[t] < 6 ? "room" : "box");
  const Writings w = write_triangles(mesh, objects);
  std::istringstream obj(w.obj), ascii(w.ascii), binary(w.binary);
  const Scene from_obj(geometry::read_obj(obj, "room.obj")), from_ascii(geometry::read_stl(ascii, "room.stl")),
      from_binary(geometry::read_stl(binary, "room_binary.stl"));
  ViewFactorOptions o = at_level(2);
  o.estimate_error = false;
  const ViewFactors a = compute_view_factors(from_obj, groups_by_object(from_obj), o);
  const ViewFactors b = compute_view_factors(from_ascii, groups_by_object(from_ascii), o);
  SurfaceGroups named;
  named.names = {"room", "box"};
  for (const std::string& name : objects) named.of_facet.push_back(name == "room" ? 0 : 1);
  const ViewFactors c = compute_view_factors(from_binary, named, o);
  EXPECT_EQ(a.names, (std::vector<std::string>{"room", "box"}));
  EXPECT_EQ(b.names, a.names);
  EXPECT_EQ(a.F, b.F);
  EXPECT_LT((a.F - c.F).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_THROW((void)groups_by_object(Scene(testing::room_with_box())), std::invalid_argument);  // no names
}

// Made reciprocal and closed: A_I F_IJ = A_J F_JI and rows summing to 1 in an enclosure, zeros
// kept, and F moved by less at the finer level; an open scene made reciprocal only.
TEST(ViewFactors, ReciprocalAndClosed) {
  const Scene scene(testing::room_with_box());
  ViewFactorOptions o = at_level(3);
  const ViewFactors raw = compute_view_factors(scene, groups_by_facet(scene), o);
  o.reciprocal = true;
  const ViewFactors v = compute_view_factors(scene, groups_by_facet(scene), o);
  EXPECT_EQ(raw.correction, 0.0);
  EXPECT_GT(v.correction, 0.0);
  // The correction shrinks with the discretization's error (second order here): 1.4e-3 at level 3
  // (n = 1,536), where the estimate is 8.8e-4 and the reciprocity defect of small faces 2.4e-2.
  o.estimate_error = false;
  o.solve.level = 4;
  const ViewFactors finer = compute_view_factors(scene, groups_by_facet(scene), o);
  EXPECT_LT(finer.correction, v.correction / 3);
  EXPECT_LT(v.correction, 2e-3);
  EXPECT_DOUBLE_EQ(v.correction, (v.F - raw.F).cwiseAbs().maxCoeff());
  for (Index I = 0; I < 12; ++I) {
    EXPECT_NEAR(v.F.row(I).sum(), 1.0, 1e-12) << I;
    EXPECT_NEAR(v.uncovered[I], 0.0, 1e-12);
    for (Index J = 0; J < 12; ++J) {
      EXPECT_NEAR(v.area[I] * v.F(I, J), v.area[J] * v.F(J, I), 1e-13) << I << " " << J;
      if (raw.F(I, J) == 0) {
        EXPECT_EQ(v.F(I, J), 0.0);
      }
    }
  }
  EXPECT_LT(v.reciprocity_defect, 1e-12);
  // Open: two squares facing each other, one-sided, the second's row as computed a little off;
  // reciprocal, each row's sum what the symmetrization leaves (the sky takes the rest), zeros kept.
  const Eigen::MatrixXd F = (Eigen::MatrixXd(2, 2) << 0, 0.2, 0.05, 0).finished();
  const Eigen::MatrixXd B = reciprocal_and_closed(F, Eigen::Vector2d(1, 4), false);
  EXPECT_DOUBLE_EQ(B(0, 1), 0.2);
  EXPECT_DOUBLE_EQ(4 * B(1, 0), B(0, 1));
  EXPECT_EQ(B(0, 0), 0.0);
  EXPECT_EQ(B(1, 1), 0.0);
  EXPECT_THROW((void)reciprocal_and_closed(F, Eigen::Vector3d(1, 1, 1), true), std::invalid_argument);
  EXPECT_THROW((void)reciprocal_and_closed(-F, Eigen::Vector2d(1, 1), true), std::invalid_argument);
}

// An open scene, a unit floor with a unit wall standing on its far edge (one-sided sheets facing
// each other): every element's sky view factor is 1 minus the closed-form point-to-polygon factor
// of the other sheet (dense, exact entries: to rounding), and the groups' sky columns are the
// area-weighted means of the elements'; the elements' CSV has a row per element.
TEST(ViewFactors, SkyOfEveryElementOfAnOpenScene) {
  geometry::TriangleMesh m;
  m.source = "floor and wall";
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {1, 1, 1}, {0, 1, 1}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}, {3, 2, 4}, {3, 4, 5}};  // floor up; wall towards -y
  m.facet_of_triangle = {0, 0, 1, 1};
  m.num_facets = 2;
  const Scene scene(std::move(m));
  ASSERT_FALSE(scene.enclosed());
  ViewFactorOptions o = at_level(2, OperatorMethod::dense);
  o.elements = true;
  const ViewFactors v = compute_view_factors(scene, groups_by_facet(scene), o);
  const ElementSky& e = v.elements;
  ASSERT_EQ(e.sky.size(), 64);
  const std::array<std::array<Vec3, 3>, 2> floor = {{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0)},
                                                     {Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}}};
  const std::array<std::array<Vec3, 3>, 2> wall = {{{Vec3(0, 1, 0), Vec3(1, 1, 0), Vec3(1, 1, 1)},
                                                    {Vec3(0, 1, 0), Vec3(1, 1, 1), Vec3(0, 1, 1)}}};
  Eigen::Vector2d weighted = Eigen::Vector2d::Zero();
  for (Index i = 0; i < 64; ++i) {
    const bool on_floor = e.facet[static_cast<std::size_t>(i)] == 0;
    const Vec3 nP = on_floor ? Vec3(0, 0, 1) : Vec3(0, -1, 0), nQ = on_floor ? Vec3(0, -1, 0) : Vec3(0, 0, 1);
    double other = 0;
    for (const auto& t : on_floor ? wall : floor) other += quadrature::form_factor(e.centroid[static_cast<std::size_t>(i)], nP, t[0], t[1], t[2], nQ);
    EXPECT_NEAR(e.sky[i], 1 - other, 1e-13) << "element " << i;
    EXPECT_GT(e.sky[i], 0.5);
    weighted[e.group[static_cast<std::size_t>(i)]] += e.area[i] * e.sky[i];
  }
  EXPECT_NEAR(weighted[0] / v.area[0], v.uncovered[0], 1e-14);
  EXPECT_NEAR(weighted[1] / v.area[1], v.uncovered[1], 1e-14);
  const std::string csv = element_sky_csv(v);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "element,facet,group,x,y,z,area,sky");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 65);
  EXPECT_NE(csv.find("\n0,0,facet 0,"), std::string::npos);
}

// A fin standing across the middle of a floor: one-sided it is seen from one half of the floor;
// two-sided (with_back_sides) its back is a group of its own, seen from the other half, each side
// exactly as a rectangle perpendicular to the half floor it faces (Howell C-14): F_half,fin =
// perpendicular_rectangles(1, 1, 1), so F_floor,side = F_half,fin / 2 and, by reciprocity,
// F_side,floor = F_half,fin (the two halves of the floor have the fin's area). Within the error
// estimate (level 4 against 3).
TEST(ViewFactors, TwoSidedFinIsSeenFromBothHalvesOfTheFloor) {
  geometry::TriangleMesh m;
  m.source = "fin on a floor";
  // The floor's two halves meet under the fin (its elements do not straddle the fin's foot, where
  // the point factor jumps).
  testing::add_polygon(m, {Vec3(-1, 0, 0), Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(-1, 1, 0)});  // floor, up
  testing::add_polygon(m, {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)});
  testing::add_polygon(m, {Vec3(0, 0, 0), Vec3(0, 1, 0), Vec3(0, 1, 1), Vec3(0, 0, 1)});  // fin, +x
  m.facet_group = {"floor", "floor", "fin"};
  const Scene one_sided(std::move(m));
  const SurfaceGroups groups = groups_by_object(one_sided);
  const TwoSidedScene two = with_back_sides(one_sided, groups, {"fin"});
  ASSERT_EQ(two.groups.names, (std::vector<std::string>{"floor", "fin", "fin (back)"}));
  EXPECT_EQ(two.scene.num_facets(), 4);
  EXPECT_FALSE(two.scene.enclosed());
  const double exact = perpendicular_rectangles(1, 1, 1);
  const ViewFactors one = compute_view_factors(one_sided, groups, at_level(4));
  const ViewFactors v = compute_view_factors(two.scene, two.groups, at_level(4));
  ASSERT_EQ(v.F.rows(), 3);
  EXPECT_NEAR(v.area[1], 1.0, 1e-15);
  EXPECT_NEAR(v.area[2], 1.0, 1e-15);
  for (const Index side : {1, 2}) {
    EXPECT_NEAR(v.F(0, side), exact / 2, v.error(0, side) + 1e-12) << v.names[side];
    EXPECT_NEAR(v.F(side, 0), exact, v.error(side, 0) + 1e-12) << v.names[side];
    EXPECT_EQ(v.F(side, 3 - side), 0.0);  // one side does not see the other
  }
  // One-sided, the floor sees the fin's front only: the same factor as the two-sided front.
  EXPECT_NEAR(one.F(0, 1), exact / 2, one.error(0, 1) + 1e-12);
  EXPECT_THROW((void)with_back_sides(one_sided, groups, {"roof"}), std::invalid_argument);
  EXPECT_THROW((void)with_back_sides(one_sided, groups, {"fin", "fin"}), std::invalid_argument);
  EXPECT_THROW((void)with_back_sides(two.scene, two.groups, {"fin (back)"}), std::invalid_argument);
}

TEST(ViewFactors, BadGroupsAreRefusedByName) {
  const Scene scene(geometry::make_cube());
  SurfaceGroups g = groups_by_facet(scene);
  EXPECT_EQ(groups_problem(scene, g), "");
  g.of_facet.pop_back();
  EXPECT_NE(groups_problem(scene, g).find("5 facets"), std::string::npos) << groups_problem(scene, g);
  g = groups_by_facet(scene);
  g.names[1] = g.names[0];
  EXPECT_NE(groups_problem(scene, g).find("twice"), std::string::npos);
  g = groups_by_facet(scene);
  g.names.push_back("unused");
  EXPECT_NE(groups_problem(scene, g).find("'unused' has no facet"), std::string::npos);
  g = groups_by_facet(scene);
  g.of_facet[2] = 9;
  EXPECT_NE(groups_problem(scene, g).find("facet 2"), std::string::npos);
  EXPECT_THROW((void)compute_view_factors(scene, g), std::invalid_argument);
  EXPECT_THROW((void)groups_by_material(scene), std::invalid_argument);  // no materials
}

}  // namespace
}  // namespace panelrad

// Solids in contact, however the file writes them (contact_scenes.hpp): each quad from each of its
// four corners (the fan takes one diagonal or the other), over shared or separate vertex lines.
// Every scene is closed, so the collocation solution with E = c (1 - rho) is u = c exactly
// (oracle_scenes.hpp derives the bound, 1e-9 near the origin): a contact handled for one writing
// and not another, a covered part left in the scene or a visible part removed moves a row sum of
// K by the form factor of that part, far above the bound. Also the refusals whose hints, applied,
// solve: a polygon given twice, a window written on a wall; and the two-sided sheet.
#include "contact_scenes.hpp"
#include "oracle_scenes.hpp"

#include <gtest/gtest.h>

#include <string>
#include <tuple>
#include <vector>

namespace panelrad {
namespace {

using testing::contact_families;
using testing::Polygon;
using testing::PolygonScene;
using testing::Writing;

void expect_constant(const PolygonScene& scene, const Writing& w, int level = -1) {
  const testing::OracleRun run = testing::run_constant_oracle(testing::read_scene(scene, w), 1.0, level);
  SCOPED_TRACE(scene.name + ", " + w.describe());
  ASSERT_TRUE(run.valid) << run.describe();
  ASSERT_TRUE(run.solved) << run.describe();
  EXPECT_LE(run.error, run.tolerance) << run.describe();
}

class ContactWritings : public ::testing::TestWithParam<std::tuple<int, int, bool>> {};

TEST_P(ContactWritings, ClosedSceneSolvesToTheConstant) {
  const auto [family, corner, separate] = GetParam();
  Writing w;
  w.first_corner = corner;
  w.separate = separate;
  expect_constant(contact_families()[static_cast<std::size_t>(family)], w);
}

INSTANTIATE_TEST_SUITE_P(EveryCornerBothVertexModes, ContactWritings,
                         ::testing::Combine(::testing::Range(0, static_cast<int>(contact_families().size())),
                                            ::testing::Range(0, 4), ::testing::Bool()));

// Two boxes stacked on shared corners, the upper one's bottom from another corner than the lower
// one's top: the two faces split the square along different diagonals. The answer is the one of
// the same diagonals, to the oracle's bound.
TEST(ContactWritings, StackedBoxesWithDifferentDiagonalsAreOneSolid) {
  PolygonScene scene = contact_families()[0];
  Writing w;
  PolygonScene other = scene;
  Polygon& bottom = other.faces[12];  // the upper box's face z = 0.4
  std::rotate(bottom.begin(), bottom.begin() + 1, bottom.end());
  const testing::OracleRun a = testing::run_constant_oracle(testing::read_scene(scene, w), 1.0, 1);
  const testing::OracleRun b = testing::run_constant_oracle(testing::read_scene(other, w), 1.0, 1);
  ASSERT_TRUE(a.valid && a.solved) << a.describe();
  ASSERT_TRUE(b.valid && b.solved) << b.describe();
  EXPECT_LE(b.error, b.tolerance) << b.describe();
  EXPECT_EQ(a.n, b.n);
}

// A lamp given twice with opposite windings, no solid behind either copy: a two-sided sheet, both
// sides surfaces. In the closed room every ray still ends on a front side: u = c.
TEST(ContactWritings, PolygonTwiceWithOppositeWindingsIsATwoSidedSheet) {
  PolygonScene scene = testing::room_scene("a two-sided lamp in the room");
  const Polygon lamp = {{0.4, 0.4, 0.9}, {0.6, 0.4, 0.9}, {0.6, 0.6, 0.9}, {0.4, 0.6, 0.9}};
  Polygon back = lamp;
  std::reverse(back.begin() + 1, back.end());
  scene.faces.push_back(lamp);
  scene.faces.push_back(back);
  for (int corner = 0; corner < 4; ++corner)
    for (bool separate : {false, true}) {
      Writing w;
      w.first_corner = corner;
      w.separate = separate;
      expect_constant(scene, w);
    }
  Writing w;
  geometry::SceneValidationReport report;
  ASSERT_TRUE(geometry::try_validate(testing::read_scene(scene, w), report)) << report.message;
  bool noted = false;
  for (const std::string& n : report.notes) noted = noted || n.find("two-sided sheet") != std::string::npos;
  EXPECT_TRUE(noted);
  EXPECT_TRUE(report.contacts.empty());
}

// The same polygon twice with the same winding is refused, naming both faces; the hint (remove
// one of them) solves.
TEST(ContactWritings, PolygonTwiceWithOneWindingIsRefusedAndTheHintSolves) {
  PolygonScene scene = testing::room_scene("a lamp given twice in the room");
  const Polygon lamp = {{0.4, 0.4, 0.9}, {0.6, 0.4, 0.9}, {0.6, 0.6, 0.9}, {0.4, 0.6, 0.9}};
  scene.faces.push_back(lamp);
  Polygon again = lamp;
  std::rotate(again.begin(), again.begin() + 1, again.end());
  scene.faces.push_back(again);
  Writing w;
  geometry::SceneValidationReport report;
  EXPECT_FALSE(geometry::try_validate(testing::read_scene(scene, w), report));
  EXPECT_NE(report.message.find("input face 7 (line"), std::string::npos) << report.message;
  EXPECT_NE(report.message.find("duplicates input face 6 (line"), std::string::npos) << report.message;
  // The hint: one copy removed. A one-sided lamp is accepted (not closed: its back faces the
  // ceiling, so only acceptance is checked here).
  scene.faces.pop_back();
  geometry::SceneValidationReport fixed;
  EXPECT_TRUE(geometry::try_validate(testing::read_scene(scene, w), fixed)) << fixed.message;
}

// A window written as a polygon on the wall: refused whichever way it faces, with a hint; the
// hint applied (the wall as polygons around the opening, the window a face of its own facing the
// room) solves to the constant.
TEST(ContactWritings, WindowWrittenOnAWallIsRefusedAndTheHintSolves) {
  const Polygon window_out = {{1, 0.4, 0.4}, {1, 0.6, 0.4}, {1, 0.6, 0.6}, {1, 0.4, 0.6}};  // front outward
  Polygon window_in = window_out;
  std::reverse(window_in.begin() + 1, window_in.end());
  for (const Polygon& window : {window_out, window_in}) {
    PolygonScene scene = testing::room_scene("a window written on the wall x = 1");
    scene.faces.push_back(window);
    geometry::SceneValidationReport report;
    EXPECT_FALSE(geometry::try_validate(testing::read_scene(scene, Writing{}), report));
    EXPECT_EQ(report.rule, "crossing");
    const bool hint = report.message.find("wall") != std::string::npos ||
                      report.message.find("remove one of them") != std::string::npos;
    EXPECT_TRUE(hint) << report.message;
  }
  // The hint: the wall x = 1 as four polygons around [0.4, 0.6]^2 (in y, z), the window facing the
  // room (-x).
  PolygonScene scene = testing::room_scene("a window cut into the wall x = 1");
  scene.faces.erase(scene.faces.begin() + 5);  // the wall x = 1
  const auto wall = [&](double y0, double y1, double z0, double z1) {
    scene.faces.push_back({{1, y0, z0}, {1, y0, z1}, {1, y1, z1}, {1, y1, z0}});  // counter-clockwise from -x
  };
  wall(0, 0.4, 0, 1);
  wall(0.6, 1, 0, 1);
  wall(0.4, 0.6, 0, 0.4);
  wall(0.4, 0.6, 0.6, 1);
  wall(0.4, 0.6, 0.4, 0.6);  // the window
  expect_constant(scene, Writing{});
}

}  // namespace
}  // namespace panelrad

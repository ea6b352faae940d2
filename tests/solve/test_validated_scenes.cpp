// The one way to a Scene goes through validation: a mesh as read is validated by the Scene
// itself (geometry::validate_mesh), a ValidatedMesh carries its shape, and nothing else builds a
// Scene. So a non-convex scene is never solved with V = 1: it is solved with V computed, or the
// request for V = 1 is refused by name. Checked on the room [0, 1]^3 with a box inside
// (occluded_scenes.hpp), by the exact oracle of a closed enclosure: E = c (1 - rho) gives u = c
// (the rows of K sum to rho when V is right; with V = 1 they would sum to more, and u != c).
#include <panelrad/panelrad.hpp>

#include <panelrad/geometry/builtin_scenes.hpp>

#include "occluded_scenes.hpp"

#include <gtest/gtest.h>

#include <string>
#include <type_traits>
#include <vector>

namespace {

using namespace panelrad;
using geometry::SceneShape;
using geometry::TriangleMesh;

// Only validation makes a ValidatedMesh, and a Scene takes nothing else with a shape.
static_assert(!std::is_constructible_v<geometry::ValidatedMesh, TriangleMesh, SceneShape>);
static_assert(!std::is_constructible_v<Scene, TriangleMesh, std::vector<std::string>, SceneShape>);
static_assert(std::is_constructible_v<Scene, TriangleMesh>);
static_assert(std::is_constructible_v<Scene, geometry::ValidatedMesh>);

constexpr double kC = 2.0;
constexpr double kRho = 0.5;

Scene oracle_room() {
  Scene scene(panelrad::testing::room_with_box());  // wound as read: the constructor validates
  scene.set_reflectivity(kRho);
  scene.set_emissivity(kC * (1 - kRho));
  return scene;
}

TEST(ValidatedScenes, ANonConvexMeshIsValidatedByTheSceneAndSolvedWithV) {
  const Scene scene = oracle_room();
  EXPECT_EQ(scene.shape(), SceneShape::general);
  EXPECT_FALSE(scene.notes().empty());  // the validation says what each piece is
  SolveOptions options;
  options.level = 1;
  options.op.method = OperatorMethod::dense;
  options.solver.tolerance = 1e-12;
  const SceneSolution s = solve_scene(scene, options);
  s.require_converged();
  EXPECT_EQ(s.visibility, Visibility::occluded);
  // Dense entries are closed forms (relative error ~1e-14), the iteration stops at 1e-12 and
  // 1 / (1 - rho) = 2 amplifies both: 1e-10 relative is far above them, far below any V error
  // (a hidden box face seen with V = 1 shifts u by O(rho F) ~ 0.1).
  for (Index i = 0; i < s.n; ++i) EXPECT_NEAR(s.channels[0].radiosity[i], kC, 1e-10 * kC) << "element " << i;
}

TEST(ValidatedScenes, VEqualToOneOnANonConvexSceneIsRefusedByName) {
  const Scene scene = oracle_room();
  SolveOptions options;
  options.level = 0;
  options.visibility = Visibility::unoccluded;
  EXPECT_THROW(solve_scene(scene, options), std::invalid_argument);
}

TEST(ValidatedScenes, AnInvalidMeshCannotBecomeAScene) {
  TriangleMesh crossing = panelrad::testing::append(panelrad::testing::quad({0.5, 0, 0}, {0.5, 1, 0}, {0.5, 1, 1}, {0.5, 0, 1}),
                                          panelrad::testing::quad({0, 0.5, 0}, {1, 0.5, 0}, {1, 0.5, 1}, {0, 0.5, 1}));
  crossing.source = "two crossing squares";
  try {
    const Scene scene(std::move(crossing));
    ADD_FAILURE() << "a crossing mesh became a scene";
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("two crossing squares: invalid scene: crossing"), std::string::npos) << e.what();
  }
}

TEST(ValidatedScenes, AConvexMeshKeepsThePapersSetting) {
  const Scene cube(geometry::make_builtin("cube"));
  EXPECT_EQ(cube.shape(), SceneShape::convex);
  // The same surface through load_scene and through a validated mesh: the same triangles.
  const Scene loaded = load_scene("builtin:cube");
  EXPECT_EQ(loaded.shape(), SceneShape::convex);
  EXPECT_EQ(loaded.mesh().triangles, cube.mesh().triangles);
  EXPECT_EQ(loaded.mesh().vertices, cube.mesh().vertices);
}

}  // namespace

// The scene model (scene/scene.hpp): C named channels, rho and E per facet or as functions, one
// rule for every value (reflectivity_problem, emission_problem, paper (7)), and the manufactured
// solution of the paper's test method (section 3).
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/validation.hpp>
#include <panelrad/scene/scene.hpp>

#include "test_support.hpp"

#include "validated_meshes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace panelrad {
namespace {

geometry::TriangleMesh valid_cube() { return testing::validated_builtin("cube"); }

using testing::expect_names;
using testing::refusal;

// A point of facet f's first triangle (its centroid).
Vec3 point_on_facet(const Scene& scene, Index f) {
  const geometry::TriangleMesh& m = scene.mesh();
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    if (m.facet_of_triangle[t] == f) {
      const auto& tri = m.triangles[t];
      return (m.vertices[static_cast<std::size_t>(tri[0])] + m.vertices[static_cast<std::size_t>(tri[1])] +
              m.vertices[static_cast<std::size_t>(tri[2])]) /
             3.0;
    }
  ADD_FAILURE() << "facet " << f << " has no triangle";
  return Vec3::Zero();
}

}  // namespace

TEST(Scene, ChannelsAreNamedOnceEach) {
  EXPECT_EQ(Scene(valid_cube()).channels(), std::vector<std::string>{"value"});
  EXPECT_EQ(Scene(valid_cube(), {"R", "G", "B"}).num_channels(), 3u);
  EXPECT_THROW(Scene(valid_cube(), {}), std::invalid_argument);
  EXPECT_THROW(Scene(valid_cube(), {"R", "R"}), std::invalid_argument);
  EXPECT_THROW(Scene(valid_cube(), {"R", ""}), std::invalid_argument);
  Scene scene(valid_cube(), {"R", "G"});
  try {
    scene.set_reflectivity(0.5, 2);
    ADD_FAILURE() << "channel 2 of a 2-channel scene accepted";
  } catch (const std::out_of_range& e) {
    EXPECT_NE(std::string(e.what()).find("no channel 2; the scene has 2 (0 to 1)"), std::string::npos) << e.what();
  }
}

// Defaults rho = 0 and E = 0 (no surface emits unless given); per-facet values read back at any
// point of their facet, per channel.
TEST(Scene, PerFacetDataPerChannel) {
  Scene scene(valid_cube(), {"R", "G"});
  const Vec3 P = point_on_facet(scene, 3);
  EXPECT_EQ(scene.reflectivity(P, 3, 1), 0.0);
  EXPECT_EQ(scene.emissivity(P, 3, 1), 0.0);
  EXPECT_EQ(scene.facet_emissivity(0), std::vector<double>(6, 0.0));
  EXPECT_EQ(scene.facet_emissivity(1), std::vector<double>(6, 0.0));
  scene.set_reflectivity({0.1, 0.2, 0.3, 0.4, 0.5, 0.6}, 1);
  scene.set_emissivity({0, 0, 0, 2.5, 0, 0}, 0);
  EXPECT_EQ(scene.reflectivity(P, 3, 1), 0.4);
  EXPECT_EQ(scene.reflectivity(P, 3, 0), 0.0);  // the other channel keeps its own data
  EXPECT_EQ(scene.emissivity(P, 3, 0), 2.5);
  EXPECT_EQ(scene.max_reflectivity(), 0.6);     // over every channel
  EXPECT_THROW(scene.set_reflectivity(std::vector<double>(5, 0.1), 0), std::invalid_argument);  // 6 facets
}

// One rule (reflectivity_problem, emission_problem) for per-facet data when it is set; a refused
// value leaves the previous data.
TEST(Scene, OneRuleForPerFacetData) {
  Scene scene(valid_cube(), {"R", "G"});
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (const double bad : {1.0, -0.1, nan, 5e-324}) {
    std::vector<double> rho(6, 0.5);
    rho[4] = bad;
    expect_names(refusal([&] { scene.set_reflectivity(rho, 1); }),
                 {"reflectivity rho", "facet 4", "channel G", reflectivity_problem(bad)});
  }
  for (const double bad : {inf, -1.0, nan, 1e101, 1e-101}) {
    std::vector<double> e(6, 1.0);
    e[2] = bad;
    expect_names(refusal([&] { scene.set_emissivity(e, 0); }), {"emission E", "facet 2", "channel R", emission_problem(bad)});
  }
  EXPECT_EQ(scene.facet_reflectivity(1), std::vector<double>(6, 0.0));
  EXPECT_EQ(scene.facet_emissivity(0), std::vector<double>(6, 0.0));  // the default, kept
  // The rule itself: 0 <= rho < 1 (paper (7)); E finite, >= 0, 0 or within [1e-100, 1e100].
  EXPECT_EQ(reflectivity_problem(0.0), "");
  EXPECT_EQ(reflectivity_problem(std::nextafter(1.0, 0.0)), "");
  EXPECT_NE(reflectivity_problem(1.0).find("[0, 1)"), std::string::npos);
  EXPECT_EQ(emission_problem(0.0), "");
  EXPECT_EQ(emission_problem(1e100), "");
  EXPECT_NE(emission_problem(-1.0).find(">= 0"), std::string::npos);
}

// Functions are checked where they are evaluated, with the point, its facet and the channel.
TEST(Scene, OneRuleForFunctionsWhereEvaluated) {
  Scene scene(valid_cube(), {"R", "G"});
  scene.set_reflectivity([](const Vec3&, Index f) { return f == 3 ? 1.0 : 0.25; }, 1);
  scene.set_emissivity([](const Vec3&, Index f) { return f == 2 ? -1.0 : 1.0; }, 0);
  EXPECT_EQ(scene.reflectivity(point_on_facet(scene, 0), 0, 1), 0.25);
  expect_names(refusal([&] { (void)scene.reflectivity(point_on_facet(scene, 3), 3, 1); }),
               {"reflectivity rho", "point (", "of facet 3", "channel G", reflectivity_problem(1.0)});
  expect_names(refusal([&] { (void)scene.emissivity(point_on_facet(scene, 2), 2, 0); }),
               {"emission E", "point (", "of facet 2", "channel R", emission_problem(-1.0)});
  EXPECT_TRUE(std::isnan(scene.max_reflectivity()));  // unknown until evaluated
  EXPECT_TRUE(scene.facet_reflectivity(1).empty());
}

// The paper's test method, E = u - K u: for u = 1 on a closed convex surface the rows of K sum to
// rho (Int_S G / pi dS_Q = 1 at every P, paper Lemma 1), so E = 1 - rho exactly. The integral is
// computed to relative accuracy 1e-11 (set_manufactured_solution's default); 1e-9 leaves room for
// the sum over the six faces.
TEST(Scene, ManufacturedSolutionOfAConstant) {
  Scene scene(valid_cube());
  scene.set_reflectivity({0.1, 0.2, 0.3, 0.4, 0.5, 0.6});
  scene.set_manufactured_solution([](const Vec3&, Index) { return 1.0; });
  ASSERT_TRUE(scene.has_manufactured_solution());
  const geometry::TriangleMesh& m = scene.mesh();
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const Index f = m.facet_of_triangle[t];
    const auto& tri = m.triangles[t];
    const Vec3 P = (m.vertices[static_cast<std::size_t>(tri[0])] + m.vertices[static_cast<std::size_t>(tri[1])] +
                    m.vertices[static_cast<std::size_t>(tri[2])]) /
                   3.0;
    EXPECT_NEAR(scene.manufactured_emissivity(P, f, scene.triangle_inner_normal(static_cast<Index>(t))),
                1.0 - scene.facet_reflectivity()[static_cast<std::size_t>(f)], 1e-9);
  }
  // A manufactured solution is for scalar scenes; setting E replaces it.
  Scene rgb(valid_cube(), {"R", "G", "B"});
  EXPECT_THROW(rgb.set_manufactured_solution([](const Vec3&, Index) { return 1.0; }), std::logic_error);
  scene.set_emissivity(1.0);
  EXPECT_FALSE(scene.has_manufactured_solution());
}

}  // namespace panelrad

// Multi-channel scene solve: one operator H for all channels, K_c = diag(rho_c) H,
// checked against known answers (constant solution), the dense operator built with rho, and the
// energy balance of a closed convex scene.
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/validation.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/scene_solver.hpp>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>

namespace panelrad {
namespace {

// A scene's data per channel and facet, made a Scene (and so checked) by scene().
struct SceneData {
  geometry::TriangleMesh mesh;
  std::vector<std::string> channels;
  std::vector<std::vector<double>> rho, emission;
  Scene scene() const {
    Scene s(mesh, channels);
    for (std::size_t c = 0; c < channels.size(); ++c) {
      s.set_reflectivity(rho[c], c);
      s.set_emissivity(emission[c], c);
    }
    return s;
  }
};

SceneData make_scene(geometry::TriangleMesh mesh, std::vector<std::string> channels) {
  const geometry::ValidationReport report = geometry::validate_closed_convex(mesh);
  EXPECT_TRUE(report.valid) << report.message;
  SceneData s;
  s.mesh = std::move(mesh);
  s.channels = std::move(channels);
  const std::size_t F = static_cast<std::size_t>(s.mesh.num_facets);
  s.rho.assign(s.channels.size(), std::vector<double>(F, 0.0));
  s.emission.assign(s.channels.size(), std::vector<double>(F, 0.0));
  return s;
}

// E = c (1 - rho) with rho constant per facet gives u = c exactly on a closed convex surface
// (rows of K sum to rho, paper Lemma 1): in every channel, with its own rho and c.
void expect_constant_solution(const std::string& method, int levels) {
  SceneData s = make_scene(geometry::make_prism(3, 1.0, 1.5), {"R", "G", "B"});
  const double c[3] = {1.0, 2.5, 0.25};
  for (std::size_t ch = 0; ch < 3; ++ch)
    for (std::size_t f = 0; f < s.rho[ch].size(); ++f) {
      s.rho[ch][f] = 0.1 + 0.15 * static_cast<double>((f + 2 * ch) % 5);  // 0.1 .. 0.7
      s.emission[ch][f] = c[ch] * (1 - s.rho[ch][f]);
    }
  SolveOptions o;
  o.level = levels;
  o.op.method = parse_operator_method(method);
  o.solver.tolerance = 1e-12;
  const SceneSolution sol = solve_scene(s.scene(), o);
  ASSERT_EQ(sol.channels.size(), 3u);
  for (std::size_t ch = 0; ch < 3; ++ch) {
    const double err = (sol.channels[ch].radiosity.array() - c[ch]).abs().maxCoeff();
    // dense, exact near field: the row-sum identity holds to rounding (1e-13 per row, amplified by
    // 1/(1 - 0.7)); fast: u = c is the constant vector, so its error is the self-check's error for
    // v = 1 amplified by at most rho/(1 - rho) = 2.3 (11), and 10 times leaves room for the rows the
    // check did not sample.
    double constant_vector_error = -1;
    for (const auto& v : sol.self_check.vectors)
      if (v.name == "1") constant_vector_error = v.relative_error;
    if (method != "dense") {
      ASSERT_GE(constant_vector_error, 0) << "no self-check entry for v = 1";
    }
    const double tol = method == "dense" ? 1e-10 : 10 * constant_vector_error + 1e-10;
    EXPECT_LT(err, tol * c[ch]) << method << " channel " << ch;
    EXPECT_TRUE(sol.channels[ch].shared_with.empty());
  }
  EXPECT_EQ(sol.field.size(), static_cast<std::size_t>(sol.n));
  EXPECT_EQ(sol.n, 8 << (2 * levels));
}

TEST(SceneSolver, ConstantSolutionInEveryChannelDense) { expect_constant_solution("dense", 2); }
TEST(SceneSolver, ConstantSolutionInEveryChannelFast) { expect_constant_solution("auto", 4); }

// The channel operator diag(rho) H equals the operator assembled with rho in the rows (33).
TEST(SceneSolver, ScaledOperatorEqualsOperatorWithReflectivity) {
  geometry::TriangleMesh mesh = geometry::make_cube();
  ASSERT_TRUE(geometry::validate_closed_convex(mesh).valid);
  Scene scene(mesh);
  std::vector<double> rho(static_cast<std::size_t>(scene.num_facets()));
  for (std::size_t f = 0; f < rho.size(); ++f) rho[f] = 0.05 * static_cast<double>(f % 7);  // some rows 0
  scene.set_reflectivity(rho);
  const Collocation col(scene, 2);
  const DenseOperator K(col, NearFieldOptions{});
  const DenseOperator H(col.with_row_weights(Eigen::VectorXd::Ones(col.size())), NearFieldOptions{});
  const ScaledOperator KH(H, col.reflectivity());
  Eigen::VectorXd v(col.size()), a, b;
  for (Index i = 0; i < col.size(); ++i) v[i] = std::cos(0.37 * i) + 1.5;
  K.apply(v, a);
  KH.apply(v, b);
  EXPECT_LE((a - b).lpNorm<Eigen::Infinity>(), 1e-14 * a.lpNorm<Eigen::Infinity>());
}

TEST(SceneSolver, IdenticalChannelsSolvedOnceAndDarkChannelIsZero) {
  SceneData s = make_scene(geometry::make_cube(), {"R", "G", "B"});
  for (std::size_t ch = 0; ch < 2; ++ch) {
    for (double& r : s.rho[ch]) r = 0.5;
    s.emission[ch][0] = 1.0;
  }
  for (double& r : s.rho[2]) r = 0.3;  // no emission in B
  SolveOptions o;
  o.level = 1;
  const SceneSolution sol = solve_scene(s.scene(), o);
  EXPECT_EQ(sol.channels[1].shared_with, "R");
  EXPECT_EQ(sol.channels[1].radiosity, sol.channels[0].radiosity);
  EXPECT_GT(sol.channels[0].iterations, 0);
  EXPECT_EQ(sol.channels[2].radiosity.lpNorm<Eigen::Infinity>(), 0.0);
  EXPECT_EQ(sol.channels[2].iterations, 0);
}

// Emitted power = absorbed power on a closed convex scene; the mismatch is a discretization
// effect and shrinks as n grows, staying below its stated expected size 0.5 h/diam. Measured
// (rho 0.2 / 0.9 alternating, one emitting facet): tall triangular prism 1.6e-1, 5.4e-2, 1.7e-2,
// 5.2e-3 at levels 1-4 (0.35 .. 0.09 h/diam); cube 1.3e-4, 7.9e-5, 2.2e-5 at levels 2-4 (the
// cube's level 1, 7.6e-5, is below level 2: the decrease is asymptotic, not from the first level).
void expect_energy_balance_shrinks(geometry::TriangleMesh mesh, int first, int last) {
  SceneData s = make_scene(std::move(mesh), {"value"});
  for (std::size_t f = 0; f < s.rho[0].size(); ++f) s.rho[0][f] = f % 2 ? 0.9 : 0.2;
  s.emission[0].back() = 3.0;  // one facet emits
  double emitter_area = 0;
  for (std::size_t t = 0; t < s.mesh.triangles.size(); ++t)
    if (s.mesh.facet_of_triangle[t] == s.mesh.num_facets - 1) {
      const auto& tri = s.mesh.triangles[t];
      const geometry::Vec3 a = s.mesh.vertices[static_cast<std::size_t>(tri[0])], b = s.mesh.vertices[static_cast<std::size_t>(tri[1])],
                           d = s.mesh.vertices[static_cast<std::size_t>(tri[2])];
      emitter_area += 0.5 * (b - a).cross(d - a).norm();
    }
  double previous = 1;
  for (int level = first; level <= last; ++level) {
    SolveOptions o;
    o.level = level;
    o.solver.tolerance = 1e-12;
    const SceneSolution sol = solve_scene(s.scene(), o);
    const ChannelSolution& c = sol.channels[0];
    std::printf("level %d n %d: emitted %.6e absorbed %.6e mismatch %.3e (expected %.3e)\n", level,
                static_cast<int>(sol.n), c.emitted, c.absorbed, c.energy_mismatch, sol.expected_energy_mismatch);
    EXPECT_NEAR(c.emitted, 3.0 * emitter_area, 1e-12 * emitter_area);  // sum A_i E_i, exactly
    EXPECT_GT(c.emitted, 0);
    EXPECT_LT(c.energy_mismatch, sol.expected_energy_mismatch);
    EXPECT_LT(c.energy_mismatch, previous);
    EXPECT_TRUE(sol.warnings.empty());
    previous = c.energy_mismatch;
  }
}

TEST(SceneSolver, EnergyBalanceMismatchShrinksWithNTallPrism) {
  expect_energy_balance_shrinks(geometry::make_prism(3, 1.0, 3.0), 1, 4);
}
TEST(SceneSolver, EnergyBalanceMismatchShrinksWithNCube) { expect_energy_balance_shrinks(geometry::make_cube(), 2, 4); }

TEST(SceneSolver, RefusesBadReflectivityAndSizes) {
  SceneData s = make_scene(geometry::make_cube(), {"value"});
  s.rho[0][3] = 1.0;
  EXPECT_THROW(solve_scene(s.scene()), std::invalid_argument);
  s.rho[0][3] = std::nan("");
  EXPECT_THROW(solve_scene(s.scene()), std::invalid_argument);
  s.rho[0][3] = 0.5;
  s.emission[0][2] = std::nan("");
  EXPECT_THROW(solve_scene(s.scene()), std::invalid_argument);
  s.emission[0][2] = 1;
  SolveOptions o;
  o.op.method = OperatorMethod::dense;
  o.level = 9;  // n = 12 * 4^9 = 3.1e6: a 79 TB matrix, refused before any work
  EXPECT_ANY_THROW(solve_scene(s.scene(), o));
  EXPECT_EQ(level_for_max_elements(12, 20000), 5);
  EXPECT_EQ(level_for_max_elements(12, 12288), 5);
  EXPECT_EQ(level_for_max_elements(12, 12287), 4);
  EXPECT_EQ(level_for_max_elements(100, 50), 0);
}

}  // namespace
}  // namespace panelrad

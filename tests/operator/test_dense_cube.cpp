// Centroid collocation and the dense operator against independent truths: the row-sum identity
// (Lemma 1: rows of K_n sum to rho on a closed convex surface) and a constant solution. The
// paper's Table 1 and Example 2 are checked in test_paper_tables.cpp.
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/validation.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/solvers.hpp>

#include "validated_meshes.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace {

using namespace panelrad;

Scene validated_scene(const std::string& builtin) { return Scene(panelrad::testing::validated_builtin(builtin)); }

// Row sums with the exact rule are rho(P_i) up to rounding (sum of O(n) terms of size <= 1).
TEST(DenseCube, RowSumsEqualReflectivityWithTheExactRule) {
  for (const char* name : {"cube", "prism:6", "tetrahedron", "octahedron"}) {
    Scene scene = validated_scene(name);
    std::vector<double> rho(static_cast<std::size_t>(scene.num_facets()));
    for (std::size_t f = 0; f < rho.size(); ++f) rho[f] = 0.2 + 0.7 * static_cast<double>(f) / static_cast<double>(rho.size());
    scene.set_reflectivity(rho);
    const Collocation col(scene, 2);
    const DenseOperator K(col, NearFieldOptions{});
    const Eigen::VectorXd sums = K.matrix().rowwise().sum();
    EXPECT_LT((sums - col.reflectivity()).lpNorm<Eigen::Infinity>(), 1e-12) << name;
    EXPECT_GE(K.matrix().minCoeff(), 0.0) << name;  // unoccluded: K >= 0
  }
}

// With the composite rule the identity holds to the rule's accuracy, which improves with mu.
TEST(DenseCube, RowSumsWithTheCompositeRuleImproveWithMu) {
  Scene scene = validated_scene("cube");
  scene.set_reflectivity(0.5);
  const Collocation col(scene, 2);
  double previous = 1;
  for (int mu : {0, 1, 2, 3}) {
    NearFieldOptions near;
    near.rule = NearRule::quadrature;
    near.mu = mu;
    const DenseOperator K(col, near);
    const double err = (K.matrix().rowwise().sum() - col.reflectivity()).lpNorm<Eigen::Infinity>();
    EXPECT_LT(err, previous) << "mu " << mu;
    previous = err;
  }
  EXPECT_LT(previous, 2e-3);
}

// E = c (1 - rho) with constant rho on a closed convex surface has the solution u = c exactly,
// and the discrete system reproduces it because K_n 1 = rho 1.
TEST(DenseCube, ConstantSolutionIsReproduced) {
  Scene scene = validated_scene("prism:5");
  const double rho = 0.6, c = 2.5;
  scene.set_reflectivity(rho);
  scene.set_emissivity(c * (1 - rho));
  const Collocation col(scene, 2);
  const DenseOperator K(col, NearFieldOptions{});
  const auto lu = solve_lu(K, col.emissivity());
  EXPECT_LT((lu.u.array() - c).abs().maxCoeff(), 1e-12);
  SolverOptions opt;
  opt.tolerance = 1e-13;
  const auto it = solve_neumann(K, col.emissivity(), opt);
  EXPECT_LT((it.u.array() - c).abs().maxCoeff(), 1e-11);
}

// The manufactured E with u = constant must be c (1 - rho): checks the high-accuracy integration.
TEST(DenseCube, ManufacturedEmissivityOfAConstantIsExact) {
  Scene scene = validated_scene("cube");
  scene.set_reflectivity(0.45);
  scene.set_manufactured_solution([](const Vec3&, Index) { return 3.0; });
  const Collocation col(scene, 3);
  EXPECT_LT((col.emissivity().array() - 3.0 * (1 - 0.45)).abs().maxCoeff(), 1e-10);
}

TEST(DenseCube, BadReflectivityIsRejectedWithTheFacet) {
  Scene scene = validated_scene("cube");
  try {
    std::vector<double> rho(6, 0.5);
    rho[4] = 1.0;
    scene.set_reflectivity(rho);
    FAIL() << "rho = 1 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("facet 4"), std::string::npos) << e.what();
  }
  EXPECT_THROW(scene.set_reflectivity(-0.1), std::invalid_argument);
  EXPECT_THROW(scene.set_reflectivity(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  scene.set_reflectivity([](const Vec3& P, Index) { return P.x() > 0.9 ? 1.5 : 0.2; });
  EXPECT_THROW(Collocation(scene, 1), std::invalid_argument);
}

}  // namespace

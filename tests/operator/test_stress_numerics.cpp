// Stress tests of numerical stability. Every case has a known answer and reports its
// worst error ("[stress] ..." lines and RecordProperty), and none may produce NaN or Inf:
//  - row-sum identity: on a closed convex surface each row of K_n sums to rho(P_i) with the exact
//    rule (Lemma 1; (33));
//  - constant solution: constant rho and E = c (1 - rho) give u = c, which the discrete system
//    keeps because K_n 1 = rho 1;
//  - manufactured solution (the paper's cube (31)): the error (51) does not depend on where the
//    cube sits or how large it is;
//  - fast against dense: FastOperator::self_check and the product against the dense product.
// Cases: slivers (aspect ratio 1e3), a flat (h = 1e-3) and a tall (h = 1e3) prism, the cube scaled
// by 1e-6 and 1e6 and translated by 1e6, collocation points next to edges (level 6), Taylor
// degree up to 8 (and the maximum, 12), and the largest level that runs in seconds.
// Runtime is kept small: constant solutions (no integration for E) wherever they give the answer.
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/cluster_tree.hpp>
#include <panelrad/geometry/validation.hpp>
#include <panelrad/quadrature/exact_integrals.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/solvers.hpp>

#include <gtest/gtest.h>

#include <sstream>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace panelrad;
using geometry::TriangleMesh;

constexpr double kRho = 0.5;
constexpr double kC = 2.0;  // constant solution u = c

void report(const std::string& key, double value) {
  std::cout << "[stress] " << key << " = " << value << "\n";
  ::testing::Test::RecordProperty(key, std::to_string(value));
}

TriangleMesh validated(TriangleMesh mesh) {
  const auto report = geometry::validate_closed_convex(mesh);
  EXPECT_TRUE(report.valid) << mesh.source << ": " << report.message;
  return mesh;
}

// Constant rho and E = c (1 - rho): the solution is u = c.
Scene constant_scene(TriangleMesh mesh) {
  Scene scene(validated(std::move(mesh)));
  scene.set_reflectivity(kRho);
  scene.set_emissivity(kC * (1 - kRho));
  return scene;
}

Eigen::VectorXd random_vector(Index n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Eigen::VectorXd v(n);
  for (Index i = 0; i < n; ++i) v[i] = U(gen);
  return v;
}

// Largest edge over shortest altitude of a triangle: 1 for "fat", large for slivers.
double aspect_ratio(const Vec3& a, const Vec3& b, const Vec3& c) {
  const double area2 = (b - a).cross(c - a).norm();
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  return longest * longest / area2;  // longest / (area2 / longest)
}

double worst_aspect_ratio(const TriangleMesh& mesh) {
  double worst = 0;
  for (const auto& t : mesh.triangles)
    worst = std::max(worst, aspect_ratio(mesh.vertices[static_cast<std::size_t>(t[0])],
                                         mesh.vertices[static_cast<std::size_t>(t[1])],
                                         mesh.vertices[static_cast<std::size_t>(t[2])]));
  return worst;
}

struct Figures {
  double row_sum_defect = 0;   // max_i |sum_j K_ij - rho|, dense exact rule
  double constant_error = 0;   // max_i |u_i - c|, LU on the dense system
  double self_check = 0;       // FastOperator::self_check relative error
  double fast_vs_dense = 0;    // max-norm relative difference of the products, v = 1 and random
};

// The known answers of one scene at one level: dense row sums and constant solution, fast vs dense.
Figures check_scene(const std::string& name, const Scene& scene, int level, const FastOptions& fast_options = {}) {
  Figures f;
  const Collocation col(scene, level);
  const DenseOperator K(col, NearFieldOptions{});
  EXPECT_TRUE(K.matrix().allFinite()) << name;
  EXPECT_GE(K.matrix().minCoeff(), 0.0) << name << ": unoccluded, so K >= 0";
  f.row_sum_defect = (K.matrix().rowwise().sum() - col.reflectivity()).lpNorm<Eigen::Infinity>();
  const SolveResult lu = solve_lu(K, col.emissivity());
  EXPECT_TRUE(lu.u.allFinite()) << name;
  f.constant_error = (lu.u.array() - kC).abs().maxCoeff();

  const FastOperator fast(col, fast_options);
  const FastSelfCheck check = fast.self_check(64);
  f.self_check = check.relative_error;
  for (const Eigen::VectorXd& v : {Eigen::VectorXd(Eigen::VectorXd::Ones(col.size())), random_vector(col.size(), 5)}) {
    Eigen::VectorXd yf, yd;
    fast.apply(v, yf);
    K.apply(v, yd);
    EXPECT_TRUE(yf.allFinite()) << name;
    f.fast_vs_dense = std::max(f.fast_vs_dense, (yf - yd).lpNorm<Eigen::Infinity>() / yd.lpNorm<Eigen::Infinity>());
  }
  const std::string tag = name + " n=" + std::to_string(col.size());
  report(tag + " row-sum defect", f.row_sum_defect);
  report(tag + " max|u-c| (LU)", f.constant_error);
  report(tag + " fast self-check", f.self_check);
  report(tag + " fast vs dense", f.fast_vs_dense);
  EXPECT_TRUE(std::isfinite(f.row_sum_defect) && std::isfinite(f.constant_error) && std::isfinite(f.self_check) &&
              std::isfinite(f.fast_vs_dense))
      << name;
  return f;
}

// Tolerances shared by the geometry cases below:
//  - row sums: n terms of size <= 1, each closed form accurate to a few ulp: 1e-12 (as on the
//    plain cube, test_dense_cube), whatever the shape;
//  - constant solution: ||(I - K)^-1|| <= 1/(1 - rho) = 2 times the row-sum defect: 1e-11;
//  - fast vs dense with the paper's (eta, M) = (0.2, 2): the 1e-3 bound that holds on the cube (test_fast_operator). The
//    Taylor remainder depends on R(tau)/|P - A(tau)| <= eta only (R is the circumradius, which
//    bounds |Q - A| for every Q of the cluster, however thin), so the bound does not depend on the
//    shape of the elements.
constexpr double kRowSumTol = 1e-12;
constexpr double kConstantTol = 1e-11;
constexpr double kFastTol = 1e-3;

void expect_figures(const std::string& name, const Figures& f) {
  EXPECT_LT(f.row_sum_defect, kRowSumTol) << name;
  EXPECT_LT(f.constant_error, kConstantTol) << name;
  EXPECT_LT(f.self_check, kFastTol) << name;
  EXPECT_LT(f.fast_vs_dense, kFastTol) << name;
}

// A long thin box 1000 x 1 x 1: the cube's triangulation stretched, its long faces are right
// triangles with legs 1000 and 1 (aspect ratio 1e3).
TEST(StressNumerics, SliverLongBox) {
  TriangleMesh box = geometry::make_cube();
  for (Vec3& v : box.vertices) v.x() *= 1000.0;
  box.source = "box 1000x1x1";
  EXPECT_GE(worst_aspect_ratio(box), 1e3);
  report("long box worst aspect ratio", worst_aspect_ratio(box));
  expect_figures("long box", check_scene("long box", constant_scene(box), 3));
}

// A prism over a very flat triangle (0,0), (1,0), (0.5, 1e-3): the caps are slivers of aspect
// ratio ~1e3 and the two long sides meet at a dihedral angle of pi - 4e-3 (nearly coplanar
// neighbours: their mutual form factors are tiny and must stay >= 0 and accurate).
TEST(StressNumerics, SliverFlatTrianglePrism) {
  TriangleMesh prism;
  prism.source = "flat-triangle prism";
  const double base[3][2] = {{0, 0}, {1, 0}, {0.5, 1e-3}};
  for (double z : {0.0, 1.0})
    for (const auto& b : base) prism.vertices.emplace_back(b[0], b[1], z);
  // Orientation deliberately unspecified: validation orients the faces outward.
  prism.triangles = {{0, 1, 2}, {3, 4, 5}, {0, 1, 4}, {0, 4, 3}, {1, 2, 5}, {1, 5, 4}, {2, 0, 3}, {2, 3, 5}};
  prism.facet_of_triangle = {0, 1, 2, 2, 3, 3, 4, 4};
  prism.num_facets = 5;
  EXPECT_GE(worst_aspect_ratio(prism), 0.99e3);
  report("flat-triangle prism worst aspect ratio", worst_aspect_ratio(prism));
  expect_figures("flat-triangle prism", check_scene("flat-triangle prism", constant_scene(prism), 3));
}

// Hexagonal prisms of height 1e-3 (a coin: sides 1 x 1e-3) and 1e3 (a needle: sides 1 x 1e3).
TEST(StressNumerics, FlatAndTallPrisms) {
  for (double h : {1e-3, 1e3}) {
    TriangleMesh prism = geometry::make_prism(6, 1.0, h);
    const std::string name = "prism:6 h=" + std::to_string(h);
    EXPECT_GE(worst_aspect_ratio(prism), 0.99e3) << name;
    report(name + " worst aspect ratio", worst_aspect_ratio(prism));
    expect_figures(name, check_scene(name, constant_scene(prism), 2));
  }
}

// The paper's cube scaled by 1e-6 and 1e6 and translated by 1e6. Known answers: the row sums, the
// constant solution, and the matrix itself: K_n is dimensionless, so it equals the unit cube's up
// to the rounding of the moved coordinates (relative 1e-16 when scaled; when translated by 1e6 the
// coordinates carry an absolute error ulp(1e6) ~ 1.2e-10 of the unit size, moving entries
// G ~ 1/r^2 by ~ 1e-10 / r with r >= h/3 ~ 0.04 at level 3: 1e-8 is a safe bound).
TEST(StressNumerics, CubeScaledAndTranslated) {
  struct Placement {
    const char* name;
    double scale;
    Vec3 offset;
    double matrix_tol;
  };
  const int level = 3;
  Scene unit = make_paper_cube_scene();
  unit.set_reflectivity(kRho);
  unit.set_emissivity(kC * (1 - kRho));
  const Collocation unit_col(unit, level);
  const DenseOperator unit_K(unit_col, NearFieldOptions{});
  for (const Placement& p : {Placement{"cube x1e-6", 1e-6, Vec3::Zero(), 1e-13},
                             Placement{"cube x1e6", 1e6, Vec3::Zero(), 1e-13},
                             Placement{"cube +1e6", 1.0, Vec3(1e6, -1e6, 1e6), 1e-8}}) {
    Scene scene = make_paper_cube_scene(p.scale, p.offset);
    scene.set_reflectivity(kRho);
    scene.set_emissivity(kC * (1 - kRho));  // replaces the manufactured E: no integration
    expect_figures(p.name, check_scene(p.name, scene, level));
    const Collocation col(scene, level);
    const DenseOperator K(col, NearFieldOptions{});
    const double diff = (K.matrix() - unit_K.matrix()).cwiseAbs().maxCoeff() / unit_K.matrix().cwiseAbs().maxCoeff();
    report(std::string(p.name) + " matrix vs unit cube", diff);
    EXPECT_LT(diff, p.matrix_tol) << p.name;
  }
}

// The manufactured solution u = |(Q - offset)/scale|^2 of the paper's cube (31): the error (51) of
// the fast method is a property of the discretization, so it must not change when the cube is
// scaled or moved (to 3 digits, the digits the paper prints; the discretization error is
// ~1e-2 and the placements perturb it by ~1e-8).
TEST(StressNumerics, ManufacturedErrorDoesNotDependOnPlacement) {
  const int level = 2;
  SolverOptions opt;
  opt.tolerance = 1e-12;
  double unit_error = 0;
  for (const auto& [name, scale, offset] :
       {std::tuple{"unit", 1.0, Vec3(Vec3::Zero())}, std::tuple{"x1e-6", 1e-6, Vec3(Vec3::Zero())},
        std::tuple{"x1e6", 1e6, Vec3(Vec3::Zero())}, std::tuple{"+1e6", 1.0, Vec3(1e6, -1e6, 1e6)}}) {
    // Default integration tolerance 1e-11 also when moved by 1e6 (an earlier integrator ran to its
    // evaluation cap there, minutes per point: u(Q) = |Q - offset|^2 carries ~1e-10 rounding).
    const Scene scene = make_paper_cube_scene(scale, offset);
    const Collocation col(scene, level);
    ASSERT_TRUE(col.emissivity().allFinite()) << name;
    const FastOperator fast(col, FastOptions{});
    const SolveResult r = solve(fast, col.emissivity(), opt, scene.max_reflectivity());
    ASSERT_TRUE(r.u.allFinite()) << name;
    const double err = col.max_error(r.u);
    report(std::string("manufactured cube ") + name + " n=192 max error (51)", err);
    if (std::string(name) == "unit") unit_error = err;
    EXPECT_NEAR(err, unit_error, 1e-3 * unit_error) << name;
  }
  // Table 1 at n = 192: 1.37e-2 (the dense method; fast with (0.2, 2) agrees to 2 digits).
  EXPECT_NEAR(unit_error, 1.37e-2, 0.02 * 1.37e-2);
}

// Collocation points very close to edges: level 6 of the tetrahedron (n = 16384, h ~ 0.02). The
// centroids of the elements along an edge lie h_perp/3 from the neighbouring facet, where the
// kernel is nearly singular. For those rows: the exact row sums (closed form over all n elements)
// must equal rho, and the fast rows must match the exact rows (v = 1 and a random v).
TEST(StressNumerics, CollocationPointsNextToEdges) {
  const Scene scene = constant_scene(geometry::make_tetrahedron());
  const Collocation col(scene, 6);
  const Index n = col.size();
  const auto elements = col.tree().elements();
  const auto& mesh = scene.mesh();
  // Distance of P to the nearest edge of the input mesh.
  auto edge_distance = [&](const Vec3& P) {
    double d = std::numeric_limits<double>::infinity();
    for (const auto& t : mesh.triangles)
      for (int k = 0; k < 3; ++k) {
        const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[static_cast<std::size_t>(k)])];
        const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[static_cast<std::size_t>((k + 1) % 3)])];
        const double s = std::clamp((P - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
        d = std::min(d, (P - (a + s * (b - a))).norm());
      }
    return d;
  };
  std::vector<std::pair<double, Index>> by_distance;
  for (Index i = 0; i < n; ++i) by_distance.emplace_back(edge_distance(col.collocation_point(i)), i);
  std::sort(by_distance.begin(), by_distance.end());
  const std::size_t rows = 96;  // the 96 points nearest to an edge (the corners' elements first)
  const double h = col.tree().mesh_size();
  report("tetrahedron level 6 h", h);
  report("tetrahedron level 6 nearest edge distance / h", by_distance.front().first / h);
  EXPECT_LT(by_distance[rows - 1].first, 0.35 * h);

  const FastOperator fast(col, FastOptions{});
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(n), wave = random_vector(n, 11);
  Eigen::VectorXd f1, f2;
  fast.apply(ones, f1);
  fast.apply(wave, f2);
  ASSERT_TRUE(f1.allFinite() && f2.allFinite());
  double worst_row_sum = 0, worst_fast = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    const Index i = by_distance[r].second;
    const Vec3& P = col.collocation_point(i);
    double exact1 = 0, exact2 = 0;
    for (Index j = 0; j < n; ++j) {
      const auto& e = elements[static_cast<std::size_t>(j)];
      if (e.facet == col.facet(i)) continue;  // coplanar: exactly 0 (section 4.2 case (a))
      const double kij = kRho * quadrature::form_factor(P, col.normal(i), e.vertex[0], e.vertex[1], e.vertex[2], e.normal);
      ASSERT_TRUE(std::isfinite(kij) && kij >= 0) << "row " << i << " element " << j;
      exact1 += kij;
      exact2 += kij * wave[j];
    }
    worst_row_sum = std::max(worst_row_sum, std::abs(exact1 - kRho));
    worst_fast = std::max({worst_fast, std::abs(f1[i] - exact1) / kRho, std::abs(f2[i] - exact2) / kRho});
  }
  const FastSelfCheck check = fast.self_check(64);
  report("tetrahedron level 6 edge rows: exact row-sum defect", worst_row_sum);
  report("tetrahedron level 6 edge rows: fast vs exact (rel. to rho)", worst_fast);
  report("tetrahedron level 6 fast self-check", check.relative_error);
  report("tetrahedron level 6 fast max|K1 - rho|", (f1.array() - kRho).abs().maxCoeff());
  // n = 16384 terms per row: rounding ~ n eps ~ 4e-12 at worst, 1e-11 with margin.
  EXPECT_LT(worst_row_sum, 1e-11);
  EXPECT_LT(worst_fast, kFastTol);
  EXPECT_LT(check.relative_error, kFastTol);
  EXPECT_LT((f1.array() - kRho).abs().maxCoeff(), kFastTol * kRho);
}

// Taylor degree M = 0..8 and 12 (the maximum): the far field's error must shrink with M and stay
// finite, with no blow-up from the powers (Q - A)^alpha or from cancellation. Checked on the unit
// cube and on the cube scaled by 1e-6 and 1e6 and moved by 1e6 (where expansions in global
// monomials Q^alpha would lose everything). Known answer: K_n is dimensionless, so the fast product
// of a fixed vector must be the unit cube's up to the rounding of the placed coordinates at every
// M (expansions are in local plane coordinates about A(tau)); bounds as in CubeScaledAndTranslated.
TEST(StressNumerics, TaylorDegreeUpToEightAndBeyond) {
  const int level = 3;  // n = 768
  struct Placement {
    const char* name;
    double scale;
    Vec3 offset;
    double product_tol;
  };
  const std::vector<Placement> placements = {{"unit", 1.0, Vec3::Zero(), 0.0},
                                             {"x1e-6", 1e-6, Vec3::Zero(), 1e-13},
                                             {"x1e6", 1e6, Vec3::Zero(), 1e-13},
                                             {"+1e6", 1.0, Vec3(1e6, -1e6, 1e6), 1e-8}};
  const std::vector<int> degrees = {0, 2, 4, 6, 8, 12};
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(12 << (2 * level)), v = random_vector(12 << (2 * level), 3);
  std::vector<std::pair<Eigen::VectorXd, Eigen::VectorXd>> unit_products;
  for (const Placement& p : placements) {
    Scene scene = make_paper_cube_scene(p.scale, p.offset);
    scene.set_emissivity(1.0);  // no manufactured E needed here
    const Collocation col(scene, level);
    double previous = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < degrees.size(); ++k) {
      const int M = degrees[k];
      FastOptions o;
      o.degree = M;
      const FastOperator fast(col, o);
      const double err = fast.self_check(128).relative_error;
      Eigen::VectorXd y1, y2;
      fast.apply(ones, y1);
      fast.apply(v, y2);
      const std::string tag = std::string("cube ") + p.name + " M=" + std::to_string(M);
      report(tag + " self-check", err);
      ASSERT_TRUE(std::isfinite(err) && y1.allFinite() && y2.allFinite()) << tag;
      // Shrinks with M until rounding (~1e-13 relative for sums of n terms) is reached.
      EXPECT_LT(err, std::max(previous, 1e-12)) << tag;
      previous = err;
      if (p.product_tol == 0) {
        unit_products.emplace_back(y1, y2);
      } else {
        const auto& [u1, u2] = unit_products[k];
        const double diff = std::max((y1 - u1).lpNorm<Eigen::Infinity>() / u1.lpNorm<Eigen::Infinity>(),
                                     (y2 - u2).lpNorm<Eigen::Infinity>() / u2.lpNorm<Eigen::Infinity>());
        report(tag + " product vs unit cube", diff);
        EXPECT_LT(diff, p.product_tol) << tag;
      }
    }
    // M = 8 with eta = 0.2: remainder ~ eta^9 ~ 5e-7 times a moderate constant.
    EXPECT_LT(previous, 1e-6) << p.name;
  }
}

// Scenes at the far ends of the accepted range (validation accepts lengths 1e-75 .. 1e75): the
// dense path is exact there (row sums = rho to rounding, measured at 1e+-150). The fast far field
// works in the length unit 2^k ~ diameter (exact scaling; G dS is scale-invariant): before that,
// it worked in absolute lengths and overflowed (NaN products from |scale| >= 1e80 at M = 2 and
// from 1e40 at M = 12), and self_check reported 0 (NaN comparisons); self_check is NaN-aware now.
TEST(StressNumerics, FastSolveAtExtremeScales) {
  for (double s : {1e-70, 1e70}) {
    TriangleMesh cube = geometry::make_cube();
    for (Vec3& v : cube.vertices) v *= s;
    const Scene scene = constant_scene(cube);
    const Collocation col(scene, 2);
    FastOptions o;
    o.degree = 12;
    const FastOperator fast(col, o);
    SolverOptions opt;
    opt.tolerance = 1e-10;
    const SolveResult r = solve(fast, col.emissivity(), opt, scene.max_reflectivity());
    ASSERT_TRUE(r.u.allFinite()) << s;
    EXPECT_LT((r.u.array() - kC).abs().maxCoeff(), 1e-6) << s;  // M = 12: product error ~1e-12
    std::ostringstream name;
    name << "cube x" << s << " M=12 max|u-c|";
    report(name.str(), (r.u.array() - kC).abs().maxCoeff());
  }
}

// The far field works in a length unit ~ the diameter (a power of two): the same accuracy at any
// scene size validation accepts (lengths 1e-75 .. 1e75), for M = 2 and M = 12.
TEST(StressNumerics, FastOperatorIsScaleFree) {
  for (double s : {1e-70, 1e-40, 1e40, 1e70})
    for (int M : {2, 12}) {
      TriangleMesh cube = geometry::make_cube();
      for (Vec3& v : cube.vertices) v *= s;
      const Scene scene = constant_scene(cube);
      const Collocation col(scene, 2);
      FastOptions o;
      o.degree = M;
      const FastOperator fast(col, o);
      Eigen::VectorXd ones = Eigen::VectorXd::Ones(col.size()), y;
      fast.apply(ones, y);
      EXPECT_TRUE(y.allFinite()) << s << " M " << M;
      const double check = fast.self_check(16).relative_error;
      EXPECT_TRUE(std::isfinite(check) && check < kFastTol) << s << " M " << M << ": " << check;
      EXPECT_LT((y.array() - kRho).abs().maxCoeff(), kFastTol) << s << " M " << M;
    }
}

// The largest cube level that runs in seconds in a test (level 6, n = 49,152) with the fast method
// and the automatic solver, on the constant solution: ||u - c|| <= c d / (1 - rho - d) where d is
// the fast operator's row-sum defect max |K 1 - rho| ((I - K)(u - c) = c (K 1 - rho 1)). The largest
// levels that fit in this machine's memory are reported (refused beyond, see test_memory_refusal).
TEST(StressNumerics, LargestLevelInSeconds) {
  int largest_tree = 0;
  while (largest_tree < 14 &&
         geometry::ClusterTree::estimate_bytes(12, largest_tree + 1) <= geometry::ClusterTree::default_memory_limit())
    ++largest_tree;
  int largest_dense = 0;
  while (largest_dense < 14 && DenseOperator::matrix_bytes(static_cast<Index>(12) << (2 * (largest_dense + 1))) <=
                                   geometry::ClusterTree::default_memory_limit())
    ++largest_dense;
  report("cube: largest level whose cluster tree fits in memory", largest_tree);
  report("cube: largest level whose dense matrix fits in memory", largest_dense);

  const int level = 6;
  const Scene scene = constant_scene(geometry::make_cube());
  const Collocation col(scene, level);
  const FastOperator fast(col, FastOptions{});
  Eigen::VectorXd ones = Eigen::VectorXd::Ones(col.size()), K1;
  fast.apply(ones, K1);
  ASSERT_TRUE(K1.allFinite());
  const double defect = (K1.array() - kRho).abs().maxCoeff();
  SolverOptions opt;
  opt.tolerance = 1e-12;
  const SolveResult r = solve(fast, col.emissivity(), opt, scene.max_reflectivity());
  ASSERT_TRUE(r.u.allFinite());
  const double err = (r.u.array() - kC).abs().maxCoeff();
  const double bound = kC * defect / (1 - kRho - defect);
  report("cube level 6 n=49152 fast row-sum defect", defect);
  report("cube level 6 n=49152 max|u-c|", err);
  report("cube level 6 n=49152 fast self-check", fast.self_check(32).relative_error);
  EXPECT_LT(defect, kFastTol * kRho);
  EXPECT_LE(err, bound * 1.01 + 1e-10);
}

}  // namespace

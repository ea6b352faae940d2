// Automatic parameters: the rule of auto_parameters.hpp keeps the solution
// within 5% of the discretization error, is deterministic, and refuses bad input; the dense matrix
// where the fast method's far field is no cheaper (few elements per root, high Taylor degree), on
// convex and occluded scenes, the fast method for the paper's cube.
#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/paper/cube_example.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/scene_validation.hpp>
#include <panelrad/geometry/validation.hpp>
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/solvers.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <utility>
#include <vector>

using namespace panelrad;

namespace {

// Neumann to 1e-9 relative: the iteration error (<= 3e-9) is negligible against the 5% margins
// compared below (>= 5e-5 for n <= 3072).
SolverOptions tight_solver() {
  SolverOptions s;
  s.tolerance = 1e-9;
  return s;
}

Scene prism_scene() {
  geometry::TriangleMesh mesh = geometry::make_builtin("prism:6");
  EXPECT_TRUE(geometry::validate_closed_convex(mesh).valid);
  Scene scene(std::move(mesh));
  std::vector<double> rho(8, 0.5);  // six sides 0.5, bottom cap 0.3, top cap 0.4
  rho[6] = 0.3;
  rho[7] = 0.4;
  scene.set_reflectivity(std::move(rho));
  scene.set_manufactured_solution([](const Vec3& Q, Index) { return Q.squaredNorm(); });
  return scene;
}

struct Outcome {
  double reference_error = 0;  // dense, exact near field: the discretization error
  double deviation = 0;        // max_k |u_auto - u_ref|
  double error = 0;            // max_k |u - u_auto|
};

/// geometry::make_icosphere, counter-clockwise seen from outside (`inward`: from inside).
geometry::TriangleMesh icosphere(int subdivisions, bool inward = false) {
  geometry::TriangleMesh m = geometry::make_icosphere(subdivisions);
  if (inward)
    for (auto& tr : m.triangles) std::swap(tr[1], tr[2]);
  return m;
}

/// The closed cube [-c, c]^3, two triangles per face (each face one more facet), counter-clockwise
/// seen from outside (`inward`: from inside), appended to `m`.
void append_cube(geometry::TriangleMesh& m, double c, bool inward) {
  const Index base = static_cast<Index>(m.vertices.size());
  for (int k = 0; k < 8; ++k) m.vertices.emplace_back(k & 1 ? c : -c, k & 2 ? c : -c, k & 4 ? c : -c);
  // Corners by bits (x, y, z); each face counter-clockwise seen from outside.
  const int faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& f : faces) {
    std::array<Index, 3> t1 = {base + f[0], base + f[1], base + f[2]}, t2 = {base + f[0], base + f[2], base + f[3]};
    if (inward) {
      std::swap(t1[1], t1[2]);
      std::swap(t2[1], t2[2]);
    }
    m.triangles.push_back(t1);
    m.triangles.push_back(t2);
    m.facet_of_triangle.insert(m.facet_of_triangle.end(), 2, m.num_facets++);
  }
}

Outcome solve_both(const Scene& scene, int level, const OperatorOptions& chosen) {
  const Collocation col(scene, level);
  OperatorOptions reference;  // dense, exact
  const auto K_ref = make_operator(col, reference);
  const auto K = make_operator(col, chosen);
  const SolveResult ref = solve(*K_ref, col.emissivity(), tight_solver(), scene.max_reflectivity());
  const SolveResult got = solve(*K, col.emissivity(), tight_solver(), scene.max_reflectivity());
  return {col.max_error(ref.u), (got.u - ref.u).lpNorm<Eigen::Infinity>(), col.max_error(got.u)};
}

}  // namespace

TEST(AutoParameters, ProblemSizeMatchesTheClusterTree) {
  const Scene cube = make_paper_cube_scene();
  for (int level = 0; level <= 3; ++level) {
    const ProblemSize s = problem_size(cube.mesh(), level);
    const Collocation col(cube, level);
    EXPECT_EQ(s.n, col.size());
    EXPECT_EQ(s.roots, static_cast<Index>(cube.mesh().triangles.size()));
    // Seen from inside, each triangle faces the 10 of the other faces, not its coplanar twin.
    EXPECT_DOUBLE_EQ(s.facing, 10.0 / 11.0);
    EXPECT_DOUBLE_EQ(s.mesh_size, col.tree().mesh_size());
    EXPECT_DOUBLE_EQ(s.diameter, col.tree().diameter());
    // The cube's equivalent level is its level (up to rounding of sqrt and log2).
    EXPECT_NEAR(s.equivalent_level(), level, 1e-12);
  }
}

TEST(AutoParameters, DeterministicAndValid) {
  const Scene cube = make_paper_cube_scene();
  for (int level = 0; level <= 8; ++level) {
    const ProblemSize s = problem_size(cube.mesh(), level);
    const OperatorOptions a = choose_parameters(s), b = choose_parameters(s);
    EXPECT_EQ(a.method, b.method);
    EXPECT_EQ(a.near.rule, b.near.rule);
    EXPECT_EQ(a.eta, b.eta);
    EXPECT_EQ(a.degree, b.degree);
    EXPECT_TRUE(a.method == OperatorMethod::dense || a.method == OperatorMethod::fast);
    EXPECT_EQ(a.near.rule, NearRule::exact);
    if (a.method == OperatorMethod::fast) {
      EXPECT_GT(a.eta, 0.0);
      EXPECT_LT(a.eta, 1.0);
      EXPECT_GE(a.degree, 0);
      EXPECT_LE(a.degree, 12);
    }
    // A looser margin m scales delta* by m / 0.05 (so the self-check's threshold too) and takes
    // the setting of lambda - log2(m / 0.05): never a stricter one (M no higher, eta no smaller).
    const OperatorOptions loose = choose_parameters(s, 0.2);
    if (a.method == OperatorMethod::fast) {
      ASSERT_EQ(loose.method, OperatorMethod::fast) << "level " << level;
      EXPECT_LE(loose.degree, a.degree) << "level " << level;
      EXPECT_GE(loose.eta, a.eta) << "level " << level;
    }
    EXPECT_DOUBLE_EQ(self_check_threshold(s, 0.5, 0.2), 4 * self_check_threshold(s, 0.5));
    EXPECT_THROW(self_check_threshold(s, 0.5, 0.04), std::invalid_argument);
  }
  // The smallest sizes are solved densely, the large ones with the fast method.
  EXPECT_EQ(choose_parameters(problem_size(cube.mesh(), 1)).method, OperatorMethod::dense);
  EXPECT_EQ(choose_parameters(problem_size(cube.mesh(), 6)).method, OperatorMethod::fast);
}

TEST(AutoParameters, RefusesBadInput) {
  const Scene cube = make_paper_cube_scene();
  const ProblemSize ok = problem_size(cube.mesh(), 2);
  EXPECT_THROW(choose_parameters(ok, 0.01), std::invalid_argument);  // tighter than measured
  EXPECT_THROW(choose_parameters(ok, std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
  ProblemSize bad = ok;
  bad.n = 0;
  EXPECT_THROW(choose_parameters(bad), std::invalid_argument);
  bad = ok;
  bad.mesh_size = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(choose_parameters(bad), std::invalid_argument);
  bad = ok;
  bad.mesh_size = -1;
  EXPECT_THROW(choose_parameters(bad), std::invalid_argument);
  bad = ok;
  bad.mesh_size = 2 * bad.diameter;
  EXPECT_THROW(choose_parameters(bad), std::invalid_argument);
  bad = ok;
  bad.roots = 0;
  EXPECT_THROW(choose_parameters(bad), std::invalid_argument);
  bad.roots = bad.n + 1;
  EXPECT_THROW(choose_parameters(bad), std::invalid_argument);
  bad = ok;
  bad.facing = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(choose_parameters(bad), std::invalid_argument);
  bad.facing = 1.5;
  EXPECT_THROW(choose_parameters(bad), std::invalid_argument);
  EXPECT_THROW(choose_parameters(ok, 0.05, 0.5, Visibility::automatic), std::invalid_argument);
  EXPECT_THROW(problem_size(cube.mesh(), -1), std::invalid_argument);
  EXPECT_THROW(problem_size(geometry::TriangleMesh{}, 1), std::invalid_argument);
}

TEST(AutoParameters, TightenIsStricterAndStops) {
  OperatorOptions o;
  o.method = OperatorMethod::fast;
  o.eta = 0.5;
  o.degree = 5;
  o = tighten_parameters(o);
  EXPECT_EQ(o.degree, 6);
  EXPECT_EQ(o.eta, 0.5);
  o = tighten_parameters(o);
  EXPECT_EQ(o.degree, 6);
  EXPECT_EQ(o.eta, 0.3);
  o.eta = 0.1;
  const OperatorOptions last = tighten_parameters(o);
  EXPECT_EQ(last.eta, 0.1);
  EXPECT_EQ(last.degree, 6);
  OperatorOptions dense;
  EXPECT_EQ(tighten_parameters(dense).method, OperatorMethod::dense);
}

// The criterion of the header, at the cube's levels 2-4 (dense at 2 and 3, fast at 4) and the
// hexagonal prism's level 3 (fast, n = 1280): the automatic solution differs from the dense
// exact one by at most 5% of the discretization error, so its error is within 5% of it.
TEST(AutoParameters, WithinFivePercentOfTheDiscretizationError) {
  const Scene cube = make_paper_cube_scene();
  bool saw_fast = false;
  for (int level = 2; level <= 4; ++level) {
    const OperatorOptions chosen = choose_parameters(problem_size(cube.mesh(), level));
    saw_fast = saw_fast || chosen.method == OperatorMethod::fast;
    const Outcome r = solve_both(cube, level, chosen);
    SCOPED_TRACE("cube level " + std::to_string(level) + ": " + describe_parameters(chosen));
    EXPECT_LE(r.deviation, 0.05 * r.reference_error);
    EXPECT_LE(r.error, 1.05 * r.reference_error);
  }
  EXPECT_TRUE(saw_fast) << "levels 2-4 should exercise the fast method at least once";
  const Scene prism = prism_scene();
  const OperatorOptions chosen = choose_parameters(problem_size(prism.mesh(), 3));
  EXPECT_EQ(chosen.method, OperatorMethod::fast);
  const Outcome r = solve_both(prism, 3, chosen);
  EXPECT_LE(r.deviation, 0.05 * r.reference_error) << describe_parameters(chosen);
}

// The same check can fail: the loosest setting of the sweep (eta 0.5, M 1) is far outside 5%.
TEST(AutoParameters, TheCriterionRejectsACheapSetting) {
  const Scene cube = make_paper_cube_scene();
  OperatorOptions cheap;
  cheap.method = OperatorMethod::fast;
  cheap.eta = 0.5;
  cheap.degree = 1;
  const Outcome r = solve_both(cube, 3, cheap);
  EXPECT_GT(r.deviation, 0.05 * r.reference_error);
}

// A setting whose self-check fails is tightened until the check passes.
TEST(AutoParameters, FailedSelfCheckTightensTheParameters) {
  panelrad::CubeRunOptions o;
  o.min_level = o.max_level = 3;
  o.op.method = OperatorMethod::fast;
  o.op.eta = 0.5;
  o.op.degree = 1;  // far outside 5% (see the header's table)
  o.tighten_on_failed_check = true;
  const auto rows = panelrad::run_paper_cube(o);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_GT(rows[0].tightened, 0);
  const panelrad::ProblemSize size = panelrad::problem_size(panelrad::make_paper_cube_scene().mesh(), 3);
  EXPECT_LE(rows[0].checked_product_error, panelrad::self_check_threshold(size));
  EXPECT_GT(rows[0].degree, 1);
}

// The conditioning (auto_parameters.hpp): at rho_max the target delta* shrinks by
// A = rho_max / (1 - rho_max), which the rule meets as the target of log2 A levels finer; at the
// cube's rho_max 0.5 (A = 1), and below it, the choice is the one for the cube.
TEST(AutoParameters, ConditioningAsksForTheTargetOfAFinerLevel) {
  const Scene cube = make_paper_cube_scene();
  for (int level = 4; level <= 6; ++level) {
    const ProblemSize s = problem_size(cube.mesh(), level);
    EXPECT_EQ(choose_parameters(s, 0.05, 0.5), choose_parameters(s));
    EXPECT_EQ(choose_parameters(s, 0.05, 0.2), choose_parameters(s));
    // rho_max 0.8: A = 4, two levels finer exactly.
    EXPECT_EQ(describe_parameters(choose_parameters(s, 0.05, 0.8)),
              describe_parameters(choose_parameters(problem_size(cube.mesh(), level + 2))));
  }
  // rho_max 0.9 at level 4 (lambda_eff 7.17) is stricter than at rho_max 0.5: a higher M at eta 0.4.
  const OperatorOptions loose = choose_parameters(problem_size(cube.mesh(), 4));
  const OperatorOptions strict = choose_parameters(problem_size(cube.mesh(), 4), 0.05, 0.9);
  EXPECT_EQ(strict.method, OperatorMethod::fast);
  EXPECT_LE(strict.eta, loose.eta);
  EXPECT_GT(strict.degree, loose.degree);
  // The cube at the sizes the README measures: n = 3072 and 12288 (0.4, 6), 49152 (0.4, 8).
  EXPECT_EQ(describe_parameters(choose_parameters(problem_size(cube.mesh(), 5))), "fast, exact near field, eta 0.4, M 6");
  EXPECT_EQ(describe_parameters(choose_parameters(problem_size(cube.mesh(), 6))), "fast, exact near field, eta 0.4, M 8");
}

// Dense or fast (auto_parameters.hpp, W): the work ratio of the fast method's far field to the
// dense matrix, phi min(n, n0 + 20 / eta^2) T(M) / n; the dense matrix from W >= 11.
TEST(AutoParameters, WorkRatioCountsRootsTaylorTermsAndFacingPairs) {
  ProblemSize s;
  s.n = 5120;
  s.roots = 5120;
  s.mesh_size = 0.05;
  s.diameter = 2;
  s.facing = 0.5;
  // Level 0: every root a far pair at most, so W is the number of Taylor terms T(M) = 28 at M = 6.
  EXPECT_DOUBLE_EQ(fast_to_dense_work(s, 0.4, 6, Visibility::unoccluded), 28.0);
  // With V, only the facing half of the pairs.
  EXPECT_DOUBLE_EQ(fast_to_dense_work(s, 0.4, 6, Visibility::occluded), 14.0);
  // 16 elements per root: (320 + 20 / 0.16) / 5120 of the pairs, 66 terms at M = 10.
  s.roots = 320;
  EXPECT_DOUBLE_EQ(fast_to_dense_work(s, 0.4, 10, Visibility::unoccluded), (320 + 125.0) / 5120 * 66);
  EXPECT_THROW(fast_to_dense_work(s, 0.4, 6, Visibility::automatic), std::invalid_argument);
  EXPECT_THROW(fast_to_dense_work(s, 0, 6, Visibility::unoccluded), std::invalid_argument);
  s.roots = 0;
  EXPECT_THROW(fast_to_dense_work(s, 0.4, 6, Visibility::unoccluded), std::invalid_argument);
}

// A convex surface of many facets: at level 0 the fast method has no cluster larger than an
// element, so the dense matrix is cheaper at any reflectivity (measured n = 5120: 2.3 s and 210 MB
// against 3.5 s and 141 MB at M = 6, 13 s and 6.7 GB at M = 10); at level 1 from M = 8; from
// level 2 on the fast method stays.
TEST(AutoParameters, DenseWhereTheFarFieldIsNoCheaperThanTheMatrix) {
  const auto choose = [](const geometry::TriangleMesh& mesh, int level, double rho_max, Visibility v) {
    return choose_parameters(problem_size(mesh, level), 0.05, rho_max, v);
  };
  geometry::TriangleMesh ico2 = icosphere(2), ico3 = icosphere(3), ico4 = icosphere(4);
  for (geometry::TriangleMesh* m : {&ico2, &ico3, &ico4}) ASSERT_TRUE(geometry::validate_closed_convex(*m).valid);
  ASSERT_EQ(ico4.triangles.size(), 5120u);
  for (double rho : {0.5, 0.8, 0.9}) {
    SCOPED_TRACE("rho_max " + std::to_string(rho));
    // n = 5120 at level 0: dense, with V or without (the roots of a convex surface face each other).
    EXPECT_EQ(choose(ico4, 0, rho, Visibility::unoccluded).method, OperatorMethod::dense);
    EXPECT_EQ(choose(ico4, 0, rho, Visibility::occluded).method, OperatorMethod::dense);
    EXPECT_EQ(choose(ico3, 0, rho, Visibility::unoccluded).method, OperatorMethod::dense);
    // 16 elements per root: fast.
    EXPECT_EQ(choose(ico2, 2, rho, Visibility::unoccluded).method, OperatorMethod::fast);
  }
  // 4 elements per root: fast at M = 6 (rho 0.5, W 7.7), dense at M = 8 and 10 (W 12.4 and 18.1).
  const OperatorOptions loose = choose(ico3, 1, 0.5, Visibility::unoccluded);
  EXPECT_EQ(describe_parameters(loose), "fast, exact near field, eta 0.4, M 6");
  EXPECT_LT(fast_to_dense_work(problem_size(ico3, 1), loose.eta, loose.degree, Visibility::unoccluded), 11);
  EXPECT_EQ(choose(ico3, 1, 0.8, Visibility::unoccluded).method, OperatorMethod::dense);
  EXPECT_EQ(choose(ico3, 1, 0.9, Visibility::unoccluded).method, OperatorMethod::dense);
  // Below the crossover: n = 1280 at level 1 (W 9.7) stays fast.
  EXPECT_EQ(choose(ico2, 1, 0.5, Visibility::unoccluded).method, OperatorMethod::fast);
  // The paper's cube keeps the fast method above n = 768 at every reflectivity measured.
  const Scene cube = make_paper_cube_scene();
  for (int level = 4; level <= 8; ++level)
    for (double rho : {0.5, 0.9}) {
      EXPECT_EQ(choose(cube.mesh(), level, rho, Visibility::unoccluded).method, OperatorMethod::fast) << level;
      EXPECT_EQ(choose(cube.mesh(), level, rho, Visibility::occluded).method, OperatorMethod::fast) << level;
    }
  EXPECT_THROW(choose(cube.mesh(), 4, 0.5, Visibility::automatic), std::invalid_argument);
}

// With V the facing fraction decides: 1280 sphere facets seen from outside inside a cube room see
// none of each other (the fast method's coverings skip them as hidden: the fast method), the same
// facets seen from inside, as the room around a small box, all see each other (the dense matrix).
TEST(AutoParameters, OccludedScenesCountOnlyFacingRoots) {
  geometry::TriangleMesh object_in_room = icosphere(3);
  append_cube(object_in_room, 2, true);
  geometry::TriangleMesh room_around_box = icosphere(3, true);
  append_cube(room_around_box, 0.3, false);
  for (geometry::TriangleMesh* m : {&object_in_room, &room_around_box}) {
    const geometry::SceneValidationReport r = geometry::validate_scene(*m);
    ASSERT_TRUE(r.valid) << r.message;
    ASSERT_EQ(r.shape, geometry::SceneShape::general);
  }
  const ProblemSize object = problem_size(object_in_room, 0), room = problem_size(room_around_box, 0);
  EXPECT_LT(object.facing, 0.01);
  EXPECT_GT(room.facing, 0.95);
  EXPECT_EQ(choose_parameters(object, 0.05, 0.5, Visibility::occluded).method, OperatorMethod::fast);
  EXPECT_EQ(choose_parameters(room, 0.05, 0.5, Visibility::occluded).method, OperatorMethod::dense);
  // Without V every pair would count: the dense matrix for both.
  EXPECT_EQ(choose_parameters(object, 0.05, 0.5, Visibility::unoccluded).method, OperatorMethod::dense);
}

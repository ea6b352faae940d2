// The operators with the line-of-sight function V(P, Q) of (1), on general (non-convex) scenes,
// against independent truths:
//  - closed enclosures (a room with a box, an L-shaped room, a room with floating boxes): every
//    ray from a point's front side ends on the front of some face, so the visible form factors
//    of a row sum to 1 and the rows of K_n to rho; E = c (1 - rho) then has the solution u = c;
//  - direct lighting under a blocker: u_floor(P) = rho_f F_vis(P) with F_vis the closed-form
//    rectangle configuration factor of the emitter minus that of its part in the blocker's
//    shadow (configuration_factors.hpp), independent of the contour formula and the clipping;
//  - convex scenes: V = 1 is taken (no visibility work), and computing V anyway changes nothing;
//  - the fast product against the dense one with visibility at every level up to the dense limit;
//  - the energy balance of a closed scene, which shrinks as n grows.
#include <panelrad/geometry/bounding_box.hpp>
#include <panelrad/geometry/mesh_io.hpp>
#include <panelrad/geometry/scene_validation.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/radiosity_solver.hpp>
#include <panelrad/solve/scene_solver.hpp>
#include <panelrad/support/resources.hpp>

#include "configuration_factors.hpp"
#include "occluded_scenes.hpp"
#include "test_scenes.hpp"
#include "validated_meshes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

namespace panelrad {
namespace {

using geometry::SceneShape;

/// A validated general scene with rho and E per facet from functions of the facet.
Scene general_scene(geometry::TriangleMesh mesh, const std::function<double(Index)>& rho,
                    const std::function<double(Index)>& E) {
  Scene scene(std::move(mesh));
  EXPECT_EQ(scene.shape(), SceneShape::general) << scene.mesh().source;
  std::vector<double> r(static_cast<std::size_t>(scene.num_facets())), e(r.size());
  for (Index f = 0; f < scene.num_facets(); ++f) {
    r[static_cast<std::size_t>(f)] = rho(f);
    e[static_cast<std::size_t>(f)] = E(f);
  }
  scene.set_reflectivity(r);
  scene.set_emissivity(e);
  return scene;
}

/// rho varying by facet in [0.2, 0.7], so that a wrong row cannot hide behind a constant.
double facet_rho(Index f) { return 0.2 + 0.1 * static_cast<double>(f % 6); }

std::vector<geometry::TriangleMesh> closed_enclosures() {
  return {testing::room_with_box(), testing::l_shaped_room(), testing::room_with_floating_boxes()};
}

OperatorOptions dense_options() {
  OperatorOptions o;
  o.method = OperatorMethod::dense;
  return o;
}

using testing::fast_options;

// Dense with exact clipping: |row sum - rho_i| <= 1e-10. Each entry is a closed-form integral over
// polygons computed in double precision (relative error ~1e-14 per form factor, a few pieces per
// element), and the margin of the shadow tests drops slivers of relative size 1e-12
// (geometry/occluders.hpp): over n <= 1536 entries the sum is off by far less than 1e-10.
TEST(OccludedDense, RowsSumToRhoInClosedEnclosures) {
  for (geometry::TriangleMesh mesh : closed_enclosures()) {
    const std::string name = mesh.source;
    const Scene scene = general_scene(std::move(mesh), facet_rho, [](Index) { return 1.0; });
    EXPECT_TRUE(scene.closed()) << name;
    for (int level = 0; level <= 2; ++level) {
      const Collocation col(scene, level);
      const auto K = make_operator(col, dense_options(), Visibility::occluded);
      const auto& dense = dynamic_cast<const DenseOperator&>(*K);
      const VisibilityWork work = visibility_work(*K);
      EXPECT_TRUE(work.computed);
      EXPECT_GT(work.hidden_pairs, 0u) << name << ": something must be hidden in these scenes";
      EXPECT_GT(work.clipped_elements, 0u) << name;
      double worst = 0;
      Index worst_row = -1;
      ASSERT_TRUE(dense.matrix().allFinite()) << name << " level " << level;
      for (Index i = 0; i < col.size(); ++i) {
        const double d = std::abs(dense.matrix().row(i).sum() - col.reflectivity()[i]);
        if (d > worst) {
          worst = d;
          worst_row = i;
        }
        ASSERT_GE(dense.matrix().row(i).minCoeff(), 0.0) << name << " row " << i;
      }
      EXPECT_LT(worst, 1e-10) << name << " level " << level << " n " << col.size() << " row " << worst_row;
    }
  }
}

// V = 1 on the same scenes: the row sums still equal rho (the unclamped kernel integrates the
// signed solid angle, and over a closed surface a hidden face pair cancels: the box's near side
// counts +, its far side -, the wall behind it +), but entries turn negative where a face is seen
// from its back. So the row-sum identity alone cannot tell V apart; with the entries' sign (above)
// it does, and the shadow test below checks V entry by entry.
TEST(OccludedDense, WithoutVisibilityEntriesTurnNegative) {
  const Scene scene = general_scene(testing::room_with_box(), facet_rho, [](Index) { return 1.0; });
  const Collocation col(scene, 1);
  const DenseOperator unoccluded(col, NearFieldOptions{});
  double worst = 0;
  for (Index i = 0; i < col.size(); ++i)
    worst = std::max(worst, std::abs(unoccluded.matrix().row(i).sum() - col.reflectivity()[i]));
  EXPECT_LT(worst, 1e-10);
  EXPECT_LT(unoccluded.matrix().minCoeff(), -1e-3);
}

// E = c (1 - rho): u = c exactly. Dense within 1e-9 (the row sums above, times the iteration's
// 1 / (1 - rho_max) = 1 / 0.3, with the solver's tolerance set to 1e-13); fast within the accuracy
// the solver states for it: the self-check value delta bounds ||u - u_f|| / ||u_f|| by
// delta rho_max / (1 - rho_max) (fast_operator.hpp), plus the iteration's tolerance; 2x margin
// for the sampled estimate. Fast at level 3 too, where the target clusters take the sources
// visible from all of them (target_clusters.hpp).
TEST(OccludedSolve, ConstantSolutionInClosedEnclosures) {
  const double c = 2.5;
  std::size_t target_sources = 0;
  for (geometry::TriangleMesh mesh : closed_enclosures()) {
    const std::string name = mesh.source;
    const Scene scene = general_scene(std::move(mesh), facet_rho, [&](Index f) { return c * (1 - facet_rho(f)); });
    for (const auto& [method, level] : {std::pair{OperatorMethod::dense, 2}, std::pair{OperatorMethod::fast, 2},
                                        std::pair{OperatorMethod::fast, 3}}) {
      SCOPED_TRACE(name + ", " + to_string(method) + ", level " + std::to_string(level));
      SolveOptions o;
      o.level = level;
      o.op = method == OperatorMethod::dense ? dense_options() : fast_options(0.4, 8);
      o.solver.tolerance = 1e-13;
      const RadiositySolver solver(scene, o);
      EXPECT_EQ(solver.info().visibility, Visibility::occluded);
      Eigen::VectorXd K1;
      solver.op().apply(Eigen::VectorXd::Ones(solver.n()), K1);
      ASSERT_TRUE(K1.allFinite()) << "H 1 is not finite";
      const ChannelSolve r = solver.solve(0);
      ASSERT_TRUE(r.converged()) << r.message;
      const double err = (r.u.array() - c).abs().maxCoeff() / c;
      if (method == OperatorMethod::dense) {
        EXPECT_LT(err, 1e-9) << name;
      } else {
        ASSERT_TRUE(solver.self_check().has_value());
        const double delta = solver.self_check()->relative_error;
        const double rho_max = 0.7;
        EXPECT_LT(err, 2 * delta * rho_max / (1 - rho_max) + 1e-12) << name << " delta " << delta;
        EXPECT_LT(err, 1e-4) << name;
        if (level == 3) {
          const FastStatistics& st = dynamic_cast<const FastOperator&>(solver.op()).statistics();
          EXPECT_GE(st.target_level, 0);
          target_sources += st.target_pairs;
        }
      }
    }
  }
  EXPECT_GT(target_sources, 0u) << "some target cluster at level 3 must take a visible source";
}

// Direct lighting under a blocker: floor points see the emitter (E = 1, rho = 0) past an opaque
// square (rho = E = 0), and the floor (rho_f) sees nothing else that is lit, so the collocation
// solution is u_i = rho_f F_vis(P_i) exactly (K^2 E = 0: the floor does not see itself). Dense
// with exact clipping: 1e-12 absolute (F <= 1; closed forms in double precision); fast: the far
// field's Taylor error, bounded by its self-check value delta times K|v| <= rho_f (v = u, |u| <= 1).
TEST(OccludedSolve, ShadowOfABlockerMatchesTheClosedForm) {
  const double rho_f = 0.5;
  const Scene scene = general_scene(
      testing::shadow_scene(), [&](Index f) { return f == 2 ? rho_f : 0.0; }, [](Index f) { return f == 0 ? 1.0 : 0.0; });
  EXPECT_FALSE(scene.closed());
  for (const OperatorMethod method : {OperatorMethod::dense, OperatorMethod::fast}) {
    for (int level = 1; level <= 3; ++level) {
      SolveOptions o;
      o.level = level;
      o.op = method == OperatorMethod::dense ? dense_options() : fast_options(0.4, 8);
      o.solver.tolerance = 1e-14;
      const RadiositySolver solver(scene, o);
      const ChannelSolve r = solver.solve(0);
      ASSERT_TRUE(r.converged()) << r.message;
      const Collocation& col = solver.collocation();
      double worst = 0, deepest = 1;  // deepest: the smallest fraction of the emitter's factor left
      int floor_points = 0;
      for (Index i = 0; i < col.size(); ++i) {
        if (col.facet(i) != 2) continue;
        ++floor_points;
        const Vec3& P = col.collocation_point(i);
        const double truth = rho_f * testing::shadow_scene_visible_factor(P.x(), P.y());
        worst = std::max(worst, std::abs(r.u[i] - truth));
        const double unshadowed =
            rho_f * testing::parallel_rectangle_factor(P.x(), P.y(), testing::shadow_scene_emitter(), 1.0);
        deepest = std::min(deepest, truth / unshadowed);
      }
      ASSERT_GT(floor_points, 0);
      // Some floor point is well in the shadow (at level 3 one is near the centre, where the
      // blocker hides the whole emitter).
      EXPECT_LT(deepest, level == 3 ? 0.25 : 0.9) << "level " << level;
      const double tol = method == OperatorMethod::dense ? 1e-12 : 2 * solver.self_check()->relative_error * rho_f + 1e-12;
      EXPECT_LT(worst, tol) << to_string(method) << " level " << level;
    }
  }
}

// Convex scenes: the automatic policy takes V = 1 with no visibility work at all; computing V
// anyway gives the same matrix (every pair is fully visible or coplanar: the same integrals).
TEST(OccludedConvex, ConvexScenesSkipVisibilityAndComputingItChangesNothing) {
  geometry::TriangleMesh mesh = geometry::make_builtin("cube");
  geometry::TriangleMesh reference = testing::validated_builtin("cube");
  const geometry::SceneValidationReport report = geometry::validate_scene(mesh);
  ASSERT_TRUE(report.valid) << report.message;
  EXPECT_EQ(report.shape, SceneShape::convex);
  EXPECT_EQ(mesh.vertices, reference.vertices);
  EXPECT_EQ(mesh.triangles, reference.triangles);
  Scene scene(mesh);
  scene.set_reflectivity(0.5);
  SolveOptions o;
  o.level = 2;
  const RadiositySolver automatic(scene, o);
  EXPECT_EQ(automatic.info().visibility, Visibility::unoccluded);
  EXPECT_FALSE(visibility_work(automatic.op()).computed);

  const Collocation col(scene, 2);
  const auto plain = make_operator(col, dense_options(), Visibility::unoccluded);
  const auto seen = make_operator(col, dense_options(), Visibility::occluded);
  const auto& a = dynamic_cast<const DenseOperator&>(*plain).matrix();
  const auto& b = dynamic_cast<const DenseOperator&>(*seen).matrix();
  // P's own plane is skipped as coplanar before any classification; on a convex surface nothing
  // else can be hidden.
  EXPECT_EQ(visibility_work(*seen).hidden_pairs, 0u);
  EXPECT_GT(visibility_work(*seen).visible_pairs, 0u);
  // 1e-14 absolute: entries are at most 1; fully visible entries are the same closed form, and an
  // entry classified partly visible by the margin is the sum of its pieces' closed forms.
  EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-14);

  // The fast operator with and without the occluders, both storing double coefficients (the
  // factory stores single precision with V: single_precision_far_field). With V a fully visible
  // admissible cluster of four elements is integrated exactly as its elements (visible_covering.hpp)
  // instead of by its far field, so the product with V is at least as close to the dense one.
  FastOptions f;
  f.eta = 0.5;
  f.degree = 6;
  const auto fast_plain = std::make_unique<FastOperator>(col, f);
  f.occluders = scene_occluders(col.tree());
  const auto fast_seen = std::make_unique<FastOperator>(col, f);
  EXPECT_TRUE(single_precision_far_field(Visibility::occluded));
  EXPECT_TRUE(single_precision_far_field(Visibility::unoccluded));  // both: far_field_costs
  Eigen::VectorXd v(col.size()), y0, y1;
  for (Index i = 0; i < col.size(); ++i) v[i] = std::cos(3.0 * col.collocation_point(i).x()) + 2;
  fast_plain->apply(v, y0);
  fast_seen->apply(v, y1);
  const Eigen::VectorXd yd = a * v;
  const double plain_error = (y0 - yd).cwiseAbs().maxCoeff(), seen_error = (y1 - yd).cwiseAbs().maxCoeff();
  EXPECT_GT(plain_error, 0);
  EXPECT_LE(seen_error, plain_error * (1 + 1e-9));
  // Fewer far pairs: the clusters of four elements went to the near field.
  EXPECT_LT(fast_seen->statistics().far_pairs, fast_plain->statistics().far_pairs);
}

// On a general scene V = 1 is refused, and so is a manufactured solution (integrated with V = 1).
TEST(OccludedSolve, UnoccludedAndManufacturedAreRefusedOnGeneralScenes) {
  Scene scene = general_scene(testing::l_shaped_room(), facet_rho, [](Index) { return 1.0; });
  SolveOptions o;
  o.level = 0;
  o.visibility = Visibility::unoccluded;
  try {
    const RadiositySolver solver(scene, o);
    FAIL() << "accepted V = 1 on a non-convex scene";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("convex"), std::string::npos) << e.what();
  }
  EXPECT_THROW(scene.set_manufactured_solution([](const Vec3&, Index) { return 1.0; }), std::logic_error);
  EXPECT_THROW((void)make_operator(Collocation(scene, 0), dense_options(), Visibility::automatic), std::invalid_argument);
}

// The operator factory refuses V = 1 on a general scene as the solver does, for either method:
// on the room with a box it would give K entries < 0 (WithoutVisibilityEntriesTurnNegative).
TEST(OccludedSolve, OperatorFactoryRefusesUnoccludedOnGeneralScenes) {
  const Scene scene = general_scene(testing::room_with_box(), facet_rho, [](Index) { return 1.0; });
  const Collocation col(scene, 1);
  ASSERT_EQ(scene.shape(), SceneShape::general);
  for (const OperatorOptions& options : {dense_options(), fast_options(0.5, 4)}) {
    try {
      (void)make_operator(col, options, Visibility::unoccluded);
      ADD_FAILURE() << "make_operator built V = 1 on a non-convex scene (" << to_string(options.method) << ")";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("V = 1"), std::string::npos) << what;
      EXPECT_NE(what.find("convex"), std::string::npos) << what;
      EXPECT_NE(what.find("occluded"), std::string::npos) << what;  // what to use instead
    }
  }
  // The row weights of H (with_row_weights) keep the scene's shape, and so the refusal.
  EXPECT_THROW((void)make_operator(col.with_row_weights(Eigen::VectorXd::Ones(col.size())), dense_options(),
                                   Visibility::unoccluded),
               std::invalid_argument);
  // The default visibility of make_operator is no way around it.
  EXPECT_THROW((void)make_operator(col, dense_options()), std::invalid_argument);
  EXPECT_NO_THROW((void)make_operator(col, dense_options(), Visibility::occluded));
}

// The fast product against the dense one with visibility, at every level up to n = 1536 (the dense
// matrix takes 19 MB there): max_i |(K_f v - K v)_i| / max_i (K|v|)_i is what the self-check
// estimates on sampled rows; over all rows it may be somewhat larger than the sampled value, so the
// bound is 4x the self-check's plus the far field's own scale at (0.4, M 8) on these scenes, 1e-4.
TEST(OccludedFast, AgreesWithDenseAtEveryLevel) {
  std::vector<geometry::TriangleMesh> scenes = closed_enclosures();
  scenes.push_back(testing::block_on_floor());
  scenes.push_back(testing::shadow_scene());
  for (geometry::TriangleMesh mesh : scenes) {
    const std::string name = mesh.source;
    const Scene scene = general_scene(std::move(mesh), facet_rho, [](Index) { return 1.0; });
    const Index n0 = static_cast<Index>(scene.mesh().triangles.size());
    for (int level = 0; (n0 << (2 * level)) <= 1536; ++level) {
      const Collocation col(scene, level);
      const auto dense = make_operator(col, dense_options(), Visibility::occluded);
      const auto fast = make_operator(col, fast_options(0.4, 8), Visibility::occluded);
      const auto& f = dynamic_cast<const FastOperator&>(*fast);
      EXPECT_TRUE(f.statistics().occluded);
      Eigen::VectorXd v(col.size()), yd, yf, scale;
      for (Index i = 0; i < col.size(); ++i) {
        const Vec3& P = col.collocation_point(i);
        v[i] = std::cos(3 * P.x()) + std::sin(2 * P.y()) * P.z() + 0.5;
      }
      dense->apply(v, yd);
      fast->apply(v, yf);
      dense->apply(v.cwiseAbs(), scale);
      const double rel = (yf - yd).cwiseAbs().maxCoeff() / scale.maxCoeff();
      const double check = f.self_check().relative_error;
      EXPECT_LT(rel, std::max(4 * check, 1e-4)) << name << " level " << level << " n " << col.size();
      EXPECT_LT(rel, 1e-3) << name << " level " << level;
    }
  }
}

// Where the scene sits does not matter: far from the origin (offset 1e7 times the scene's size)
// the coordinates are rounded to about 1e-9 of the size, and a collocation point may then lie a
// rounding behind its own face; the occluders' margin covers that rounding (occluders.hpp), so
// the matrix changes only by the rounding: entries (at most ~0.3) within 1e-6, where a point
// hidden by its own face would lose whole entries. The measured Cornell box (its non-planar left
// wall folds next to the points on it), the block on a floor (touching faces) and the L room.
TEST(OccludedDense, IndependentOfWhereTheSceneSits) {
  std::vector<geometry::TriangleMesh> meshes = {testing::block_on_floor(), testing::l_shaped_room()};
  meshes.push_back(geometry::read_mesh(std::string(PANELRAD_SOURCE_DIR) + "/examples/scenes/cornell_box.obj"));
  for (geometry::TriangleMesh mesh : meshes) {
    const std::string name = mesh.source;
    geometry::TriangleMesh far = mesh;
    const double size = geometry::bounding_box_diameter(mesh.vertices);
    for (Vec3& v : far.vertices) v += Vec3(1e7, -2e7, 3e7) * size;
    const Scene near_scene = general_scene(std::move(mesh), facet_rho, [](Index) { return 1.0; });
    const Scene far_scene = general_scene(std::move(far), facet_rho, [](Index) { return 1.0; });
    const Collocation a(near_scene, 1), b(far_scene, 1);
    const auto Ka = make_operator(a, dense_options(), Visibility::occluded);
    const auto Kb = make_operator(b, dense_options(), Visibility::occluded);
    const auto& A = dynamic_cast<const DenseOperator&>(*Ka).matrix();
    const auto& B = dynamic_cast<const DenseOperator&>(*Kb).matrix();
    EXPECT_LT((A - B).cwiseAbs().maxCoeff(), 1e-6) << name;
  }
}

// The near entries with V in single precision (the factory's choice, single_precision_near_field):
// the same covering, each entry rounded once to float, so the product differs from the double
// one by at most 2^-24 relative per entry: |y_f - y_d| <= 2^-24 (K_near |v|) <= 2^-24 (K |v|), and
// the lists take 4 bytes less per near entry. Without V the near field stays double.
TEST(OccludedFast, SinglePrecisionNearEntriesRoundOnlyTheEntries) {
  EXPECT_TRUE(single_precision_near_field(Visibility::occluded));
  EXPECT_FALSE(single_precision_near_field(Visibility::unoccluded));
  const Scene scene = general_scene(testing::room_with_box(), facet_rho, [](Index) { return 1.0; });
  const Collocation col(scene, 2);
  FastOptions f;
  f.eta = 0.5;
  f.degree = 6;
  f.occluders = scene_occluders(col.tree());
  const FastOperator doubles(col, f);
  f.single_precision_near = true;
  const FastOperator singles(col, f);
  ASSERT_EQ(singles.statistics().near_pairs, doubles.statistics().near_pairs);
  ASSERT_GT(singles.statistics().near_pairs, 0u);
  EXPECT_EQ(doubles.bytes() - singles.bytes(), 4 * doubles.statistics().near_pairs);
  Eigen::VectorXd v(col.size()), yd, ys, scale;
  for (Index i = 0; i < col.size(); ++i) v[i] = std::cos(3.0 * col.collocation_point(i).x()) - 0.25;
  doubles.apply(v, yd);
  singles.apply(v, ys);
  doubles.apply(v.cwiseAbs(), scale);
  EXPECT_NE(ys, yd);  // the entries were rounded
  for (Index i = 0; i < col.size(); ++i)
    EXPECT_LE(std::abs(ys[i] - yd[i]), 0x1p-24 * scale[i] * (1 + 1e-9) + 1e-300) << "row " << i;
  // Block products read the same entries: a column of a block is that column's product.
  Eigen::MatrixXd V(col.size(), 2), Y;
  V.col(0) = v;
  V.col(1) = v.cwiseAbs();
  singles.apply_block(V, Y);
  EXPECT_EQ(Eigen::VectorXd(Y.col(0)), ys);
}

// Deterministic for any thread count: the product is bit-identical with 1 and 2 threads.
TEST(OccludedFast, BitIdenticalForAnyThreadCount) {
  const Scene scene = general_scene(testing::room_with_box(), facet_rho, [](Index) { return 1.0; });
  const Collocation col(scene, 2);
  Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(col.size(), 0.5, 1.5), y1, y2;
  const int threads = max_threads();
  set_threads(1);
  make_operator(col, fast_options(0.5, 6), Visibility::occluded)->apply(v, y1);
  set_threads(std::max(2, threads));
  make_operator(col, fast_options(0.5, 6), Visibility::occluded)->apply(v, y2);
  set_threads(threads);
  EXPECT_EQ(y1, y2);
}

// In a closed scene, emitted = absorbed up to the discretization (point-to-element form factors
// are not reciprocal): the mismatch shrinks as n grows, level after level (room with a box, the
// ceiling's first triangle pair emitting).
TEST(OccludedSolve, EnergyBalanceOfAClosedSceneShrinksWithN) {
  const Scene scene = general_scene(testing::room_with_box(), facet_rho, [](Index f) { return f == 5 ? 1.0 : 0.0; });
  double previous = 1;
  for (int level = 0; level <= 3; ++level) {
    SolveOptions o;
    o.level = level;
    o.op = dense_options();
    o.solver.tolerance = 1e-12;
    const SceneSolution s = solve_scene(scene, o);
    ASSERT_EQ(s.channels.size(), 1u);
    const double mismatch = s.channels[0].energy_mismatch;
    EXPECT_LT(mismatch, previous) << "level " << level;
    previous = mismatch;
  }
  EXPECT_LT(previous, 0.05);
}

}  // namespace
}  // namespace panelrad

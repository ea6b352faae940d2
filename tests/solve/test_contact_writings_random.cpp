// The contact families of contact_scenes.hpp written every way an exporter might (fixed seeds):
// each quad from a random corner, shared or separate vertex lines, 6 decimals, 9 or 17 digits,
// at the origin, scaled by 1e-3 and 1e3, and moved to 1e6. Each is a closed scene, so u = c, to
// 1e-9 wherever the written digits resolve the scene (below the oracle's bound, oracle_scenes.hpp:
// 1e-9 + 10 delta / (1 - rho_max), delta the coordinate resolution, 4e-9 at 1e6), at level 0 (the
// identity holds at every level; level 0 keeps the sweep short).
// Six decimals: the bodies' coordinates are decimals of at most 3 places here, exact in 6
// decimals at every frame but the 1e-3 one, where they keep 3 significant digits, still exact.
#include "contact_scenes.hpp"
#include "oracle_scenes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <stdexcept>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

namespace panelrad {
namespace {

const testing::Frame kOrigin{"origin", 1.0, Vec3::Zero()};

TEST(ContactWritingsSweep, EveryFamilyEveryWritingSolvesToTheConstant) {
  const std::vector<testing::PolygonScene> families = testing::contact_families();
  const std::vector<testing::Frame> frames = {{"origin", 1.0, Vec3::Zero()},
                                              {"small", 1e-3, Vec3::Zero()},
                                              {"large", 1e3, Vec3::Zero()},
                                              {"moved", 1.0, Vec3(1e6, -1e6, 1e6)}};
  int scenes = 0, worst_index = -1;
  double worst = 0;
  std::uint64_t seed = 20261207;
  for (std::size_t f = 0; f < families.size(); ++f)
    for (const testing::Frame& frame : frames)
      for (int digits : {6, 9, 17})
        for (bool separate : {false, true}) {
          testing::Writing w;
          w.first_corner = -1;
          w.separate = separate;
          w.digits = digits;
          w.frame = frame;
          w.seed = ++seed;
          const testing::OracleRun run =
              testing::run_constant_oracle(testing::read_scene(families[f], w), 1.0, 0);
          ++scenes;
          SCOPED_TRACE(families[f].name + ", " + w.describe());
          ASSERT_TRUE(run.valid) << run.describe();
          ASSERT_TRUE(run.solved) << run.describe();
          EXPECT_LE(run.error, 1e-9) << run.describe();
          if (run.error / run.tolerance > worst) {
            worst = run.error / run.tolerance;
            worst_index = scenes;
          }
        }
  std::printf("%d scenes; largest error relative to its bound %.3g (scene %d)\n", scenes, worst, worst_index);
}

/// Each family of contact_scenes.hpp under `rotations` random rotations about the room's centre
/// (from `seed`: the same rotations for every `digits` and frame), random first corners, shared
/// and separate vertex lines in turn, in `frame`, written with `digits`: validated and solved by
/// the closed-scene oracle at level 0, each accepted and solved, then `check`(run).
template <class Check>
void for_each_rotated_writing(int digits, const testing::Frame& frame, int rotations, std::uint64_t seed,
                              Check&& check) {
  const std::vector<testing::PolygonScene> families = testing::contact_families();
  std::mt19937_64 rng(seed);
  for (std::size_t f = 0; f < families.size(); ++f)
    for (int r = 0; r < rotations; ++r) {
      testing::Writing w;
      w.rotation = testing::random_rotation(rng);
      w.first_corner = -1;
      w.separate = (r % 2) == 1;
      w.digits = digits;
      w.seed = rng();
      w.frame = frame;
      const testing::OracleRun run = testing::run_constant_oracle(testing::read_scene(families[f], w), 1.0, 0);
      SCOPED_TRACE(families[f].name + ", " + w.describe());
      ASSERT_TRUE(run.valid) << run.describe();
      ASSERT_TRUE(run.solved) << run.describe();
      check(run);
    }
}

// Written with 17 significant digits: the corners then carry the writer's rounding (an ulp or
// two), so faces in contact cross, part or lie back to back by that much, and corners meant to lie
// on another solid's edge lie an ulp off it. Accepted, and u = c to the oracle's bound (the
// rounded scene is closed once its contacts are closed within the rounding, so the identity holds
// for it exactly).
TEST(ContactWritingsSweep, EveryFamilyRotatedSolvesToTheConstant) {
  int scenes = 0;
  double worst = 0;
  for_each_rotated_writing(17, kOrigin, 20, 7, [&](const testing::OracleRun& run) {
    ++scenes;
    EXPECT_LE(run.error, run.tolerance) << run.describe();
    worst = std::max(worst, run.error / run.tolerance);
  });
  std::printf("%d rotated scenes; largest error relative to its bound %.3g\n", scenes, worst);
}

// The same rotations written with 6 decimals (as Blender writes OBJ) and with 9 significant
// digits: the writer's rounding (5e-7 and 5e-10 of the room) bends each quad and leaves each
// contact apart or crossing by that much. The faces are moved back onto their common planes
// (common_planes.cpp), so that the scene is closed again, with a corner written on another face's
// edge (a box's corner on the wall's diagonal) held on that edge and its own planes fitted through
// it: accepted, and u = c to 1e-9, the bound of the exact writings.
TEST(ContactWritingsSweep, EveryFamilyRotatedAndRoundedSolvesToTheConstant) {
  for (int digits : {6, 9}) {
    int scenes = 0;
    double worst = 0;
    for_each_rotated_writing(digits, kOrigin, 20, 7, [&](const testing::OracleRun& run) {
      ++scenes;
      EXPECT_LE(run.error, 1e-9) << run.describe();
      worst = std::max(worst, run.error);
    });
    std::printf("%d rotated scenes written with %s: largest max |u - c| / c %.3g\n", scenes,
                digits == 6 ? "6 decimals" : "9 digits", worst);
  }
}

// Rotation together with the other frames: 5 rotations of each family (seed 11) scaled by 1e-3
// and 1e3 and moved to 1e6. Where the written digits resolve the scene (the rounding below the
// contact tolerance's cap of 1e-4 of a pair's size) every scene is accepted and u = c to 1e-9,
// the bound of the exact writings, also 1e6 from the origin, where the corners carry a rounding of
// 1e-10 of the room. (A gap is closed by moving the smaller triangle's corners onto the larger
// one's plane, contact_removal.hpp: the plane of a leg's top, extended over a table's top, moved
// its far corners by 1e-8 there.) Left out: 6 decimals at 1e-3 (3 significant digits: the quads
// are refused as not planar); 9 digits at 1e6 (2 decimals, a rounding of 5e-3 of the room:
// crossings are refused and joints beyond the cap are gaps, a different scene).
TEST(ContactWritingsSweep, EveryFamilyRotatedInEveryFrameSolvesToTheConstant) {
  struct Case {
    testing::Frame frame;
    int digits;
  };
  const std::vector<Case> cases = {{{"small", 1e-3, Vec3::Zero()}, 9},        {{"small", 1e-3, Vec3::Zero()}, 17},
                                   {{"large", 1e3, Vec3::Zero()}, 6},         {{"large", 1e3, Vec3::Zero()}, 9},
                                   {{"large", 1e3, Vec3::Zero()}, 17},        {{"moved", 1.0, Vec3(1e6, -1e6, 1e6)}, 6},
                                   {{"moved", 1.0, Vec3(1e6, -1e6, 1e6)}, 17}};
  for (const Case& c : cases) {
    double worst = 0, largest = 0;
    int scenes = 0;
    for_each_rotated_writing(c.digits, c.frame, 5, 11, [&](const testing::OracleRun& run) {
      EXPECT_LE(run.error, 1e-9) << run.describe();
      worst = std::max(worst, run.error / run.tolerance);
      largest = std::max(largest, run.error);
      ++scenes;
    });
    std::printf("%d rotated scenes, %s, %d digits: largest max |u - c| / c %.3g, %.3g of the oracle's bound\n",
                scenes, c.frame.describe().c_str(), c.digits, largest, worst);
  }
}

// Where the written digits do not resolve the scene (a rounding beyond 1e-4 of a face's size, the
// most that is taken for rounding): 6 decimals at 1e-3 (3 significant digits) and 9 digits at 1e6
// (2 decimals). A refusal says that the printing could account for what it refuses and asks for
// more digits, and that hint applied (the same scene written with 17 digits) solves to 1e-9. An
// accepted closed scene solves to the oracle's bound; none is accepted open (the tiles' corners a
// rounding off the walls' edges lie on them, t_junction_tolerance: 2026-12-07, 19 closed and 36
// refused at 1e6 with 9 digits).
TEST(ContactWritingsSweep, WritingsTooShortForTheSceneAreRefusedAndMoreDigitsSolve) {
  struct Case {
    testing::Frame frame;
    int digits;
  };
  for (const Case& c : {Case{{"small", 1e-3, Vec3::Zero()}, 6}, Case{{"moved", 1.0, Vec3(1e6, -1e6, 1e6)}, 9}}) {
    const std::vector<testing::PolygonScene> families = testing::contact_families();
    std::mt19937_64 rng(11);
    int refused = 0, solved = 0, open = 0;
    for (std::size_t f = 0; f < families.size(); ++f)
      for (int r = 0; r < 5; ++r) {
        testing::Writing w;
        w.rotation = testing::random_rotation(rng);
        w.first_corner = -1;
        w.separate = (r % 2) == 1;
        w.digits = c.digits;
        w.seed = rng();
        w.frame = c.frame;
        SCOPED_TRACE(families[f].name + ", " + w.describe());
        geometry::TriangleMesh mesh;
        std::string refusal;
        try {
          mesh = testing::read_scene(families[f], w);
        } catch (const std::exception& e) {  // a polygon refused by the reader
          refusal = e.what();
        }
        if (refusal.empty()) {
          const testing::OracleRun run = testing::run_constant_oracle(mesh, 1.0, 0);
          if (run.valid) {
            ASSERT_TRUE(run.solved) << run.describe();
            if (!run.closed) {
              ++open;
              continue;
            }
            EXPECT_LE(run.error, run.tolerance) << run.describe();
            ++solved;
            continue;
          }
          refusal = run.message;
        }
        ++refused;
        EXPECT_NE(refusal.find("write the coordinates with more digits"), std::string::npos) << refusal;
        testing::Writing more = w;
        more.digits = 17;
        const testing::OracleRun run = testing::run_constant_oracle(testing::read_scene(families[f], more), 1.0, 0);
        ASSERT_TRUE(run.valid) << run.describe();
        ASSERT_TRUE(run.solved) << run.describe();
        EXPECT_LE(run.error, 1e-9) << run.describe();
      }
    std::printf("%s, %d digits: %d closed and solved to the oracle's bound, %d refused asking for more digits (each "
                "solved with 17 to 1e-9), %d accepted open\n",
                c.frame.describe().c_str(), c.digits, solved, refused, open);
    EXPECT_EQ(open, 0);  // every room of the families is closed
  }
}

/// The dense level-0 solution of `mesh` lit by some of its input faces (E = 1 on every fourth,
/// rho as the oracle's), with each element's collocation point taken back to the room's frame by
/// `back`.
struct LitSolution {
  std::vector<Vec3> points;
  std::vector<double> u;
};
template <class Back>
LitSolution lit_solution(geometry::TriangleMesh mesh, Back&& back) {
  geometry::SceneValidationReport report;
  std::optional<geometry::ValidatedMesh> validated = geometry::try_validate(std::move(mesh), report);
  if (!validated) throw std::runtime_error(report.message);
  Scene scene(std::move(*validated));
  std::vector<double> r(static_cast<std::size_t>(scene.num_facets())), e(r.size());
  for (Index f = 0; f < scene.num_facets(); ++f) {
    r[static_cast<std::size_t>(f)] = testing::oracle_rho(f);
    e[static_cast<std::size_t>(f)] = f % 4 == 1 ? 1.0 : 0.0;
  }
  scene.set_reflectivity(r);
  scene.set_emissivity(e);
  const RadiositySolver solver(scene, testing::oracle_solver_options(0));
  const ChannelSolve s = solver.solve(0);
  s.require_converged();
  LitSolution out;
  for (Index i = 0; i < solver.n(); ++i) {
    out.points.push_back(back(solver.collocation().collocation_point(i)));
    out.u.push_back(s.u[i]);
  }
  return out;
}

// Rotation invariance of the answer itself, not only of u = c: each family lit by some of its
// faces, under 5 rotations (seed 13), at the origin and moved to 1e6, written with 17 digits from
// the same first corners as the unrotated writing. Every rotated scene must have the unrotated
// elements (collocation points within 1e-7 of the room once rotated back: the triangulation of what
// a contact's cut leaves takes its diagonals by the plane's own metric and the vertex numbers,
// canonical_diagonals.hpp, not by the rounding of the rotated coordinates), and u must agree with
// the unrotated answer to 1e-9 of the largest u.
TEST(ContactWritingsSweep, EveryFamilyRotatedGivesItsUnrotatedAnswer) {
  const std::vector<testing::PolygonScene> families = testing::contact_families();
  const Vec3 centre(0.5, 0.5, 0.5);
  for (const testing::Frame& frame : {kOrigin, testing::Frame{"moved", 1.0, Vec3(1e6, -1e6, 1e6)}}) {
    std::mt19937_64 rng(13);
    int compared = 0, scenes = 0;
    double largest = 0;
    for (std::size_t f = 0; f < families.size(); ++f) {
      testing::Writing plain;
      plain.first_corner = -1;
      plain.seed = 100 + f;
      const LitSolution reference = lit_solution(testing::read_scene(families[f], plain), [](const Vec3& x) { return x; });
      double umax = 0;
      for (double u : reference.u) umax = std::max(umax, std::abs(u));
      for (int r = 0; r < 5; ++r) {
        testing::Writing w = plain;
        w.rotation = testing::random_rotation(rng);
        w.frame = frame;
        SCOPED_TRACE(families[f].name + ", " + w.describe());
        const LitSolution rotated = lit_solution(testing::read_scene(families[f], w), [&](const Vec3& x) {
          return Vec3(centre + w.rotation.transpose() * ((x - frame.offset) / frame.scale - centre));
        });
        ++scenes;
        // The element matched to each rotated one, when every element has one.
        std::vector<std::size_t> match;
        for (std::size_t i = 0; i < rotated.u.size(); ++i)
          for (std::size_t k = 0; k < reference.u.size(); ++k)
            if ((rotated.points[i] - reference.points[k]).norm() < 1e-7) {
              match.push_back(k);
              break;
            }
        ASSERT_EQ(rotated.u.size(), reference.u.size());
        ASSERT_EQ(match.size(), rotated.u.size()) << "elements of the rotated scene with no unrotated one";
        ++compared;
        double here = 0;
        for (std::size_t i = 0; i < match.size(); ++i)
          here = std::max(here, std::abs(rotated.u[i] - reference.u[match[i]]) / umax);
        EXPECT_LE(here, 1e-9);
        largest = std::max(largest, here);
      }
    }
    std::printf("%s: %d rotated scenes, %d with the unrotated elements; largest |u - u_unrotated| / max u %.3g\n",
                frame.describe().c_str(), scenes, compared, largest);
    EXPECT_EQ(compared, scenes);
  }
}

}  // namespace
}  // namespace panelrad

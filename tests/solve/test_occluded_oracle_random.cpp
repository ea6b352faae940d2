// The closed-scene oracle u = c (oracle_scenes.hpp) on a fixed sweep of random scenes: a room of
// random size with 1-3 axis boxes that stand on the floor, hang from the ceiling, stand against
// a wall or against each other, or float at a log-uniform gap in [1e-15, 1e-2] from them or
// freely; random rho per facet in [0.2, 0.7], random windings, some scenes 1e8 away or scaled by
// 1e-3 or 1e3 (random_oracle_scene). Every scene is valid by construction, so each must be
// accepted and solved with max |u - c| / c < 1e-9 (dense, level 0 or 1), or for the scenes 1e8
// away 1e-9 + 10 delta / (1 - rho_max) with delta the coordinates' resolution (oracle_tolerance;
// the bound's derivation is in test_occluded_oracle.cpp). The windings are the file's statement:
// where more pieces are wound as a solid with cavities (the room outward, its boxes inward) than
// as a room with bodies, the orientation rule reads the scene so (BoxScene::read_as_solid), and
// the oracle is then u = c in the closed cavities, u = E on the outer faces (a box: they see
// nothing) and E <= u <= c in a cavity that touches the outer surface (open there: a dent), each
// within the same bound. A refusal names the rule and the faces; every failure names the
// scene, its number and every parameter, and PANELRAD_ORACLE_SCENE=k runs scene k alone.
#include "oracle_scenes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace panelrad {
namespace {

constexpr std::uint64_t kSeed = 20260412;
constexpr int kScenes = 500;

TEST(OccludedOracleRandom, ClosedScenesSolveToTheConstant) {
  int first = 0, last = kScenes;
  if (const char* only = std::getenv("PANELRAD_ORACLE_SCENE")) {
    first = std::atoi(only);
    last = first + 1;
  }
  int accepted = 0, refused = 0, unsolved = 0, inaccurate = 0, touching = 0, gapped = 0, far = 0, scaled = 0,
      solids = 0, dented = 0;
  double worst = 0;
  int worst_scene = -1;
  long elements = 0;
  for (int k = first; k < last; ++k) {
    const testing::RandomOracleScene s = testing::random_oracle_scene(kSeed, k);
    for (const double g : s.gaps) {
      touching += g == 0;
      gapped += g > 0;
    }
    if (s.frame.offset.norm() > 0) ++far;
    if (s.frame.scale != 1) ++scaled;
    const bool solid = s.boxes.read_as_solid();
    const std::vector<bool> dents = s.boxes.dents();
    const bool dent = solid && std::count(dents.begin(), dents.end(), true) > 0;
    solids += solid;
    dented += dent;
    const testing::OracleRun run = testing::run_constant_oracle(
        s.boxes.mesh(s.frame), s.c, s.level, [&](Index f) { return s.rho_of(f); }, 1024, s.boxes.open_air(s.frame));
    if (!run.valid) {
      ++refused;
      ADD_FAILURE() << s.describe() << "\n  valid by construction, " << run.describe();
      continue;
    }
    ++accepted;
    elements += run.n;
    if (!run.solved) {
      ++unsolved;
      ADD_FAILURE() << s.describe() << "\n  " << run.describe();
      continue;
    }
    // Read as a solid without a dent, every element of its outside sees nothing (the room is a box).
    if (!run.within_bounds() || (solid && !dent && run.seeing > 0) || (!solid && run.blind + run.seeing > 0)) {
      ++inaccurate;
      ADD_FAILURE() << s.describe() << "\n  read as " << (solid ? dent ? "a solid with a dent" : "a solid" : "a room")
                    << ", " << run.describe();
    }
    const double relative =
        std::max({run.error, run.blind_error, run.seeing > 0 ? run.outside_bounds : 0.0}) / run.tolerance;
    if (!(relative <= worst)) {
      worst = relative;
      worst_scene = k;
    }
  }
  std::printf("occluded oracle sweep: %d scenes (seed %llu), %d accepted, %d refused, %d not solved, %d above the bound; "
              "bodies: %d touching, %d at a gap; %d read as a solid (%d with a dent); %d far, %d scaled; %ld elements; "
              "largest error relative to its bound %.3g (scene %d)\n",
              last - first, static_cast<unsigned long long>(kSeed), accepted, refused, unsolved, inaccurate, touching,
              gapped, solids, dented, far, scaled, elements, worst, worst_scene);
  EXPECT_EQ(refused, 0);
}

}  // namespace
}  // namespace panelrad

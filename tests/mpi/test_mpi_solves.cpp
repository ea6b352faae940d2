// Run by ctest under `mpirun -np K` (K = 1, 2, 3, oversubscribed): the solves of
// distributed_solves.hpp with the ranks of MPI_COMM_WORLD sharing the rows, against the same solves
// on this process alone (every rank computes that reference itself), bit for bit; and the
// MPI communicator's collectives against their definitions.
#include "distributed_solves.hpp"

#include <panelrad/distributed/blocked_reductions.hpp>
#include <panelrad/mpi/mpi_communicator.hpp>

#include <gtest/gtest.h>

namespace panelrad {
namespace {

const MpiCommunicator& world() {
  static const MpiCommunicator comm;
  return comm;
}

// all_gather concatenates in rank order, counts differing by rank (rank r gives r + 1 values
// r, r + 0.5, ...); max is the largest of the ranks' values.
TEST(MpiCommunicator, Collectives) {
  const int rank = world().rank(), size = world().size();
  std::vector<double> mine;
  for (int k = 0; k <= rank; ++k) mine.push_back(rank + 0.5 * k);
  Eigen::VectorXd all;
  world().all_gather(mine.data(), mine.size(), all);
  ASSERT_EQ(all.size(), size * (size + 1) / 2);
  Eigen::Index at = 0;
  for (int r = 0; r < size; ++r)
    for (int k = 0; k <= r; ++k) EXPECT_EQ(all[at++], r + 0.5 * k);
  EXPECT_EQ(world().max(-static_cast<double>(rank)), 0.0);
  EXPECT_EQ(world().max(static_cast<double>(rank)), size - 1.0);
  world().all_gather(nullptr, 0, all);  // no values anywhere
  EXPECT_EQ(all.size(), 0);
}

// The convex cube and the occluded room, Neumann and GMRES: the ranks' answers are this process's
// alone, bit for bit.
TEST(MpiSolves, SameBitsAsOneProcess) {
  for (const SolverKind kind : {SolverKind::neumann, SolverKind::gmres}) {
    const std::string what = std::to_string(world().size()) + " ranks, rank " + std::to_string(world().rank()) +
                             ", " + to_string(kind);
    testing::expect_same_bits(testing::paper_cube_solve(kind, nullptr), testing::paper_cube_solve(kind, &world()),
                              "cube, " + what);
    const SolverKind room = kind == SolverKind::neumann ? SolverKind::automatic : kind;  // channels together
    testing::expect_same_bits(testing::room_scene_solve(room, nullptr), testing::room_scene_solve(room, &world()),
                              "room, " + what);
  }
}

}  // namespace
}  // namespace panelrad

int main(int argc, char** argv) {
  const panelrad::MpiSession session(argc, argv);
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}

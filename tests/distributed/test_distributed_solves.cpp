// K processes, played by threads (ThreadCommunicator), against one process: the blocked
// reductions, the operator of a process's rows and the solvers give the same bits for K = 1..4,
// and the same as an exact sum where one exists.
#include "distributed_solves.hpp"
#include "thread_communicator.hpp"
#include "test_support.hpp"

#include <panelrad/distributed/blocked_reductions.hpp>
#include <panelrad/distributed/row_block_operator.hpp>
#include <panelrad/distributed/row_partition.hpp>
#include <panelrad/solve/solvers.hpp>

#include <gtest/gtest.h>

#include <mutex>

namespace panelrad {
namespace {

using testing::run_ranks;

// The partition of n rows into `parts` runs of blocks with equal costs.
RowPartition equal_partition(Index n, int parts) {
  return partition_rows(n, std::vector<double>(static_cast<std::size_t>((n + kRowBlock - 1) / kRowBlock), 1.0), parts);
}

// dot, norm, inf_norm over K threads holding the rows of a partition: the same bits as one
// process; for integer entries (every partial sum exact) the exact value.
TEST(BlockedReductions, SameBitsOnAnyNumberOfProcesses) {
  const Index n = 1000;  // 4 blocks, the last one partial
  const Eigen::VectorXd a = testing::random_vector(n, 1).array() - 0.5, b = testing::random_vector(n, 2);
  const BlockedReductions one;
  const double dot = one.dot(a, b), norm = one.norm(a), inf = one.inf_norm(a);
  EXPECT_EQ(inf, a.lpNorm<Eigen::Infinity>());
  EXPECT_NEAR(dot, a.dot(b), 1e-12 * n);  // another order of the same sum
  for (int K = 1; K <= 4; ++K) {
    const RowPartition p = equal_partition(n, K);
    std::mutex m;
    run_ranks(K, [&](const Communicator& comm) {
      const RowRange r = p.rows(comm.rank());
      const BlockedReductions sums(&comm);
      const Eigen::VectorXd ar = a.segment(r.begin, r.end - r.begin), br = b.segment(r.begin, r.end - r.begin);
      const double d = sums.dot(ar, br), nr = sums.norm(ar), in = sums.inf_norm(ar);
      const Index total = sums.total_rows(r.end - r.begin);
      const bool finite = sums.all_finite(ar);
      const std::lock_guard<std::mutex> lock(m);
      EXPECT_EQ(0, std::memcmp(&d, &dot, sizeof d)) << K << " processes";
      EXPECT_EQ(0, std::memcmp(&nr, &norm, sizeof nr)) << K << " processes";
      EXPECT_EQ(in, inf);
      EXPECT_EQ(total, n);
      EXPECT_TRUE(finite);
    });
  }
  // Integers: every partial sum is exact, so the sum is sum_i i (i mod 7) exactly.
  Eigen::VectorXd i(n), j(n);
  double exact = 0;
  for (Index k = 0; k < n; ++k) {
    i[k] = k;
    j[k] = k % 7;
    exact += static_cast<double>(k) * (k % 7);
  }
  EXPECT_EQ(one.dot(i, j), exact);
  Eigen::VectorXd bad = a;
  bad[n - 1] = std::numeric_limits<double>::quiet_NaN();
  run_ranks(3, [&](const Communicator& comm) {  // the NaN is on the last process only
    const RowRange r = equal_partition(n, 3).rows(comm.rank());
    EXPECT_FALSE(BlockedReductions(&comm).all_finite(bad.segment(r.begin, r.end - r.begin)));
  });
}

// The operator of each process's rows, its block product and the Neumann and GMRES solvers on
// them: the rows of the whole fast operator's product and the one-process solutions, bit for bit.
TEST(RowBlockOperator, ProductsAndSolversAsOnOneProcess) {
  const Scene scene = make_paper_cube_scene();
  const Collocation col(scene, 3);
  const Index n = col.size();
  FastOptions f;
  f.eta = 0.4;
  f.degree = 4;
  const FastOperator whole(col, f);
  const Eigen::VectorXd v = testing::random_vector(n, 3);
  Eigen::VectorXd y;
  whole.apply(v, y);
  Eigen::MatrixXd V(n, 3), Y;
  V << v, testing::random_vector(n, 4), testing::random_vector(n, 5);
  whole.apply_block(V, Y);
  SolverOptions s;
  s.tolerance = 1e-12;
  const Eigen::VectorXd E = testing::random_vector(n, 6);
  const SolveResult neumann = solve_neumann(whole, E, s), gmres = solve_gmres(whole, E, s, 0.8);
  for (int K = 2; K <= 3; ++K) {
    const RowPartition p = partition_rows(n, fast_product_block_costs(col, f.eta, f.degree), K);
    std::mutex m;
    run_ranks(K, [&](const Communicator& comm) {
      const RowRange r = p.rows(comm.rank());
      FastOptions mine = f;
      mine.rows = r;
      const RowBlockOperator op(std::make_unique<FastOperator>(col, mine), r, comm);
      Eigen::VectorXd yr;
      op.apply(op.rows_of(v), yr);
      Eigen::MatrixXd Yr;
      op.apply_block(V.middleRows(r.begin, r.end - r.begin), Yr);
      SolverOptions so = s;
      so.communicator = &comm;
      const SolveResult nr = solve_neumann(op, op.rows_of(E), so), gr = solve_gmres(op, op.rows_of(E), so, 0.8);
      const Eigen::VectorXd nu = op.gather(nr.u), gu = op.gather(gr.u), yw = op.gather(yr);
      const std::lock_guard<std::mutex> lock(m);
      EXPECT_EQ(testing::first_difference(yw, y), -1) << K << " processes";
      for (Eigen::Index c = 0; c < 3; ++c)
        EXPECT_EQ(testing::first_difference(Yr.col(c), Y.col(c).segment(r.begin, r.end - r.begin)), -1) << c;
      EXPECT_EQ(testing::first_difference(nu, neumann.u), -1) << K << " processes, Neumann";
      EXPECT_EQ(testing::first_difference(gu, gmres.u), -1) << K << " processes, GMRES";
      EXPECT_EQ(nr.iterations, neumann.iterations);
      EXPECT_EQ(gr.iterations, gmres.iterations);
    });
  }
}

// The solver object and the scene solver on 2 and 3 processes: the one-process answers, convex and
// occluded, Neumann (channels together) and GMRES.
TEST(DistributedSolves, SameBitsAsOneProcess) {
  for (const SolverKind kind : {SolverKind::neumann, SolverKind::gmres}) {
    const testing::SolveBits cube = testing::paper_cube_solve(kind, nullptr);
    const testing::SolveBits room = testing::room_scene_solve(kind == SolverKind::neumann ? SolverKind::automatic : kind, nullptr);
    for (int K = 2; K <= 3; ++K) {
      std::mutex m;
      run_ranks(K, [&](const Communicator& comm) {
        const testing::SolveBits c = testing::paper_cube_solve(kind, &comm);
        const testing::SolveBits r =
            testing::room_scene_solve(kind == SolverKind::neumann ? SolverKind::automatic : kind, &comm);
        const std::lock_guard<std::mutex> lock(m);
        const std::string what = std::to_string(K) + " processes, rank " + std::to_string(comm.rank()) + ", " + to_string(kind);
        testing::expect_same_bits(cube, c, "cube, " + what);
        testing::expect_same_bits(room, r, "room, " + what);
      });
    }
  }
}

}  // namespace
}  // namespace panelrad

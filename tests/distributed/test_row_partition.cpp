// The row partition: contiguous runs of whole blocks of kRowBlock rows covering [0, n), cut so
// that the runs' costs differ from the mean by at most one block's cost; and the measured costs of
// the fast product's rows against the pairs the fast operator really holds.
#include "occluded_scenes.hpp"

#include <panelrad/distributed/row_partition.hpp>
#include <panelrad/geometry/scene_validation.hpp>
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/scene/scene.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

namespace panelrad {
namespace {

void expect_partition(const RowPartition& p, Index n, int parts) {
  ASSERT_EQ(p.parts(), parts);
  EXPECT_EQ(p.begin.front(), 0);
  EXPECT_EQ(p.begin.back(), n);
  for (int r = 0; r < parts; ++r) {
    const RowRange rows = p.rows(r);
    EXPECT_LE(rows.begin, rows.end);
    EXPECT_TRUE(rows.begin % kRowBlock == 0 || rows.begin == n) << "part " << r << " starts at " << rows.begin;
  }
}

double cost_of(const RowPartition& p, int part, const std::vector<double>& cost) {
  const RowRange r = p.rows(part);
  const std::size_t first = static_cast<std::size_t>(r.begin / kRowBlock);
  const std::size_t last = static_cast<std::size_t>((r.end + kRowBlock - 1) / kRowBlock);
  return std::accumulate(cost.begin() + static_cast<std::ptrdiff_t>(first), cost.begin() + static_cast<std::ptrdiff_t>(last), 0.0);
}

TEST(RowPartition, BalancedRunsOfWholeBlocks) {
  const Index n = 100 * kRowBlock + 17;  // a partial last block
  std::vector<double> cost(101);
  for (std::size_t b = 0; b < cost.size(); ++b) cost[b] = 1.0 + static_cast<double>((b * 37) % 11);  // uneven
  const double total = std::accumulate(cost.begin(), cost.end(), 0.0);
  const double largest = *std::max_element(cost.begin(), cost.end());
  for (int parts : {1, 2, 3, 7, 16}) {
    const RowPartition p = partition_rows(n, cost, parts);
    expect_partition(p, n, parts);
    // Each cut is at the block boundary nearest its target r/K of the total: every run is within
    // one block's cost of the mean.
    for (int r = 0; r < parts; ++r)
      EXPECT_NEAR(cost_of(p, r, cost), total / parts, largest) << parts << " parts, part " << r;
  }
}

TEST(RowPartition, EdgeCases) {
  // More parts than blocks: some parts empty, all rows covered once.
  const RowPartition p = partition_rows(300, {1.0, 1.0}, 5);
  expect_partition(p, 300, 5);
  // No cost at all: equal numbers of blocks.
  const RowPartition q = partition_rows(4 * kRowBlock, std::vector<double>(4, 0.0), 2);
  EXPECT_EQ(q.begin[1], 2 * kRowBlock);
  EXPECT_THROW(partition_rows(300, {1.0}, 2), std::invalid_argument);      // 2 blocks, 1 cost
  EXPECT_THROW(partition_rows(300, {1.0, -1.0}, 2), std::invalid_argument);
  EXPECT_THROW(partition_rows(300, {1.0, 1.0}, 0), std::invalid_argument);
  EXPECT_THROW(p.rows(5), std::out_of_range);
}

// The measured costs against the pairs the fast operator really holds. At n = 3072 (12 blocks, one
// a run) all 256 rows of every block are sampled, so the costs are the operator's work exactly (up
// to the rounding of a run's per-row average), and each part's operator holds a third of the work
// to within one block's.
TEST(RowPartition, FastProductCostsBalanceTheOperatorsWork) {
  const Scene scene = make_paper_cube_scene();
  const Collocation col(scene, 4);  // n = 3072, 12 blocks
  FastOptions f;
  f.eta = 0.4;
  f.degree = 4;
  f.local.enabled = false;  // the per-point coverings alone: the pairs the cost counts
  const std::vector<double> cost = fast_product_block_costs(col, f.eta, f.degree);
  ASSERT_EQ(cost.size(), 12u);
  const double terms = num_taylor_terms(f.degree);
  const auto work = [&](const FastStatistics& s) {
    return static_cast<double>(s.far_pairs) * terms + static_cast<double>(s.near_pairs);
  };
  const FastOperator whole(col, f);
  const double total = std::accumulate(cost.begin(), cost.end(), 0.0);
  EXPECT_NEAR(total, work(whole.statistics()), 1e-9 * work(whole.statistics()));
  const double largest = *std::max_element(cost.begin(), cost.end());
  const RowPartition p = partition_rows(col.size(), cost, 3);
  for (int r = 0; r < 3; ++r) {
    FastOptions part = f;
    part.rows = p.rows(r);
    const FastOperator op(col, part);
    EXPECT_NEAR(work(op.statistics()), work(whole.statistics()) / 3, largest) << "part " << r;
  }
}

// With V: the measured costs of a room with a box inside (occluded_row_work on 16 rows a block)
// against the work the fast operator's setup really found: far pairs and classified pairs x terms
// + near pairs, over all rows. 16 of 256 rows a block are sampled, evenly spaced (the rows of a
// block are the elements of one cluster, whose work varies smoothly over it): 0.14% apart when
// written; accepted to 2%.
TEST(RowPartition, OccludedCostsMatchTheOperatorsWork) {
  geometry::TriangleMesh mesh = testing::room_with_box();
  Scene scene(std::move(mesh));
  scene.set_reflectivity(0.5);  // rows with rho = 0 do no work
  const Collocation col(scene, 3);  // n = 1536, 6 blocks
  const auto occluders = scene_occluders(col.tree());
  FastOptions f;
  f.eta = 0.4;
  f.degree = 4;
  f.occluders = occluders;
  f.local.enabled = false;
  const std::vector<double> cost = fast_product_block_costs(col, f.eta, f.degree, occluders.get(), f.near);
  const FastOperator op(col, f);
  const FastStatistics& s = op.statistics();
  const double terms = num_taylor_terms(f.degree);
  const double work = static_cast<double>(s.far_pairs + s.visible_pairs + s.hidden_pairs + s.partial_pairs) * terms +
                      static_cast<double>(s.near_pairs);
  const double total = std::accumulate(cost.begin(), cost.end(), 0.0);
  ASSERT_GT(work, 0);
  EXPECT_NEAR(total, work, 0.02 * work);
}

}  // namespace
}  // namespace panelrad

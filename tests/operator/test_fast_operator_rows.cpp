// The fast operator on a range of rows [begin, end) of K_n (FastOptions::rows): the blocks of a
// partition of the rows, each set up on its own, give the whole operator's product row for row,
// bit for bit (each row's sum (43) + (47) is formed from the same covering (42) in the same order),
// and their covering counts and held bytes add up to the whole operator's.
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/validation.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/detail/fast_operator_testing.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/scene/scene.hpp>

#include "validated_meshes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace panelrad;

Scene validated_scene(const std::string& builtin) { return Scene(panelrad::testing::validated_builtin(builtin)); }

// Two vectors unlike each other: uniform in [0, 1) and a sign-changing oscillation.
std::vector<Eigen::VectorXd> test_vectors(Index n) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  Eigen::VectorXd a(n), b(n);
  for (Index i = 0; i < n; ++i) {
    a[i] = U(gen);
    b[i] = std::cos(0.37 * static_cast<double>(i)) - 0.2;
  }
  return {a, b};
}

FastOptions with_rows(FastOptions o, Index begin, Index end) {
  o.rows = RowRange{begin, end};
  return o;
}

// Sets up the whole operator and one operator per range of `ranges` (a partition of [0, n) in
// order; end -1 = n) and compares products, counts, lists and bytes.
void expect_blocks_make_the_whole(const Collocation& col, const FastOptions& options, const std::vector<RowRange>& ranges) {
  const Index n = col.size();
  const FastOperator whole(col, options);
  ASSERT_TRUE(whole.holds_all_rows());
  const FastOperator empty(col, with_rows(options, n / 2, n / 2));
  std::vector<std::unique_ptr<FastOperator>> parts;
  for (const RowRange& r : ranges) parts.push_back(std::make_unique<FastOperator>(col, with_rows(options, r.begin, r.end)));
  std::vector<const FastOperator*> blocks;
  for (const auto& p : parts) blocks.push_back(p.get());

  // The ranges partition [0, n), the last one's end -1 resolved to n.
  Index next = 0;
  for (const FastOperator* part : blocks) {
    const FastOperator& b = *part;
    EXPECT_EQ(b.rows().begin, next);
    EXPECT_EQ(b.size(), n);
    next = b.rows().end;
  }
  ASSERT_EQ(next, n);

  for (const Eigen::VectorXd& v : test_vectors(n)) {
    Eigen::VectorXd y;
    whole.apply(v, y);
    for (const FastOperator* part : blocks) {
    const FastOperator& b = *part;
      Eigen::VectorXd block;
      b.apply_rows(v, block);
      ASSERT_EQ(block.size(), b.rows().end - b.rows().begin);
      for (Index i = b.rows().begin; i < b.rows().end; ++i) ASSERT_EQ(block[i - b.rows().begin], y[i]) << "row " << i;
    }
  }

  // Counts and lists: each row's covering is the whole operator's row.
  FastStatistics sum;
  std::size_t bytes_above_empty = 0;
  for (const FastOperator* part : blocks) {
    const FastOperator& b = *part;
    const FastStatistics& s = b.statistics();
    sum.near_pairs += s.near_pairs;
    sum.far_pairs += s.far_pairs;
    sum.skipped_coplanar += s.skipped_coplanar;
    sum.skipped_rows += s.skipped_rows;
    // Each part decides the storage of its coefficients by its own size; a part with far pairs
    // stores them here as the whole operator does (a limit of 1 byte stores none).
    if (s.far_pairs > 0) {
      EXPECT_EQ(s.far_stored, whole.statistics().far_stored);
    }
    bytes_above_empty += b.bytes() - empty.bytes();
    for (Index i = b.rows().begin; i < b.rows().end; ++i) {
      EXPECT_EQ(detail::near_elements(b, i), detail::near_elements(whole, i)) << "row " << i;
      EXPECT_EQ(detail::far_clusters(b, i), detail::far_clusters(whole, i)) << "row " << i;
    }
  }
  EXPECT_EQ(sum.near_pairs, whole.statistics().near_pairs);
  EXPECT_EQ(sum.far_pairs, whole.statistics().far_pairs);
  EXPECT_EQ(sum.skipped_coplanar, whole.statistics().skipped_coplanar);
  EXPECT_EQ(sum.skipped_rows, whole.statistics().skipped_rows);
  // The bytes beyond those of an operator holding no rows (frames and moments of the whole
  // surface) are the lists, coefficients and row starts of the rows held: the lists and
  // coefficients add up, and the row starts (with their blocks of 256 rows, a range cut inside a
  // block holds a block of its own) are what fixed_bytes counts for each range's rows.
  std::size_t clusters = 0;
  for (int l = 0; l <= col.tree().finest_level(); ++l) clusters += static_cast<std::size_t>(col.tree().level_size(l));
  const auto row_bytes = [&](std::size_t rows) {
    return FastOperator::fixed_bytes(static_cast<std::size_t>(n), clusters, options.degree, rows) -
           FastOperator::fixed_bytes(static_cast<std::size_t>(n), clusters, options.degree, 0);
  };
  std::size_t part_row_bytes = 0;
  for (const FastOperator* part : blocks)
    part_row_bytes += row_bytes(static_cast<std::size_t>(part->rows().end - part->rows().begin));
  EXPECT_EQ(bytes_above_empty - part_row_bytes, whole.bytes() - empty.bytes() - row_bytes(static_cast<std::size_t>(n)));
  EXPECT_EQ(empty.statistics().near_pairs + empty.statistics().far_pairs, 0u);
}

// Cube, level 3 (n = 768): four ranges of uneven sizes, a single row and an empty one.
TEST(FastOperatorRows, CubeBlocksMakeTheWholeProductBitForBit) {
  const Scene scene = make_paper_cube_scene();
  const Collocation col(scene, 3);
  ASSERT_EQ(col.size(), 768);
  FastOptions o;
  o.eta = 0.3;
  o.degree = 4;
  const std::vector<RowRange> ranges = {{0, 1}, {1, 300}, {300, 300}, {300, -1}};
  expect_blocks_make_the_whole(col, o, ranges);
}

// Cube, level 2 (n = 192), the paper's parameters: three ranges; far coefficients stored, and
// recomputed in every product.
TEST(FastOperatorRows, CubeLevel2BlocksMakeTheWholeProductBitForBit) {
  const Scene scene = make_paper_cube_scene();
  const Collocation col(scene, 2);
  ASSERT_EQ(col.size(), 192);
  FastOptions o;
  expect_blocks_make_the_whole(col, o, {{0, 191}, {191, 192}, {192, -1}});
  o.far_storage_limit = 1;  // coefficients recomputed per product
  const FastOperator recomputed(col, o);
  ASSERT_FALSE(recomputed.statistics().far_stored);
  expect_blocks_make_the_whole(col, o, {{0, 0}, {0, 57}, {57, 58}, {58, -1}});
}

// Hexagonal prism, level 2, with one black facet (rho = 0: its rows are skipped) and the
// quadrature near field.
TEST(FastOperatorRows, PrismBlocksMakeTheWholeProductBitForBit) {
  Scene scene = validated_scene("prism:6");
  std::vector<double> rho(static_cast<std::size_t>(scene.num_facets()));
  for (std::size_t f = 0; f < rho.size(); ++f) rho[f] = f == 3 ? 0.0 : 0.2 + 0.6 * static_cast<double>(f) / static_cast<double>(rho.size());
  scene.set_reflectivity(rho);
  const Collocation col(scene, 2);
  const Index n = col.size();
  FastOptions o;
  o.eta = 0.25;
  o.degree = 3;
  o.near.rule = NearRule::quadrature;
  const FastOperator whole(col, o);
  ASSERT_GT(whole.statistics().skipped_rows, 0u);
  expect_blocks_make_the_whole(col, o, {{0, 0}, {0, n / 3}, {n / 3, n / 3 + 1}, {n / 3 + 1, n}});
}

// A partial operator cannot give all n rows: apply() refuses, apply_rows() gives the rows held;
// the lists of a row not held are refused too. [0, n) given explicitly is the whole operator.
TEST(FastOperatorRows, PartialOperatorRefusesTheWholeProduct) {
  const Scene scene = make_paper_cube_scene();
  const Collocation col(scene, 2);
  const FastOperator part(col, with_rows(FastOptions{}, 10, 20));
  EXPECT_FALSE(part.holds_all_rows());
  const Eigen::VectorXd v = Eigen::VectorXd::Ones(192);
  Eigen::VectorXd y;
  EXPECT_THROW(part.apply(v, y), std::logic_error);
  part.apply_rows(v, y);
  EXPECT_EQ(y.size(), 10);
  EXPECT_THROW(part.apply_rows(Eigen::VectorXd::Ones(191), y), std::invalid_argument);
  EXPECT_THROW(detail::near_elements(part, 9), std::out_of_range);
  EXPECT_THROW(detail::far_clusters(part, 20), std::out_of_range);
  EXPECT_NO_THROW(detail::far_clusters(part, 19));
  const FastOperator whole(col, with_rows(FastOptions{}, 0, 192));
  EXPECT_TRUE(whole.holds_all_rows());
  EXPECT_NO_THROW(whole.apply(v, y));
  EXPECT_EQ(y.size(), 192);
}

// The self-check of a partial operator samples its own rows only; with samples >= the rows held it
// compares each of them with the exact rows, which agree with the whole operator's to the
// product's accuracy at the paper's parameters (within 1e-3 of dense, test_fast_operator).
TEST(FastOperatorRows, SelfCheckSamplesTheRowsHeld) {
  const Scene scene = make_paper_cube_scene();
  const Collocation col(scene, 2);
  const FastOperator part(col, with_rows(FastOptions{}, 40, 77));
  const FastSelfCheck all = part.self_check(1000);
  ASSERT_EQ(all.rows, 37);
  for (Index k = 0; k < 37; ++k) EXPECT_EQ(all.sampled_rows[static_cast<std::size_t>(k)], 40 + k);
  EXPECT_GT(all.relative_error, 0.0);
  EXPECT_LT(all.relative_error, 1e-3);
  const FastSelfCheck some = part.self_check(8);
  for (Index i : some.sampled_rows) {
    EXPECT_GE(i, 40);
    EXPECT_LT(i, 77);
  }
  EXPECT_EQ(FastOperator(col, with_rows(FastOptions{}, 5, 5)).self_check(8).rows, 0);
}

// A range outside [0, n] or with begin > end is refused by name, with n, by the operator and by
// the memory estimate.
TEST(FastOperatorRows, InvalidRangesAreRefusedNamingTheRangeAndN) {
  const Scene scene = make_paper_cube_scene();
  const Collocation col(scene, 2);
  const std::vector<std::pair<RowRange, std::string>> bad = {
      {{-1, 5}, "[-1, 5)"}, {{5, 3}, "[5, 3)"}, {{0, 193}, "[0, 193)"}, {{193, -1}, "[193, -1)"}, {{0, -2}, "[0, -2)"}};
  for (const auto& [range, text] : bad) {
    try {
      const FastOperator op(col, with_rows(FastOptions{}, range.begin, range.end));
      ADD_FAILURE() << text << " accepted";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(text), std::string::npos) << what;
      EXPECT_NE(what.find("192"), std::string::npos) << what;
    }
    EXPECT_THROW(FastOperator::estimate_memory(col, 0.2, 2, range), std::invalid_argument) << text;
  }
  EXPECT_NO_THROW(FastOperator(col, with_rows(FastOptions{}, 192, -1)));  // empty, at the end
}

// The estimates scale with the rows: the row starts by 8 bytes a row, plus a fixed part per block
// of 256 rows (at most 256 bytes: the block's record and its two closing starts); the lists of a
// range of at most 256 rows (every row sampled) are those setup finds, up to the rounding of the
// per-row average times the row count (one pair); the whole range is the estimate without rows.
TEST(FastOperatorRows, MemoryEstimatesScaleWithTheRows) {
  const std::size_t n = 3072, clusters = 4092;
  EXPECT_EQ(FastOperator::fixed_bytes(n, clusters, 4), FastOperator::fixed_bytes(n, clusters, 4, n));
  const auto row_bytes = [&](std::size_t rows) {
    return FastOperator::fixed_bytes(n, clusters, 4, rows) - FastOperator::fixed_bytes(n, clusters, 4, 0);
  };
  const std::size_t per_block = row_bytes(256) - 256 * 2 * sizeof(std::uint32_t);
  EXPECT_GT(per_block, 0u);
  EXPECT_LE(per_block, 256u);
  EXPECT_EQ(row_bytes(512), 2 * row_bytes(256));
  EXPECT_EQ(row_bytes(1000), 1000 * 2 * sizeof(std::uint32_t) + 4 * per_block);  // 4 blocks, the last partial

  const Scene scene = make_paper_cube_scene();
  const Collocation col(scene, 3);
  const FastOperator::MemoryEstimate all = FastOperator::estimate_memory(col, 0.3, 4);
  const FastOperator::MemoryEstimate same = FastOperator::estimate_memory(col, 0.3, 4, RowRange{0, 768});
  EXPECT_EQ(all.bytes, same.bytes);
  EXPECT_EQ(all.far_pairs, same.far_pairs);
  FastOptions o;
  o.eta = 0.3;
  o.degree = 4;
  std::size_t far_sum = 0;
  for (const RowRange r : {RowRange{0, 200}, RowRange{200, 456}, RowRange{456, 712}, RowRange{712, 768}}) {
    const FastOperator part(col, with_rows(o, r.begin, r.end));
    const FastOperator::MemoryEstimate e = FastOperator::estimate_memory(col, 0.3, 4, r);
    const double far = static_cast<double>(part.statistics().far_pairs);
    EXPECT_NEAR(static_cast<double>(e.far_pairs), far, 1.0) << r.begin;
    const double lists = static_cast<double>(part.statistics().near_pairs) * (sizeof(Index) + sizeof(double)) +
                         far * sizeof(Index);
    EXPECT_NEAR(static_cast<double>(e.list_bytes), lists, 16.0) << r.begin;  // one near and one far pair
    EXPECT_LT(e.bytes, all.bytes);
    far_sum += e.far_pairs;
  }
  // The whole estimate samples 256 of 768 rows: the sum of the exact per-range counts is the true
  // far-pair count, which the whole estimate approximates to a few percent (the cube's rows differ
  // little from one another).
  EXPECT_NEAR(static_cast<double>(all.far_pairs), static_cast<double>(far_sum), 0.05 * static_cast<double>(far_sum));
}

// With target clusters (on by default, on a convex scene) the per-point coverings start below the
// targets: the estimate for a range of at most 256 rows (every row sampled) finds the far pairs
// that setup finds, and its bytes cover what the operator holds (the targets' values counted for
// every target, the coefficients not stored here); on the whole surface it is far below the
// estimate of the per-point coverings from the roots.
TEST(FastOperatorRows, MemoryEstimateCountsTheCoveringsBelowTheTargets) {
  const Scene scene = make_paper_cube_scene();
  const Collocation col(scene, 5);  // n = 12288: targets of levels 0..2
  FastOptions o;
  o.eta = 0.5;
  o.degree = 6;
  o.far_storage_limit = 1;  // coefficients recomputed: bytes() holds no coefficients
  for (const RowRange r : {RowRange{0, 256}, RowRange{6000, 6200}, RowRange{12200, 12288}}) {
    const FastOperator part(col, with_rows(o, r.begin, r.end));
    ASSERT_GE(part.statistics().target_level, 0);
    const FastOperator::MemoryEstimate e = FastOperator::estimate_memory(col, with_rows(o, r.begin, r.end));
    EXPECT_NEAR(static_cast<double>(e.far_pairs), static_cast<double>(part.statistics().far_pairs), 1.0) << r.begin;
    EXPECT_GE(e.bytes, part.bytes()) << r.begin;
    EXPECT_LE(static_cast<double>(e.bytes), 1.25 * static_cast<double>(part.bytes())) << r.begin;
  }
  const FastOperator::MemoryEstimate with_targets = FastOperator::estimate_memory(col, o);
  const FastOperator::MemoryEstimate from_roots = FastOperator::estimate_memory(col, o.eta, o.degree);
  EXPECT_LT(static_cast<double>(with_targets.far_pairs), 0.5 * static_cast<double>(from_roots.far_pairs));
  FastOptions paper = o;
  paper.local.enabled = false;  // the paper's per-point coverings: the estimate from the roots
  EXPECT_EQ(FastOperator::estimate_memory(col, paper).far_pairs, from_roots.far_pairs);
}

}  // namespace

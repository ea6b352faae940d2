// The fast product (section 4) against the dense product, and its covering, skipping and
// determinism.
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/operator/detail/fast_operator_testing.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/support/chunk_pool.hpp>
#include <panelrad/support/resources.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/solvers.hpp>

#include "paper_cube_fixture.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <omp.h>

#include <cstring>
#include <random>
#include <vector>

namespace {

using namespace panelrad;

using panelrad::testing::random_vector;

double relative_product_error(const RadiosityOperator& fast, const DenseOperator& dense, const Eigen::VectorXd& v) {
  Eigen::VectorXd yf, yd;
  fast.apply(v, yf);
  dense.apply(v, yd);
  return (yf - yd).lpNorm<Eigen::Infinity>() / yd.lpNorm<Eigen::Infinity>();
}

using CubeLevel3 = panelrad::testing::PaperCubeFixture<3>;  // n = 768

// The paper's parameters with the exact near field: the product is within 1e-3 of dense.
TEST_F(CubeLevel3, MatchesDenseProductOnRandomVectors) {
  FastOptions o;  // eta 0.2, M 2, exact near field
  const FastOperator fast(*collocation, o);
  for (unsigned seed : {1u, 2u, 3u}) EXPECT_LT(relative_product_error(fast, *dense, random_vector(768, seed)), 1e-3);
}

TEST_F(CubeLevel3, ErrorDecreasesWithDegreeAndWithEta) {
  const Eigen::VectorXd v = random_vector(768, 11);
  double previous = 1;
  for (int M : {0, 1, 2, 3, 4, 6}) {
    FastOptions o;
    o.degree = M;
    const double err = relative_product_error(FastOperator(*collocation, o), *dense, v);
    // Odd degrees can tie with the even one below (the centre of a symmetric cluster cancels the
    // odd terms' integrals); allow equality up to a few percent there, demand a drop overall.
    EXPECT_LT(err, previous * 1.05) << "M " << M;
    previous = std::min(previous, err);
  }
  EXPECT_LT(previous, 1e-5);
  previous = 1;
  for (double eta : {0.5, 0.3, 0.2, 0.1}) {
    FastOptions o;
    o.eta = eta;
    const double err = relative_product_error(FastOperator(*collocation, o), *dense, v);
    EXPECT_LT(err, previous) << "eta " << eta;
    previous = err;
  }
}

// The covering (42) plus the skipped coplanar facet partitions the surface: every element of
// another facet is in exactly one far cluster or is a near element; none of P's facet appears.
TEST_F(CubeLevel3, CoveringPartitionsTheSurface) {
  const FastOperator fast(*collocation, FastOptions{});
  const auto& tree = collocation->tree();
  for (Index i = 0; i < collocation->size(); i += 37) {
    std::vector<int> count(static_cast<std::size_t>(collocation->size()), 0);
    for (Index id : detail::far_clusters(fast, i)) {
      const auto [l, k] = detail::cluster_of_id(fast, id);
      ASSERT_NE(tree.cluster(l, k).facet, collocation->facet(i));
      for (Index e = tree.first_element(l, k); e < tree.end_element(l, k); ++e) ++count[static_cast<std::size_t>(e)];
    }
    for (Index e : detail::near_elements(fast, i)) ++count[static_cast<std::size_t>(e)];
    for (Index e = 0; e < collocation->size(); ++e) {
      const bool coplanar = collocation->facet(e) == collocation->facet(i);
      ASSERT_EQ(count[static_cast<std::size_t>(e)], coplanar ? 0 : 1) << "row " << i << " element " << e;
    }
  }
  const auto& s = fast.statistics();
  // Each row skips at least its own facet's two roots' subtrees: 2 clusters per row on the cube.
  EXPECT_GE(s.skipped_coplanar, 2u * static_cast<std::size_t>(collocation->size()));
  EXPECT_GT(s.near_pairs, 0u);
  EXPECT_GT(s.far_pairs, 0u);
  // Even at this small n the covering needs fewer terms than the dense matrix has nonzero
  // entries (5/6 of n^2 on the cube: own facet excluded).
  EXPECT_LT(s.far_pairs + s.near_pairs, static_cast<std::size_t>(768) * 768 / 2);
}

TEST_F(CubeLevel3, BitIdenticalForAnyThreadCount) {
  const Eigen::VectorXd v = random_vector(768, 5);
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  const FastOperator one(*collocation, FastOptions{});
  Eigen::VectorXd y1;
  one.apply(v, y1);
  omp_set_num_threads(2);
  const FastOperator two(*collocation, FastOptions{});
  Eigen::VectorXd y2, y3;
  two.apply(v, y2);
  one.apply(v, y3);
  omp_set_num_threads(saved);
  EXPECT_EQ(0, std::memcmp(y1.data(), y2.data(), sizeof(double) * 768));
  EXPECT_EQ(0, std::memcmp(y1.data(), y3.data(), sizeof(double) * 768));
}

// The lists live in chunks that the process keeps between operators (support/chunk_pool.hpp):
// an operator set up on kept chunks, filled with garbage first, has the same near and far lists
// and the same product bits as one set up on fresh memory.
TEST_F(CubeLevel3, SameListsAndProductOnKeptChunks) {
  const Eigen::VectorXd v = random_vector(768, 9);
  ChunkPool& pool = ChunkPool::process();
  const std::size_t saved_limit = pool.limit();
  const auto lists = [&](const FastOperator& op) {
    std::vector<std::vector<geometry::Index>> out;
    for (geometry::Index i = 0; i < 768; ++i) {
      out.push_back(detail::near_elements(op, i));
      out.push_back(detail::far_clusters(op, i));
    }
    return out;
  };
  pool.set_limit(0);  // nothing kept: the first operator's chunks are new memory, freed after it
  Eigen::VectorXd y_fresh;
  std::vector<std::vector<geometry::Index>> fresh;
  {
    const FastOperator op(*collocation, FastOptions{});
    op.apply(v, y_fresh);
    fresh = lists(op);
  }
  EXPECT_EQ(pool.kept_bytes(), 0u);
  pool.set_limit(ChunkPool::kMinDefaultLimit);
  { const FastOperator op(*collocation, FastOptions{}); }
  const std::size_t kept = pool.kept_bytes();
  EXPECT_GT(kept, 0u);
  const std::vector<ChunkPool::Chunk> taken = pool.take_kept();  // overwritten with NaN bytes
  EXPECT_EQ(pool.kept_bytes(), 0u);
  for (const ChunkPool::Chunk& c : taken) std::memset(c.data, 0xff, c.bytes);
  for (const ChunkPool::Chunk& c : taken) pool.give_back(c);
  {
    const FastOperator op(*collocation, FastOptions{});
    EXPECT_LT(pool.kept_bytes(), kept);  // it took kept chunks
    Eigen::VectorXd y;
    op.apply(v, y);
    EXPECT_EQ(0, std::memcmp(y.data(), y_fresh.data(), sizeof(double) * 768));
    EXPECT_TRUE(lists(op) == fresh);
  }
  pool.set_limit(saved_limit);
}

// The stored far coefficients (44)-(45) go back to the pool with their operator: the next
// operator of the same size stores its coefficients in that chunk (no new memory) and gives the
// same product bits as one on new memory.
TEST_F(CubeLevel3, StoredCoefficientsReuseTheKeptChunk) {
  const Eigen::VectorXd v = random_vector(768, 10);
  ChunkPool& pool = ChunkPool::process();
  const std::size_t saved_limit = pool.limit();
  pool.set_limit(0);
  Eigen::VectorXd y_fresh;
  std::size_t store_bytes = 0;
  {
    const FastOperator op(*collocation, FastOptions{});
    ASSERT_TRUE(op.statistics().far_stored);
    const auto terms = static_cast<std::size_t>(num_taylor_terms(FastOptions{}.degree));
    store_bytes = op.statistics().far_pairs * terms * sizeof(double);
    op.apply(v, y_fresh);
  }
  // More than one chunk: no chunk of the lists or of a smaller array (one each here) can take it.
  ASSERT_GT(store_bytes, ChunkPool::kChunkBytes);
  pool.set_limit(std::size_t{1} << 30);
  EXPECT_EQ(pool.kept_for(store_bytes), 0u);
  { const FastOperator op(*collocation, FastOptions{}); }
  const std::size_t chunk = pool.kept_for(store_bytes);
  EXPECT_GE(chunk, store_bytes);
  const std::size_t kept = pool.kept_bytes();
  {
    const FastOperator op(*collocation, FastOptions{});
    ASSERT_TRUE(op.statistics().far_stored);
    EXPECT_LE(pool.kept_bytes(), kept - chunk);  // the store's chunk, at least, was taken
    Eigen::VectorXd y;
    op.apply(v, y);
    EXPECT_EQ(0, std::memcmp(y.data(), y_fresh.data(), sizeof(double) * 768));
  }
  pool.set_limit(saved_limit);
}

// The self-check on sampled rows measures the real product error: it agrees with the error
// against the dense product for v = 1 on the same rows, and shrinks with M.
TEST_F(CubeLevel3, SelfCheckMeasuresTheProductError) {
  double previous = 1;
  for (int M : {0, 2, 4}) {
    FastOptions o;
    o.degree = M;
    const FastOperator fast(*collocation, o);
    const FastSelfCheck all = fast.self_check(768);  // every row
    Eigen::VectorXd yf, yd;
    const Eigen::VectorXd ones = Eigen::VectorXd::Ones(768);
    fast.apply(ones, yf);
    dense->apply(ones, yd);
    const double dense_error = (yf - yd).lpNorm<Eigen::Infinity>() / yd.lpNorm<Eigen::Infinity>();
    EXPECT_GE(all.relative_error, dense_error * 0.999) << "M " << M;  // covers v = 1 and more
    EXPECT_LT(all.relative_error, previous) << "M " << M;
    EXPECT_LE(fast.self_check(32).relative_error, all.relative_error * 1.000001);  // a subset
    previous = all.relative_error;
  }
  EXPECT_LT(previous, 1e-4);
}

TEST_F(CubeLevel3, StoredAndRecomputedFarFieldAgree) {
  FastOptions stored, recomputed;
  recomputed.far_storage_limit = 1;  // nothing fits: recompute in every product
  const FastOperator a(*collocation, stored), b(*collocation, recomputed);
  EXPECT_TRUE(a.statistics().far_stored);
  EXPECT_FALSE(b.statistics().far_stored);
  const Eigen::VectorXd v = random_vector(768, 9);
  Eigen::VectorXd ya, yb;
  a.apply(v, ya);
  b.apply(v, yb);
  // The same coefficients (the stored ones come from the recomputing kernels, one pair at a time),
  // summed pair by pair when stored and in SIMD lanes when recomputed: the same value up to the
  // rounding of the sums' order, a few ulps of (K|v|)_i (v >= 0 here, so of y itself); 1e-14.
  EXPECT_LE((ya - yb).lpNorm<Eigen::Infinity>(), 1e-14 * ya.lpNorm<Eigen::Infinity>());
  EXPECT_LT(b.bytes(), a.bytes());
}

// With the exact near field and (eta, M) = (0.2, 2) the solution error equals dense's to 2 digits.
TEST_F(CubeLevel3, SolutionErrorMatchesDense) {
  SolverOptions opt;
  opt.tolerance = 1e-10;
  const auto dense_solution = solve_neumann(*dense, collocation->emissivity(), opt);
  const FastOperator fast(*collocation, FastOptions{});
  const auto fast_solution = solve_neumann(fast, collocation->emissivity(), opt);
  const double ed = collocation->max_error(dense_solution.u), ef = collocation->max_error(fast_solution.u);
  EXPECT_NEAR(ef, ed, 0.005 * ed);
}

TEST(FastOperator, RowsWithZeroReflectivityAreNotComputed) {
  Scene scene = make_paper_cube_scene();
  std::vector<double> rho(6, 0.5);
  rho[2] = 0.0;
  scene.set_reflectivity(rho);
  const Collocation col(scene, 2);
  const FastOperator fast(col, FastOptions{});
  std::size_t zero_rows = 0;
  for (Index i = 0; i < col.size(); ++i) zero_rows += col.facet(i) == 2;
  EXPECT_EQ(fast.statistics().skipped_rows, zero_rows);
  Eigen::VectorXd y;
  fast.apply(Eigen::VectorXd::Ones(col.size()), y);
  for (Index i = 0; i < col.size(); ++i) {
    if (col.facet(i) == 2) {
      EXPECT_EQ(y[i], 0.0);
    }
  }
}

// Translating the cube by 1e6 leaves the solution error unchanged to 3 digits: expansions are in
// local coordinates about A(tau).
TEST(FastOperator, TranslationInvariance) {
  SolverOptions opt;
  opt.tolerance = 1e-10;
  double errors[2];
  int k = 0;
  for (double shift : {0.0, 1e6}) {
    const Scene scene = make_paper_cube_scene(1.0, Vec3(shift, -shift, shift));
    const Collocation col(scene, 3);
    const FastOperator fast(col, FastOptions{});
    errors[k++] = col.max_error(solve_neumann(fast, col.emissivity(), opt).u);
  }
  EXPECT_NEAR(errors[1], errors[0], 5e-4 * errors[0]);
}

TEST(FastOperator, BadParametersAreRejected) {
  const Scene scene = make_paper_cube_scene();
  const Collocation col(scene, 0);
  FastOptions o;
  o.eta = 1.0;
  EXPECT_THROW(FastOperator(col, o), std::invalid_argument);
  o.eta = 0.2;
  o.degree = 13;
  EXPECT_THROW(FastOperator(col, o), std::invalid_argument);
}

}  // namespace

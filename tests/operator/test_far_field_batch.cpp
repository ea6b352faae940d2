// The far field (44)-(45) computed for kFarFieldLanes pairs at once in SIMD lanes, against the
// one-pair recurrence kernel_taylor_coefficients, for every degree M, both instruction sets and
// batches of 1..4 pairs; and the fast product that recomputes its coefficients in the lanes
// against the product from stored coefficients and from the dense operator.
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/operator/far_field.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/scene/scene.hpp>

#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include <omp.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

namespace {

using namespace panelrad;

constexpr double kEps = std::numeric_limits<double>::epsilon();

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  Vec3 v;
  do v = Vec3(g(rng), g(rng), g(rng));
  while (v.norm() < 1e-3);
  return v.normalized();
}

// A bound on the rounding of every Taylor coefficient as kernel_taylor_coefficients computes it
// (far_field.cpp): the same recurrence run on the absolute values of its inputs (each dot
// product a_i, hn, l_i replaced by the sum of the absolute values of its terms) and weights,
//   |F|_n = 2(n+1)/n (|a1| |F|_{n-1} + |a2| ...) + (n+2)/n (|F|_{n-2} + ...),
//   |c|_n = |factor| |hn| (|l0| |F|_n + |l1| |F|_{n-1} + |l2| |F|_{n-1}) / rho^(n+2),
// majorizes every intermediate of both computations. Forward error analysis: each step of the
// recurrence makes at most 4 roundings (products and sums, fused or not), its inputs a_i, l_i,
// hn carry at most 4 each (a scaled dot product), and the unscaling by rho^-(n+2) and the factor
// n + 4, so either computation's coefficient of degree n is within (9 n + 16) eps |c|_n of the
// exact one, and the two within twice that. Returns |c| in graded order.
std::vector<double> absolute_bound(const Vec3& P, const Vec3& nP, const PlaneFrame& f, int M, double factor) {
  const Vec3 d = P - f.origin;
  const double rho = d.norm();
  const Vec3 dn = d / rho;
  // Dot products as sums of the absolute values of their terms (their rounding is relative to that).
  const auto dot = [](const Vec3& x, const Vec3& y) { return x.cwiseAbs().dot(y.cwiseAbs()); };
  const double a1 = dot(dn, f.e1), a2 = dot(dn, f.e2), hn = dot(dn, f.normal);
  const double l0 = dot(dn, nP), l1 = dot(f.e1, nP), l2 = dot(f.e2, nP);
  std::vector<double> F(static_cast<std::size_t>(num_taylor_terms(M)), 0.0), c(F.size());
  const auto at = [&](std::vector<double>& v, int n, int q) -> double& { return v[static_cast<std::size_t>(taylor_index(n - q, q))]; };
  const auto get = [&](int n, int q) { return (q < 0 || q > n || n < 0) ? 0.0 : at(F, n, q); };
  for (int n = 0; n <= M; ++n)
    for (int q = 0; q <= n; ++q) {
      if (n == 0) at(F, n, q) = 1;
      else if (n == 1) at(F, n, q) = 4 * (q == 0 ? a1 : a2);
      else
        at(F, n, q) = 2.0 * (n + 1) / n * (a1 * get(n - 1, q) + a2 * get(n - 1, q - 1)) +
                      (n + 2.0) / n * (get(n - 2, q) + get(n - 2, q - 2));
    }
  for (int n = 0; n <= M; ++n)
    for (int q = 0; q <= n; ++q)
      at(c, n, q) = std::abs(factor) * hn * (l0 * get(n, q) + l1 * get(n - 1, q) + l2 * get(n - 1, q - 1)) /
                    std::pow(rho, n + 2);
  return c;
}

// Frames of random planes with centres on the unit sphere, and a point P at a distance from
// them; the frames of a batch differ (the clusters of a row lie anywhere).
struct Batch {
  Vec3 P, nP;
  std::vector<PlaneFrame> frames;
};

Batch random_batch(std::mt19937_64& rng, int count) {
  std::uniform_real_distribution<double> U(0.0, 1.0);
  Batch b;
  b.P = Vec3(U(rng) - 0.5, U(rng) - 0.5, U(rng) - 0.5);
  b.nP = random_unit(rng);
  for (int w = 0; w < count; ++w) {
    Vec3 A = b.P + (0.3 + 3.0 * U(rng)) * random_unit(rng);
    if (w == 1) A = b.P + 1e-3 * random_unit(rng);  // a near pair: large coefficients
    b.frames.push_back(make_plane_frame(A, random_unit(rng)));
  }
  return b;
}

TEST(FarFieldBatch, LanesEqualTheOnePairRecurrenceForEveryDegree) {
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  double worst = 0;  // the largest difference seen, in units of eps |c|_n
  for (const FarFieldInstructions which : {FarFieldInstructions::best, FarFieldInstructions::baseline}) {
    for (int M = 0; M <= kMaxTaylorDegree; ++M) {
      const int T = num_taylor_terms(M);
      for (int trial = 0; trial < 40; ++trial) {
        const int count = 1 + trial % kFarFieldLanes;  // full batches and a row's tails
        const Batch b = random_batch(rng, count);
        const double factor = 0.1 + U(rng);
        std::vector<const PlaneFrame*> frames;
        for (const PlaneFrame& f : b.frames) frames.push_back(&f);
        // Lanes beyond `count` must stay untouched: a sentinel after the count * T values.
        std::vector<double> lanes(static_cast<std::size_t>(kFarFieldLanes * T), -7.0);
        kernel_taylor_coefficients_lanes(b.P, b.nP, frames.data(), count, M, factor, lanes.data(), which);
        for (std::size_t k = static_cast<std::size_t>(count * T); k < lanes.size(); ++k) ASSERT_EQ(lanes[k], -7.0);
        std::vector<double> one(static_cast<std::size_t>(T));
        for (int w = 0; w < count; ++w) {
          kernel_taylor_coefficients(b.P, b.nP, b.frames[static_cast<std::size_t>(w)], M, one.data());
          const std::vector<double> bound = absolute_bound(b.P, b.nP, b.frames[static_cast<std::size_t>(w)], M, factor);
          for (int n = 0; n <= M; ++n)
            for (int q = 0; q <= n; ++q) {
              const int t = taylor_index(n - q, q);
              const double ref = factor * one[static_cast<std::size_t>(t)];
              const double got = lanes[static_cast<std::size_t>(w * T + t)];
              // Twice either computation's bound (absolute_bound), plus the rounding of factor * c.
              const double tol = (2 * (9 * n + 16) + 1) * kEps * bound[static_cast<std::size_t>(t)];
              ASSERT_TRUE(std::isfinite(got));
              EXPECT_LE(std::abs(got - ref), tol) << far_field_instructions_name(which) << " M " << M << " trial "
                                                  << trial << " lane " << w << " term (" << n - q << ", " << q << ")";
              if (bound[static_cast<std::size_t>(t)] > 0)
                worst = std::max(worst, std::abs(got - ref) / (kEps * bound[static_cast<std::size_t>(t)]));
            }
        }
      }
    }
  }
  RecordProperty("worst_difference_in_eps_of_bound", std::to_string(worst));
}

// Lane w's coefficients do not depend on the other lanes: a pair alone and in a batch agree bit
// for bit (what makes the stored coefficients equal the recomputed ones).
TEST(FarFieldBatch, EachLaneIsIndependentOfTheOthers) {
  std::mt19937_64 rng(43);
  for (const int M : {0, 5, 12}) {
    const int T = num_taylor_terms(M);
    const Batch b = random_batch(rng, kFarFieldLanes);
    std::vector<const PlaneFrame*> frames;
    for (const PlaneFrame& f : b.frames) frames.push_back(&f);
    std::vector<double> all(static_cast<std::size_t>(kFarFieldLanes * T)), alone(static_cast<std::size_t>(T));
    kernel_taylor_coefficients_lanes(b.P, b.nP, frames.data(), kFarFieldLanes, M, 0.25, all.data());
    for (int w = 0; w < kFarFieldLanes; ++w) {
      kernel_taylor_coefficients_lanes(b.P, b.nP, &frames[static_cast<std::size_t>(w)], 1, M, 0.25, alone.data());
      EXPECT_EQ(0, std::memcmp(alone.data(), &all[static_cast<std::size_t>(w * T)], sizeof(double) * static_cast<std::size_t>(T)))
          << "M " << M << " lane " << w;
    }
  }
}

TEST(FarFieldBatch, BadInputIsRefused) {
  const PlaneFrame f = make_plane_frame(Vec3::Zero(), Vec3(0, 0, 1));
  const PlaneFrame g = make_plane_frame(Vec3(0, 0, 2), Vec3(0, 0, 1));
  const PlaneFrame* frames[] = {&g, &f, &g, &g};
  std::vector<double> c(4 * 91);
  const Vec3 nP(0, 0, -1);
  EXPECT_THROW(kernel_taylor_coefficients_lanes(Vec3(0, 0, 1), nP, frames, 4, 13, 1.0, c.data()), std::invalid_argument);
  EXPECT_THROW(kernel_taylor_coefficients_lanes(Vec3(0, 0, 1), nP, frames, 4, -1, 1.0, c.data()), std::invalid_argument);
  EXPECT_THROW(kernel_taylor_coefficients_lanes(Vec3(0, 0, 1), nP, frames, 0, 2, 1.0, c.data()), std::invalid_argument);
  EXPECT_THROW(kernel_taylor_coefficients_lanes(Vec3(0, 0, 1), nP, frames, 5, 2, 1.0, c.data()), std::invalid_argument);
  // P = A of lane 1 (and only of it), or P not finite.
  EXPECT_THROW(kernel_taylor_coefficients_lanes(Vec3::Zero(), nP, frames, 2, 2, 1.0, c.data()), std::invalid_argument);
  EXPECT_THROW(kernel_taylor_coefficients_lanes(Vec3(NAN, 0, 1), nP, frames, 1, 2, 1.0, c.data()), std::invalid_argument);
  // Lane 1 is not in a batch of 1: fine.
  EXPECT_NO_THROW(kernel_taylor_coefficients_lanes(Vec3::Zero(), nP, frames, 1, 2, 1.0, c.data()));
  const std::string name = far_field_instructions_name();
  EXPECT_TRUE(name == "avx2+fma" || name == "baseline") << name;
  EXPECT_EQ(std::string(far_field_instructions_name(FarFieldInstructions::baseline)), "baseline");
}

struct CubeLevel3Lanes : ::testing::Test {
  static void SetUpTestSuite() {
    scene = new Scene(make_paper_cube_scene());
    collocation = new Collocation(*scene, 3);  // n = 768
  }
  static void TearDownTestSuite() {
    delete collocation;
    delete scene;
  }
  static Scene* scene;
  static Collocation* collocation;
};
Scene* CubeLevel3Lanes::scene = nullptr;
Collocation* CubeLevel3Lanes::collocation = nullptr;

Eigen::VectorXd random_signs(Index n, unsigned seed) {
  std::mt19937 gen(seed);
  Eigen::VectorXd v(n);
  for (Index i = 0; i < n; ++i) v[i] = (gen() & 1) ? 1.0 : -1.0;
  return v;
}

// Recomputed in the lanes, stored in double (computed by the same lanes, one pair at a time) and
// stored in float: the first two equal up to the order of the sums, the float one within its rounding, and all
// three within the truncation error (44) of the dense product, for M = 0..12 (every kernel).
TEST_F(CubeLevel3Lanes, RecomputedEqualsStoredForEveryDegree) {
  const Index n = collocation->size();
  const DenseOperator dense(*collocation, NearFieldOptions{});
  const Eigen::VectorXd v = random_signs(n, 3), a = v.cwiseAbs();
  Eigen::VectorXd yd, scale;
  dense.apply(v, yd);
  dense.apply(a, scale);  // (K |v|)_i: the scale of the products' rounding
  const double s = scale.lpNorm<Eigen::Infinity>();
  for (int M = 0; M <= kMaxTaylorDegree; ++M) {
    FastOptions stored, single, recomputed;
    stored.eta = single.eta = recomputed.eta = 0.5;
    stored.degree = single.degree = recomputed.degree = M;
    single.single_precision_coefficients = true;
    recomputed.far_storage_limit = 1;  // nothing fits: recomputed in every product
    const FastOperator fs(*collocation, stored), ff(*collocation, single), fr(*collocation, recomputed);
    ASSERT_TRUE(fs.statistics().far_stored && ff.statistics().far_stored);
    ASSERT_FALSE(fr.statistics().far_stored);
    Eigen::VectorXd ys, yf, yr;
    fs.apply(v, ys);
    ff.apply(v, yf);
    fr.apply(v, yr);
    // The same coefficients, summed pair by pair when stored and in the lanes' fixed tree when
    // recomputed: equal up to the sums' order, a few ulps of (K|v|)_i (1e-14 of the scale, with
    // the row's few hundred terms' rounding ~ 100 u).
    EXPECT_LE((ys - yr).lpNorm<Eigen::Infinity>(), 1e-14 * s) << "M " << M;
    // float coefficients: each rounded by 2^-24 relative, so a row by 2^-24 sum_t |c_t m_t(|v|)|;
    // the Taylor terms of degree n are at most C(n+3,3) eta^n times the degree-0 term (the bound
    // of far_field.hpp), summing to at most (1 - eta)^-4 = 16 times (K|v|)_i at eta = 0.5.
    EXPECT_LE((yf - ys).lpNorm<Eigen::Infinity>(), 16 * 0x1p-24 * s) << "M " << M;
    // Truncation (44): the error falls like eta^(M+1) (the bound of far_field.hpp); measured on
    // this cube 0.058 (K|v|) at M = 0 down to 1.6e-6 at M = 12, at least 2x below 0.12 eta^M.
    EXPECT_LE((yr - yd).lpNorm<Eigen::Infinity>(), 0.12 * std::pow(0.5, M) * s) << "M " << M;
  }
}

// The recomputing product for every number of threads, and its block columns, bit for bit.
TEST_F(CubeLevel3Lanes, RecomputedIsBitIdenticalForAnyThreadCountAndBlock) {
  const Index n = collocation->size();
  FastOptions o;
  o.eta = 0.4;
  o.degree = 7;
  o.far_storage_limit = 1;
  const FastOperator op(*collocation, o);
  Eigen::MatrixXd V(n, 3);
  V.col(0) = random_signs(n, 5);
  V.col(1) = Eigen::VectorXd::LinSpaced(n, 0.25, 1.0);
  V.col(2) = random_signs(n, 7);
  const int saved = omp_get_max_threads();
  std::vector<Eigen::VectorXd> y(3);
  for (int threads = 1; threads <= 3; ++threads) {
    omp_set_num_threads(threads);
    Eigen::VectorXd yt;
    Eigen::MatrixXd Y;
    op.apply_block(V, Y);
    for (int c = 0; c < 3; ++c) {
      op.apply(V.col(c), yt);
      if (threads == 1) y[static_cast<std::size_t>(c)] = yt;
      EXPECT_EQ(0, std::memcmp(yt.data(), y[static_cast<std::size_t>(c)].data(), sizeof(double) * static_cast<std::size_t>(n)))
          << "threads " << threads << " column " << c;
      EXPECT_EQ(0, std::memcmp(Y.col(c).data(), yt.data(), sizeof(double) * static_cast<std::size_t>(n)))
          << "threads " << threads << " column " << c;
    }
  }
  omp_set_num_threads(saved);
}

}  // namespace

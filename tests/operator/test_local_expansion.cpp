// Local expansions of target clusters (local_expansion.hpp): the Chebyshev interpolant against
// polynomials it must reproduce and an analytic function it must converge to, and the fast
// product with target clusters against the dense product, its coverings, its determinism and
// its rows.
#include <panelrad/geometry/admissibility.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/operator/detail/fast_operator_testing.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/operator/local_expansion.hpp>
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/scene/scene.hpp>

#include "paper_cube_fixture.hpp"
#include "test_support.hpp"

#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <vector>

namespace {

using namespace panelrad;
using panelrad::testing::random_vector;

constexpr double kEps = std::numeric_limits<double>::epsilon();

PlaneFrame tilted_frame() { return make_plane_frame(Vec3(0.3, -1.2, 2.0), Vec3(1.0, 2.0, -0.5)); }

// The tensor interpolant of degree d reproduces every polynomial x^a y^b with a, b <= d (up to the
// rounding of the points and the barycentric sums: a few hundred eps of the values' size), and
// the basis is a partition of unity and exact at the nodes.
TEST(ChebyshevInterpolant, ReproducesTensorPolynomials) {
  const PlaneFrame frame = tilted_frame();
  const LocalBox box{0.25, -0.5, 0.75, 0.4};
  for (int d = 0; d <= kMaxLocalDegree; ++d) {
    std::vector<Vec3> points(static_cast<std::size_t>(num_local_points(d)));
    box.points(frame, d, points.data());
    const auto t = chebyshev_points(d);
    double a[kMaxLocalDegree + 1];
    for (double s : {-1.0, -0.3, 0.0, 0.77, 1.0}) {
      chebyshev_basis(d, s, a);
      double sum = 0;
      for (int j = 0; j <= d; ++j) sum += a[j];
      EXPECT_NEAR(sum, 1.0, 4 * (d + 1) * kEps) << "d " << d;
    }
    for (int j = 0; j <= d; ++j) {
      chebyshev_basis(d, t[static_cast<std::size_t>(j)], a);
      for (int k = 0; k <= d; ++k) EXPECT_EQ(a[k], k == j ? 1.0 : 0.0);
    }
    for (int pa = 0; pa <= d; ++pa)
      for (int pb = 0; pb <= d; pb += std::max(1, d / 3)) {
        // f = ((x - cx)/hx)^pa ((y - cy)/hy)^pb at the points, of size <= 1 on the box.
        const auto f = [&](const Vec3& P) {
          const auto x = frame.local(P);
          return std::pow((x[0] - box.cx) / box.hx, pa) * std::pow((x[1] - box.cy) / box.hy, pb);
        };
        std::vector<double> values(points.size());
        for (std::size_t q = 0; q < points.size(); ++q) values[q] = f(points[q]);
        for (double s : {-0.9, -0.2, 0.35, 0.99})
          for (double r : {-0.7, 0.1, 0.8}) {
            const Vec3 P = frame.origin + (box.cx + s * box.hx) * frame.e1 + (box.cy + r * box.hy) * frame.e2;
            double out;
            box.interpolate(frame, d, values.data(), 1, P, &out);
            EXPECT_NEAR(out, f(P), 400 * kEps) << "d " << d << " x^" << pa << " y^" << pb;
          }
      }
  }
}

// f(P) = 1/|P - S|^2 with S = (1.5, 0, 1) over the square [-1, 1]^2 of the plane z = 0. Its
// nearest complex singularities: along y at x = 1, y = +-i sqrt(1.25), Bernstein-ellipse
// parameter r = sqrt(1.25) + 1.5 = 2.62; along x at y = 0, x = 1.5 +- i, r = 3.5. So the error
// falls like 2.62^-(d+1): demanded, a factor 2 every two degrees (6.9 expected), and below 2e-5
// at d = 12 (2.62^-13 = 3.7e-6 times the Lebesgue constant and the size of f).
TEST(ChebyshevInterpolant, ConvergesGeometricallyForAnAnalyticKernel) {
  const PlaneFrame frame = make_plane_frame(Vec3(0, 0, 0), Vec3(0, 0, 1));
  const LocalBox box{0, 0, 1, 1};
  const Vec3 S = frame.origin + 1.5 * frame.e1 + 1.0 * frame.normal;
  const auto f = [&](const Vec3& P) { return 1.0 / (P - S).squaredNorm(); };
  double previous = std::numeric_limits<double>::infinity();
  for (int d = 2; d <= 12; d += 2) {
    std::vector<Vec3> points(static_cast<std::size_t>(num_local_points(d)));
    box.points(frame, d, points.data());
    std::vector<double> values(points.size());
    for (std::size_t q = 0; q < points.size(); ++q) values[q] = f(points[q]);
    double err = 0;
    for (int a = -10; a <= 10; ++a)
      for (int b = -10; b <= 10; ++b) {
        const Vec3 P = frame.origin + (0.1 * a) * frame.e1 + (0.1 * b) * frame.e2;
        double out;
        box.interpolate(frame, d, values.data(), 1, P, &out);
        err = std::max(err, std::abs(out - f(P)));
      }
    EXPECT_LT(err, 0.5 * previous) << "d " << d;
    previous = err;
  }
  EXPECT_LT(previous, 2e-5);
}

TEST(ChebyshevInterpolant, RefusesBadArguments) {
  const PlaneFrame frame = tilted_frame();
  double a[kMaxLocalDegree + 2];
  EXPECT_THROW(chebyshev_points(-1), std::invalid_argument);
  EXPECT_THROW(chebyshev_points(kMaxLocalDegree + 1), std::invalid_argument);
  EXPECT_THROW(chebyshev_basis(kMaxLocalDegree + 1, 0.0, a), std::invalid_argument);
  const LocalBox box{0, 0, 1, 1};
  double values[5 * 4] = {}, out[5];
  EXPECT_THROW(box.interpolate(frame, 1, values, 5, frame.origin, out), std::invalid_argument);
  EXPECT_THROW(LocalBox::bounding(frame, frame.origin, frame.origin, frame.origin), std::invalid_argument);
}

// The cube at level 4 (n = 3072) with target clusters of 16 points or more (levels 0..2).
struct CubeLevel4 : panelrad::testing::PaperCubeFixture<4> {
  static FastOptions options(int d, bool local = true) {
    FastOptions o;
    o.eta = 0.5;
    o.degree = 6;
    o.local.enabled = local;
    o.local.degree = d;
    o.local.min_points = 16;
    return o;
  }
  static double error(const FastOperator& fast, const Eigen::VectorXd& v) {
    Eigen::VectorXd yf, yd;
    fast.apply(v, yf);
    dense->apply(v, yd);
    return (yf - yd).lpNorm<Eigen::Infinity>() / yd.lpNorm<Eigen::Infinity>();
  }
};

// Against the dense product: the interpolation error falls with d, and at d = M = 6 the product
// is as accurate as the per-point product (within 25%: the target pairs obey a stricter
// admissibility, so their Taylor error is smaller, while the interpolation adds its own).
TEST_F(CubeLevel4, ConvergesToThePerPointAccuracy) {
  const Eigen::VectorXd v = random_vector(collocation->size(), 3);
  const double per_point = error(FastOperator(*collocation, options(0, false)), v);
  const double e1 = error(FastOperator(*collocation, options(1)), v);
  const double e3 = error(FastOperator(*collocation, options(3)), v);
  const double e6 = error(FastOperator(*collocation, options(6)), v);
  EXPECT_LT(e3, 0.5 * e1);
  EXPECT_LT(e6, 1.25 * per_point);
  EXPECT_LT(per_point, 3e-4);  // the Taylor error at (0.5, 6): 1.2e-4 measured
  const FastOperator fast(*collocation, options(4));
  const FastStatistics& s = fast.statistics();
  EXPECT_EQ(s.target_level, 2);
  EXPECT_EQ(s.local_degree, 4);
  EXPECT_GT(s.target_pairs, 0u);
  EXPECT_LT(s.far_pairs, FastOperator(*collocation, options(0, false)).statistics().far_pairs);
}

// The far field of every row (its target ancestors' sources, then its own covering), its near
// field and the clusters in its plane partition the surface, and every far cluster satisfies
// (41) for P itself; the coplanar skips are counted as without target clusters.
TEST_F(CubeLevel4, CoveringsPartitionTheSurface) {
  const FastOperator fast(*collocation, options(4));
  const FastOperator per_point(*collocation, options(0, false));
  const auto& tree = collocation->tree();
  const Index n = collocation->size();
  for (Index i = 0; i < n; i += 41) {
    std::vector<int> count(static_cast<std::size_t>(n), 0);
    const Vec3& P = collocation->collocation_point(i);
    for (Index id : detail::far_clusters(fast, i)) {
      const auto [l, k] = detail::cluster_of_id(fast, id);
      const geometry::Cluster& c = tree.cluster(l, k);
      ASSERT_TRUE(geometry::is_admissible(P, c.centre, c.radius, 0.5)) << "row " << i << " cluster " << id;
      for (Index e = tree.first_element(l, k); e < tree.end_element(l, k); ++e) ++count[static_cast<std::size_t>(e)];
    }
    for (Index e : detail::near_elements(fast, i)) ++count[static_cast<std::size_t>(e)];
    std::vector<Index> a = detail::near_elements(fast, i), b = detail::near_elements(per_point, i);
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b) << "row " << i;
    for (Index e = 0; e < n; ++e) {
      const bool coplanar = tree.plane(tree.finest_level(), e) == tree.plane(tree.finest_level(), i);
      ASSERT_EQ(count[static_cast<std::size_t>(e)], coplanar ? 0 : 1) << "row " << i << " element " << e;
    }
  }
  EXPECT_EQ(fast.statistics().skipped_coplanar, per_point.statistics().skipped_coplanar);
  EXPECT_EQ(fast.statistics().near_pairs, per_point.statistics().near_pairs);
}

// Bit for bit: any thread count; a block's columns against single products; the operator of
// some rows against the whole one; a probe's self-check against the whole operator's.
TEST_F(CubeLevel4, DeterministicAcrossThreadsBlocksRowsAndProbes) {
  const Index n = collocation->size();
  const Eigen::VectorXd v = random_vector(n, 8);
  const int saved = omp_get_max_threads();
  std::vector<Eigen::VectorXd> y(3);
  for (int threads = 1; threads <= 3; ++threads) {
    omp_set_num_threads(threads);
    const FastOperator fast(*collocation, options(4));
    fast.apply(v, y[static_cast<std::size_t>(threads - 1)]);
  }
  omp_set_num_threads(saved);
  EXPECT_EQ(0, std::memcmp(y[0].data(), y[1].data(), sizeof(double) * static_cast<std::size_t>(n)));
  EXPECT_EQ(0, std::memcmp(y[0].data(), y[2].data(), sizeof(double) * static_cast<std::size_t>(n)));

  const FastOperator whole(*collocation, options(4));
  Eigen::MatrixXd V(n, 3), Y;
  V.col(0) = v;
  V.col(1) = random_vector(n, 9);
  V.col(2) = Eigen::VectorXd::Ones(n);
  whole.apply_block(V, Y);
  for (int c = 0; c < 3; ++c) {
    Eigen::VectorXd yc;
    whole.apply(V.col(c), yc);
    EXPECT_EQ(0, std::memcmp(yc.data(), Y.col(c).data(), sizeof(double) * static_cast<std::size_t>(n))) << "column " << c;
  }

  FastOptions part_options = options(4);
  part_options.rows = {1000, 2100};
  const FastOperator part(*collocation, part_options);
  Eigen::VectorXd y_part;
  part.apply_rows(v, y_part);
  EXPECT_EQ(0, std::memcmp(y_part.data(), y[0].data() + 1000, sizeof(double) * 1100));

  FastOptions probe_options = options(4);
  probe_options.probe_samples = 24;
  const FastOperator probe(*collocation, probe_options);
  const FastSelfCheck a = probe.self_check(24), b = whole.self_check(24);
  ASSERT_EQ(a.vectors.size(), b.vectors.size());
  for (std::size_t k = 0; k < a.vectors.size(); ++k) EXPECT_EQ(a.vectors[k].relative_error, b.vectors[k].relative_error);
  EXPECT_GT(b.relative_error, 0);
}

// Target clusters down to level 3 (min_points 4): with one thread the levels from 1 on are taken
// in subtree tasks, with two to four threads those from 2 on (at least 32 subtrees a thread), so
// a task spans two or three levels. The same sources (counts) and the same product, bit for bit,
// for 1..4 threads.
TEST_F(CubeLevel4, DeepTargetLevelsSameForAnyThreadCount) {
  const Index n = collocation->size();
  const Eigen::VectorXd v = random_vector(n, 12);
  FastOptions o = options(4);
  o.local.min_points = 4;
  const int saved = omp_get_max_threads();
  std::vector<Eigen::VectorXd> y(4);
  std::vector<FastStatistics> stats(4);
  for (int threads = 1; threads <= 4; ++threads) {
    omp_set_num_threads(threads);
    const FastOperator fast(*collocation, o);
    fast.apply(v, y[static_cast<std::size_t>(threads - 1)]);
    stats[static_cast<std::size_t>(threads - 1)] = fast.statistics();
  }
  omp_set_num_threads(saved);
  EXPECT_EQ(stats[0].target_level, 3);
  EXPECT_GT(stats[0].target_pairs, 0u);
  for (std::size_t t = 1; t < y.size(); ++t) {
    EXPECT_EQ(stats[t].target_pairs, stats[0].target_pairs) << t + 1 << " threads";
    EXPECT_EQ(stats[t].target_clusters, stats[0].target_clusters) << t + 1 << " threads";
    EXPECT_EQ(stats[t].far_pairs, stats[0].far_pairs) << t + 1 << " threads";
    EXPECT_EQ(0, std::memcmp(y[0].data(), y[t].data(), sizeof(double) * static_cast<std::size_t>(n))) << t + 1 << " threads";
  }
  // Against the dense product, as accurate as with the targets of levels 0..2.
  EXPECT_LT(error(FastOperator(*collocation, o), v), 1.25 * error(FastOperator(*collocation, options(4)), v));
}

// With V (occluders given) on a convex surface every (target, cluster) shaft is clear: the same
// targets and sources as without, none hidden or undecided (target_clusters.hpp). Below
// min_points nothing changes: the same coverings and product, bit for bit, as with target
// clusters off.
TEST_F(CubeLevel4, OccludedTakesTheSameTargetsAndTooSmallNone) {
  FastOptions occluded = options(4);
  occluded.occluders = scene_occluders(collocation->tree());
  const FastOperator seen(*collocation, occluded), plain(*collocation, options(4));
  EXPECT_GE(plain.statistics().target_level, 0);
  EXPECT_EQ(seen.statistics().target_level, plain.statistics().target_level);
  EXPECT_EQ(seen.statistics().target_pairs, plain.statistics().target_pairs);
  EXPECT_EQ(seen.statistics().target_hidden_pairs, 0u);
  EXPECT_EQ(seen.statistics().target_undecided_pairs, 0u);
  FastOptions small = options(4);
  small.local.min_points = 1 << 20;  // more points than any cluster holds
  const FastOperator a(*collocation, small), b(*collocation, options(4, false));
  EXPECT_EQ(a.statistics().target_level, -1);
  EXPECT_EQ(a.statistics().far_pairs, b.statistics().far_pairs);
  const Eigen::VectorXd v = random_vector(collocation->size(), 4);
  Eigen::VectorXd ya, yb;
  a.apply(v, ya);
  b.apply(v, yb);
  EXPECT_EQ(0, std::memcmp(ya.data(), yb.data(), sizeof(double) * static_cast<std::size_t>(collocation->size())));
}

TEST_F(CubeLevel4, RefusesBadLocalOptions) {
  FastOptions o = options(4);
  o.local.degree = kMaxLocalDegree + 1;
  EXPECT_THROW(FastOperator(*collocation, o), std::invalid_argument);
  o = options(4);
  o.local.eta = 1.5;
  EXPECT_THROW(FastOperator(*collocation, o), std::invalid_argument);
  o = options(4);
  o.local.min_points = -1;
  EXPECT_THROW(FastOperator(*collocation, o), std::invalid_argument);
}

}  // namespace

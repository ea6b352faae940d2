// A size that will not fit in memory is refused before allocating, with the estimate shown
// (issue 5.6): the dense matrix K_n (33), the cluster tree (40) and, through the tree, the
// collocation and the fast operator. "Before allocating" is checked with the peak resident set
// size (VmHWM): it must not grow by more than a small slack across the refused call.
#include <panelrad/collocation.hpp>
#include <panelrad/dense_operator.hpp>
#include <panelrad/fast_operator.hpp>
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/cluster_tree.hpp>
#include <panelrad/geometry/validation.hpp>
#include <panelrad/resources.hpp>
#include <panelrad/scene.hpp>

#include <gtest/gtest.h>

#include <iostream>
#include <limits>
#include <string>

namespace {

using namespace panelrad;
using geometry::ClusterTree;

// Peak RSS may grow by the message strings and the allocator's bookkeeping, never by the refused
// structure (gigabytes); 64 MiB is far below any refused size here and far above the noise.
constexpr double kSlackMb = 64;

Scene constant_cube() {
  geometry::TriangleMesh mesh = geometry::make_cube();
  const auto report = geometry::validate_closed_convex(mesh);
  EXPECT_TRUE(report.valid) << report.message;
  Scene scene(std::move(mesh));
  scene.set_reflectivity(0.5);
  scene.set_emissivity(1.0);  // no manufactured E: the refused sizes must not cost integration
  return scene;
}

template <class Error, class F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

TEST(MemoryRefusal, DenseMatrixBytesAreExactAndSaturate) {
  EXPECT_EQ(DenseOperator::matrix_bytes(12288), std::size_t{12288} * 12288 * 8);  // 1.2 GB (issue 3)
  EXPECT_EQ(DenseOperator::matrix_bytes(0), 0u);
  // n^2 * 8 exceeds 2^64 for n > 2^30.5: an unchecked product wraps (n = 1518500250 would give
  // 291 MB) and a 18 EB matrix would be accepted. It must saturate instead.
  const std::size_t max = std::numeric_limits<std::size_t>::max();
  EXPECT_EQ(DenseOperator::matrix_bytes(1518500250), max);
  EXPECT_EQ(DenseOperator::matrix_bytes(std::numeric_limits<Index>::max()), max);
  EXPECT_EQ(DenseOperator::matrix_bytes(1518500249), std::size_t{1518500249} * 1518500249 * 8);  // still fits
  for (Index n : {Index{1518500250}, std::numeric_limits<Index>::max()})
    EXPECT_THROW(DenseOperator::check_fits(n), std::runtime_error) << n;
}

// check_fits names n, the estimate and what is available.
TEST(MemoryRefusal, DenseCheckFitsShowsTheEstimate) {
  const Index n = 12 << (2 * 7);  // cube level 7: 196,608^2 doubles = 309 GB
  const std::size_t need = DenseOperator::matrix_bytes(n);
  if (need <= available_memory_bytes()) GTEST_SKIP() << "this machine could hold a " << format_bytes(need) << " matrix";
  const std::string msg = message_of<std::runtime_error>([&] { DenseOperator::check_fits(n); });
  std::cout << "[refusal] " << msg << "\n";
  EXPECT_NE(msg.find("n = 196608"), std::string::npos) << msg;
  EXPECT_NE(msg.find(format_bytes(static_cast<double>(need))), std::string::npos) << msg;  // "309.24 GB"
  EXPECT_NE(msg.find("available"), std::string::npos) << msg;
  EXPECT_NO_THROW(DenseOperator::check_fits(768));  // 4.7 MB
}

// The constructor refuses before the matrix is allocated or any entry computed.
TEST(MemoryRefusal, DenseOperatorRefusesBeforeAllocating) {
  const Scene scene = constant_cube();
  const Collocation col(scene, 7);  // n = 196,608: the tree fits (~60 MB), the matrix (309 GB) not
  if (DenseOperator::matrix_bytes(col.size()) <= available_memory_bytes()) GTEST_SKIP() << "the matrix would fit";
  const double before = peak_rss_mb();
  const std::string msg = message_of<std::runtime_error>([&] { DenseOperator(col, NearFieldOptions{}); });
  const double after = peak_rss_mb();
  std::cout << "[refusal] peak RSS " << before << " -> " << after << " MiB: " << msg << "\n";
  EXPECT_NE(msg.find("309.24 GB"), std::string::npos) << msg;
  EXPECT_LT(after - before, kSlackMb);
}

// The cluster tree under an explicit limit: refused just below its estimate, built at it.
TEST(MemoryRefusal, ClusterTreeUnderALimit) {
  const geometry::TriangleMesh cube = constant_cube().mesh();
  const std::size_t estimate = ClusterTree::estimate_bytes(12, 4);
  const std::string msg = message_of<geometry::MeshError>([&] { ClusterTree(cube, 4, estimate - 1); });
  std::cout << "[refusal] " << msg << "\n";
  EXPECT_NE(msg.find("level 4"), std::string::npos) << msg;
  EXPECT_NE(msg.find("estimate"), std::string::npos) << msg;
  const ClusterTree tree(cube, 4, estimate);
  EXPECT_LE(tree.bytes(), estimate + estimate / 100);  // the estimate is honest (1%: vector slack)
}

// Through the scene: a level whose cluster tree cannot fit is refused by the collocation, before
// allocating, with the estimate in GB. Every operator (dense or fast) is built on a collocation,
// so this also guards the fast method.
TEST(MemoryRefusal, CollocationAndFastOperatorRefuseTreesThatCannotFit) {
  const Scene scene = constant_cube();
  const int level = 12;  // n = 201,326,592: the tree alone needs ~60 GB
  if (ClusterTree::estimate_bytes(12, level) <= ClusterTree::default_memory_limit())
    GTEST_SKIP() << "this machine could hold level " << level;
  const double before = peak_rss_mb();
  const std::string msg = message_of<geometry::MeshError>([&] {
    const Collocation col(scene, level);
    FastOperator fast(col, FastOptions{});  // never reached
  });
  const double after = peak_rss_mb();
  std::cout << "[refusal] peak RSS " << before << " -> " << after << " MiB: " << msg << "\n";
  EXPECT_NE(msg.find("level 12"), std::string::npos) << msg;
  EXPECT_NE(msg.find("201326592"), std::string::npos) << msg;
  EXPECT_NE(msg.find(" GB"), std::string::npos) << msg;
  EXPECT_LT(after - before, kSlackMb);
}

// The fast operator's far-field coefficients are stored only under their limit; above it they
// are recomputed per product (reported), so a tight limit shrinks the operator instead of failing.
TEST(MemoryRefusal, FastFarFieldFallsBackToRecomputing) {
  const Scene scene = constant_cube();
  const Collocation col(scene, 3);
  FastOptions stored, tight;
  tight.far_storage_limit = 1;
  const FastOperator a(col, stored), b(col, tight);
  ASSERT_TRUE(a.statistics().far_stored);
  EXPECT_FALSE(b.statistics().far_stored);
  // What the limit saved: the (far pairs) x (terms) coefficients, M = 2: 6 terms.
  EXPECT_EQ(a.bytes() - b.bytes(), a.statistics().far_pairs * 6 * sizeof(double));
}

// The fast operator's memory is estimated from sampled coverings before setup: the estimate
// matches what setup then holds (within 15%; the far pairs per row vary smoothly over the
// surface), and a limit below it refuses with the estimate shown, before allocating.
TEST(MemoryRefusal, FastOperatorEstimateMatchesAndRefuses) {
  const Scene scene = constant_cube();
  for (int level : {3, 4}) {
    const Collocation col(scene, level);
    for (double eta : {0.2, 0.5}) {
      FastOptions o;
      o.eta = eta;
      o.degree = 4;
      o.far_storage_limit = 1;  // coefficients recomputed: bytes() is what the estimate covers
      const FastOperator::MemoryEstimate est = FastOperator::estimate_memory(col, eta, 4);
      const FastOperator fast(col, o);
      const double far = static_cast<double>(fast.statistics().far_pairs);
      std::cout << "[memory] level " << level << " eta " << eta << ": estimated " << est.bytes << " B, "
                << est.far_pairs << " far pairs; actual " << fast.bytes() << " B, " << far << " far pairs\n";
      EXPECT_NEAR(static_cast<double>(est.far_pairs), far, 0.15 * far);
      EXPECT_NEAR(static_cast<double>(est.bytes), static_cast<double>(fast.bytes()), 0.15 * static_cast<double>(fast.bytes()));
      EXPECT_EQ(est.coefficient_bytes, est.far_pairs * 15 * sizeof(double));  // M = 4: 15 terms
      o.memory_limit = est.bytes / 2;
      try {
        const FastOperator refused(col, o);
        ADD_FAILURE() << "not refused at level " << level;
      } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("needs about"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("use fewer levels"), std::string::npos) << e.what();
      }
    }
  }
}

}  // namespace

// A size that will not fit in memory is refused before allocating, with the estimate shown
// for the dense matrix K_n (33), the cluster tree (40) and, through the tree, the
// collocation and the fast operator. "Before allocating" is checked with the peak resident set
// size (VmHWM): it must not grow by more than a small slack across the refused call.
#include "test_support.hpp"
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/cluster_tree.hpp>
#include <panelrad/geometry/validation.hpp>
#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/solve/memory_plan.hpp>
#include <panelrad/solve/radiosity_solver.hpp>
#include <panelrad/solve/scene_solver.hpp>
#include <panelrad/support/resources.hpp>
#include <panelrad/scene/scene.hpp>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <string>
#include <utility>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

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
  EXPECT_EQ(DenseOperator::matrix_bytes(12288), std::size_t{12288} * 12288 * 8);  // 1.2 GB
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

// ---- The memory this process may still allocate, and the up-front estimate of a level ---------


// A made-up cgroup hierarchy under a temporary root: the headroom is limit - (usage - inactive
// file cache), the least over the process's cgroup and its ancestors; "max" is no limit.
class CgroupTree : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = std::filesystem::temp_directory_path() / ("panelrad_cgroup_" + std::to_string(::getpid()));
    std::filesystem::remove_all(root_);
  }
  void TearDown() override { std::filesystem::remove_all(root_); }
  void put(const std::string& file, const std::string& text) const {
    const std::filesystem::path p = root_ / file.substr(1);
    std::filesystem::create_directories(p.parent_path());
    std::ofstream(p) << text;
  }
  std::size_t headroom(const std::string& cgroup, const std::string& mountinfo) const {
    return detail::cgroup_headroom(cgroup, mountinfo, root_.string());
  }
  std::filesystem::path root_;
};

TEST_F(CgroupTree, Version2TakesTheLeastHeadroomAlongTheAncestors) {
  const std::string mountinfo = "41 31 0:38 / /sys/fs/cgroup rw,relatime - cgroup2 cgroup2 rw\n";
  put("/sys/fs/cgroup/a/memory.max", "8000000000\n");     // 8 GB, 5 GB used: 5 GB free
  put("/sys/fs/cgroup/a/memory.current", "5000000000\n");
  put("/sys/fs/cgroup/a/memory.stat", "anon 1\ninactive_file 2000000000\nactive_file 7\n");
  put("/sys/fs/cgroup/a/b/memory.max", "max\n");          // no limit of its own
  put("/sys/fs/cgroup/a/b/memory.current", "100\n");
  // a: 8e9 - (5e9 - 2e9 of reclaimable cache) = 5e9
  EXPECT_EQ(headroom("0::/a/b\n", mountinfo), std::size_t{5000000000});
  put("/sys/fs/cgroup/a/b/memory.max", "1000000000\n");   // now b's own 1 GB is the least
  EXPECT_EQ(headroom("0::/a/b\n", mountinfo), std::size_t{1000000000} - 100);
  EXPECT_EQ(headroom("0::/\n", mountinfo), MemoryAvailability::kUnlimited);  // the root has no memory.max
  EXPECT_EQ(headroom("", mountinfo), MemoryAvailability::kUnlimited);
}

TEST_F(CgroupTree, Version1UsesTheMemoryControllersMountAndItsRoot) {
  // A cgroup namespace: the mount's root is /outer, the process sees its cgroup as /outer/job.
  const std::string mountinfo =
      "32 31 0:29 / /sys/fs/cgroup/cpu rw,relatime - cgroup cgroup rw,cpu\n"
      "35 31 0:32 /outer /sys/fs/cgroup/memory rw,relatime - cgroup cgroup rw,memory\n";
  put("/sys/fs/cgroup/memory/job/memory.limit_in_bytes", "3000000000\n");
  put("/sys/fs/cgroup/memory/job/memory.usage_in_bytes", "1000000000\n");
  put("/sys/fs/cgroup/memory/job/memory.stat", "cache 5\ntotal_inactive_file 500000000\n");
  put("/sys/fs/cgroup/memory/memory.limit_in_bytes", "9223372036854771712\n");  // v1's "no limit"
  put("/sys/fs/cgroup/memory/memory.usage_in_bytes", "1\n");
  EXPECT_EQ(headroom("5:cpu:/outer/job\n4:memory:/outer/job\n", mountinfo), std::size_t{2500000000});
  // Without a memory line, or without the memory controller's mount, nothing is known.
  EXPECT_EQ(headroom("5:cpu:/outer/job\n", mountinfo), MemoryAvailability::kUnlimited);
  EXPECT_EQ(headroom("4:memory:/outer/job\n", "32 31 0:29 / /x rw - cgroup cgroup rw,cpu\n"),
            MemoryAvailability::kUnlimited);
}

// RLIMIT_AS (ulimit -v) bounds what can be allocated: available_memory_bytes() must not exceed
// the soft limit minus the mapped size. Checked in a child process, which lowers its own limit.
// ASan reserves terabytes of address space, so the limit cannot be lowered under it.
TEST(MemoryAvailable, HonoursTheAddressSpaceLimit) {
#ifdef PANELRAD_ASAN
  GTEST_SKIP() << "AddressSanitizer maps terabytes of shadow memory: RLIMIT_AS cannot be lowered";
#else
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const std::size_t before = available_memory_bytes();
    std::ifstream status("/proc/self/status");
    long long vm_kb = -1;
    for (std::string line; std::getline(status, line);)
      if (line.rfind("VmSize:", 0) == 0) vm_kb = std::stoll(line.substr(7));
    const std::size_t headroom = std::size_t{256} << 20;  // 256 MiB above what is mapped now
    rlimit limit{};
    limit.rlim_cur = limit.rlim_max = static_cast<rlim_t>(vm_kb * 1024) + headroom;
    if (vm_kb <= 0 || ::setrlimit(RLIMIT_AS, &limit) != 0) ::_exit(3);
    const MemoryAvailability m = memory_availability();
    // The mapped size moves by a few pages between the two readings (the ifstream's buffer).
    const bool bounded = m.address_space <= headroom && m.address_space + (std::size_t{16} << 20) >= headroom;
    const bool least = m.bytes() == std::min(m.address_space, before) && available_memory_bytes() <= headroom;
    const bool named = describe_available_memory().find("ulimit -v") != std::string::npos || before < headroom;
    ::_exit(bounded && least && named ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << "3: the limit could not be set; 1: available memory ignores it";
#endif
}

// The system part is MemAvailable of /proc/meminfo, read here independently with a stream before
// and after. MemAvailable moves while other processes (or tests run beside this one) allocate, so
// a reading counts when it lies between the two bracketing ones (16 MiB of slack: a few pages of
// this process and the kernel's per-CPU counters); a few attempts find a quiet moment.
TEST(MemoryAvailable, SystemPartIsMemAvailable) {
  const auto mem_available = [] {
    std::ifstream meminfo("/proc/meminfo");
    for (std::string line; std::getline(meminfo, line);)
      if (line.rfind("MemAvailable:", 0) == 0) return std::stoll(line.substr(13)) * 1024;
    return -1LL;
  };
  if (mem_available() < 0) GTEST_SKIP() << "no MemAvailable in /proc/meminfo";
  const long long slack = 16LL << 20;
  bool between = false;
  long long low = 0, high = 0, read = 0;
  for (int attempt = 0; attempt < 10 && !between; ++attempt) {
    const long long before = mem_available();
    read = static_cast<long long>(memory_availability().system);
    const long long after = mem_available();
    low = std::min(before, after) - slack;
    high = std::max(before, after) + slack;
    between = read >= low && read <= high;
  }
  EXPECT_TRUE(between) << read << " B outside [" << low << ", " << high << "]";
}

// The dense level estimate is exact in its parts: the matrix n^2 doubles, the tree's estimate,
// the collocation's vectors and the solver's work vectors.
TEST(LevelMemoryEstimate, DensePartsAreTheKnownSizes) {
  const geometry::TriangleMesh cube = constant_cube().mesh();
  OperatorOptions op;
  op.method = OperatorMethod::dense;
  SolverOptions neumann;
  neumann.kind = SolverKind::neumann;
  const LevelMemoryEstimate e = estimate_level_memory(cube, 6, op, neumann, 0.5);
  const std::size_t n = 12 << 12;
  EXPECT_EQ(e.n, static_cast<long double>(n));
  EXPECT_EQ(e.op, DenseOperator::matrix_bytes(static_cast<Index>(n)));
  EXPECT_EQ(e.tree, ClusterTree::estimate_bytes(12, 6));
  EXPECT_EQ(e.collocation, 3 * n * sizeof(double));
  EXPECT_EQ(e.solver, 6 * n * sizeof(double));
  EXPECT_FALSE(e.op_is_lower_bound);
  EXPECT_EQ(e.total(), e.op + e.tree + e.collocation + e.solver);
  SolverOptions gmres;
  gmres.kind = SolverKind::gmres;  // restart 60: the basis of 61 vectors and 5 more
  EXPECT_EQ(estimate_level_memory(cube, 6, op, gmres, 0.5).solver, 66 * n * sizeof(double));
  // Sizes beyond the 32-bit index saturate (and are then refused), never wrap.
  EXPECT_EQ(estimate_level_memory(cube, 15, op, neumann, 0.5).total(), std::numeric_limits<std::size_t>::max());
}

// The fast operator's up-front figure is a lower bound of its precise estimate on the built tree
// (the far pairs per row only grow under refinement) and of what setup then holds.
TEST(LevelMemoryEstimate, FastFigureIsALowerBoundOfThePreciseOne) {
  const Scene scene = constant_cube();
  for (double eta : {0.5, 0.3}) {
    OperatorOptions op;
    op.method = OperatorMethod::fast;
    op.eta = eta;
    op.degree = 4;
    const LevelMemoryEstimate e = estimate_level_memory(scene.mesh(), 4, op, SolverOptions{}, 0.5);
    const Collocation col(scene, 4);  // n = 3072; the coarse level has 768 elements
    const FastOperator::MemoryEstimate precise = FastOperator::estimate_memory(col, eta, 4);
    FastOptions o;
    o.eta = eta;
    o.degree = 4;
    o.far_storage_limit = 1;  // coefficients not stored: what the lower bound covers
    const FastOperator fast(col, o);
    std::cout << "[memory] eta " << eta << ": up-front " << e.op << " B, precise " << precise.bytes + precise.list_bytes
              << " B (setup peak), held " << fast.bytes() << " B\n";
    EXPECT_TRUE(e.op_is_lower_bound);
    EXPECT_LE(e.op, precise.bytes + precise.list_bytes);
    // The far lists twice and the fixed arrays: more than the fixed arrays alone.
    EXPECT_GT(e.op, FastOperator::fixed_bytes(3072, 4092, 4));
    EXPECT_GT(e.op, fast.bytes() / 2);  // not a vacuous bound: within 2x of what is held
  }
}

// Refusal names the level, n, the breakdown and the limit that binds.
TEST(LevelMemoryEstimate, RefusalNamesTheLevelTheEstimateAndTheLimit) {
  const geometry::TriangleMesh cube = constant_cube().mesh();
  OperatorOptions op;
  op.method = OperatorMethod::dense;
  const std::vector<LevelMemoryEstimate> levels = {estimate_level_memory(cube, 2, op, SolverOptions{}, 0.5),
                                                   estimate_level_memory(cube, 5, op, SolverOptions{}, 0.5)};
  MemoryAvailability small;
  small.address_space = levels[1].total();  // level 5 needs more than 90% of it
  const std::string msg = message_of<ResourceError>([&] { refuse_levels_that_cannot_fit(levels, "cube ", small); });
  std::cout << "[refusal] " << msg << "\n";
  EXPECT_NE(msg.find("cube level 5 (n = 12288, dense"), std::string::npos) << msg;
  EXPECT_NE(msg.find(format_bytes(static_cast<double>(levels[1].op))), std::string::npos) << msg;  // 1.21 GB
  EXPECT_NE(msg.find("ulimit -v"), std::string::npos) << msg;
  EXPECT_NE(msg.find("before any work"), std::string::npos) << msg;
  small.address_space = levels[1].total() / 9 * 10 + 10;  // fits within 90%
  EXPECT_NO_THROW(refuse_levels_that_cannot_fit(levels, "cube ", small));
}

// A level whose element count n = 4^L n0 exceeds the 32-bit element index is refused by that
// reason, before any work, by every entry that takes a level: the problem's size (which the
// automatic parameters and the memory plan start from), the solver object and solve_scene. The
// paper's cube (n0 = 12) holds level 13 at most: 12 * 4^14 = 3,221,225,472 > 2^31 - 1.
TEST(LevelMemoryEstimate, LevelBeyondTheElementIndexIsRefusedByItsCount) {
  const Scene cube = constant_cube();
  const auto expect_count_named = [](const std::string& msg, int level, const std::string& n) {
    EXPECT_NE(msg.find("level " + std::to_string(level)), std::string::npos) << msg;
    EXPECT_NE(msg.find("12 * 4^" + std::to_string(level)), std::string::npos) << msg;
    EXPECT_NE(msg.find(n), std::string::npos) << msg;
    EXPECT_NE(msg.find("2147483647"), std::string::npos) << msg;  // the largest 32-bit index
    EXPECT_NE(msg.find("level 13"), std::string::npos) << msg;    // the largest level that has one
    EXPECT_EQ(msg.find("must be positive"), std::string::npos) << msg;
  };
  for (const auto& [level, n] : std::vector<std::pair<int, std::string>>{
           {14, "3221225472"}, {15, "12884901888"}, {16, "51539607552"}, {40, "1.45"}}) {
    expect_count_named(message_of<ResourceError>([&] { (void)problem_size(cube.mesh(), level); }), level, n);
    SolveOptions o;
    o.level = level;
    int lines = 0;
    o.progress = [&lines](const std::string&) { ++lines; };
    expect_count_named(message_of<ResourceError>([&] { RadiositySolver solver(cube, o); }), level, n);
    expect_count_named(message_of<ResourceError>([&] { (void)solve_scene(cube, o); }), level, n);
    EXPECT_EQ(lines, 0) << "level " << level << ": refused before any work";
  }
  // Level 13 has its 805,306,368 elements numbered: refused, if at all, by memory.
  EXPECT_EQ(problem_size(cube.mesh(), 13).n, 805306368);
}

// An allocation failure inside a stage becomes a ResourceError naming the stage, n and the size.
TEST(LevelMemoryEstimate, AllocationFailureNamesTheStage) {
  const std::string msg = message_of<ResourceError>([] {
    run_stage("building the near field", 196608, std::size_t{1210000000}, []() -> int { throw std::bad_alloc(); });
  });
  EXPECT_NE(msg.find("out of memory while building the near field (n = 196608; about 1.21 GB needed; "), std::string::npos)
      << msg;
  EXPECT_NE(msg.find("available ("), std::string::npos) << msg;
  EXPECT_EQ(run_stage("nothing", 1, 0, [] { return 7; }), 7);
}

}  // namespace

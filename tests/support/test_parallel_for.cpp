// parallel_for: every index visited once, and of several failing indices the lowest one's
// exception is the one rethrown, whatever the thread count and the order the failures happen in.
#include <panelrad/support/parallel_for.hpp>

#include <gtest/gtest.h>
#include <omp.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <set>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace {

using panelrad::parallel_for;

/// Restores the OpenMP thread count on scope exit.
class ThreadCount {
 public:
  explicit ThreadCount(int threads) : saved_(omp_get_max_threads()) { omp_set_num_threads(threads); }
  ~ThreadCount() { omp_set_num_threads(saved_); }
  ThreadCount(const ThreadCount&) = delete;
  ThreadCount& operator=(const ThreadCount&) = delete;

 private:
  int saved_;
};

struct IndexFailure : std::runtime_error {
  explicit IndexFailure(std::int64_t k) : std::runtime_error("index " + std::to_string(k)), index(k) {}
  std::int64_t index;
};

TEST(ParallelFor, VisitsEveryIndexOnce) {
  for (int threads : {1, 2, 4, 8}) {
    ThreadCount tc(threads);
    for (int chunk : {1, 16, 256}) {
      constexpr std::int32_t n = 5000;
      std::vector<std::atomic<int>> visits(n);
      parallel_for(n, [&](std::int32_t k) { visits[static_cast<std::size_t>(k)].fetch_add(1); }, chunk);
      for (std::int32_t k = 0; k < n; ++k)
        ASSERT_EQ(visits[static_cast<std::size_t>(k)].load(), 1) << "k " << k << ", threads " << threads;
    }
    int calls = 0;
    parallel_for(0, [&](int) { ++calls; });  // empty range: no call, no throw
    EXPECT_EQ(calls, 0);
  }
}

// The lowest failing index (3) throws only after a higher one has thrown on another thread (when
// the team has more than one thread), so a loop that kept the first or the last exception caught
// would report a higher index. Every index still runs: a failure cancels nothing.
TEST(ParallelFor, RethrowsTheLowestFailingIndex) {
  const std::set<std::int64_t> failing = {3, 10, 40, 41, 63};
  for (int threads : {1, 2, 4, 8}) {
    ThreadCount tc(threads);
    for (int chunk : {1, 4}) {
      std::atomic<bool> higher_failed{false};
      std::atomic<int> visited{0};
      try {
        parallel_for(
            std::int64_t{64},
            [&](std::int64_t k) {
              visited.fetch_add(1);
              if (!failing.count(k)) return;
              if (k == 3 && omp_get_num_threads() > 1) {
                // Bounded wait (the other threads may all be busy elsewhere): the check below
                // holds either way.
                const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(5);
                while (!higher_failed.load() && std::chrono::steady_clock::now() < until)
                  std::this_thread::yield();
              }
              if (k > 3) higher_failed.store(true);
              throw IndexFailure(k);
            },
            chunk);
        ADD_FAILURE() << "no exception, threads " << threads;
      } catch (const IndexFailure& e) {
        EXPECT_EQ(e.index, 3) << e.what() << ", threads " << threads << ", chunk " << chunk;
      }
      EXPECT_EQ(visited.load(), 64);
    }
  }
}

// The rethrown object is the one the body threw (its dynamic type and contents), not a copy
// sliced to a base class.
TEST(ParallelFor, KeepsTheExceptionType) {
  ThreadCount tc(4);
  EXPECT_THROW(parallel_for(100, [](int k) {
                 if (k == 50) throw std::out_of_range("k = 50");
                 if (k == 70) throw std::invalid_argument("k = 70");
               }),
               std::out_of_range);
}

}  // namespace

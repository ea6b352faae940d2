// The operator's large arrays (support/large_buffer.hpp): 2 MiB aligned, their memory taken from
// and given back to the process's pool, reused by the next array of about the same size and not
// by a small one. Each test runs in a process of its own, so the process's pool starts empty.
#include <panelrad/support/chunk_pool.hpp>
#include <panelrad/support/large_buffer.hpp>

#include <gtest/gtest.h>

#include <cstdint>
#include <new>

namespace {

using panelrad::ChunkPool;
using panelrad::LargeArray;

constexpr std::size_t MiB = std::size_t{1} << 20;

std::uintptr_t address(const void* p) { return reinterpret_cast<std::uintptr_t>(p); }

TEST(LargeArray, MemoryGoesBackToThePoolAndIsReused) {
  ChunkPool& pool = ChunkPool::process();
  pool.release();
  const void* where = nullptr;
  {
    LargeArray<double> a(3 * MiB / sizeof(double));
    EXPECT_EQ(a.bytes(), 3 * MiB);
    EXPECT_EQ(address(a.data()) % (2 * MiB), 0u);
    for (std::size_t i = 0; i < a.size(); i += 4096) a[i] = static_cast<double>(i);
    where = a.data();
  }
  EXPECT_EQ(pool.kept_bytes(), 4 * MiB);
  LargeArray<float> b(3 * MiB / sizeof(float));  // the same bytes: the kept chunk
  EXPECT_EQ(static_cast<const void*>(b.data()), where);
  EXPECT_EQ(pool.kept_bytes(), 0u);
}

// A small array takes a new chunk, not a kept one many times its size.
TEST(LargeArray, SmallArrayLeavesALargeKeptChunk) {
  ChunkPool& pool = ChunkPool::process();
  pool.release();
  const void* big_data = nullptr;
  {
    LargeArray<double> big(64 * MiB / sizeof(double));
    big_data = big.data();
  }
  ASSERT_EQ(pool.kept_bytes(), 64 * MiB);
  {
    LargeArray<double> small(1);
    EXPECT_NE(static_cast<const void*>(small.data()), big_data);
    EXPECT_EQ(pool.kept_bytes(), 64 * MiB);
  }
  EXPECT_EQ(pool.kept_bytes(), 66 * MiB);
  pool.release();
}

TEST(LargeArray, EmptyAndImpossibleSizes) {
  const LargeArray<double> empty(0);
  EXPECT_EQ(empty.data(), nullptr);
  EXPECT_EQ(empty.bytes(), 0u);
  EXPECT_THROW(LargeArray<double>(std::size_t{1} << 62), std::bad_alloc);
}

}  // namespace

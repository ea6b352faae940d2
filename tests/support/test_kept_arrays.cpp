// Arrays whose storage the process's pool keeps (support/chunk_pool.hpp):
//   - KeptVector (support/kept_vector.hpp): which sizes go to the pool, reuse of the kept storage
//     by the next vector, alignment, and the limit;
//   - LargeArray (support/large_buffer.hpp): 2 MiB aligned, its chunk reused by the next array of
//     about the same size and not by a small one.
// Each test runs in a process of its own (gtest_discover_tests), so the process's pool starts
// empty.
#include <panelrad/support/chunk_pool.hpp>
#include <panelrad/support/kept_vector.hpp>
#include <panelrad/support/large_buffer.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <new>
#include <numeric>

namespace {

using panelrad::ChunkPool;
using panelrad::KeptAllocator;
using panelrad::KeptVector;
using panelrad::LargeArray;

constexpr std::size_t kKept = KeptAllocator<double>::kMinKeptBytes / sizeof(double);  // doubles at the threshold
constexpr std::size_t MiB = std::size_t{1} << 20;

std::uintptr_t address(const void* p) { return reinterpret_cast<std::uintptr_t>(p); }

// Below the threshold: the global allocator, nothing kept. At and above: a chunk, kept when freed
// (the array and its 64-byte header rounded up to whole 2 MiB chunks).
TEST(KeptVector, LargeStorageGoesBackToThePool) {
  ChunkPool& pool = ChunkPool::process();
  pool.release();
  { KeptVector<double> small(kKept - 1); }
  EXPECT_EQ(pool.kept_bytes(), 0u);
  { KeptVector<double> at(kKept); }
  EXPECT_EQ(pool.kept_bytes(), ChunkPool::kChunkBytes);
  pool.release();
  { KeptVector<double> two_chunks(2 * MiB / sizeof(double)); }  // 2 MiB + the header
  EXPECT_EQ(pool.kept_bytes(), 2 * ChunkPool::kChunkBytes);
  pool.release();
}

// The next vector of a size that fits takes the kept chunk: the same storage, with what the first
// wrote still in it (resize leaves the elements unwritten), and nothing kept while it lives.
TEST(KeptVector, NextVectorReusesTheKeptStorageUnwritten) {
  ChunkPool& pool = ChunkPool::process();
  pool.release();
  const double* where = nullptr;
  {
    KeptVector<double> first(kKept);
    std::iota(first.begin(), first.end(), 1.0);
    where = first.data();
  }
  KeptVector<double> second;
  second.resize(kKept);
  EXPECT_EQ(second.data(), where);
  EXPECT_EQ(pool.kept_bytes(), 0u);
  for (std::size_t i = 0; i < kKept; i += 997) EXPECT_EQ(second[i], static_cast<double>(i + 1)) << i;
}

// Kept storage is 64-byte aligned, the rest aligned for the element; growth by push_back moves
// the contents across both paths, and a copy gets storage of its own.
TEST(KeptVector, AlignedAndGrowsLikeAVector) {
  ChunkPool::process().release();
  KeptVector<std::array<double, 2>> v;
  for (std::size_t i = 0; i < 3 * kKept; ++i) {
    v.push_back({static_cast<double>(i), -static_cast<double>(i)});
    const bool kept = v.capacity() * sizeof(v[0]) >= KeptAllocator<double>::kMinKeptBytes;
    EXPECT_EQ(address(v.data()) % (kept ? 64 : alignof(std::array<double, 2>)), 0u) << "size " << v.size();
  }
  for (std::size_t i = 0; i < v.size(); ++i) ASSERT_EQ(v[i][0], static_cast<double>(i)) << i;
  const KeptVector<std::array<double, 2>> copy = v;
  EXPECT_TRUE(std::equal(copy.begin(), copy.end(), v.begin()));
  EXPECT_NE(copy.data(), v.data());
}

// The pool's limit holds for kept vectors too: with limit 0 nothing is kept.
TEST(KeptVector, PoolLimitBoundsWhatIsKept) {
  ChunkPool& pool = ChunkPool::process();
  pool.release();
  const std::size_t saved = pool.limit();
  pool.set_limit(0);
  { KeptVector<double> v(4 * kKept); }
  EXPECT_EQ(pool.kept_bytes(), 0u);
  pool.set_limit(saved);
}

TEST(KeptVector, ImpossibleSizeThrowsBadAlloc) {
  KeptAllocator<double> a;
  EXPECT_THROW((void)a.allocate(std::size_t{1} << 62), std::bad_alloc);
}

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

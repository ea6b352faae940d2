// The pool of kept chunks and the arenas carved from it (support/chunk_pool.hpp): sizes and
// alignment, reuse of kept memory, the limit, and arrays that never overlap.
#include <panelrad/support/chunk_pool.hpp>

#include <gtest/gtest.h>

#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

namespace {

using panelrad::ChunkArena;
using panelrad::ChunkPool;

constexpr std::size_t MiB = std::size_t{1} << 20;

std::uintptr_t address(const void* p) { return reinterpret_cast<std::uintptr_t>(p); }

TEST(ChunkPool, ChunksAreWholeHugePagesAligned) {
  ChunkPool pool;
  const ChunkPool::Chunk a = pool.acquire(1), b = pool.acquire(3 * MiB), c = pool.acquire(4 * MiB);
  EXPECT_EQ(a.bytes, 2 * MiB);
  EXPECT_EQ(b.bytes, 4 * MiB);
  EXPECT_EQ(c.bytes, 4 * MiB);
  for (const ChunkPool::Chunk& k : {a, b, c}) EXPECT_EQ(address(k.data) % (2 * MiB), 0u);
  EXPECT_EQ(pool.kept_bytes(), 0u);
  for (const ChunkPool::Chunk& k : {a, b, c}) pool.give_back(k);
  EXPECT_EQ(pool.kept_bytes(), 10 * MiB);
  pool.release();
  EXPECT_EQ(pool.kept_bytes(), 0u);
}

// A chunk given back is handed out again with its contents: the memory stayed with the process.
TEST(ChunkPool, KeptChunkIsHandedOutAgain) {
  ChunkPool pool;
  ChunkPool::Chunk a = pool.acquire(2 * MiB);
  std::memset(a.data, 0x5a, a.bytes);
  std::byte* const where = a.data;
  pool.give_back(a);
  const ChunkPool::Chunk b = pool.acquire(MiB);
  EXPECT_EQ(b.data, where);
  EXPECT_EQ(b.bytes, 2 * MiB);
  EXPECT_EQ(pool.kept_bytes(), 0u);
  EXPECT_TRUE(std::all_of(b.data, b.data + b.bytes, [](std::byte x) { return x == std::byte{0x5a}; }));
  pool.give_back(b);
}

// The smallest kept chunk that holds the request is taken; a larger request gets a new chunk.
TEST(ChunkPool, SmallestFittingChunkIsTaken) {
  ChunkPool pool;
  const ChunkPool::Chunk big = pool.acquire(6 * MiB), small = pool.acquire(2 * MiB);
  pool.give_back(big);
  pool.give_back(small);
  const ChunkPool::Chunk a = pool.acquire(1);
  EXPECT_EQ(a.data, small.data);
  const ChunkPool::Chunk b = pool.acquire(8 * MiB);
  EXPECT_NE(b.data, big.data);
  EXPECT_EQ(b.bytes, 8 * MiB);
  EXPECT_EQ(pool.kept_bytes(), 6 * MiB);
  pool.give_back(a);
  pool.give_back(b);
}

// A kept chunk more than twice the request (and more than one chunk above it) stays kept.
TEST(ChunkPool, SmallRequestLeavesALargeChunk) {
  ChunkPool pool;
  const ChunkPool::Chunk big = pool.acquire(8 * MiB), fits = pool.acquire(4 * MiB);
  pool.give_back(big);
  EXPECT_EQ(pool.kept_for(1), 0u);  // kept_for names what acquire hands out: here new memory
  EXPECT_EQ(pool.kept_for(5 * MiB), 8 * MiB);
  const ChunkPool::Chunk a = pool.acquire(1);
  EXPECT_NE(a.data, big.data);
  EXPECT_EQ(a.bytes, 2 * MiB);
  pool.give_back(fits);
  const ChunkPool::Chunk b = pool.acquire(1);  // 4 MiB: one chunk above the request
  EXPECT_EQ(b.data, fits.data);
  const ChunkPool::Chunk c = pool.acquire(5 * MiB);  // 6 MiB wanted: the 8 MiB chunk fits
  EXPECT_EQ(c.data, big.data);
  EXPECT_EQ(pool.kept_bytes(), 0u);
  EXPECT_EQ(pool.kept_for(5 * MiB), 0u);
  EXPECT_EQ(pool.kept_for(std::size_t{1} << 63), 0u);
  for (const ChunkPool::Chunk& k : {a, b, c}) pool.give_back(k);
}

TEST(ChunkPool, TakeKeptEmptiesThePool) {
  ChunkPool pool;
  const ChunkPool::Chunk a = pool.acquire(1), b = pool.acquire(5 * MiB);
  pool.give_back(a);
  pool.give_back(b);
  std::vector<ChunkPool::Chunk> taken = pool.take_kept();
  EXPECT_EQ(pool.kept_bytes(), 0u);
  ASSERT_EQ(taken.size(), 2u);
  std::sort(taken.begin(), taken.end(),
            [](const ChunkPool::Chunk& x, const ChunkPool::Chunk& y) { return x.bytes < y.bytes; });
  EXPECT_EQ(taken[0].data, a.data);
  EXPECT_EQ(taken[1].data, b.data);
  for (const ChunkPool::Chunk& k : taken) pool.give_back(k);
  EXPECT_EQ(pool.kept_bytes(), 8 * MiB);
}

// The process's pool keeps a sixteenth of the memory available, in whole chunks, and at least
// 256 MiB: 1.5 GiB of 24 GiB.
TEST(ChunkPool, DefaultLimitIsASixteenthOfTheAvailableMemory) {
  EXPECT_EQ(ChunkPool::default_limit(0), ChunkPool::kMinDefaultLimit);
  EXPECT_EQ(ChunkPool::default_limit(16 * ChunkPool::kMinDefaultLimit), ChunkPool::kMinDefaultLimit);
  EXPECT_EQ(ChunkPool::default_limit(24 * 1024 * MiB), 1536 * MiB);
  EXPECT_EQ(ChunkPool::default_limit(16 * (300 * MiB) + 31 * MiB), 300 * MiB);
  EXPECT_EQ(ChunkPool::default_limit(16 * (301 * MiB)), 300 * MiB);  // rounded down to whole chunks
  EXPECT_EQ(ChunkPool::default_limit(std::numeric_limits<std::size_t>::max() / 4), ChunkPool::kMinDefaultLimit);
  EXPECT_GE(ChunkPool::process().limit(), ChunkPool::kMinDefaultLimit);
}

TEST(ChunkPool, LimitBoundsWhatIsKept) {
  ChunkPool pool;
  EXPECT_EQ(pool.limit(), ChunkPool::kMinDefaultLimit);
  pool.set_limit(4 * MiB);
  const ChunkPool::Chunk a = pool.acquire(1), b = pool.acquire(1), c = pool.acquire(1);
  pool.give_back(a);
  pool.give_back(b);
  pool.give_back(c);  // above the limit: freed
  EXPECT_EQ(pool.kept_bytes(), 4 * MiB);
  pool.set_limit(2 * MiB);
  EXPECT_EQ(pool.kept_bytes(), 2 * MiB);
  pool.set_limit(0);
  EXPECT_EQ(pool.kept_bytes(), 0u);
  pool.give_back(pool.acquire(1));
  EXPECT_EQ(pool.kept_bytes(), 0u);
}

// Random sizes from two slots: every array is 64-byte aligned, lies in its slot's chunks and
// overlaps no other; an array larger than a chunk gets a chunk of its own. Clearing gives every
// chunk back.
TEST(ChunkArena, ArraysAreAlignedAndDisjoint) {
  ChunkPool pool;
  pool.set_limit(std::size_t{1} << 40);
  std::vector<std::pair<std::uintptr_t, std::uintptr_t>> spans;
  std::size_t held = 0;
  {
    ChunkArena arena(2, pool);
    std::mt19937 rng(7);
    std::uniform_int_distribution<std::size_t> size(1, 200'000);
    for (int k = 0; k < 200; ++k) {
      const std::size_t bytes = k == 100 ? 5 * MiB : size(rng);
      std::byte* p = arena.allocate(k % 2, bytes);
      EXPECT_EQ(address(p) % 64, 0u);
      std::memset(p, k, bytes);  // writable over its whole length (the sanitizer build checks)
      spans.emplace_back(address(p), address(p) + bytes);
    }
    held = arena.chunk_bytes();
    EXPECT_GE(held, 5 * MiB + 2 * ChunkPool::kChunkBytes);
    EXPECT_EQ(held % ChunkPool::kChunkBytes, 0u);
    EXPECT_EQ(pool.kept_bytes(), 0u);
  }
  std::sort(spans.begin(), spans.end());
  for (std::size_t k = 1; k < spans.size(); ++k) EXPECT_LE(spans[k - 1].second, spans[k].first);
  EXPECT_EQ(pool.kept_bytes(), held);
}

// One thread per slot at once, each writing and reading back its own arrays.
TEST(ChunkArena, ThreadsFillTheirOwnSlots) {
  ChunkPool pool;
  const int threads = 4;
  ChunkArena arena(threads, pool);
  std::vector<int> wrong(threads, 0);
#pragma omp parallel num_threads(threads)
  {
    const int t = omp_get_thread_num();
    std::vector<std::int32_t*> arrays;
    for (int k = 0; k < 64; ++k) {
      auto* a = reinterpret_cast<std::int32_t*>(arena.allocate(t, 10'000 * sizeof(std::int32_t)));
      for (int j = 0; j < 10'000; ++j) a[j] = t * 1'000'000 + k * 10'000 + j;
      arrays.push_back(a);
    }
    for (int k = 0; k < 64; ++k)
      for (int j = 0; j < 10'000; ++j) wrong[static_cast<std::size_t>(t)] += arrays[static_cast<std::size_t>(k)][j] != t * 1'000'000 + k * 10'000 + j;
  }
  for (int t = 0; t < threads; ++t) EXPECT_EQ(wrong[static_cast<std::size_t>(t)], 0) << "slot " << t;
  arena.clear();
  EXPECT_EQ(arena.chunk_bytes(), 0u);
}

TEST(ChunkArena, RejectsSlotsOutOfRange) {
  ChunkPool pool;
  EXPECT_THROW(ChunkArena(0, pool), std::invalid_argument);
  ChunkArena arena(2, pool);
  EXPECT_THROW(arena.allocate(2, 8), std::out_of_range);
  EXPECT_THROW(arena.allocate(-1, 8), std::out_of_range);
  EXPECT_THROW(arena.allocate(0, std::size_t{1} << 63), std::bad_alloc);
}

}  // namespace

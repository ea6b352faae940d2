#pragma once
// Memory in chunks for arrays that a setup builds and a later setup builds again: the fast
// operator's near and far field lists (42)-(43). A chunk is 2 MiB or a multiple, 2 MiB aligned,
// with huge pages advised (large_buffer.hpp). When its owner is destroyed the chunk goes back to
// the process's pool, which keeps it, up to a limit, instead of returning it to the system: the
// next setup then writes to memory already backed, where new memory costs a page fault per 4 KiB
// (in a virtual machine, the host backing the page as well), or the kernel zeroing each huge page
// on one processor's memory bandwidth, and the allocator may give freed memory back between two
// setups. The process's pool keeps up to a sixteenth of the memory available when it is first
// used (at least 256 MiB): enough for the stored far coefficients of n ~ 5e4 on a 24 GB machine.
// The memory gate of a setup (FastOperator) releases the kept chunks before it refuses a size,
// and stores the far coefficients without asking for new memory when a kept chunk takes them.
#include <cstddef>
#include <mutex>
#include <vector>

namespace panelrad {

class ChunkPool {
 public:
  struct Chunk {
    std::byte* data = nullptr;
    std::size_t bytes = 0;
  };
  static constexpr std::size_t kChunkBytes = std::size_t{2} << 20;  ///< the unit: one huge page
  /// The least default limit, and the limit of a pool made without one.
  static constexpr std::size_t kMinDefaultLimit = std::size_t{256} << 20;

  /// The process's pool (never destroyed, so that owners may give chunks back at exit), its
  /// limit default_limit(available_memory_bytes()) read at the first call.
  static ChunkPool& process();
  /// The process pool's limit for `available` bytes of memory: the larger of kMinDefaultLimit and
  /// available / 16, rounded down to whole chunks; kMinDefaultLimit when `available` is unknown
  /// (SIZE_MAX / 4 or more, as available_memory_bytes() reports no limit).
  static std::size_t default_limit(std::size_t available);

  /// A kept chunk of at least `bytes` rounded up to kChunkBytes (the smallest such, and only if
  /// at most twice that or one chunk more: a small array does not take a large array's memory),
  /// else a new one of that size; its contents are unspecified. When the new one cannot be had,
  /// the kept chunks are freed and it is tried once more; then std::bad_alloc.
  Chunk acquire(std::size_t bytes);
  /// The size of the kept chunk that acquire(bytes) would hand out now, 0 when it would take new
  /// memory.
  std::size_t kept_for(std::size_t bytes) const;
  /// Keeps `chunk` while the kept bytes stay within the limit, else frees it.
  void give_back(Chunk chunk) noexcept;
  /// Frees every kept chunk.
  void release() noexcept;
  /// Takes every kept chunk out of the pool: the caller's to give back (or to free).
  std::vector<Chunk> take_kept();
  std::size_t kept_bytes() const;
  std::size_t limit() const;
  /// Sets the most that is kept (0: nothing), freeing what is above it.
  void set_limit(std::size_t bytes);

  explicit ChunkPool(std::size_t limit = kMinDefaultLimit) : limit_(limit) {}
  ChunkPool(const ChunkPool&) = delete;
  ChunkPool& operator=(const ChunkPool&) = delete;
  ~ChunkPool();

 private:
  void trim_to(std::size_t bytes) noexcept;  // with mutex_ held
  // The kept chunk for a request of `wanted` bytes (whole chunks), or kept_.end(); with mutex_ held.
  std::vector<Chunk>::const_iterator fitting(std::size_t wanted) const;

  mutable std::mutex mutex_;
  std::vector<Chunk> kept_;
  std::size_t kept_bytes_ = 0;
  std::size_t limit_;
};

/// The chunks of one owner, taken from a pool and carved into arrays by up to `slots` threads at
/// once, each slot from chunks of its own; all given back when the owner clears or destroys it.
class ChunkArena {
 public:
  ChunkArena() = default;
  explicit ChunkArena(int slots, ChunkPool& pool = ChunkPool::process());
  ChunkArena(const ChunkArena&) = delete;
  ChunkArena& operator=(const ChunkArena&) = delete;
  ~ChunkArena() { clear(); }

  /// `bytes` uninitialized bytes, 64-byte aligned, from slot `slot`'s chunks (a new chunk when
  /// the current one has no room); std::bad_alloc when no chunk can be had. One thread per slot.
  std::byte* allocate(int slot, std::size_t bytes);
  /// Gives every chunk back to the pool.
  void clear() noexcept;
  /// Gives every chunk back, then takes `slots` slots from `pool`.
  void reset(int slots, ChunkPool& pool = ChunkPool::process());
  /// The bytes of the chunks held.
  std::size_t chunk_bytes() const;

 private:
  struct alignas(64) Slot {  // a cache line of its own: each thread moves its own `used`
    std::vector<ChunkPool::Chunk> chunks;
    std::size_t used = 0;  // of the last chunk
  };
  ChunkPool* pool_ = nullptr;
  std::vector<Slot> slots_;
};

}  // namespace panelrad

#pragma once
// A std::vector for the arrays that a setup sizes once, fills in parallel and a later setup sizes
// again (the fast operator's cluster frames and reflectivities, the target clusters' lists).
//   - Storage of at least kMinKeptBytes is a chunk of the process's pool (chunk_pool.hpp), given
//     back to it when the vector frees it: the next setup writes to memory already backed.
//     Whether glibc keeps such an array's memory after free, or unmaps it (or trims its heap),
//     depends on its history (its mmap threshold moves between 128 KiB and 32 MiB as mapped
//     blocks are freed): in some processes every setup would pay a page fault per 4 KiB (in a
//     virtual machine, one of the host's too), and page faults do not scale with threads.
//   - Smaller storage comes from the global operator new, aligned for T.
//   - resize() leaves new elements default-initialized, as UninitializedVector: a
//     parallel loop writes them first.
#include <panelrad/support/uninitialized_vector.hpp>

#include <cstddef>
#include <limits>
#include <new>
#include <vector>

namespace panelrad {

namespace kept_detail {
/// Storage of at least kMinKeptBytes bytes: a chunk of ChunkPool::process(), 64-byte aligned.
void* acquire(std::size_t bytes);
/// Gives storage from acquire() back to the pool.
void give_back(void* p) noexcept;
}  // namespace kept_detail

/// An UninitializedAllocator (resize default-initializes) whose large storage the pool keeps.
template <class T>
struct KeptAllocator : UninitializedAllocator<T> {
  static_assert(alignof(T) <= 64, "KeptAllocator: storage is 64-byte aligned");
  using value_type = T;
  template <class U>
  struct rebind {
    using other = KeptAllocator<U>;
  };
  /// Arrays of this size and more are kept: an eighth of a chunk (ChunkPool::kChunkBytes).
  static constexpr std::size_t kMinKeptBytes = std::size_t{256} << 10;

  KeptAllocator() = default;
  template <class U>
  KeptAllocator(const KeptAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    if (n > std::numeric_limits<std::size_t>::max() / sizeof(T)) throw std::bad_array_new_length();
    if (n * sizeof(T) >= kMinKeptBytes) return static_cast<T*>(kept_detail::acquire(n * sizeof(T)));
    return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t{alignof(T)}));
  }
  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) >= kMinKeptBytes)
      kept_detail::give_back(p);
    else
      ::operator delete(p, std::align_val_t{alignof(T)});
  }
};

template <class T>
using KeptVector = std::vector<T, KeptAllocator<T>>;

}  // namespace panelrad

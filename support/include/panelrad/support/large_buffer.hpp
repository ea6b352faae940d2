#pragma once
// A large array of numbers for operator data (gigabytes at n ~ 2e5): allocated uninitialized,
// aligned to 2 MiB and advised to use transparent huge pages (one page fault per 2 MiB instead
// of per 4 KiB, which dominates setup in virtual machines), and first touched by the threads that
// fill it. Its memory is a chunk of the process's pool (chunk_pool.hpp) and goes back to it, so
// that a later operator's array of about the same size is written to memory already backed
// (when the pool's limit lets it keep the chunk). Throws std::bad_alloc when the memory cannot
// be had.
#include <panelrad/support/chunk_pool.hpp>

#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>

namespace panelrad {

namespace large_buffer_detail {
void* allocate(std::size_t bytes);  ///< 2 MiB aligned, huge pages advised; std::bad_alloc on failure
void release(void* p);
}  // namespace large_buffer_detail

template <class T>
class LargeArray {
  static_assert(std::is_trivially_copyable_v<T>, "LargeArray holds plain numbers, left uninitialized");

 public:
  LargeArray() = default;
  explicit LargeArray(std::size_t count) : size_(count) {
    if (count > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    if (count) {
      const ChunkPool::Chunk chunk = ChunkPool::process().acquire(count * sizeof(T));
      data_ = std::unique_ptr<T[], Free>(reinterpret_cast<T*>(chunk.data), Free{chunk.bytes});
    }
  }
  T* data() { return data_.get(); }
  const T* data() const { return data_.get(); }
  std::size_t size() const { return size_; }
  std::size_t bytes() const { return size_ * sizeof(T); }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }

 private:
  struct Free {
    std::size_t chunk_bytes = 0;
    void operator()(T* p) const { ChunkPool::process().give_back({reinterpret_cast<std::byte*>(p), chunk_bytes}); }
  };
  std::unique_ptr<T[], Free> data_;
  std::size_t size_ = 0;
};

using LargeBuffer = LargeArray<double>;

}  // namespace panelrad

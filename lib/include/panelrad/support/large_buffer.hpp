#pragma once
// A large array of numbers for operator data (gigabytes at n ~ 2e5): allocated uninitialized,
// aligned to 2 MiB and advised to use transparent huge pages (one page fault per 2 MiB instead
// of per 4 KiB, which dominates setup in virtual machines), and first touched by the threads that
// fill it. Its memory is a chunk of the process's pool (chunk_pool.hpp) and goes back to it, so
// that a later operator's array of about the same size is written to memory already backed
// (when the pool's limit lets it keep the chunk). Throws std::bad_alloc when the memory cannot
// be had.
#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>

namespace panelrad {

namespace large_buffer_detail {
void* allocate(std::size_t bytes);  ///< 2 MiB aligned, huge pages advised; std::bad_alloc on failure
void release(void* p);
/// A chunk of ChunkPool::process() of at least `bytes`; its size is stored in `chunk_bytes`.
void* acquire_kept(std::size_t bytes, std::size_t& chunk_bytes);
/// Gives a chunk from acquire_kept back to the pool.
void give_back_kept(void* p, std::size_t chunk_bytes) noexcept;
}  // namespace large_buffer_detail

template <class T>
class LargeArray {
  static_assert(std::is_trivially_copyable_v<T>, "LargeArray holds plain numbers, left uninitialized");

 public:
  LargeArray() = default;
  explicit LargeArray(std::size_t count) : size_(count) {
    if (count > static_cast<std::size_t>(-1) / sizeof(T)) throw std::bad_array_new_length();
    std::size_t chunk_bytes = 0;
    if (count) {
      T* p = static_cast<T*>(large_buffer_detail::acquire_kept(count * sizeof(T), chunk_bytes));
      data_ = std::unique_ptr<T[], Free>(p, Free{chunk_bytes});
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
    void operator()(T* p) const { large_buffer_detail::give_back_kept(p, chunk_bytes); }
  };
  std::unique_ptr<T[], Free> data_;
  std::size_t size_ = 0;
};

using LargeBuffer = LargeArray<double>;

}  // namespace panelrad

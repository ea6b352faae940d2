#pragma once
// A std::vector whose resize leaves new elements default-initialized (for numbers and Eigen's
// fixed-size vectors: not written at all), so that a large array sized once and then filled by a
// parallel loop is first touched by the threads that fill it, not zeroed by one thread first.
#include <memory>
#include <type_traits>
#include <utility>
#include <vector>

namespace panelrad {

template <class T>
struct UninitializedAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() = default;
  template <class U>
  UninitializedAllocator(const UninitializedAllocator<U>&) noexcept {}
  /// resize(n) and the vector's other value-initializations: default-initialization instead.
  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible_v<U>) {
    ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <class T>
using UninitializedVector = std::vector<T, UninitializedAllocator<T>>;

}  // namespace panelrad

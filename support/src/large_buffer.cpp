#include <panelrad/support/large_buffer.hpp>

#include <sys/mman.h>

#include <cstdlib>
#include <new>

namespace panelrad::large_buffer_detail {

void* allocate(std::size_t bytes) {
  constexpr std::size_t kHugePage = std::size_t{2} << 20;
  const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
  void* p = nullptr;
  if (posix_memalign(&p, kHugePage, rounded) != 0 || p == nullptr) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
  (void)madvise(p, rounded, MADV_HUGEPAGE);  // advice only: fine if the kernel declines
#endif
  return p;
}

void release(void* p) { std::free(p); }

}  // namespace panelrad::large_buffer_detail

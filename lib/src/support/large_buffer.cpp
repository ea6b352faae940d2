#include <panelrad/support/large_buffer.hpp>

#include <sys/mman.h>

#include <cstdlib>
#include <new>

namespace panelrad {

void LargeBuffer::Free::operator()(double* p) const { std::free(p); }

LargeBuffer::LargeBuffer(std::size_t count) : size_(count) {
  if (count == 0) return;
  constexpr std::size_t kHugePage = std::size_t{2} << 20;
  const std::size_t bytes = (count * sizeof(double) + kHugePage - 1) / kHugePage * kHugePage;
  void* p = nullptr;
  if (posix_memalign(&p, kHugePage, bytes) != 0 || p == nullptr) throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
  (void)madvise(p, bytes, MADV_HUGEPAGE);  // advice only: fine if the kernel declines
#endif
  data_.reset(static_cast<double*>(p));
}

}  // namespace panelrad

#pragma once
// A large array of doubles for operator data (gigabytes at n ~ 2e5): allocated uninitialized,
// aligned to 2 MiB and advised to use transparent huge pages (one page fault per 2 MiB instead
// of per 4 KiB, which dominates setup in virtual machines), and first touched by the threads that
// fill it. Throws std::bad_alloc when the memory cannot be had.
#include <cstddef>
#include <memory>

namespace panelrad {

class LargeBuffer {
 public:
  LargeBuffer() = default;
  explicit LargeBuffer(std::size_t count);
  double* data() { return data_.get(); }
  const double* data() const { return data_.get(); }
  std::size_t size() const { return size_; }
  std::size_t bytes() const { return size_ * sizeof(double); }
  double& operator[](std::size_t i) { return data_[i]; }
  const double& operator[](std::size_t i) const { return data_[i]; }

 private:
  struct Free {
    void operator()(double* p) const;
  };
  std::unique_ptr<double[], Free> data_;
  std::size_t size_ = 0;
};

}  // namespace panelrad

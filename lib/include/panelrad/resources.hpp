#pragma once
// Run-time resources: wall clock, peak resident memory, memory available for a new allocation.
#include <chrono>
#include <cstddef>
#include <string>

namespace panelrad {

/// Wall-clock stopwatch.
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  void restart() { start_ = std::chrono::steady_clock::now(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

/// Peak resident set size of this process in MiB (VmHWM), 0 if unknown.
double peak_rss_mb();
/// Bytes the system can still give this process (MemAvailable), or a large number if unknown.
std::size_t available_memory_bytes();
/// "1.23 GB" style.
std::string format_bytes(double bytes);

/// Threads used by parallel regions (OpenMP); set_threads(0) keeps the default.
void set_threads(int threads);
int max_threads();

}  // namespace panelrad

#pragma once
// Run-time resources: wall clock, peak resident memory, memory available for a new allocation,
// and the number of threads worth starting.
#include <panelrad/support/error.hpp>
#include <panelrad/support/byte_size.hpp>

#include <chrono>
#include <cstddef>
#include <stdexcept>
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

/// The memory this process can still allocate, from each limit that applies, in bytes.
/// A limit that does not apply (or cannot be read) is kUnlimited.
struct MemoryAvailability {
  static constexpr std::size_t kUnlimited = static_cast<std::size_t>(-1);
  std::size_t system = kUnlimited;         ///< MemAvailable of /proc/meminfo
  std::size_t address_space = kUnlimited;  ///< RLIMIT_AS (ulimit -v) soft limit minus VmSize
  std::size_t cgroup = kUnlimited;         ///< memory.max - memory.current (cgroup v2) or
                                           ///< memory.limit_in_bytes - memory.usage_in_bytes (v1),
                                           ///< the least over the process's cgroup and its ancestors
  /// The least of the three (a large number when none is known).
  std::size_t bytes() const;
  /// Which limit is the least: "system memory (MemAvailable)", "address-space limit (ulimit -v)"
  /// or "cgroup memory limit".
  std::string binding() const;
};

/// Reads the three limits now. Which cgroups hold the process (/proc/self/cgroup and
/// /proc/self/mountinfo) is looked up at the first call; their limits and usage at every call.
MemoryAvailability memory_availability();

namespace detail {
/// The cgroup part of MemoryAvailability from the texts of /proc/self/cgroup and
/// /proc/self/mountinfo, with the cgroup file systems looked up under `fs_root` ("" for the real
/// ones; a test passes a directory holding a made-up hierarchy). For the memory controller's
/// cgroup (v2: the "0::" line; v1: the line naming "memory") and each ancestor up to its mount,
/// headroom = limit - (usage - inactive file cache), the cache being reclaimable; the least wins.
std::size_t cgroup_headroom(const std::string& proc_self_cgroup, const std::string& mountinfo,
                            const std::string& fs_root);
}  // namespace detail

/// Bytes this process can still allocate: min(MemAvailable, RLIMIT_AS headroom, cgroup
/// headroom), see MemoryAvailability; SIZE_MAX / 4 when none of them is known.
std::size_t available_memory_bytes();

/// "5.86 GB available (address-space limit, ulimit -v)": the figure and which limit gives it.
std::string describe_available_memory();

/// Threads used by parallel regions (OpenMP); set_threads(0) keeps the default.
void set_threads(int threads);
int max_threads();
/// The most threads accepted for set_threads: 4 per processor this process may run on
/// (omp_get_num_procs), and at most the OpenMP thread limit (omp_get_thread_limit). More threads
/// than that only add stacks and scheduling, never speed, and can exhaust the address space.
int max_useful_threads();

}  // namespace panelrad

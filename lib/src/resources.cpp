#include <panelrad/resources.hpp>

#include <omp.h>

#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

namespace panelrad {

namespace {
// Reads "<key>: <value> kB" from a /proc file; returns -1 when absent.
long long read_proc_kb(const char* file, const std::string& key) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.compare(0, key.size(), key) == 0 && line.size() > key.size() && line[key.size()] == ':') {
      std::istringstream ss(line.substr(key.size() + 1));
      long long kb = -1;
      ss >> kb;
      return kb;
    }
  }
  return -1;
}
}  // namespace

double peak_rss_mb() {
  const long long kb = read_proc_kb("/proc/self/status", "VmHWM");
  return kb < 0 ? 0.0 : static_cast<double>(kb) / 1024.0;
}

std::size_t available_memory_bytes() {
  const long long kb = read_proc_kb("/proc/meminfo", "MemAvailable");
  if (kb < 0) return std::numeric_limits<std::size_t>::max() / 4;
  return static_cast<std::size_t>(kb) * 1024u;
}

std::string format_bytes(double bytes) {
  char buf[64];
  if (bytes >= 1e9) std::snprintf(buf, sizeof buf, "%.2f GB", bytes / 1e9);
  else if (bytes >= 1e6) std::snprintf(buf, sizeof buf, "%.1f MB", bytes / 1e6);
  else if (bytes >= 1e3) std::snprintf(buf, sizeof buf, "%.1f kB", bytes / 1e3);
  else std::snprintf(buf, sizeof buf, "%.0f B", bytes);
  return buf;
}

void set_threads(int threads) {
  if (threads > 0) omp_set_num_threads(threads);
}

int max_threads() { return omp_get_max_threads(); }

}  // namespace panelrad

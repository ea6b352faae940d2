#include <panelrad/support/resources.hpp>

#include <omp.h>
#include <sys/resource.h>

#include <algorithm>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

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

// At most max_bytes of a file, read in pieces of 16 KiB: the /proc and cgroup files are a few KiB,
// and a buffer of max_bytes filled up front would cost its page faults on every call.
std::string read_text(const std::string& file, std::size_t max_bytes = 1 << 20) {
  std::ifstream in(file);
  if (!in) return {};
  std::string text;
  char piece[1 << 14];
  while (text.size() < max_bytes && in) {
    in.read(piece, static_cast<std::streamsize>(std::min(sizeof piece, max_bytes - text.size())));
    text.append(piece, static_cast<std::size_t>(in.gcount()));
  }
  return text;
}

// A cgroup file holding one number ("max" or a value at or above 2^62, v1's "no limit", count as
// unlimited); -1 when absent or unlimited.
long long read_limit(const std::string& file) {
  std::istringstream in(read_text(file, 64));
  std::string word;
  if (!(in >> word) || word == "max") return -1;
  try {
    const unsigned long long v = std::stoull(word);
    return v >= (1ULL << 62) ? -1 : static_cast<long long>(v);
  } catch (const std::exception&) {
    return -1;
  }
}

// "<key> <value>" in a memory.stat file; 0 when absent.
long long read_stat(const std::string& file, const std::string& key) {
  std::istringstream in(read_text(file));
  std::string k;
  long long v = 0;
  while (in >> k >> v)
    if (k == key) return v;
  return 0;
}

struct CgroupMount {
  std::string root, point;  // root of the hierarchy seen at `point` (mountinfo fields 4 and 5)
};

// The mount of the memory controller: cgroup2, or cgroup v1 with "memory" among its options.
bool find_mount(const std::string& mountinfo, bool v2, CgroupMount& out) {
  std::istringstream lines(mountinfo);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream f(line);
    std::vector<std::string> field;
    for (std::string w; f >> w;) field.push_back(w);
    const auto dash = std::find(field.begin(), field.end(), "-");
    if (field.size() < 5 || dash == field.end() || dash + 1 == field.end()) continue;
    const std::string& type = *(dash + 1);
    const std::string options = dash + 3 < field.end() ? *(dash + 3) : std::string();
    const bool memory_v1 = type == "cgroup" && ("," + options + ",").find(",memory,") != std::string::npos;
    if ((v2 && type == "cgroup2") || (!v2 && memory_v1)) {
      out.root = field[3];
      out.point = field[4];
      return true;
    }
  }
  return false;
}

// Headroom of the cgroup at `path` (as /proc/self/cgroup names it) and of its ancestors up to
// the mount point; kUnlimited when none has a limit.
std::size_t headroom_along(const CgroupMount& mount, std::string path, const std::string& fs_root, bool v2) {
  // The path relative to the mount's root (a cgroup namespace shows the mount root as "/").
  if (mount.root != "/" && path.compare(0, mount.root.size(), mount.root) == 0) path = path.substr(mount.root.size());
  while (path.size() > 1 && path.back() == '/') path.pop_back();
  const char* limit_file = v2 ? "/memory.max" : "/memory.limit_in_bytes";
  const char* usage_file = v2 ? "/memory.current" : "/memory.usage_in_bytes";
  const char* cache_key = v2 ? "inactive_file" : "total_inactive_file";
  std::size_t least = MemoryAvailability::kUnlimited;
  for (;;) {
    const std::string dir = fs_root + mount.point + (path == "/" ? "" : path);
    const long long limit = read_limit(dir + limit_file);
    if (limit >= 0) {
      long long usage = read_limit(dir + usage_file);
      usage = std::max(0LL, usage - read_stat(dir + "/memory.stat", cache_key));
      least = std::min(least, static_cast<std::size_t>(std::max(0LL, limit - usage)));
    }
    if (path.empty() || path == "/") break;
    const std::size_t slash = path.rfind('/');
    path = slash == 0 || slash == std::string::npos ? std::string("/") : path.substr(0, slash);
  }
  return least;
}
}  // namespace

namespace detail {
std::size_t cgroup_headroom(const std::string& proc_self_cgroup, const std::string& mountinfo,
                            const std::string& fs_root) {
  std::size_t least = MemoryAvailability::kUnlimited;
  std::istringstream lines(proc_self_cgroup);
  for (std::string line; std::getline(lines, line);) {
    // "hierarchy-id:controllers:path"
    const std::size_t a = line.find(':'), b = a == std::string::npos ? a : line.find(':', a + 1);
    if (b == std::string::npos) continue;
    const std::string id = line.substr(0, a), controllers = line.substr(a + 1, b - a - 1), path = line.substr(b + 1);
    const bool v2 = id == "0" && controllers.empty();
    const bool v1 = ("," + controllers + ",").find(",memory,") != std::string::npos;
    if (!v2 && !v1) continue;
    CgroupMount mount;
    if (find_mount(mountinfo, v2, mount)) least = std::min(least, headroom_along(mount, path, fs_root, v2));
  }
  return least;
}
}  // namespace detail

double peak_rss_mb() {
  const long long kb = read_proc_kb("/proc/self/status", "VmHWM");
  return kb < 0 ? 0.0 : static_cast<double>(kb) / 1024.0;
}

std::size_t MemoryAvailability::bytes() const {
  const std::size_t least = std::min({system, address_space, cgroup});
  return least == kUnlimited ? std::numeric_limits<std::size_t>::max() / 4 : least;
}

std::string MemoryAvailability::binding() const {
  const std::size_t least = std::min({system, address_space, cgroup});
  if (least == kUnlimited) return "no memory limit could be read";
  if (least == address_space) return "address-space limit, ulimit -v";
  if (least == cgroup) return "cgroup memory limit";
  return "system memory, MemAvailable";
}

MemoryAvailability memory_availability() {
  MemoryAvailability m;
  const long long available_kb = read_proc_kb("/proc/meminfo", "MemAvailable");
  if (available_kb >= 0) m.system = static_cast<std::size_t>(available_kb) * 1024u;
  // RLIMIT_AS bounds the virtual size: what is left is the soft limit minus what is mapped now.
  rlimit as{};
  if (::getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY) {
    const long long vm_kb = read_proc_kb("/proc/self/status", "VmSize");
    const std::size_t mapped = vm_kb > 0 ? static_cast<std::size_t>(vm_kb) * 1024u : 0;
    const auto limit = static_cast<std::size_t>(as.rlim_cur);
    m.address_space = limit > mapped ? limit - mapped : 0;
  }
  m.cgroup = detail::cgroup_headroom(read_text("/proc/self/cgroup"), read_text("/proc/self/mountinfo"), "");
  return m;
}

std::size_t available_memory_bytes() { return memory_availability().bytes(); }

std::string describe_available_memory() {
  const MemoryAvailability m = memory_availability();
  return format_bytes(static_cast<double>(m.bytes())) + " available (" + m.binding() + ")";
}

void set_threads(int threads) {
  if (threads > 0) omp_set_num_threads(threads);
}

int max_threads() { return omp_get_max_threads(); }

int max_useful_threads() {
  const int per_processor = 4 * std::max(1, omp_get_num_procs());
  return std::max(1, std::min(per_processor, omp_get_thread_limit()));
}

}  // namespace panelrad

#include <panelrad/support/resources.hpp>

#include <fcntl.h>
#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <limits>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace panelrad {

namespace {
// At most max_bytes of a file, by read(2) into a stack piece: no stream, locale or buffer to set up
// (the gate runs, serially, in every setup of the fast operator). The /proc and cgroup files are a
// few KiB; an absent or unreadable file gives "".
std::string read_text(const std::string& file, std::size_t max_bytes = 1 << 20) {
  const int fd = ::open(file.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return {};
  std::string text;
  char piece[1 << 12];
  while (text.size() < max_bytes) {
    const ssize_t got = ::read(fd, piece, std::min(sizeof piece, max_bytes - text.size()));
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break;
    text.append(piece, static_cast<std::size_t>(got));
  }
  ::close(fd);
  return text;
}

// "<key>: <value> kB" of a /proc file's text; -1 when absent.
long long proc_kb(const std::string& text, std::string_view key) {
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t end = std::min(text.find('\n', at), text.size());
    const std::string_view line(text.data() + at, end - at);
    if (line.size() > key.size() && line.substr(0, key.size()) == key && line[key.size()] == ':') {
      long long kb = -1;
      const char* first = line.data() + key.size() + 1;
      const char* last = line.data() + line.size();
      while (first < last && (*first == ' ' || *first == '\t')) ++first;
      return std::from_chars(first, last, kb).ec == std::errc() ? kb : -1;
    }
    at = end + 1;
  }
  return -1;
}

long long read_proc_kb(const char* file, std::string_view key) { return proc_kb(read_text(file, 1 << 16), key); }

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

// A directory of the memory controller: the process's cgroup or one of its ancestors.
struct MemoryCgroup {
  std::string dir;
  bool v2 = false;
};

// The directories of the cgroup at `path` (as /proc/self/cgroup names it) and of its ancestors up
// to the mount point, the cgroup's own first.
void cgroups_along(const CgroupMount& mount, std::string path, const std::string& fs_root, bool v2,
                   std::vector<MemoryCgroup>& out) {
  // The path relative to the mount's root (a cgroup namespace shows the mount root as "/").
  if (mount.root != "/" && path.compare(0, mount.root.size(), mount.root) == 0) path = path.substr(mount.root.size());
  while (path.size() > 1 && path.back() == '/') path.pop_back();
  for (;;) {
    out.push_back({fs_root + mount.point + (path == "/" ? "" : path), v2});
    if (path.empty() || path == "/") break;
    const std::size_t slash = path.rfind('/');
    path = slash == 0 || slash == std::string::npos ? std::string("/") : path.substr(0, slash);
  }
}

// The memory controller's directories of this process: from the texts of /proc/self/cgroup and
// /proc/self/mountinfo, for each hierarchy that has the controller (v2: the "0::" line; v1: the
// line naming "memory").
std::vector<MemoryCgroup> memory_cgroups(const std::string& proc_self_cgroup, const std::string& mountinfo,
                                         const std::string& fs_root) {
  std::vector<MemoryCgroup> out;
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
    if (find_mount(mountinfo, v2, mount)) cgroups_along(mount, path, fs_root, v2, out);
  }
  return out;
}

// The least headroom = limit - (usage - inactive file cache) over the directories, the cache
// being reclaimable; kUnlimited when none has a limit. Limits and usage are read at each call.
std::size_t headroom(const std::vector<MemoryCgroup>& cgroups) {
  std::size_t least = MemoryAvailability::kUnlimited;
  for (const MemoryCgroup& cg : cgroups) {
    const long long limit = read_limit(cg.dir + (cg.v2 ? "/memory.max" : "/memory.limit_in_bytes"));
    if (limit < 0) continue;
    long long usage = read_limit(cg.dir + (cg.v2 ? "/memory.current" : "/memory.usage_in_bytes"));
    usage = std::max(0LL, usage - read_stat(cg.dir + "/memory.stat", cg.v2 ? "inactive_file" : "total_inactive_file"));
    least = std::min(least, static_cast<std::size_t>(std::max(0LL, limit - usage)));
  }
  return least;
}
}  // namespace

namespace detail {
std::size_t cgroup_headroom(const std::string& proc_self_cgroup, const std::string& mountinfo,
                            const std::string& fs_root) {
  return headroom(memory_cgroups(proc_self_cgroup, mountinfo, fs_root));
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
  // Which cgroups hold the process is looked up once (a process is rarely moved between them);
  // their limits and usage are read now.
  static const std::vector<MemoryCgroup> cgroups =
      memory_cgroups(read_text("/proc/self/cgroup"), read_text("/proc/self/mountinfo"), "");
  m.cgroup = headroom(cgroups);
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

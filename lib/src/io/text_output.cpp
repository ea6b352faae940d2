#include <panelrad/io/text_output.hpp>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <random>
#include <set>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace panelrad {

namespace {

// ---------------------------------------------------------------------------------------------
// The temporaries in progress, as the signal handler sees them: a fixed array of C strings, each
// with a state. Only lock-free atomics, unlink(), sigaction() and raise() are used in the handler
// (all async-signal-safe).

static_assert(std::atomic<int>::is_always_lock_free);

enum SlotState : int { kFree = 0, kReserved = 1, kArmed = 2, kTakenByHandler = 3 };
constexpr int kSlots = 64;

struct Slot {
  std::atomic<int> state{kFree};
  char path[PATH_MAX];
};
Slot g_slots[kSlots];

// Process phase: the handler may remove temporaries only in kRunning; during the renames of a
// commit (kCommitting) a signal is recorded and re-raised when the set is in place.
enum Phase : int { kRunning = 0, kCommitting = 1, kTerminating = 2 };
std::atomic<int> g_phase{kRunning};
std::atomic<int> g_pending_signal{0};
std::mutex g_commit_mutex;  // one commit at a time (threads of one program)

constexpr int kCleanedSignals[] = {SIGINT, SIGTERM, SIGHUP};

extern "C" void remove_temporaries_and_reraise(int sig) {
  const int saved_errno = errno;
  int phase = kRunning;
  if (!g_phase.compare_exchange_strong(phase, kTerminating)) {
    if (phase == kCommitting) g_pending_signal.store(sig);
    // kTerminating: another thread is already removing them and will end the process.
    errno = saved_errno;
    return;
  }
  for (Slot& s : g_slots) {
    int armed = kArmed;
    if (s.state.compare_exchange_strong(armed, kTakenByHandler)) ::unlink(s.path);
  }
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  ::sigaction(sig, &dfl, nullptr);
  ::raise(sig);  // blocked while this handler runs: delivered, with the default action, on return
  errno = saved_errno;
}

/// Reserves a slot for `path`; -1 when the path does not fit (the caller fails with a message).
int reserve_slot(const std::string& path) {
  if (path.size() >= PATH_MAX) return -1;
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (g_slots[i].state.compare_exchange_strong(expected, kReserved)) {
      std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
      return i;
    }
  }
  return -1;
}

void arm_slot(int i) {
  if (i >= 0) g_slots[i].state.store(kArmed);
}

/// Takes the slot back from the handler (armed -> reserved). False when the handler has already
/// taken it: the process is terminating and the handler removes the file.
bool disarm_slot(int i) {
  if (i < 0) return true;
  int state = kArmed;
  return g_slots[i].state.compare_exchange_strong(state, kReserved) || state == kReserved;
}

void free_slot(int i) {
  if (i >= 0) g_slots[i].state.store(kFree);
}

[[noreturn]] void fail(const std::string& path, const std::string& why) {
  throw std::runtime_error("cannot write '" + path + "': " + why);
}

std::string errno_text(int e) { return std::strerror(e); }

/// A name beside `path` that no file has yet: PATH.<tag>.<pid>.<random>.
std::string unique_name(const std::string& path, const char* tag) {
  static std::mt19937_64 gen(std::random_device{}() ^
                             static_cast<std::uint64_t>(
                                 std::chrono::steady_clock::now().time_since_epoch().count()));
  static std::mutex m;
  std::uint64_t r;
  {
    std::lock_guard<std::mutex> lock(m);
    r = gen();
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, "%08x", static_cast<unsigned>(r & 0xffffffffu));
  return path + "." + tag + "." + std::to_string(::getpid()) + "." + buf;
}

/// Creates a new temporary beside `path` with O_EXCL, registered with the signal handler.
/// Returns the descriptor; `temporary` and `slot` receive its name and slot.
int create_temporary(const std::string& path, std::string& temporary, int& slot) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    temporary = unique_name(path, "tmp");
    slot = reserve_slot(temporary);
    if (slot < 0)
      fail(path, temporary.size() >= PATH_MAX ? "the path is too long"
                                              : "too many output files in progress at once");
    const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0) {
      arm_slot(slot);
      return fd;
    }
    const int e = errno;
    free_slot(slot);
    slot = -1;
    if (e != EEXIST) fail(path, errno_text(e));
  }
  fail(path, "no unused temporary name beside it");
}

/// Removes a temporary of ours. Unlinked first, then taken back from the handler, so no signal
/// between the two can leave it behind (a second unlink of the unique name finds nothing).
void remove_temporary(const std::string& temporary, int slot) noexcept {
  ::unlink(temporary.c_str());
  if (disarm_slot(slot)) free_slot(slot);
}

bool write_all(int fd, const char* data, std::size_t size, int& error) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      error = errno;
      return false;
    }
    if (n == 0) {
      error = ENOSPC;
      return false;
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

std::string directory_of(const std::string& path) {
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  return dir.empty() ? std::string(".") : dir.string();
}

void sync_directory(const std::string& dir) noexcept {
  const int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);  // some file systems refuse fsync on a directory (EINVAL): nothing more to do
  ::close(fd);
}

/// Holds SIGINT/SIGTERM/SIGHUP during the renames (the handler records them), then re-raises.
class CommitPhase {
 public:
  CommitPhase() : lock_(g_commit_mutex) {
    int phase = kRunning;
    while (!g_phase.compare_exchange_strong(phase, kCommitting)) {
      // kTerminating: a handler is removing the temporaries and ending the process.
      ::pause();
      phase = kRunning;
    }
  }
  ~CommitPhase() {
    g_phase.store(kRunning);
    if (const int sig = g_pending_signal.exchange(0)) ::raise(sig);
  }

 private:
  std::lock_guard<std::mutex> lock_;
};

}  // namespace

// ---------------------------------------------------------------------------------------------

OutputSet::~OutputSet() { discard(); }

void OutputSet::discard() noexcept {
  for (const File& f : files_) remove_temporary(f.temporary, f.slot);
  files_.clear();
}

std::vector<std::string> OutputSet::paths() const {
  std::vector<std::string> out;
  for (const File& f : files_) out.push_back(f.path);
  return out;
}

void OutputSet::add(const std::string& path, const std::string& contents) {
  for (const File& f : files_)
    if (f.path == path) throw std::invalid_argument("output '" + path + "' is given twice");
  files_.reserve(files_.size() + 1);  // so that the push_back below cannot throw
  try {
    File file{path, {}, -1};
    const int fd = create_temporary(path, file.temporary, file.slot);
    files_.push_back(std::move(file));
    int error = 0;
    const bool written = write_all(fd, contents.data(), contents.size(), error);
    if (written && ::fsync(fd) != 0) error = errno;
    if (::close(fd) != 0 && error == 0) error = errno;
    if (!written || error != 0) fail(path, errno_text(error ? error : EIO));
  } catch (...) {
    discard();
    throw;
  }
}

void OutputSet::commit() {
  struct Replaced {
    std::string backup;  // hard link to the previous file; empty when there was none
    bool had_previous = false;
    bool renamed = false;
  };
  std::vector<Replaced> replaced(files_.size());
  std::string error;
  {
    const CommitPhase phase;
    // Keep each previous file under a second name, so a failed rename can put it back.
    for (std::size_t i = 0; i < files_.size(); ++i) {
      struct stat st {};
      if (::lstat(files_[i].path.c_str(), &st) != 0) continue;
      replaced[i].had_previous = true;
      if (S_ISDIR(st.st_mode)) continue;  // the rename below fails and names it
      for (int attempt = 0; attempt < 100; ++attempt) {
        const std::string backup = unique_name(files_[i].path, "old");
        if (::link(files_[i].path.c_str(), backup.c_str()) == 0) {
          replaced[i].backup = backup;
          break;
        }
        if (errno != EEXIST) break;  // no hard links here: this file cannot be put back
      }
    }
    for (std::size_t i = 0; i < files_.size() && error.empty(); ++i) {
      disarm_slot(files_[i].slot);
      if (::rename(files_[i].temporary.c_str(), files_[i].path.c_str()) == 0) {
        free_slot(files_[i].slot);
        files_[i].slot = -1;
        replaced[i].renamed = true;
      } else {
        error = "cannot write '" + files_[i].path + "': " + errno_text(errno);
        arm_slot(files_[i].slot);
      }
    }
    if (!error.empty()) {
      // Put the previous set back: the files already replaced get their previous contents (or
      // are removed when they are new); the temporaries not yet renamed are removed.
      std::string lost;
      for (std::size_t i = 0; i < files_.size(); ++i) {
        if (replaced[i].renamed) {
          if (!replaced[i].had_previous) {
            ::unlink(files_[i].path.c_str());
          } else if (replaced[i].backup.empty()) {
            lost += (lost.empty() ? "" : ", ") + files_[i].path;
          } else if (::rename(replaced[i].backup.c_str(), files_[i].path.c_str()) != 0) {
            lost += (lost.empty() ? "" : ", ") + files_[i].path + " (kept as " + replaced[i].backup + ")";
            replaced[i].backup.clear();  // keep it: it is the only copy of the previous file
          } else {
            replaced[i].backup.clear();  // renamed back
          }
        } else {
          remove_temporary(files_[i].temporary, files_[i].slot);
        }
      }
      if (!lost.empty()) error += "; could not restore the previous " + lost;
      else error += "; the previous files are unchanged";
    }
    for (const Replaced& r : replaced)
      if (!r.backup.empty()) ::unlink(r.backup.c_str());
    std::set<std::string> dirs;
    for (const File& f : files_) dirs.insert(directory_of(f.path));
    for (const std::string& d : dirs) sync_directory(d);
    files_.clear();
  }
  if (!error.empty()) throw std::runtime_error(error);
}

void write_file_atomically(const std::string& path, const std::string& contents) {
  OutputSet set;
  set.add(path, contents);
  set.commit();
}

void check_output_path(const std::string& path) {
  if (path.empty()) throw std::runtime_error("cannot write '': empty path");
  const std::string dir = directory_of(path);
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0) fail(path, "directory '" + dir + "': " + errno_text(errno));
  if (!S_ISDIR(st.st_mode)) fail(path, "'" + dir + "' is not a directory");
  if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode)) fail(path, "it is a directory");
  std::string temporary;
  int slot = -1;
  const int fd = create_temporary(path, temporary, slot);
  ::close(fd);
  remove_temporary(temporary, slot);
}

void install_output_signal_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    for (const int sig : kCleanedSignals) {
      struct sigaction old {};
      if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler == SIG_IGN) continue;
      struct sigaction sa {};
      sa.sa_handler = remove_temporaries_and_reraise;
      sigemptyset(&sa.sa_mask);
      for (const int other : kCleanedSignals) sigaddset(&sa.sa_mask, other);
      sa.sa_flags = 0;
      ::sigaction(sig, &sa, nullptr);
    }
  });
}

}  // namespace panelrad

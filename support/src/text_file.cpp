// Bounded reading of text input files (text_file.hpp): stat before open, a size limit known before
// the first byte is read, chunked reading with a NUL check per chunk.
#include <panelrad/support/text_file.hpp>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <istream>
#include <sstream>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace panelrad {
namespace {

/// The first chunk is small so that a binary file is refused after reading little of it.
constexpr std::size_t kFirstChunk = std::size_t{64} << 10;
constexpr std::size_t kChunk = std::size_t{1} << 20;

[[noreturn]] void fail(const std::string& name, const std::string& what) { throw TextFileError(name + ": " + what); }

std::string with_role(const std::string& verb, const std::string& role) {
  return role.empty() ? verb : verb + " " + role;
}

/// What a file that is not a regular file is, for messages.
const char* file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "is a directory";
  if (S_ISFIFO(mode)) return "is a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "is a character device";
  if (S_ISBLK(mode)) return "is a block device";
  if (S_ISSOCK(mode)) return "is a socket";
  return "is not a regular file";
}

std::string too_large(std::uint64_t size, std::uint64_t limit) {
  return "is " + std::to_string(size) + " bytes (" + describe_bytes(size) + "), above the limit of " +
         std::to_string(limit) + " bytes (" + describe_bytes(limit) +
         ") for text input files (panelrad::TextReadOptions::max_bytes)";
}

/// Refuses the text when its bytes from `from` on contain a NUL: names the line, the byte offset
/// in the file and the column.
void check_no_nul(const std::string& text, std::size_t from, const std::string& name) {
  const void* hit = std::memchr(text.data() + from, '\0', text.size() - from);
  if (!hit) return;
  const auto offset = static_cast<std::size_t>(static_cast<const char*>(hit) - text.data());
  const auto begin = text.begin();
  const long line = 1 + static_cast<long>(std::count(begin, begin + static_cast<std::ptrdiff_t>(offset), '\n'));
  const std::size_t line_start = text.rfind('\n', offset == 0 ? 0 : offset - 1);
  const std::size_t column = (line_start == std::string::npos || offset == 0) ? offset + 1 : offset - line_start;
  throw TextFileError(name + ":" + std::to_string(line) + ": NUL byte at byte offset " + std::to_string(offset) +
                      " (column " + std::to_string(column) + "): binary data, not a text file");
}

void strip_bom(std::string& text, const TextReadOptions& options) {
  if (options.strip_utf8_bom && text.size() >= 3 && text.compare(0, 3, "\xEF\xBB\xBF") == 0) text.erase(0, 3);
}

/// Reads chunks with `read_some(buffer, count) -> bytes read (0 at the end)` until the end, checking
/// each chunk for NUL before the next is read and stopping past `limit`.
template <class ReadSome>
std::string read_chunks(ReadSome read_some, std::uint64_t expected_size, const std::string& name,
                        const TextReadOptions& options) {
  std::string text;
  std::size_t chunk = kFirstChunk;
  bool reserved = false;
  // At most limit + 1 bytes in all: one byte past the limit shows that the file is too large.
  const std::uint64_t most = options.max_bytes == UINT64_MAX ? UINT64_MAX : options.max_bytes + 1;
  while (true) {
    const std::uint64_t room = most - std::min<std::uint64_t>(text.size(), most);
    if (room == 0) fail(name, "grew while being read: " + too_large(text.size(), options.max_bytes));
    auto want = static_cast<std::size_t>(std::min<std::uint64_t>(chunk, room));
    const std::size_t old = text.size();
    // Within the room reserved for the expected size (no reallocation of a large text), unless
    // the file has grown beyond it.
    if (reserved && text.capacity() > old) want = std::min(want, text.capacity() - old);
    text.resize(old + want);
    const std::size_t got = read_some(text.data() + old, want);
    text.resize(old + got);
    if (got == 0) break;
    check_no_nul(text, old, name);
    if (!reserved) {
      // The first chunk is text: make room for the whole file at once (no page is touched before
      // it is read into).
      text.reserve(static_cast<std::size_t>(std::min(expected_size, options.max_bytes) + 1));
      reserved = true;
      chunk = kChunk;
    }
  }
  if (text.size() > options.max_bytes) fail(name, "grew while being read: " + too_large(text.size(), options.max_bytes));
  strip_bom(text, options);
  return text;
}

/// Closes a file descriptor on every path out.
struct Descriptor {
  int fd = -1;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string describe_bytes(std::uint64_t bytes) {
  static const char* const kUnits[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
  if (bytes < 1024) return std::to_string(bytes) + (bytes == 1 ? " byte" : " bytes");
  double v = static_cast<double>(bytes) / 1024.0;
  int unit = 0;
  while (v >= 1024.0 && unit < 5) {
    v /= 1024.0;
    ++unit;
  }
  std::ostringstream os;
  os.precision(3);
  os << v << " " << kUnits[unit];
  return os.str();
}

std::string read_text_file(const std::string& path, const std::string& role, const TextReadOptions& options) {
  // stat() first: opening a FIFO for reading would wait for a writer.
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    const int err = errno;
    if (err == ENOENT || err == ENOTDIR) fail(path, with_role("cannot open", role) + ": no such file");
    fail(path, with_role("cannot open", role) + ": " + std::strerror(err));
  }
  if (!S_ISREG(st.st_mode))
    fail(path, with_role("cannot read", role) + ": " + file_kind(st.st_mode) + ", not a regular file");
  if (static_cast<std::uint64_t>(st.st_size) > options.max_bytes)
    fail(path, with_role("cannot read", role) + ": the file " + too_large(static_cast<std::uint64_t>(st.st_size), options.max_bytes));

  // Non-blocking, so that a FIFO put in the file's place since the stat() cannot block the open;
  // fstat() of the open file decides.
  Descriptor file;
  file.fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (file.fd < 0) {
    const int err = errno;
    fail(path, with_role("cannot open", role) + " for reading: " + std::strerror(err));
  }
  if (::fstat(file.fd, &st) != 0) {
    const int err = errno;
    fail(path, with_role("cannot read", role) + ": " + std::strerror(err));
  }
  if (!S_ISREG(st.st_mode))
    fail(path, with_role("cannot read", role) + ": " + file_kind(st.st_mode) + ", not a regular file");
  const auto size = static_cast<std::uint64_t>(st.st_size);
  if (size > options.max_bytes)
    fail(path, with_role("cannot read", role) + ": the file " + too_large(size, options.max_bytes));

  const auto read_some = [&](char* buffer, std::size_t count) -> std::size_t {
    while (true) {
      const ssize_t n = ::read(file.fd, buffer, count);
      if (n >= 0) return static_cast<std::size_t>(n);
      const int err = errno;
      if (err == EINTR) continue;
      fail(path, with_role("read error in", role.empty() ? std::string("the file") : role) + ": " + std::strerror(err));
    }
  };
  return read_chunks(read_some, size, path, options);
}

std::string read_text_stream(std::istream& in, const std::string& name, const TextReadOptions& options) {
  const auto read_some = [&](char* buffer, std::size_t count) -> std::size_t {
    in.read(buffer, static_cast<std::streamsize>(count));
    if (in.bad()) fail(name, "read error");
    return static_cast<std::size_t>(in.gcount());
  };
  return read_chunks(read_some, 0, name, options);
}

}  // namespace panelrad

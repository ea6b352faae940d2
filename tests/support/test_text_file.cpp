// The bounded text reader (support/text_file.hpp) shared by the mesh, MTL and JSON readers:
// non-regular files refused before they are opened for reading, the size limit, NUL bytes refused
// at the first one with line and byte offset, the UTF-8 byte-order mark.
#include "test_support.hpp"
#include <panelrad/support/text_file.hpp>

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << "message: " << (haystack)

template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const panelrad::TextFileError& e) {
    return e.what();
  }
  return "";
}

/// Peak resident memory of this process so far, in KiB (Linux: ru_maxrss is in KiB).
long peak_rss_kib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss;
}

class TextFile : public panelrad::testing::TempDirTest {
 protected:
  TextFile() : TempDirTest("panelrad_text_file") {}
};

}  // namespace

TEST_F(TextFile, ReadsARegularFileWhole) {
  std::string text;
  for (int i = 0; i < 200000; ++i) text += "v " + std::to_string(i) + " 0 0\n";  // > 1 MiB: several chunks
  ASSERT_GT(text.size(), std::size_t{2} << 20);
  EXPECT_EQ(panelrad::read_text_file(write("big.obj", text)), text);
  EXPECT_EQ(panelrad::read_text_file(write("empty.obj", "")), "");
  std::istringstream in(text);
  EXPECT_EQ(panelrad::read_text_stream(in, "stream"), text);
}

TEST_F(TextFile, MissingFileAndDirectory) {
  EXPECT_CONTAINS(error_of([&] { panelrad::read_text_file((dir_ / "missing.off").string()); }),
                  "missing.off: cannot open: no such file");
  EXPECT_CONTAINS(error_of([&] { panelrad::read_text_file((dir_ / "missing.mtl").string(), "MTL file named by a.obj:2"); }),
                  "missing.mtl: cannot open MTL file named by a.obj:2: no such file");
  EXPECT_CONTAINS(error_of([&] { panelrad::read_text_file(dir_.string()); }), "cannot read: is a directory, not a regular file");
}

// A FIFO without a writer: open() for reading would block for ever. The reader must look at it
// with stat() first and refuse it; if it blocked, this test would hang (and time out in ctest).
TEST_F(TextFile, FifoIsRefusedWithoutBlocking) {
  const std::string fifo = (dir_ / "pipe.off").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_CONTAINS(error_of([&] { panelrad::read_text_file(fifo); }),
                  fifo + ": cannot read: is a FIFO (named pipe), not a regular file");
}

// /dev/zero is endless: reading it to the end would never finish. It is a character device, and
// so is a symbolic link to it (stat follows links).
TEST_F(TextFile, CharacterDeviceIsRefused) {
  ASSERT_TRUE(fs::exists("/dev/zero"));
  EXPECT_CONTAINS(error_of([] { panelrad::read_text_file("/dev/zero"); }),
                  "/dev/zero: cannot read: is a character device, not a regular file");
  const fs::path link = dir_ / "zero.json";
  fs::create_symlink("/dev/zero", link);
  EXPECT_CONTAINS(error_of([&] { panelrad::read_text_file(link.string(), "JSON sidecar of x.off"); }),
                  "zero.json: cannot read JSON sidecar of x.off: is a character device");
}

TEST_F(TextFile, SizeLimitIsNamedAndConfigurable) {
  EXPECT_EQ(panelrad::kDefaultMaxTextFileBytes, std::uint64_t{1} << 30);
  EXPECT_EQ(panelrad::TextReadOptions{}.max_bytes, panelrad::kDefaultMaxTextFileBytes);
  panelrad::TextReadOptions small;
  small.max_bytes = 100;
  const std::string at_limit = write("at.off", std::string(100, 'x'));
  EXPECT_EQ(panelrad::read_text_file(at_limit, "", small).size(), 100u);
  const std::string above = write("above.off", std::string(101, 'x'));
  EXPECT_CONTAINS(error_of([&] { panelrad::read_text_file(above, "", small); }),
                  "above.off: cannot read: the file is 101 bytes (101 bytes), above the limit of 100 bytes (100 bytes) "
                  "for text input files (panelrad::TextReadOptions::max_bytes)");
  // A stream has no size up front: it is read up to the limit and refused one byte past it.
  std::istringstream in(std::string(101, 'x'));
  EXPECT_CONTAINS(error_of([&] { panelrad::read_text_stream(in, "stream.obj", small); }),
                  "stream.obj: grew while being read: is 101 bytes");
  std::istringstream fits(std::string(100, 'x'));
  EXPECT_EQ(panelrad::read_text_stream(fits, "stream.obj", small).size(), 100u);
  // A regular file whose size is not known up front (/proc files say 0): stopped at the limit.
  if (fs::exists("/proc/self/status")) {
    EXPECT_CONTAINS(error_of([&] { panelrad::read_text_file("/proc/self/status", "", small); }),
                    "/proc/self/status: grew while being read: is 101 bytes");
    EXPECT_CONTAINS(panelrad::read_text_file("/proc/self/status"), "VmPeak:");
  }
  // No limit at all (the largest count): limit + 1 must not wrap around to 0.
  panelrad::TextReadOptions unlimited;
  unlimited.max_bytes = UINT64_MAX;
  EXPECT_EQ(panelrad::read_text_file(above, "", unlimited).size(), 101u);
  std::istringstream any(std::string(101, 'x'));
  EXPECT_EQ(panelrad::read_text_stream(any, "stream.obj", unlimited).size(), 101u);
}

TEST_F(TextFile, DescribesByteCounts) {
  EXPECT_EQ(panelrad::describe_bytes(1), "1 byte");
  EXPECT_EQ(panelrad::describe_bytes(1000), "1000 bytes");
  EXPECT_EQ(panelrad::describe_bytes(1536), "1.5 KiB");
  EXPECT_EQ(panelrad::describe_bytes(std::uint64_t{1} << 30), "1 GiB");
  EXPECT_EQ(panelrad::describe_bytes(std::uint64_t{3} << 29), "1.5 GiB");
}

TEST_F(TextFile, NulByteIsRefusedWithLineAndOffset) {
  const std::string path = write("nul.obj", std::string("v 0 0 0\nv 1 0 0\nv 0 \0 1\n", 25));
  // Byte offset 8 + 8 + 4 = 20 is on line 3, column 5.
  EXPECT_CONTAINS(error_of([&] { panelrad::read_text_file(path); }),
                  "nul.obj:3: NUL byte at byte offset 20 (column 5): binary data, not a text file");
  // Past the first chunk (64 KiB) and past a 1 MiB chunk boundary, the offset is still exact.
  for (const std::size_t offset : {std::size_t{70000}, std::size_t{(1u << 20) + (64u << 10) + 5}}) {
    std::string text(offset + 100, 'a');
    for (std::size_t i = 99; i < offset; i += 100) text[i] = '\n';  // line k ends at byte 100 k - 1
    text[offset] = '\0';
    const std::string big = write("late_nul.off", text);
    const std::string expected_line = std::to_string(offset / 100 + 1);
    const std::string expected_column = std::to_string(offset % 100 + 1);
    EXPECT_CONTAINS(error_of([&] { panelrad::read_text_file(big); }),
                    "late_nul.off:" + expected_line + ": NUL byte at byte offset " + std::to_string(offset) +
                        " (column " + expected_column + ")");
    std::istringstream in(text);
    EXPECT_CONTAINS(error_of([&] { panelrad::read_text_stream(in, "s"); }),
                    "s:" + expected_line + ": NUL byte at byte offset " + std::to_string(offset));
  }
}

// A 1 GiB file of NUL bytes (sparse: no disk space) is refused at its first byte, and reading it
// costs one 64 KiB chunk, not 1 GiB: the peak resident memory of the process grows by far less
// than the file (the reader used to take 2.1 GB for it). 64 MiB of slack covers allocator and
// sanitizer overheads; the file is 16 times that.
TEST_F(TextFile, GigabyteOfNulBytesIsRefusedAtTheFirstByte) {
  const fs::path path = dir_ / "zeros.off";
  std::ofstream(path, std::ios::binary).put('\0');
  fs::resize_file(path, panelrad::kDefaultMaxTextFileBytes);  // exactly at the limit: the NUL decides
  const long before = peak_rss_kib();
  EXPECT_CONTAINS(error_of([&] { panelrad::read_text_file(path.string()); }),
                  "zeros.off:1: NUL byte at byte offset 0 (column 1): binary data, not a text file");
  const long grown = peak_rss_kib() - before;
  EXPECT_LT(grown, 64L << 10) << "peak resident memory grew by " << grown << " KiB";
  // One byte more and the size limit refuses it before any byte is read.
  fs::resize_file(path, panelrad::kDefaultMaxTextFileBytes + 1);
  EXPECT_CONTAINS(error_of([&] { panelrad::read_text_file(path.string()); }),
                  "the file is 1073741825 bytes (1 GiB), above the limit of 1073741824 bytes (1 GiB)");
}

TEST_F(TextFile, Utf8ByteOrderMarkIsRemoved) {
  const std::string bom = "\xEF\xBB\xBF";
  EXPECT_EQ(panelrad::read_text_file(write("bom.off", bom + "OFF\n")), "OFF\n");
  panelrad::TextReadOptions keep;
  keep.strip_utf8_bom = false;
  EXPECT_EQ(panelrad::read_text_file(write("bom.json", bom + "{}"), "", keep), bom + "{}");
  std::istringstream in(bom + "v 0 0 0\n");
  EXPECT_EQ(panelrad::read_text_stream(in, "s"), "v 0 0 0\n");
  // Only a leading mark: the same bytes later are content (and a lone EF BB is no mark).
  EXPECT_EQ(panelrad::read_text_file(write("mid.off", "OFF\n" + bom)), "OFF\n" + bom);
  EXPECT_EQ(panelrad::read_text_file(write("short.off", "\xEF\xBB")), "\xEF\xBB");
}

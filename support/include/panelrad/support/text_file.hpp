#pragma once
// Bounded reading of the text input files (mesh OFF and OBJ, MTL, JSON sidecars): one reader for
// all of them, so that no input can make the program read without end or without limit.
//
// A file is refused, with a TextFileError naming it, when
//   - it does not exist or cannot be opened;
//   - it is not a regular file: a directory, a FIFO (named pipe), a character device such as
//     /dev/zero, a block device or a socket. It is looked at with stat() before it is opened (an
//     open() of a FIFO would wait for a writer), and again with fstat() on the opened descriptor
//     (opened non-blocking), so a file swapped in between is refused as well;
//   - it is larger than TextReadOptions::max_bytes, by default kDefaultMaxTextFileBytes = 1 GiB
//     (2^30 bytes). The size comes from fstat() before any byte is read; a file that grows while
//     being read is stopped at the limit;
//   - it contains a NUL byte (a binary file): refused at the first NUL with its line and byte
//     offset. The file is read in chunks (the first 64 KiB, then 1 MiB at a time) and each chunk
//     is checked before the next is read, so a 1 GiB file of NUL bytes costs one 64 KiB chunk of
//     memory, not 1 GiB.
// A leading UTF-8 byte-order mark (EF BB BF) is removed unless TextReadOptions::strip_utf8_bom is
// false (line numbers are unchanged by the removal).
//
// Why 1 GiB: the mesh reader keeps the text and the mesh it builds, about 5 bytes of memory per
// byte of OBJ text (measured: 557 MB peak for a 107 MB OBJ of 2 million vertices and 2 million
// triangles); a 1 GiB OBJ holds some 20 million vertices, far more facets than a solve can use,
// and its reading stays within about 6 GB.
#include <panelrad/support/error.hpp>

#include <cstdint>
#include <iosfwd>
#include <stdexcept>
#include <string>

namespace panelrad {

/// The default size limit of a text input file: 1 GiB.
inline constexpr std::uint64_t kDefaultMaxTextFileBytes = std::uint64_t{1} << 30;

struct TextReadOptions {
  std::uint64_t max_bytes = kDefaultMaxTextFileBytes;  ///< larger files are refused
  bool strip_utf8_bom = true;                          ///< remove a leading EF BB BF
};

/// A text input file that cannot be read as such: the message names the file, what it is or what
/// is wrong with it, and for a NUL byte its line and byte offset.
class TextFileError : public Error {
 public:
  using Error::Error;
};

/// The whole text of the regular file `path`. `role` says what the file is for, in messages
/// (e.g. "MTL file named by scene.obj:3"); may be empty. Throws TextFileError.
std::string read_text_file(const std::string& path, const std::string& role = "",
                           const TextReadOptions& options = {});

/// The same for an already open stream (`name` in messages): read in chunks up to the limit,
/// NUL bytes refused at the first one, a leading byte-order mark removed. Throws TextFileError.
std::string read_text_stream(std::istream& in, const std::string& name, const TextReadOptions& options = {});

/// "1 GiB", "512 MiB", "1.5 GiB", "3 bytes": a byte count for messages.
std::string describe_bytes(std::uint64_t bytes);

}  // namespace panelrad

#pragma once
// Output files are written whole or not at all.
#include <string>

namespace panelrad {

/// Writes `contents` to a temporary file beside `path`, then renames it over `path`.
/// Throws std::runtime_error naming the path when any step fails; never leaves a partial file.
void write_file_atomically(const std::string& path, const std::string& contents);

}  // namespace panelrad

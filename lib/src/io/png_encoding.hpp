#pragma once
// An 8-bit RGB image encoded as PNG in memory (internal to panelrad_io).
#include <string>

namespace panelrad::io_detail {

/// The PNG file of a width x height image, rows top to bottom, 3 bytes per pixel. Throws
/// std::runtime_error("write_radiosity_png: libpng: ...") when libpng fails.
std::string encode_png(const unsigned char* rgb, int width, int height);

}  // namespace panelrad::io_detail

#include "png_encoding.hpp"

#include <png.h>

#include <cstddef>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace panelrad::io_detail {

namespace {

// No C++ object with a destructor lives in encode_into's frame across
// setjmp; errors come back as a message in the sink.

struct PngSink {
  std::string* out;
  char message[256];
};

void png_fail(png_structp png, png_const_charp msg) {
  auto* sink = static_cast<PngSink*>(png_get_error_ptr(png));
  std::snprintf(sink->message, sizeof sink->message, "%s", msg ? msg : "unknown error");
  png_longjmp(png, 1);
}

void png_warn(png_structp, png_const_charp) {}

void png_append(png_structp png, png_bytep data, png_size_t length) {
  auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
  bool ok = true;
  try {
    sink->out->append(reinterpret_cast<const char*>(data), length);
  } catch (...) {
    ok = false;
  }
  if (!ok) png_error(png, "out of memory");
}

void png_flush(png_structp) {}

bool encode_into(const unsigned char* rgb, int width, int height, PngSink* sink) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, sink, png_fail, png_warn);
  if (!png) {
    std::snprintf(sink->message, sizeof sink->message, "cannot create the PNG writer");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    std::snprintf(sink->message, sizeof sink->message, "cannot create the PNG info");
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, sink, png_append, png_flush);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  const std::size_t stride = 3 * static_cast<std::size_t>(width);
  for (int y = 0; y < height; ++y)
    png_write_row(png, rgb + stride * static_cast<std::size_t>(y));
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

std::string encode_png(const unsigned char* rgb, int width, int height) {
  std::string png;
  PngSink sink{&png, {}};
  if (!encode_into(rgb, width, height, &sink))
    throw std::runtime_error(std::string("write_radiosity_png: libpng: ") + sink.message);
  return png;
}

}  // namespace panelrad::io_detail

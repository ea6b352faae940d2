// The PNG picture of a solved scene: the frame (picture_frame.hpp) coloured by element_colours(),
// a colour bar for scalar scenes, each pixel the average of its samples.
#include "element_colours.hpp"
#include "field_checks.hpp"
#include "picture_camera.hpp"
#include "picture_frame.hpp"
#include "png_encoding.hpp"

#include <panelrad/io/scene_output.hpp>
#include <panelrad/io/text_output.hpp>

#include <algorithm>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

namespace panelrad {

using geometry::Vec3;
using io_detail::kSamples;
using io_detail::Rgb;

namespace {

constexpr Rgb kBackground = {32, 32, 32};

void check_options(const RenderOptions& o) {
  constexpr int kMaxSide = 16384;
  if (o.width < 1 || o.height < 1 || o.width > kMaxSide || o.height > kMaxSide)
    throw std::invalid_argument("write_radiosity_png: image size " + std::to_string(o.width) +
                                " x " + std::to_string(o.height) + " is outside 1.." +
                                std::to_string(kMaxSide));
  if (!o.view_direction.allFinite() || !(o.view_direction.norm() > 0.0))
    throw std::invalid_argument("write_radiosity_png: view_direction must be finite and non-zero");
  if (!o.up.allFinite() || !(o.up.norm() > 0.0))
    throw std::invalid_argument("write_radiosity_png: up must be finite and non-zero");
}

/// Each sample in the colour of the element seen there, the background where none is.
std::vector<Rgb> sample_colours(const io_detail::Frame& frame, const std::vector<Rgb>& colour) {
  std::vector<Rgb> out(frame.element.size(), kBackground);
  for (std::size_t k = 0; k < out.size(); ++k)
    if (frame.element[k] >= 0) out[k] = colour[static_cast<std::size_t>(frame.element[k])];
  return out;
}

/// Colour bar right of the plot area: bottom = minimum, top = maximum, with a thin light frame.
void draw_colour_bar(std::vector<Rgb>& samples, int W, int H, int plot_w) {
  const int x0 = kSamples * (plot_w + std::max(4, (W - plot_w) / 3));
  const int x1 = kSamples * (W - std::max(4, (W - plot_w) / 3));
  const int y0 = kSamples * (H / 10), y1 = kSamples * (H - H / 10);
  const std::size_t row = static_cast<std::size_t>(kSamples) * static_cast<std::size_t>(W);
  for (int y = y0 - 2; y < y1 + 2; ++y)
    for (int x = x0 - 2; x < x1 + 2; ++x) {
      const bool inside = y >= y0 && y < y1 && x >= x0 && x < x1;
      const double t = 1.0 - (y + 0.5 - y0) / (y1 - y0);
      samples[static_cast<std::size_t>(y) * row + static_cast<std::size_t>(x)] =
          inside ? io_detail::colour_map(t) : Rgb{200, 200, 200};
    }
}

/// The W x H RGB image: each pixel the rounded average of its kSamples x kSamples samples.
std::vector<unsigned char> average_samples(const std::vector<Rgb>& samples, int W, int H) {
  std::vector<unsigned char> image(3 * static_cast<std::size_t>(W) * static_cast<std::size_t>(H));
  const std::size_t row = static_cast<std::size_t>(kSamples) * static_cast<std::size_t>(W);
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x)
      for (std::size_t c = 0; c < 3; ++c) {
        int sum = 0;
        for (int sy = 0; sy < kSamples; ++sy)
          for (int sx = 0; sx < kSamples; ++sx)
            sum += samples[static_cast<std::size_t>(kSamples * y + sy) * row +
                           static_cast<std::size_t>(kSamples * x + sx)][c];
        constexpr int kCount = kSamples * kSamples;
        image[(static_cast<std::size_t>(y) * static_cast<std::size_t>(W) + static_cast<std::size_t>(x)) * 3 + c] =
            static_cast<unsigned char>((sum + kCount / 2) / kCount);
      }
  return image;
}

}  // namespace

Vec3 brightest_view_direction(const ElementField& field) {
  io_detail::validate("brightest_view_direction", field);
  return io_detail::brightest_diagonal(field, Vec3::UnitZ());
}

void write_radiosity_png(const std::string& path, const ElementField& field, const RenderOptions& options) {
  write_file_atomically(path, radiosity_png(field, options));
}

std::string radiosity_png(const ElementField& field, const RenderOptions& options) {
  io_detail::validate("write_radiosity_png", field);
  check_options(options);
  const io_detail::Frame frame = io_detail::draw_frame(field, options);
  std::vector<Rgb> samples = sample_colours(frame, io_detail::colours_of_valid(field));
  const int W = options.width, H = options.height;
  if (frame.plot_w < W) draw_colour_bar(samples, W, H, frame.plot_w);
  const std::vector<unsigned char> image = average_samples(samples, W, H);
  return io_detail::encode_png(image.data(), W, H);
}

}  // namespace panelrad

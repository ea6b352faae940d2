// Colours of the elements: RGB scenes through one exposure and gamma 2.2, scalar scenes through a
// perceptual colour map between the minimum and the maximum of the reflected light.
#include "element_colours.hpp"
#include "field_checks.hpp"

#include <panelrad/io/scene_output.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace panelrad {

namespace io_detail {

namespace {

unsigned char to_byte(double v) {  // v in [0, 1]
  return static_cast<unsigned char>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
}

}  // namespace

/// Viridis sampled at 9 evenly spaced stops, interpolated linearly (perceptually near-uniform).
Rgb colour_map(double t) {
  static constexpr unsigned char stops[9][3] = {{68, 1, 84},    {71, 44, 122},  {59, 81, 139},
                                                {44, 113, 142}, {33, 144, 141}, {39, 173, 129},
                                                {92, 200, 99},  {170, 220, 50}, {253, 231, 37}};
  t = std::clamp(std::isfinite(t) ? t : 0.5, 0.0, 1.0) * 8.0;
  const int k = std::min(7, static_cast<int>(t));
  const double w = t - k;
  Rgb c;
  for (int j = 0; j < 3; ++j)
    c[static_cast<std::size_t>(j)] = static_cast<unsigned char>(
        std::lround((1.0 - w) * stops[k][j] + w * stops[k + 1][j]));
  return c;
}

std::vector<Rgb> colours_of_valid(const ElementField& f) {
  const std::size_t n = f.size();
  std::vector<Rgb> out(n);
  if (is_rgb(f)) {
    // RGB: one exposure for all channels, 1 / (95th percentile of the brightest channel over the
    // elements that emit nothing; over all elements when every one emits), so the walls fill the
    // range and the lights saturate; then clamp to [0, 1] and gamma-encode (v^(1/2.2)).
    std::vector<double> lit, all;
    for (std::size_t i = 0; i < n; ++i) {
      double m = -std::numeric_limits<double>::infinity();
      bool emits = false;
      for (std::size_t c = 0; c < 3; ++c) {
        m = std::max(m, value(f.radiosity[c], i));
        emits = emits || value(f.emission[c], i) != 0.0;
      }
      all.push_back(m);
      if (!emits) lit.push_back(m);
    }
    std::vector<double>& base = lit.empty() ? all : lit;
    std::sort(base.begin(), base.end());
    const std::size_t rank = static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(base.size())));
    double white = base[std::max<std::size_t>(rank, 1) - 1];
    if (!(white > 0.0)) white = *std::max_element(all.begin(), all.end());
    const double exposure = white > 0.0 ? 1.0 / white : 1.0;
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t c = 0; c < 3; ++c) {
        const double v = std::clamp(value(f.radiosity[c], i) * exposure, 0.0, 1.0);
        out[i][c] = to_byte(std::pow(v, 1.0 / 2.2));
      }
  } else {
    // Other channel sets: the first channel, linear from its minimum to its maximum over the
    // elements that emit nothing (so that the reflected light, not the lamp, fills the map; the
    // emitters are clamped to its top), over all elements when that range is empty; a constant
    // field gets the map's middle colour.
    const Eigen::VectorXd& u = f.radiosity[0];
    const double lo = u.minCoeff();
    double hi = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < n; ++i)
      if (value(f.emission[0], i) == 0.0) hi = std::max(hi, value(u, i));
    if (!(hi > lo)) hi = u.maxCoeff();
    for (std::size_t i = 0; i < n; ++i)
      out[i] = colour_map(hi > lo ? std::clamp((value(u, i) - lo) / (hi - lo), 0.0, 1.0) : 0.5);
  }
  return out;
}

}  // namespace io_detail

std::vector<std::array<unsigned char, 3>> element_colours(const ElementField& field) {
  io_detail::validate("element_colours", field);
  return io_detail::colours_of_valid(field);
}

}  // namespace panelrad

// Rasterizer: 2x2 supersampled, vertices snapped to 1/256 of a sample so edge functions are exact
// integers; the top-left fill rule then covers every sample of a shared edge exactly once.
#include "picture_frame.hpp"
#include "field_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>

namespace panelrad::io_detail {

using geometry::Vec3;

namespace {

constexpr std::int64_t kSub = 256;  // fixed-point units per sample

struct ScreenPoint {
  std::int64_t x, y;  // fixed point, y downwards
  double z;
};

std::int64_t edge(const ScreenPoint& a, const ScreenPoint& b, std::int64_t px, std::int64_t py) {
  return (b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x);
}

bool top_left(const ScreenPoint& a, const ScreenPoint& b) {  // interior on the positive side
  const std::int64_t dx = b.x - a.x, dy = b.y - a.y;
  return dy < 0 || (dy == 0 && dx > 0);
}

void fill_triangle(Frame& fr, ScreenPoint v0, ScreenPoint v1, ScreenPoint v2, std::int32_t id, int x_end) {
  std::int64_t area = edge(v0, v1, v2.x, v2.y);
  if (area == 0) return;
  if (area < 0) {
    std::swap(v1, v2);
    area = -area;
  }
  const std::int64_t xmin = std::min({v0.x, v1.x, v2.x}), xmax = std::max({v0.x, v1.x, v2.x});
  const std::int64_t ymin = std::min({v0.y, v1.y, v2.y}), ymax = std::max({v0.y, v1.y, v2.y});
  // Sample (i, j) sits at ((i + 1/2) kSub, (j + 1/2) kSub).
  const auto first = [](std::int64_t lo) { return std::max<std::int64_t>(0, (lo - kSub / 2) / kSub); };
  const std::int64_t i0 = first(xmin), j0 = first(ymin);
  const std::int64_t i1 = std::min<std::int64_t>(x_end - 1, xmax / kSub + 1);
  const std::int64_t j1 = std::min<std::int64_t>(fr.h - 1, ymax / kSub + 1);
  const bool tl0 = top_left(v1, v2), tl1 = top_left(v2, v0), tl2 = top_left(v0, v1);
  const double inv = 1.0 / static_cast<double>(area);
  for (std::int64_t j = j0; j <= j1; ++j) {
    const std::int64_t py = j * kSub + kSub / 2;
    for (std::int64_t i = i0; i <= i1; ++i) {
      const std::int64_t px = i * kSub + kSub / 2;
      const std::int64_t w0 = edge(v1, v2, px, py), w1 = edge(v2, v0, px, py), w2 = edge(v0, v1, px, py);
      if (w0 < 0 || w1 < 0 || w2 < 0) continue;
      if ((w0 == 0 && !tl0) || (w1 == 0 && !tl1) || (w2 == 0 && !tl2)) continue;
      const double z =
          (static_cast<double>(w0) * v0.z + static_cast<double>(w1) * v1.z + static_cast<double>(w2) * v2.z) * inv;
      const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(fr.w) + static_cast<std::size_t>(i);
      if (z > fr.depth[k]) {
        fr.depth[k] = z;
        fr.element[k] = id;
      }
    }
  }
}

/// Fits the projected box of the field into the plot area (plot_w x H pixels) with a 5% margin,
/// keeping the aspect ratio.
ScreenFit fit_to_plot(const ElementField& field, const Camera& camera, int plot_w, int H) {
  double xlo = std::numeric_limits<double>::infinity(), xhi = -xlo, ylo = xlo, yhi = -xlo;
  for (const auto& tri : field.triangle)
    for (const Vec3& p : tri) {
      const Projection s = project(camera, p);
      xlo = std::min(xlo, s.x);
      xhi = std::max(xhi, s.x);
      ylo = std::min(ylo, s.y);
      yhi = std::max(yhi, s.y);
    }
  const double sw = kSamples * plot_w * 0.9, sh = kSamples * H * 0.9;
  const double bw = xhi - xlo, bh = yhi - ylo;
  double scale = std::min(bw > 0.0 ? sw / bw : std::numeric_limits<double>::infinity(),
                          bh > 0.0 ? sh / bh : std::numeric_limits<double>::infinity());
  if (!std::isfinite(scale)) scale = 1.0;
  const double cx = 0.5 * (xlo + xhi), cy = 0.5 * (ylo + yhi);
  const double ox = 0.5 * kSamples * plot_w, oy = 0.5 * kSamples * H;
  return ScreenFit{scale, cx, cy, ox, oy};
}

ScreenPoint screen_point(const Frame& fr, const Vec3& p) {
  const Projection s = project(fr.camera, p);
  const double x = fr.fit.ox + (s.x - fr.fit.cx) * fr.fit.scale, y = fr.fit.oy - (s.y - fr.fit.cy) * fr.fit.scale;
  return ScreenPoint{std::llround(x * kSub), std::llround(y * kSub), s.depth};
}

}  // namespace

int plot_width(const ElementField& field, const RenderOptions& options) {
  const int W = options.width, H = options.height;
  const bool bar = !is_rgb(field) && W >= 24 && H >= 16;
  return bar ? W - std::max(12, W / 8) : W;
}

std::array<double, 2> frame_position(const Frame& frame, const Vec3& p) {
  const Projection s = project(frame.camera, p);
  return {frame.fit.ox + (s.x - frame.fit.cx) * frame.fit.scale, frame.fit.oy - (s.y - frame.fit.cy) * frame.fit.scale};
}

Frame draw_frame(const ElementField& field, const RenderOptions& options) {
  Frame fr;
  fr.w = kSamples * options.width;
  fr.h = kSamples * options.height;
  fr.plot_w = plot_width(field, options);
  fr.camera = picture_camera(field, options);
  fr.fit = fit_to_plot(field, fr.camera, fr.plot_w, options.height);
  const std::size_t samples = static_cast<std::size_t>(fr.w) * static_cast<std::size_t>(fr.h);
  fr.element.assign(samples, -1);
  fr.depth.assign(samples, -std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < field.size(); ++i) {
    // An element whose front side is turned away (a room's near wall) is not drawn: a cut-away.
    if (!sees_front(fr.camera, field.centroid[i], field.inner_normal[i])) continue;
    const auto& t = field.triangle[i];
    fill_triangle(fr, screen_point(fr, t[0]), screen_point(fr, t[1]), screen_point(fr, t[2]),
                  static_cast<std::int32_t>(i), kSamples * fr.plot_w);
  }
  return fr;
}

}  // namespace panelrad::io_detail

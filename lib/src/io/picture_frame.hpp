#pragma once
// The picture's frame (internal to panelrad_io): which element is seen at each sample of the
// image, after the depth test. The PNG colours each sample by its element; the tests read the
// frame to check what a viewpoint shows.
#include "picture_camera.hpp"

#include <panelrad/io/scene_output.hpp>
#include <panelrad/solve/element_field.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace panelrad::io_detail {

constexpr int kSamples = 2;  // samples per pixel and axis

/// Screen position (in samples) = o + (projection - c) * scale, y downwards.
struct ScreenFit {
  double scale, cx, cy, ox, oy;
};

struct Frame {
  int w = 0, h = 0;  // in samples: kSamples times the image's width and height
  int plot_w = 0;    // the plot area's width in pixels (the rest: the colour bar)
  Camera camera;
  ScreenFit fit{};
  std::vector<std::int32_t> element;  // [y * w + x]: the element seen there, -1 for none
  std::vector<double> depth;          // its depth (Projection::depth), larger = nearer
};

/// Width in pixels of the plot area: scalar scenes keep the right eighth for the colour bar.
int plot_width(const ElementField& field, const RenderOptions& options);

/// Position of p in the frame, in samples (x right, y down; sample (i, j) is centred at
/// (i + 1/2, j + 1/2)).
std::array<double, 2> frame_position(const Frame& frame, const geometry::Vec3& p);

/// The frame of a validated field with checked options: the elements whose front side faces the
/// camera, rasterized (2x2 samples per pixel, exact edge functions, the top-left fill rule) with a
/// depth test; the projected field fitted into the plot area with a 5% margin.
Frame draw_frame(const ElementField& field, const RenderOptions& options);

}  // namespace panelrad::io_detail

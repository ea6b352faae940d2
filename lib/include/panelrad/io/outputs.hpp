#pragma once
// A solved scene's files, written as one set: PREFIX.csv (per-element radiosity), PREFIX.ply
// (per-face colours), PREFIX.vtk (ParaView) and PREFIX.png (a picture), each as scene_output.hpp
// writes it, all or none (text_output.hpp's OutputSet: temporaries renamed over the outputs once
// every one was written).
#include <panelrad/geometry/mesh.hpp>
#include <panelrad/solve/scene_solver.hpp>

#include <optional>
#include <string>
#include <vector>

namespace panelrad {

/// How the picture is taken (PNG only).
struct OutputOptions {
  /// Direction from the scene's centre towards the viewer; none: chosen from the scene
  /// (RenderOptions::view_from_scene: a room from its open side or through a wall, a body from
  /// outside).
  std::optional<geometry::Vec3> view_direction;
  /// The scene's direction shown upwards on the screen; none: chosen from the scene
  /// (RenderOptions::up_from_scene).
  std::optional<geometry::Vec3> up;
};

/// The formats write_outputs knows, in writing order.
inline const std::vector<std::string>& output_formats() {
  static const std::vector<std::string> formats{"csv", "ply", "vtk", "png"};
  return formats;
}

/// The output paths PREFIX.<format> for `formats` (each one of output_formats(), at least one,
/// none twice: std::invalid_argument naming the entry otherwise), in writing order.
std::vector<std::string> output_paths(const std::string& prefix, const std::vector<std::string>& formats);

/// Writes `solution`'s files PREFIX.<format> for `formats` (output_paths), all or none: a failure
/// leaves the previous files in place and throws std::runtime_error naming the path. The channel
/// names must be usable as CSV columns (check_channel_names). Returns the paths written.
std::vector<std::string> write_outputs(const SceneSolution& solution, const std::string& prefix,
                                       const std::vector<std::string>& formats, const OutputOptions& options = {});

}  // namespace panelrad

// Scene files: a validated mesh with rho and E per input facet (the data of the radiosity
// equation, paper (7)), in one or more channels, from OBJ + MTL (obj_scene.cpp) or OFF + JSON
// sidecar (off_scene.cpp). Every error names the file and the line or facet; nothing is returned
// partially.
#include "scene_file_internal.hpp"
#include "scene_reading.hpp"

#include <panelrad/io/scene_file.hpp>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

namespace panelrad {

namespace {

namespace fs = std::filesystem;

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

}  // namespace

Scene load_channel_scene(const std::string& path, const std::string& materials_path,
                         const TextReadOptions& options) {
  const std::string ext = lower_extension(path);
  if (ext == ".obj") {
    if (!materials_path.empty())
      io_detail::fail(path, 0, "a materials file (" + materials_path + ") applies to OFF scenes only; an OBJ names "
                               "its MTL files with mtllib");
    return io_detail::to_scene(io_detail::load_obj_scene(path, options));
  }
  if (ext == ".off") return io_detail::to_scene(io_detail::load_off_scene(path, materials_path, options));
  if (ext == ".stl")
    io_detail::fail(path, 0, "an STL file is a mesh without reflectivity or emission: read it as geometry only "
                             "(LoadOptions::geometry_only; in Python geometry_only=True; `panelrad viewfactors` "
                             "does), or give the scene as .obj (with MTL) or .off (with a JSON sidecar)");
  io_detail::fail(path, 0, "unknown scene format " + io_detail::in_quotes(ext.empty() ? "(no extension)" : ext) +
                               ": expected .obj (with MTL) or .off (with a JSON sidecar)");
}

}  // namespace panelrad

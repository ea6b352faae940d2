#pragma once
// The scene-file readers behind load_scene (scene_file.hpp).
#include <panelrad/scene/scene.hpp>
#include <panelrad/support/text_file.hpp>

#include <string>

namespace panelrad {

/// SCENE.obj with its MTL files, or SCENE.off with its JSON sidecar (`materials_path`, or the OFF's
/// path with extension .json), by extension; SceneFileError for anything else.
Scene load_channel_scene(const std::string& path, const std::string& materials_path, const TextReadOptions& options);

}  // namespace panelrad

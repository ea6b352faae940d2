// load_scene: one entry for every supported scene (builtin, OBJ + MTL, OFF + JSON, a mesh alone).
#include <panelrad/io/scene_file.hpp>

#include "scene_file_internal.hpp"
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/mesh_io.hpp>

namespace panelrad {

Scene load_scene(const std::string& path, const LoadOptions& options) {
  const bool builtin = path.rfind("builtin:", 0) == 0;
  if (!builtin && !options.geometry_only) return load_channel_scene(path, options.materials_path, options.read);
  if (!options.materials_path.empty())
    throw SceneFileError(path + ": a materials file (" + options.materials_path +
                         ") was given for a scene read as geometry only");
  std::vector<std::string> notes;
  geometry::TriangleMesh mesh = builtin ? geometry::make_builtin(path.substr(8)) : geometry::read_mesh(path, &notes, options.read);
  geometry::ValidatedMesh validated = geometry::validate_mesh(std::move(mesh), &notes);
  Scene scene(std::move(validated));
  scene.set_emissivity(1.0);  // a mesh alone: every facet emits 1 (LoadOptions::geometry_only)
  for (std::string& note : notes) scene.add_note(std::move(note));
  return scene;
}

}  // namespace panelrad

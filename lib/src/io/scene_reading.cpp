// What reading a scene file in either format shares: the data as read, the validated mesh, the
// file's text, value checks, and errors naming the file and the line.
#include "scene_reading.hpp"

#include <charconv>
#include <system_error>
#include <utility>

namespace panelrad::io_detail {

Scene to_scene(SceneData&& data) {
  Scene scene(std::move(*data.mesh), std::move(data.channels));
  for (std::size_t c = 0; c < data.rho.size(); ++c) {
    scene.set_reflectivity(std::move(data.rho[c]), c);
    scene.set_emissivity(std::move(data.emission[c]), c);
  }
  for (std::size_t c = 0; c < data.environment.size(); ++c) scene.set_environment(data.environment[c], c);
  scene.set_facet_material(std::move(data.facet_material));
  for (std::string& note : data.notes) scene.add_note(std::move(note));
  return scene;
}

[[noreturn]] void fail(const std::string& file, long line, const std::string& what) {
  if (line > 0) throw SceneFileError(file + ":" + std::to_string(line) + ": " + what);
  throw SceneFileError(file + ": " + what);
}

std::string in_quotes(const std::string& s) { return "'" + s + "'"; }

/// Shortest round-trip text of a number (inf, nan as such).
std::string number(double v) {
  char buf[40];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return ec == std::errc() ? std::string(buf, ptr) : std::to_string(v);
}

std::string read_text(const std::string& path, const std::string& role, const TextReadOptions& options) {
  try {
    return read_text_file(path, role, options);
  } catch (const TextFileError& e) {
    throw SceneFileError(e.what());
  }
}

std::string value_problem(bool is_rho, double v) { return is_rho ? reflectivity_problem(v) : emission_problem(v); }

geometry::ValidatedMesh load_mesh(const std::string& path, std::vector<std::string>& notes,
                                  const TextReadOptions& options, geometry::ObjMaterialUse* materials) {
  geometry::TriangleMesh mesh;
  try {
    mesh = materials ? geometry::read_obj_with_materials(path, *materials, &notes, options)
                     : geometry::read_mesh(path, &notes, options);
  } catch (const geometry::MeshError& e) {
    throw SceneFileError(e.what());
  }
  geometry::SceneValidationReport report;
  std::optional<geometry::ValidatedMesh> validated = geometry::try_validate(std::move(mesh), report);
  if (!validated) fail(path, 0, "invalid scene mesh: " + report.message);
  for (const std::string& n : report.notes) notes.push_back(path + ": " + n);
  return std::move(*validated);
}

}  // namespace panelrad::io_detail

#pragma once
// What reading a scene file in either format (OBJ + MTL, OFF + JSON sidecar) shares (internal to
// panelrad_io): the data as it is read, the mesh read and validated as a scene, the file's text,
// and errors that name the file and the line.
#include <panelrad/geometry/mesh_io.hpp>
#include <panelrad/geometry/scene_validation.hpp>
#include <panelrad/io/scene_file.hpp>
#include <panelrad/support/text_file.hpp>

#include <optional>
#include <string>
#include <vector>

namespace panelrad::io_detail {

// A scene file's data as it is read; a Scene once complete (to_scene).
struct SceneData {
  std::optional<geometry::ValidatedMesh> mesh;  // set by load_mesh
  std::vector<std::string> channels;
  std::vector<std::vector<double>> rho, emission;  // [channel][facet], checked as read
  std::vector<double> environment;                 // [channel], or empty: none
  std::vector<std::string> facet_material;
  std::vector<std::string> notes;
};

Scene to_scene(SceneData&& data);

/// Throws SceneFileError "file:line: what" ("file: what" when line <= 0).
[[noreturn]] void fail(const std::string& file, long line, const std::string& what);

std::string in_quotes(const std::string& s);

/// Shortest round-trip text of a number (inf, nan as such).
std::string number(double v);

/// The whole file, by the bounded reader (text_file.hpp: regular files only, size limit, no NUL
/// byte); `role` says what it is for in messages ("MTL file named by x.obj:3").
std::string read_text(const std::string& path, const std::string& role, const TextReadOptions& options);

/// Checks one value of rho or E; returns what is wrong, or "" when fine.
std::string value_problem(bool is_rho, double v);

/// Reads and validates the mesh as a scene (geometry::try_validate: convex, or general with its
/// visibility computed); notes get the reader's and the validator's notes. For an OBJ,
/// `materials` (when given) gets its mtllib and per-face usemtl statements.
geometry::ValidatedMesh load_mesh(const std::string& path, std::vector<std::string>& notes,
                                  const TextReadOptions& options, geometry::ObjMaterialUse* materials = nullptr);

/// An OBJ and the MTL files it names: rho = Kd and E = Ke per facet in channels R, G, B.
SceneData load_obj_scene(const std::string& path, const TextReadOptions& options);

/// An OFF and its JSON sidecar (`materials_path`, or the OFF's path with extension .json).
SceneData load_off_scene(const std::string& path, const std::string& materials_path, const TextReadOptions& options);

}  // namespace panelrad::io_detail

#pragma once
// Scene files for `panelrad solve`: a polyhedral scene with reflectivity rho and emission E
// per input facet (the data of the radiosity equation, paper (7)), in one or more colour channels.
//   - OBJ + MTL: faces take the material of the last `usemtl`; materials come from the files named
//     by `mtllib` (relative to the OBJ's folder). Kd "r g b" -> rho (3 channels R, G, B), Ke "r g b"
//     -> E (0 when absent). A material without Kd, a face before any usemtl, an unknown material,
//     a missing or unreadable MTL file are errors naming the file and line.
//     MTL statements are case-sensitive. Read: newmtl, Kd, Ke. Errors naming the line: Kd or Ke
//     given twice in one material (naming both lines), a miscased newmtl/Kd/Ke (`kd`, `KE`), an
//     unknown statement. Read over, as they do not enter diffuse radiosity: Ka, Ks, Ns, Ni, d, Tr,
//     Tf, illum, sharpness, bump, disp, decal, refl, the PBR statements Pr, Pm, Ps, Pc, Pcr, aniso,
//     anisor, norm, and every texture map map_*; a note (Scene::notes) names the line where
//     that changes what the file means: map_Kd / map_Ke (the texture is not applied), d < 1 or
//     Tr > 0 (read as opaque), and a miscased ignored statement (`ns`).
//   - OFF + JSON sidecar (the OFF's path with extension .json, or an explicit path):
//       { "channels": ["R","G","B"],            optional; default one channel "value"
//         "default": { "rho": 0.5, "E": 0 },    optional; used for facets not listed
//         "facets": [ { "id": 0, "rho": 0.7, "E": [1, 0.9, 0.8] },
//                     { "ids": [1, 2], "rho": [0.2, 0.6, 0.2] }, ... ] }
//     "id"/"ids": input face indices (0-based, OFF face order); a value is a number (all channels)
//     or an array with one number per channel. A facet with no value and no default, an id out
//     of range or given twice, a wrong array length, a non-number or a key given twice in one
//     object (JSON leaves open which value counts) are errors naming the file, the line and the
//     entry (e.g. "facets[3]").
// Every value is checked (reflectivity_problem, emission_problem): rho finite, in [0, 1) and not
// subnormal; E finite, >= 0, and either 0 or in [kMinPositiveEmission, kMaxEmission] = [1e-100,
// 1e100]; else an error naming the file, the line, the facet (input face index) or the material.
// All files are read by the bounded reader (support/text_file.hpp): regular files only, at most
// TextReadOptions::max_bytes (default 1 GiB), no NUL byte; a UTF-8 byte-order mark is accepted.
// The mesh is read with geometry::read_mesh and validated with geometry::validate_scene (a closed
// convex surface, or any set of planar polygons that do not cross, each piece consistently
// oriented; the Scene's shape says which): an invalid mesh is a SceneFileError with the
// validator's reason.
#include <panelrad/geometry/mesh.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/scene/errors.hpp>
#include <panelrad/support/text_file.hpp>

#include <stdexcept>
#include <string>
#include <vector>

namespace panelrad {

/// What load_scene reads beside the scene file.
struct LoadOptions {
  /// OFF: the JSON sidecar's path (empty: the OFF's path with extension .json).
  std::string materials_path;
  /// Read the mesh only (OFF or OBJ, no MTL or sidecar): one channel "value", rho = 0 and E = 1
  /// on every facet, to be set in code (Scene::set_reflectivity, set_emissivity).
  bool geometry_only = false;
  /// The size limit of every file read (mesh, MTL, JSON).
  TextReadOptions read;
};

/// Loads a scene, validated (geometry::validated), whatever its format:
///   - "builtin:NAME" (cube, prism:K, tetrahedron, octahedron): geometry only, as above;
///   - SCENE.obj with its MTL files, or SCENE.off with its JSON sidecar, by extension
///     (case-insensitive): the file's channels, rho and E per facet, its notes and (OBJ) the
///     material of each facet;
///   - with options.geometry_only, the mesh of an OFF or OBJ file alone.
/// The scene's shape (convex: V = 1; general: V computed) comes from the validation. Throws
/// SceneFileError (a scene file or its materials), MeshError (the mesh, builtin or geometry
/// only), TextFileError; never returns a partial scene.
Scene load_scene(const std::string& path, const LoadOptions& options = {});

}  // namespace panelrad

#pragma once
// Scene files for `panelrad solve` (issue 6): a convex polyhedral scene with reflectivity rho and
// emission E per input facet, in one or more colour channels.
//   - OBJ + MTL: faces take the material of the last `usemtl`; materials come from the files named
//     by `mtllib` (relative to the OBJ's folder). Kd "r g b" -> rho (3 channels R, G, B), Ke "r g b"
//     -> E (0 when absent). A material without Kd, a face before any usemtl, an unknown material,
//     a missing or unreadable MTL file are errors naming the file and line.
//   - OFF + JSON sidecar (the OFF's path with extension .json, or an explicit path):
//       { "channels": ["R","G","B"],            optional; default one channel "value"
//         "default": { "rho": 0.5, "E": 0 },    optional; used for facets not listed
//         "facets": [ { "id": 0, "rho": 0.7, "E": [1, 0.9, 0.8] },
//                     { "ids": [1, 2], "rho": [0.2, 0.6, 0.2] }, ... ] }
//     "id"/"ids": input face indices (0-based, OFF face order); a value is a number (all channels)
//     or an array with one number per channel. A facet with no value and no default, an id out
//     of range or given twice, a wrong array length or a non-number are errors naming the file and
//     the facet.
// Every value is checked: rho finite and in [0, 1), E finite and >= 0; else an error naming the
// file, the facet (input face index) and, for MTL, the material and line.
// The mesh is read with geometry::read_mesh and validated with geometry::validate_closed_convex
// (closed, convex, non-degenerate): an invalid mesh is a SceneFileError with the validator's reason.
#include <panelrad/geometry/mesh.hpp>

#include <stdexcept>
#include <string>
#include <vector>

namespace panelrad {

/// Any problem with a scene file or its materials: the message names the file, and the line or
/// facet where it can.
class SceneFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A validated closed convex scene with per-facet data in C channels.
struct ChannelScene {
  geometry::TriangleMesh mesh;                ///< validated (outward oriented), facet = input face
  std::vector<std::string> channels;          ///< {"R", "G", "B"} for OBJ+MTL; from the JSON otherwise
  std::vector<std::vector<double>> rho;       ///< rho[c][facet], 0 <= rho < 1
  std::vector<std::vector<double>> emission;  ///< emission[c][facet], finite, >= 0
  std::vector<std::string> facet_material;    ///< material name per facet (OBJ), else empty
  std::vector<std::string> notes;             ///< what loading did: merged vertices, re-orientation,
                                              ///< hull re-triangulation, files read
  std::size_t num_channels() const { return channels.size(); }
};

/// Loads SCENE (.obj with its MTL files, or .off with its JSON sidecar), by extension
/// (case-insensitive). `materials_path` overrides the sidecar's path (OFF only; empty: default).
/// Throws SceneFileError (never a partial scene).
ChannelScene load_channel_scene(const std::string& path, const std::string& materials_path = "");

}  // namespace panelrad

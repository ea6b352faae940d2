#pragma once
// Scene files for `panelrad solve`: a convex polyhedral scene with reflectivity rho and emission E
// per input facet (the data of the radiosity equation, paper (7)), in one or more colour channels.
//   - OBJ + MTL: faces take the material of the last `usemtl`; materials come from the files named
//     by `mtllib` (relative to the OBJ's folder). Kd "r g b" -> rho (3 channels R, G, B), Ke "r g b"
//     -> E (0 when absent). A material without Kd, a face before any usemtl, an unknown material,
//     a missing or unreadable MTL file are errors naming the file and line.
//     MTL statements are case-sensitive. Read: newmtl, Kd, Ke. Errors naming the line: Kd or Ke
//     given twice in one material (naming both lines), a miscased newmtl/Kd/Ke (`kd`, `KE`), an
//     unknown statement. Read over, as they do not enter diffuse radiosity: Ka, Ks, Ns, Ni, d, Tr,
//     Tf, illum, sharpness, bump, disp, decal, refl, the PBR statements Pr, Pm, Ps, Pc, Pcr, aniso,
//     anisor, norm, and every texture map map_*; a note (ChannelScene::notes) names the line where
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
// All files are read by the bounded reader (geometry/text_file.hpp): regular files only, at most
// TextReadOptions::max_bytes (default 1 GiB), no NUL byte; a UTF-8 byte-order mark is accepted.
// The mesh is read with geometry::read_mesh and validated with geometry::validate_closed_convex
// (closed, convex, non-degenerate): an invalid mesh is a SceneFileError with the validator's reason.
#include <panelrad/geometry/mesh.hpp>
#include <panelrad/geometry/text_file.hpp>

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

/// The largest emission E accepted. The solution of the radiosity equation (7) satisfies
/// |u| <= max E / (1 - max rho), and 1 / (1 - rho) reaches 2^53 ~ 9e15 for the largest double
/// below 1, so u <= 9e115; its squares (residual norms) summed over 1e9 elements stay below
/// 1e242, and its products with areas (at most 1e150: validation bounds lengths by 1e75) summed
/// over 1e9 elements below 1e275: finite.
inline constexpr double kMaxEmission = 1e100;
/// The smallest non-zero emission E accepted: with areas down to 1e-150, products area * E stay
/// above 1e-250 and squares of E above 1e-200, normal numbers (no underflow to subnormal or 0).
/// Subnormal E (below DBL_MIN) have lost precision already and are refused with that reason.
inline constexpr double kMinPositiveEmission = 1e-100;

/// What is wrong with a reflectivity rho ("is outside [0, 1) ..."), or "" when it is accepted:
/// finite, 0 <= rho < 1, not subnormal.
std::string reflectivity_problem(double rho);
/// What is wrong with an emission E, or "" when it is accepted: finite, E = 0 or
/// kMinPositiveEmission <= E <= kMaxEmission; a subnormal E is named as such.
std::string emission_problem(double e);

/// Loads SCENE (.obj with its MTL files, or .off with its JSON sidecar), by extension
/// (case-insensitive). `materials_path` overrides the sidecar's path (OFF only; empty: default).
/// `options` sets the size limit of every file read (mesh, MTL, JSON).
/// Throws SceneFileError (never a partial scene).
ChannelScene load_channel_scene(const std::string& path, const std::string& materials_path = "",
                                const geometry::TextReadOptions& options = {});

}  // namespace panelrad

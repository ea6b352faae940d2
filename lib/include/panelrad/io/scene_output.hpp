#pragma once
// Outputs of a solved scene: per-element radiosity as CSV, a PLY with per-face colours
// (MeshLab, ParaView), a legacy VTK polydata file (ParaView), and a PNG picture from a default
// viewpoint. Each write_* function writes its file whole or not at all (write_file_atomically);
// the radiosity_* functions return the file's contents, so that a program can write several of
// them as one OutputSet (text_output.hpp): all of them, or none.
#include <panelrad/geometry/mesh.hpp>
#include <panelrad/solve/element_field.hpp>

#include <Eigen/Core>

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace panelrad {

/// Throws std::invalid_argument unless the names can be CSV columns and PLY/VTK property names:
/// at least one, each a non-empty token of letters, digits, '_', '-', '.', no name twice. Lets a
/// program check a scene's channels before solving it.
void check_channel_names(const std::vector<std::string>& channels);

/// CSV, one row per element: element,facet,x,y,z,area, then rho_<c>, E_<c>, u_<c> for each channel
/// c (for a single channel: rho,E,u). Numbers with 17 significant digits (round-trip).
void write_radiosity_csv(const std::string& path, const ElementField& field);
std::string radiosity_csv(const ElementField& field);

/// ASCII PLY: vertices (shared, deduplicated bit-exactly) and one face per element with uchar
/// red, green, blue (the picture's colour mapping) and a property u_<c> per channel: float (9
/// significant digits) when every value of the channel is zero or a normal float32
/// (FLT_MIN <= |u| <= FLT_MAX), otherwise double (17 digits), so no value becomes inf or 0.
void write_radiosity_ply(const std::string& path, const ElementField& field);
std::string radiosity_ply(const ElementField& field);

/// Legacy ASCII VTK POLYDATA: points, triangles, CELL_DATA scalars facet, area and per channel
/// rho_<c>, E_<c>, u_<c>.
void write_radiosity_vtk(const std::string& path, const ElementField& field);
std::string radiosity_vtk(const ElementField& field);

/// One CELL_DATA array of cells_vtk: its name and the value of element i.
struct CellValues {
  std::string name;
  std::function<double(std::size_t)> value;
};

/// Legacy ASCII VTK POLYDATA of any per-element values: the triangles' corners as points
/// (shared bit-exactly), the triangles, CELL_DATA `facet` (int) and each of `cells` (double, 17
/// digits). A character of a name other than a letter, digit, '_', '-', '.' becomes '_'.
std::string cells_vtk(const std::string& title, const std::vector<std::array<geometry::Vec3, 3>>& triangle,
                      const std::vector<geometry::Index>& facet, const std::vector<CellValues>& cells);

/// ASCII PLY of the same per-element values, for MeshLab and ParaView: the triangles' corners as
/// vertices (shared bit-exactly), one face per triangle with the int property `facet` and a double
/// property per entry of `cells` (17 significant digits, named as in cells_vtk).
std::string cells_ply(const std::string& title, const std::vector<std::array<geometry::Vec3, 3>>& triangle,
                      const std::vector<geometry::Index>& facet, const std::vector<CellValues>& cells);

struct RenderOptions {
  int width = 960;
  int height = 720;
  /// Direction from the scene's centre towards the viewer (need not be unit).
  geometry::Vec3 view_direction = geometry::Vec3(-1.0, -1.7, 1.2);
  /// The scene's direction shown upwards on the screen (need not be unit, nor orthogonal to
  /// view_direction): z for the built-in scenes, y for the Cornell box's data.
  geometry::Vec3 up = geometry::Vec3::UnitZ();
  /// Choose the viewpoint from the scene instead of view_direction: a room (its walls' front
  /// sides facing inward) in perspective from in front of its open side, level with its centre,
  /// looking in; a closed room likewise from outside one of its walls, which is left out (the eye
  /// sees its back side), on the side across `up` whose far walls show the most light; any other
  /// scene (bodies seen from outside) orthographically along the brightest of the eight
  /// diagonals, as brightest_view_direction() but about the chosen `up`.
  bool view_from_scene = false;
  /// Choose `up` from the scene: y when the lights face along the y axis (the data's y up, as the
  /// Cornell box's), otherwise z.
  bool up_from_scene = false;
};

/// Colour of each element as shown in the picture and the PLY: RGB scenes (3 channels named R, G,
/// B) map radiosity to colour with one exposure for all channels and gamma 2.2; any other channel
/// set maps its first channel through a perceptual colour map between its minimum and its maximum
/// over the non-emitting elements (emitters clamped to the top).
std::vector<std::array<unsigned char, 3>> element_colours(const ElementField& field);

/// A viewpoint that shows the light: among the eight directions (+-1, +-1.7, +-1.2), the one whose
/// visible walls (inner side towards the viewer) carry the most projected light,
/// sum area (n . d) sum_c u_c; ties go to the first in a fixed order, so the choice is
/// deterministic. For a scene lit from its ceiling this looks up into the light.
geometry::Vec3 brightest_view_direction(const ElementField& field);

/// PNG picture of the scene: an orthographic cut-away view from outside along view_direction (or
/// the view chosen from the scene, view_from_scene) showing the faces whose front side (inner
/// normal) looks at the viewer (a room's far walls, the near sides of the bodies in it), nearest
/// first (a depth buffer), each element flat-coloured by element_colours(), with a colour bar for
/// scalar scenes.
void write_radiosity_png(const std::string& path, const ElementField& field, const RenderOptions& options = {});
std::string radiosity_png(const ElementField& field, const RenderOptions& options = {});

}  // namespace panelrad

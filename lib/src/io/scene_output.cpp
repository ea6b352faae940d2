// The solved field as text files: CSV rows, a PLY with per-face colours, a legacy VTK polydata.
#include "element_colours.hpp"
#include "field_checks.hpp"

#include <panelrad/io/scene_output.hpp>
#include <panelrad/io/text_output.hpp>

#include <array>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

namespace panelrad {

using geometry::Vec3;
using io_detail::colours_of_valid;
using io_detail::is_rgb;
using io_detail::Rgb;
using io_detail::validate;
using io_detail::value;

namespace {

// ---------------------------------------------------------------------------------------------
// Text helpers

void append_g17(std::string& out, double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  out += buf;
}

void append_g9(std::string& out, double v) {  // float properties: 9 digits round-trip a float
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(static_cast<float>(v)));
  out += buf;
}

/// True when float32 holds v to its full relative precision: v is zero or a normal float after
/// rounding (FLT_MIN <= |v| <= FLT_MAX). Larger values would become inf, smaller ones subnormal
/// (fewer digits) or 0.
bool fits_float(double v) {
  if (v == 0.0) return true;
  const float f = static_cast<float>(v);
  return std::fpclassify(f) == FP_NORMAL;
}

/// Column/property suffix of channel c: "_<name>", or "" for a single-channel field (rho, E, u).
std::string suffix(const ElementField& f, std::size_t c) {
  return f.channels.size() == 1 ? std::string() : "_" + f.channels[c];
}

/// Corners shared between elements, deduplicated on the bit patterns of their coordinates.
struct SharedVertices {
  std::vector<Vec3> points;
  std::vector<std::array<std::size_t, 3>> corner;  // [element] -> point indices
};

SharedVertices share_vertices(const std::vector<std::array<Vec3, 3>>& triangle) {
  SharedVertices s;
  std::map<std::array<std::uint64_t, 3>, std::size_t> index;
  s.corner.resize(triangle.size());
  for (std::size_t i = 0; i < triangle.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = triangle[i][static_cast<std::size_t>(k)];
      const std::array<std::uint64_t, 3> key = {std::bit_cast<std::uint64_t>(p.x()),
                                                std::bit_cast<std::uint64_t>(p.y()),
                                                std::bit_cast<std::uint64_t>(p.z())};
      const auto [it, inserted] = index.emplace(key, s.points.size());
      if (inserted) s.points.push_back(p);
      s.corner[i][static_cast<std::size_t>(k)] = it->second;
    }
  return s;
}

}  // namespace

// ---------------------------------------------------------------------------------------------

void check_channel_names(const std::vector<std::string>& channels) {
  io_detail::check_names("channel names", channels);
}

void write_radiosity_csv(const std::string& path, const ElementField& field) {
  write_file_atomically(path, radiosity_csv(field));
}

std::string radiosity_csv(const ElementField& field) {
  validate("write_radiosity_csv", field);
  std::string out = "element,facet,x,y,z,area";
  for (std::size_t c = 0; c < field.channels.size(); ++c) {
    const std::string s = suffix(field, c);
    out += ",rho" + s + ",E" + s + ",u" + s;
  }
  out += '\n';
  for (std::size_t i = 0; i < field.size(); ++i) {
    out += std::to_string(i) + ',' + std::to_string(field.facet[i]);
    for (int k = 0; k < 3; ++k) {
      out += ',';
      append_g17(out, field.centroid[i][k]);
    }
    out += ',';
    append_g17(out, field.area[i]);
    for (std::size_t c = 0; c < field.channels.size(); ++c)
      for (const auto* v : {&field.rho[c], &field.emission[c], &field.radiosity[c]}) {
        out += ',';
        append_g17(out, value(*v, i));
      }
    out += '\n';
  }
  return out;
}

namespace {
// One line "x y z" per shared vertex, 17 significant digits (round-trip).
/// "3 a b c": triangle i's corners as indices of the shared vertices (a PLY or VTK polygon).
void append_corners(std::string& out, const SharedVertices& sv, std::size_t i) {
  out += "3 " + std::to_string(sv.corner[i][0]) + ' ' + std::to_string(sv.corner[i][1]) + ' ' +
         std::to_string(sv.corner[i][2]);
}

void append_points(std::string& out, const std::vector<Vec3>& points) {
  for (const Vec3& p : points) {
    append_g17(out, p.x());
    out += ' ';
    append_g17(out, p.y());
    out += ' ';
    append_g17(out, p.z());
    out += '\n';
  }
}
}  // namespace

void write_radiosity_ply(const std::string& path, const ElementField& field) {
  write_file_atomically(path, radiosity_ply(field));
}

std::string radiosity_ply(const ElementField& field) {
  validate("write_radiosity_ply", field);
  std::vector<bool> as_float(field.channels.size(), true);
  for (std::size_t c = 0; c < field.channels.size(); ++c)
    for (std::size_t i = 0; i < field.size() && as_float[c]; ++i)
      as_float[c] = fits_float(value(field.radiosity[c], i));
  const SharedVertices sv = share_vertices(field.triangle);
  const std::vector<Rgb> colour = colours_of_valid(field);
  std::string out = "ply\nformat ascii 1.0\ncomment panelrad radiosity\n";
  out += "element vertex " + std::to_string(sv.points.size()) + "\n";
  out += "property double x\nproperty double y\nproperty double z\n";
  out += "element face " + std::to_string(field.size()) + "\n";
  out += "property list uchar int vertex_indices\n";
  out += "property uchar red\nproperty uchar green\nproperty uchar blue\n";
  for (std::size_t c = 0; c < field.channels.size(); ++c)
    out += std::string(as_float[c] ? "property float u" : "property double u") + suffix(field, c) + "\n";
  out += "end_header\n";
  append_points(out, sv.points);
  for (std::size_t i = 0; i < field.size(); ++i) {
    append_corners(out, sv, i);
    for (const unsigned char b : colour[i]) out += ' ' + std::to_string(static_cast<int>(b));
    for (std::size_t c = 0; c < field.channels.size(); ++c) {
      out += ' ';
      if (as_float[c]) append_g9(out, value(field.radiosity[c], i));
      else append_g17(out, value(field.radiosity[c], i));
    }
    out += '\n';
  }
  return out;
}

void write_radiosity_vtk(const std::string& path, const ElementField& field) {
  write_file_atomically(path, radiosity_vtk(field));
}

namespace {

/// A name as one token of a VTK or PLY header: a character other than a letter, digit, '_', '-',
/// '.' becomes '_'.
std::string header_token(std::string name) {
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch)) && ch != '_' && ch != '-' && ch != '.') ch = '_';
  return name;
}

}  // namespace

std::string cells_ply(const std::string& title, const std::vector<std::array<Vec3, 3>>& triangle,
                      const std::vector<geometry::Index>& facet, const std::vector<CellValues>& cells) {
  const SharedVertices sv = share_vertices(triangle);
  const std::size_t n = triangle.size();
  std::string out = "ply\nformat ascii 1.0\ncomment " + title + "\n";
  out += "element vertex " + std::to_string(sv.points.size()) + "\n";
  out += "property double x\nproperty double y\nproperty double z\n";
  out += "element face " + std::to_string(n) + "\n";
  out += "property list uchar int vertex_indices\nproperty int facet\n";
  for (const CellValues& cell : cells) out += "property double " + header_token(cell.name) + "\n";
  out += "end_header\n";
  append_points(out, sv.points);
  for (std::size_t i = 0; i < n; ++i) {
    append_corners(out, sv, i);
    out += ' ' + std::to_string(facet[i]);
    for (const CellValues& cell : cells) {
      out += ' ';
      append_g17(out, cell.value(i));
    }
    out += '\n';
  }
  return out;
}

std::string cells_vtk(const std::string& title, const std::vector<std::array<Vec3, 3>>& triangle,
                      const std::vector<geometry::Index>& facet, const std::vector<CellValues>& cells) {
  const SharedVertices sv = share_vertices(triangle);
  const std::size_t n = triangle.size();
  std::string out = "# vtk DataFile Version 3.0\n" + title + "\nASCII\nDATASET POLYDATA\n";
  out += "POINTS " + std::to_string(sv.points.size()) + " double\n";
  append_points(out, sv.points);
  out += "POLYGONS " + std::to_string(n) + ' ' + std::to_string(4 * n) + '\n';
  for (std::size_t i = 0; i < n; ++i) {
    append_corners(out, sv, i);
    out += '\n';
  }
  out += "CELL_DATA " + std::to_string(n) + '\n';
  out += "SCALARS facet int 1\nLOOKUP_TABLE default\n";
  for (std::size_t i = 0; i < n; ++i) out += std::to_string(facet[i]) + '\n';
  for (const CellValues& cell : cells) {
    out += "SCALARS " + header_token(cell.name) + " double 1\nLOOKUP_TABLE default\n";
    for (std::size_t i = 0; i < n; ++i) {
      append_g17(out, cell.value(i));
      out += '\n';
    }
  }
  return out;
}

std::string radiosity_vtk(const ElementField& field) {
  validate("write_radiosity_vtk", field);
  std::vector<CellValues> cells{{"area", [&](std::size_t i) { return field.area[i]; }}};
  for (std::size_t c = 0; c < field.channels.size(); ++c) {
    const std::string s = suffix(field, c);
    cells.push_back({"rho" + s, [&field, c](std::size_t i) { return value(field.rho[c], i); }});
    cells.push_back({"E" + s, [&field, c](std::size_t i) { return value(field.emission[c], i); }});
    cells.push_back({"u" + s, [&field, c](std::size_t i) { return value(field.radiosity[c], i); }});
  }
  std::string out = cells_vtk("panelrad radiosity", field.triangle, field.facet, cells);
  if (is_rgb(field)) {  // the picture's colours, for ParaView's "Map Scalars" off
    out += "COLOR_SCALARS colour 3\n";
    char buf[64];
    for (const Rgb& c : colours_of_valid(field)) {
      std::snprintf(buf, sizeof buf, "%.6g %.6g %.6g\n", c[0] / 255.0, c[1] / 255.0, c[2] / 255.0);
      out += buf;
    }
  }
  return out;
}

}  // namespace panelrad

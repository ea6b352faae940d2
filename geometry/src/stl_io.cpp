// STL meshes, ASCII and binary, read with CGAL::IO::read_STL (mesh_io.hpp: read_stl, read_mesh).
//
// CGAL parses the geometry and merges the corners with identical coordinates; this file bounds the
// input, decides what CGAL may be given, and names the facets' solids and lines:
//   - binary: 80 bytes of header, a 32-bit facet count N, then N records of 50 bytes (normal,
//     three corners as float32, 2 attribute bytes), the size exactly 84 + 50 N. Every corner must
//     be finite, checked before CGAL reads them (its map of corners orders them by value, which a
//     NaN would break);
//   - ASCII: text starting with `solid`, of any other size; its bytes must all be text (no NUL,
//     DEL or bytes that are not UTF-8), so that whatever CGAL reads from it as binary, should the
//     text not parse, is finite. One or more `solid NAME ... endsolid` blocks; each `facet` line
//     starts a facet, named after the solid it is in (TriangleMesh::facet_group) and its line.
// Each triangle is one input face (an STL has no polygons); corners are float32 in binary files and
// decimal in ASCII ones, as written.
#include "stl_io.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/STL.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace panelrad::geometry {

namespace {

using StlPoint = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;

[[noreturn]] void fail(const std::string& name, const std::string& what) { throw MeshError(name + ": " + what); }

constexpr std::size_t kHeader = 84, kRecord = 50;

/// The facet count of a binary STL when the size matches 84 + 50 N, else -1.
long long binary_facets(const std::string& bytes) {
  if (bytes.size() < kHeader) return -1;
  std::uint32_t n = 0;
  std::memcpy(&n, bytes.data() + 80, sizeof n);
  return bytes.size() == kHeader + kRecord * static_cast<std::size_t>(n) ? static_cast<long long>(n) : -1;
}

/// Every corner of the binary records finite (their normals are not used).
void check_binary_corners(const std::string& bytes, long long facets, const std::string& name) {
  for (long long f = 0; f < facets; ++f)
    for (int k = 3; k < 12; ++k) {
      float x;
      std::memcpy(&x, bytes.data() + kHeader + static_cast<std::size_t>(f) * kRecord + 4 * static_cast<std::size_t>(k),
                  sizeof x);
      if (!std::isfinite(x))
        fail(name, "binary STL facet " + std::to_string(f) + " has a non-finite coordinate (corner " +
                       std::to_string((k - 3) / 3) + ")");
    }
}

/// Text only: no NUL, DEL, and no byte 0xC0, 0xC1 or 0xF5..0xFF (never in UTF-8).
void check_text(const std::string& bytes, const std::string& name) {
  long line = 1;
  for (const char ch : bytes) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '\n') ++line;
    if (c == 0 || c == 0x7f || c == 0xc0 || c == 0xc1 || c >= 0xf5)
      fail(name, "line " + std::to_string(line) + ": byte " + std::to_string(c) +
                     " is not text: neither an ASCII STL nor a binary one (whose size is 84 + 50 N bytes for N facets)");
  }
}

/// The solid and the line of every `facet` of an ASCII STL, in order.
void name_ascii_facets(const std::string& text, std::vector<std::string>& group, std::vector<long>& line) {
  std::istringstream in(text);
  std::string solid, row;
  for (long number = 1; std::getline(in, row); ++number) {
    std::istringstream words(row);
    std::string first;
    if (!(words >> first)) continue;
    if (first == "solid") {
      std::string rest;
      std::getline(words, rest);
      const std::size_t a = rest.find_first_not_of(" \t\r"), b = rest.find_last_not_of(" \t\r");
      solid = a == std::string::npos ? std::string() : rest.substr(a, b - a + 1);
    } else if (first == "facet") {
      group.push_back(solid);
      line.push_back(number);
    }
  }
}

TriangleMesh parse_stl(const std::string& bytes, const std::string& name, std::vector<std::string>* notes) {
  if (bytes.empty()) fail(name, "empty file");
  const long long facets = binary_facets(bytes);
  const bool ascii = facets < 0 || (bytes.compare(0, 5, "solid") == 0 && bytes.find('\0') == std::string::npos);
  if (facets >= 0) check_binary_corners(bytes, facets, name);
  if (facets < 0) {
    check_text(bytes, name);
    if (bytes.find("solid") == std::string::npos)
      fail(name, "not an STL: no `solid` in the text, and the size is not that of a binary STL (84 + 50 N bytes)");
  }
  std::vector<StlPoint> points;
  std::vector<std::array<int, 3>> triangles;
  std::istringstream in(bytes);
  const bool read = CGAL::IO::read_STL(in, points, triangles, CGAL::parameters::verbose(false));
  // Text that does not parse as ASCII is tried as binary too: too short for a header, that reads
  // as an empty file, so an unparsed `facet` is a failure however CGAL reports it.
  if (!read || (triangles.empty() && ascii && bytes.find("facet") != std::string::npos))
    fail(name, ascii ? "not a readable ASCII STL (solid, facet normal, outer loop, three vertex lines, endloop, "
                       "endfacet, endsolid)"
                     : "not a readable binary STL");
  if (triangles.empty()) fail(name, "no facet");
  TriangleMesh mesh;
  mesh.source = name;
  mesh.vertices.reserve(points.size());
  for (const StlPoint& p : points) {
    const Vec3 v(p.x(), p.y(), p.z());
    if (!v.allFinite()) fail(name, "a non-finite coordinate");
    mesh.vertices.push_back(v);
  }
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    mesh.triangles.push_back({triangles[t][0], triangles[t][1], triangles[t][2]});
    mesh.facet_of_triangle.push_back(static_cast<Index>(t));
  }
  mesh.num_facets = static_cast<Index>(triangles.size());
  if (ascii && facets < 0) {
    std::vector<std::string> group;
    std::vector<long> line;
    name_ascii_facets(bytes, group, line);
    if (group.size() == triangles.size()) {
      mesh.facet_line = std::move(line);
      bool named = false;
      for (const std::string& g : group) named = named || !g.empty();
      if (named) mesh.facet_group = std::move(group);
    }
  }
  if (notes)
    notes->push_back(name + ": " + (ascii && facets < 0 ? "ASCII" : "binary") + " STL, " +
                     std::to_string(triangles.size()) + " facets, " + std::to_string(points.size()) +
                     " distinct corners (corners with identical coordinates merged)");
  return mesh;
}

}  // namespace

TriangleMesh read_stl(std::istream& in, const std::string& name, std::vector<std::string>* notes,
                      const TextReadOptions& options) {
  std::string bytes;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    bytes.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (bytes.size() > options.max_bytes)
      fail(name, "larger than the limit of " + describe_bytes(options.max_bytes));
  }
  return parse_stl(bytes, name, notes);
}

TriangleMesh read_stl_file(const std::string& path, std::vector<std::string>* notes, const TextReadOptions& options) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (ec || !fs::exists(status)) fail(path, "cannot open: no such file");
  if (!fs::is_regular_file(status)) fail(path, "not a regular file");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) fail(path, "cannot read its size: " + ec.message());
  if (size > options.max_bytes)
    fail(path, "is " + describe_bytes(size) + ", larger than the limit of " + describe_bytes(options.max_bytes));
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open");
  return read_stl(in, path, notes, options);
}

}  // namespace panelrad::geometry

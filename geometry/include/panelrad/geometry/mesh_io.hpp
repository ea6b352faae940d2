#pragma once
// Mesh input: OFF and OBJ files. Polygonal faces are fan-triangulated here (validation may
// re-triangulate them exactly, see validation.hpp); vertices are shared.
#include <panelrad/geometry/mesh.hpp>

#include <iosfwd>
#include <string>

namespace panelrad::geometry {

/// Reads an OFF or OBJ file, chosen by extension (case-insensitive). Throws MeshError naming the
/// file, the line and what is wrong: missing/unreadable file, unknown extension, empty or
/// truncated file, garbage, a face index out of range, a face with fewer than 3 vertices, a
/// non-finite coordinate. Never returns a partial mesh.
TriangleMesh read_mesh(const std::string& path);

/// The same from a stream; `name` is used in messages.
TriangleMesh read_off(std::istream& in, const std::string& name);
TriangleMesh read_obj(std::istream& in, const std::string& name);

}  // namespace panelrad::geometry

#pragma once
// The STL file reader behind read_mesh (stl_io.cpp): bounded like the text readers (regular file,
// TextReadOptions::max_bytes), but binary-safe.
#include <panelrad/geometry/mesh_io.hpp>

namespace panelrad::geometry {

TriangleMesh read_stl_file(const std::string& path, std::vector<std::string>* notes, const TextReadOptions& options);

}  // namespace panelrad::geometry

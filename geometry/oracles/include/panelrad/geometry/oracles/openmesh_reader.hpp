#pragma once
// A second, independent mesh reader for cross-checks in the tests: OpenMesh's OFF/OBJ readers.
// Not installed and not part of the package: the library's reader is geometry/mesh_io.hpp.
#include <panelrad/geometry/mesh.hpp>

#include <string>

namespace panelrad::geometry {

/// The same file read by OpenMesh's readers (OpenMesh::IO, double precision), fan-triangulated
/// like read_mesh but without merging vertices: an independent second reader, to cross-check
/// read_mesh on well-formed files. Throws MeshError when OpenMesh cannot read the file or reads
/// no face (its OFF reader takes a file with '#' comment lines for an empty mesh, without error).
TriangleMesh read_mesh_with_openmesh(const std::string& path);

}  // namespace panelrad::geometry

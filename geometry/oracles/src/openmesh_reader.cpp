// A second, independent reader: OpenMesh's OFF/OBJ readers (OpenMesh::IO), for cross-checking
// read_mesh on well-formed files in the tests. Not the main reader: OpenMesh
// drops faces that would make the mesh non-manifold with a message on stderr instead of an error
// and reports no line numbers (see mesh_io.cpp).
#include <panelrad/geometry/oracles/openmesh_reader.hpp>

// g++ 12 -O3 reports -Wmaybe-uninitialized inside OpenMesh's property containers (a false
// positive in its headers, instantiated here); the rest of the project keeps the warning.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <filesystem>

namespace panelrad::geometry {
namespace {
struct DoubleTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;  // (its readers still parse in single precision: see the test)
};
using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<DoubleTraits>;
}  // namespace

TriangleMesh read_mesh_with_openmesh(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw MeshError(path + ": no such file (OpenMesh reader)");
  PolyMesh mesh;
  OpenMesh::IO::Options options;
  if (!OpenMesh::IO::read_mesh(mesh, path, options))
    throw MeshError(path + ": OpenMesh's reader could not read it");
  if (mesh.n_faces() == 0)  // e.g. an OFF with '#' comment lines: OpenMesh reads it as empty, "successfully"
    throw MeshError(path + ": OpenMesh's reader read no faces");
  TriangleMesh out;
  out.source = path;
  out.vertices.reserve(mesh.n_vertices());
  for (const auto vh : mesh.vertices()) {
    const OpenMesh::Vec3d& p = mesh.point(vh);
    out.vertices.emplace_back(p[0], p[1], p[2]);
  }
  Index facet = 0;
  for (const auto fh : mesh.faces()) {  // fan triangulation from the first vertex, as read_mesh
    std::vector<Index> corners;
    for (const auto vh : mesh.fv_range(fh)) corners.push_back(static_cast<Index>(vh.idx()));
    for (std::size_t k = 1; k + 1 < corners.size(); ++k) {
      out.triangles.push_back({corners[0], corners[k], corners[k + 1]});
      out.facet_of_triangle.push_back(facet);
    }
    ++facet;
  }
  out.num_facets = facet;
  return out;
}

}  // namespace panelrad::geometry

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

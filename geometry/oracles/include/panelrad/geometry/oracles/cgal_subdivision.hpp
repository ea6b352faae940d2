#pragma once
// An independent implementation of uniform 4-way midpoint subdivision through CGAL's primal
// triangle quadrisection (CGAL::Subdivision_method_3::PTQ), for cross-checking ClusterTree.
// Plain types only: CGAL stays in geometry/src.
#include <panelrad/geometry/mesh.hpp>

#include <array>
#include <vector>

namespace panelrad::geometry {

/// Triangles of a subdivided mesh, in CGAL's face order (not ClusterTree's numbering).
struct SubdividedTriangles {
  std::vector<std::array<Vec3, 3>> triangle;  ///< corners, in the orientation of the input triangle
  std::vector<Index> facet;                   ///< input facet id per triangle
};

/// The mesh refined `levels` times by CGAL's PTQ with midpoint edge nodes and fixed vertices:
/// an independent implementation of uniform 4-way midpoint subdivision, for cross-checks.
/// Returns the triangles as corner triples (double), each with its input facet id.
/// Each edge node is (p + q) * 0.5 componentwise in double, as ClusterTree computes it; old
/// vertices keep their positions. The facet id of an output triangle is that of the input
/// triangle containing its centroid (in its plane up to 1e-12 of the diameter, barycentric
/// coordinates >= -1e-12; the best such triangle), found by an O(n n0) search: meant for test
/// sizes. Throws MeshError when levels < 0, when n0 4^levels would overflow Index, when the
/// mesh is not a closed 2-manifold triangle mesh (bad index, CGAL refuses a face) or when a
/// triangle cannot be located.
SubdividedTriangles subdivide_with_cgal(const TriangleMesh& validated_mesh, int levels);

}  // namespace panelrad::geometry

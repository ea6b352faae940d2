#pragma once
// Built-in convex scenes: the paper's cube and a few other solids.
#include <panelrad/geometry/mesh.hpp>

#include <string>

namespace panelrad::geometry {

/// The unit cube [0,1]^3 as 12 triangles, two per square face (6 facets). Each square is split
/// along the diagonal joining its two vertices with odd coordinate sum x+y+z, so the diagonals are
/// the six edges of the tetrahedron (1,0,0),(0,1,0),(0,0,1),(1,1,1). This choice reproduces the
/// paper's Table 1 (section 3, example (31)).
TriangleMesh make_cube();

/// Right prism over a regular k-gon (k >= 3) of circumradius r and height h, axis z, base at z=0.
/// Caps are fan-triangulated (k-2 triangles each), each rectangular side split in two.
/// Facets: k sides, then bottom cap, then top cap.
TriangleMesh make_prism(int k, double circumradius = 1.0, double height = 1.0);

/// Regular tetrahedron (1,0,0),(0,1,0),(0,0,1),(1,1,1) and octahedron (+-1,0,0),(0,+-1,0),(0,0,+-1),
/// both with edge length sqrt(2); one facet per triangle.
TriangleMesh make_tetrahedron();
TriangleMesh make_octahedron();

/// The icosahedron inscribed in the unit sphere, each triangle split into four by its edge
/// midpoints `subdivisions` times (0..8) and the new vertices pushed onto the sphere: 20 4^S
/// triangles, counter-clockwise seen from outside, one facet each.
TriangleMesh make_icosphere(int subdivisions);

/// By name: "cube", "prism:K" (circumradius 1, height 1), "tetrahedron", "octahedron".
/// Throws MeshError for an unknown name or a bad K.
TriangleMesh make_builtin(const std::string& spec);

}  // namespace panelrad::geometry

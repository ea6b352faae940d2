#pragma once
// Plain mesh types shared by every layer. No CGAL here: geometry/src is the only place CGAL lives.
#include <panelrad/support/error.hpp>

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace panelrad::geometry {

using Vec3 = Eigen::Vector3d;
using Index = std::int32_t;

/// A polyhedral surface as triangles over shared vertices. Every triangle remembers the input
/// facet (maximal planar polygon of the input: an OFF/OBJ face, or a square of the cube) it came
/// from, so that reflectivity and emissivity can be given per facet.
/// After validate_closed_convex() succeeds, every triangle is oriented counter-clockwise seen from
/// outside (outward geometric normal); the paper's inner normal n is its negative.
struct TriangleMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<Index, 3>> triangles;  ///< vertex indices
  std::vector<Index> facet_of_triangle;         ///< input facet id per triangle, in [0, num_facets)
  Index num_facets = 0;
  std::string source;                           ///< file name or built-in name, for messages
  /// Per facet, the 1-based line of the file where its face is written (read_mesh); empty for
  /// meshes built in code. Messages name facet f as "input face f (line L)".
  std::vector<long> facet_line;
  /// Per facet, the name of the object it belongs to as the file says (OBJ: the `o` or `g`
  /// statement in force, "" before any; STL: its `solid`); empty when the file names none.
  std::vector<std::string> facet_group;
};

/// Any problem with mesh input or geometry: the message names what, where and which rule.
class MeshError : public Error {
 public:
  using Error::Error;
};

/// Surface area (sum of triangle areas, double precision).
double surface_area(const TriangleMesh& mesh);

}  // namespace panelrad::geometry

#include <panelrad/geometry/mesh.hpp>

#include <Eigen/Geometry>

#include <Eigen/Geometry>  // cross()

namespace panelrad::geometry {

double surface_area(const TriangleMesh& mesh) {
  double area = 0;
  for (const auto& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    area += 0.5 * (b - a).cross(c - a).norm();
  }
  return area;
}

}  // namespace panelrad::geometry

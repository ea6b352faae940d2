#pragma once
// Elements of the unit cube [0, 1]^3 for tests of the output writers: each face an m x m grid of
// squares cut into two triangles, each triangle counter-clockwise seen from outside (its
// geometric normal is the face's outward normal).
#include <Eigen/Core>

#include <array>

namespace panelrad::testing {

/// Calls add(facet, outward, triangle) for every triangle; facet 2 a + s is the face x_a = s.
template <class Add>
void for_each_unit_cube_triangle(int m, Add&& add) {
  using Vec3 = Eigen::Vector3d;
  for (int facet = 0; facet < 6; ++facet) {
    const int axis = facet / 2;
    const double side = facet % 2;
    Vec3 outward = Vec3::Zero();
    outward[axis] = side == 0 ? -1.0 : 1.0;
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    const auto corner = [&](int i, int j) {
      Vec3 p;
      p[axis] = side;
      p[a1] = static_cast<double>(i) / m;
      p[a2] = static_cast<double>(j) / m;
      return p;
    };
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j) {
        const Vec3 q[4] = {corner(i, j), corner(i + 1, j), corner(i + 1, j + 1), corner(i, j + 1)};
        for (std::array<Vec3, 3> t : {std::array<Vec3, 3>{q[0], q[1], q[2]}, std::array<Vec3, 3>{q[0], q[2], q[3]}}) {
          if ((t[1] - t[0]).cross(t[2] - t[0]).dot(outward) < 0) std::swap(t[1], t[2]);
          add(facet, outward, t);
        }
      }
  }
}

}  // namespace panelrad::testing

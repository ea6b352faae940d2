#pragma once
// The solution of a scene on its elements: what the output writers (io/scene_output.hpp) need.
#include <panelrad/geometry/mesh.hpp>

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace panelrad {

/// The solved field on the elements (finest-level triangles), C channels.
struct ElementField {
  std::vector<std::array<geometry::Vec3, 3>> triangle;  ///< element corners, counter-clockwise
                                                        ///< seen from outside
  std::vector<geometry::Vec3> inner_normal;             ///< n of (2), into the solid
  std::vector<geometry::Vec3> centroid;                 ///< collocation point P_i, (22)
  std::vector<double> area;
  std::vector<geometry::Index> facet;                   ///< input facet of each element
  std::vector<std::string> channels;                    ///< channel names, e.g. R, G, B
  std::vector<Eigen::VectorXd> rho, emission, radiosity;  ///< [channel](element)
  std::size_t size() const { return triangle.size(); }
};

}  // namespace panelrad

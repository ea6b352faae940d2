#pragma once
// The configuration of the near-singular kernel integrals of the quadrature tests: the triangle
// (a, b, c) in the plane z = 0 with inner normal +z, and collocation points P on a neighbouring
// facet through its edge a-b (the x axis), as on the cube's edges at 90 degrees.
#include <panelrad/quadrature/singular_integration.hpp>

#include <cmath>
#include <numbers>

namespace panelrad::testing {

using quadrature::Vec3;

inline const Vec3 kEdgeA(0, 0, 0), kEdgeB(1, 0, 0), kApexC(0, 1, 0), kTriangleNormal(0, 0, 1);

/// P on the neighbouring facet at dihedral angle alpha (degrees): the facet spans direction
/// d = (0, cos alpha, sin alpha) from the edge; its inner normal points into the wedge between
/// the two facets. P = (x, 0, 0) + dist d.
struct Neighbour {
  Vec3 P, nP;
};
inline Neighbour neighbour_point(double alpha_deg, double x, double dist) {
  const double al = alpha_deg * std::numbers::pi / 180;
  const Vec3 d(0, std::cos(al), std::sin(al));
  return {Vec3(x, 0, 0) + dist * d, Vec3(0, std::sin(al), -std::cos(al))};
}

/// The short names of the tests of this configuration (`using namespace` it at file scope):
/// the triangle (a, b, c) with inner normal nQ = +z, pi, and the neighbouring points.
namespace edge_triangle {
inline const Vec3& a = kEdgeA;
inline const Vec3& b = kEdgeB;
inline const Vec3& c = kApexC;
inline const Vec3& nQ = kTriangleNormal;
inline constexpr double kPi = std::numbers::pi;
using testing::Neighbour;
using testing::neighbour_point;
}  // namespace edge_triangle

}  // namespace panelrad::testing

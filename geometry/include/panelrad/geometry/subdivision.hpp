#pragma once
// Uniform 4-way midpoint subdivision of a triangle (section 4, (39)-(40)): the corners and the
// three edge midpoints give four congruent children, each similar to the parent with ratio 1/2.
#include <panelrad/geometry/mesh.hpp>

#include <array>

namespace panelrad::geometry {

/// Edge midpoint (p + q) / 2, computed as (p + q) * 0.5 componentwise in double: symmetric in p,
/// q (addition commutes exactly), so the triangles on both sides of an edge share it bit for bit.
inline Vec3 midpoint(const Vec3& p, const Vec3& q) { return (p + q) * 0.5; }

/// The four children of (a, b, c) with ab, bc, ca the edge midpoints, in the cluster tree's order
/// (children 4k .. 4k+3 of triangle k): (a, ab, ca), (ab, b, bc), (ca, bc, c) at the corners,
/// then the middle one (ab, bc, ca). All keep the parent's orientation.
inline std::array<std::array<Vec3, 3>, 4> midpoint_subdivision(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
  return {{{a, ab, ca}, {ab, b, bc}, {ca, bc, c}, {ab, bc, ca}}};
}

}  // namespace panelrad::geometry

#pragma once
// The diagonal of the axis-aligned bounding box of a point set, the diameter that scales the mesh
// size h (section 3) and the convexity violations: at least the set's diameter and at most sqrt(3)
// times it.
#include <panelrad/geometry/mesh.hpp>


namespace panelrad::geometry {

/// |v| computed as 2^e |2^-e v|, 2^e the power of two of v's largest component (an exact scaling),
/// so that the squares neither overflow nor underflow; 0 for v = 0, v.norm() (inf or NaN) for a
/// non-finite v. Equal to v.norm() bit for bit when every nonzero component lies in
/// [2^-511, 2^511) and within a factor 2^510 of the largest: then every square and partial sum of
/// the one is the exact power-of-two scaling of the other's (all in the normal double range), and
/// so are their correctly rounded square roots.
double overflow_free_length(const Vec3& v);

/// The diagonal |hi - lo| (overflow_free_length) of the bounding box [lo, hi] of the points,
/// lo and hi their componentwise minimum and maximum; 0 for no points. `points`: any container
/// of Vec3 that a range-for can traverse.
template <class Points>
double bounding_box_diameter(const Points& points) {
  bool first = true;
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
  for (const Vec3& v : points) {
    if (first) {
      lo = hi = v;
      first = false;
    }
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  return first ? 0.0 : overflow_free_length(hi - lo);
}

}  // namespace panelrad::geometry

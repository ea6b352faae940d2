#include <panelrad/geometry/bounding_box.hpp>

#include <cmath>

namespace panelrad::geometry {

double overflow_free_length(const Vec3& v) {
  if (!v.allFinite()) return v.norm();
  if ((v.array() == 0.0).all()) return 0;
  const int e = std::ilogb(v.cwiseAbs().maxCoeff());
  const Vec3 s(std::ldexp(v.x(), -e), std::ldexp(v.y(), -e), std::ldexp(v.z(), -e));
  return std::ldexp(s.norm(), e);
}

}  // namespace panelrad::geometry

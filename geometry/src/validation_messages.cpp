// How validate_closed_convex names what it refuses: vertices and triangles with their indices and
// coordinates (shortest round-trip decimals, so that a reader can find them in the file), lengths
// in scientific notation.
#include "validation_internal.hpp"

#include <charconv>
#include <limits>
#include <sstream>

namespace panelrad::geometry::validation_detail {

std::string num(double x) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, x);  // shortest round-trip form
  return std::string(buf, res.ptr);
}

std::string sci(double x) {
  std::ostringstream os;
  os.precision(2);
  os << std::scientific << x;
  return os.str();
}

std::string relative(double dist, double diam) {
  if (!(diam > 0)) return "n/a";
  const double r = dist / diam;
  return r > 0 ? sci(r) : "< " + sci(std::numeric_limits<double>::denorm_min());
}

std::string Describe::point(Index v) const {
  const Vec3& p = mesh.vertices[at(v)];
  std::string s(1, '(');  // appended piecewise: GCC 12 warns falsely (-Wrestrict) on "(" + string
  s.append(num(p.x())).append(", ").append(num(p.y())).append(", ").append(num(p.z())).append(")");
  return s;
}

std::string Describe::vertex(Index v) const { return "vertex " + std::to_string(v) + " " + point(v); }

std::string Describe::triangle(Index t) const {
  const Tri& tr = mesh.triangles[at(t)];
  return "triangle " + std::to_string(t) + " (input face " + std::to_string(mesh.facet_of_triangle[at(t)]) +
         "; vertices " + std::to_string(tr[0]) + " " + point(tr[0]) + ", " + std::to_string(tr[1]) + " " +
         point(tr[1]) + ", " + std::to_string(tr[2]) + " " + point(tr[2]) + ")";
}

}  // namespace panelrad::geometry::validation_detail

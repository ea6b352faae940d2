// How validate_closed_convex names what it refuses: vertices and triangles with their indices and
// coordinates (shortest round-trip decimals, so that a reader can find them in the file), the input
// face of a triangle as the mesh reader names it ("input face F (line L)", F counted from 0), lengths
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

std::string point_text(const Vec3& x) {
  std::string s(1, '(');
  s.append(num(x.x())).append(", ").append(num(x.y())).append(", ").append(num(x.z())).append(")");
  return s;
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

namespace {

/// "input face F (line L)": F the 0-based facet id, L its line in the file when the mesh was read
/// from one (facet_line has an entry per facet), as the mesh reader names faces.
std::string input_face(const TriangleMesh& mesh, Index f) {
  std::string s = "input face " + std::to_string(f);
  if (f >= 0 && mesh.facet_line.size() == at(mesh.num_facets) && at(f) < mesh.facet_line.size())
    s.append(" (line ").append(std::to_string(mesh.facet_line[at(f)])).append(")");
  return s;
}

}  // namespace

std::string Describe::face(Index f) const { return input_face(mesh, f); }

std::string Describe::faces(Index f, Index g) const {
  const std::string second = input_face(mesh, g);
  return "input faces " + input_face(mesh, f).substr(11) + " and " + second.substr(11);  // past "input face "
}

std::string Describe::triangle(Index t) const {
  const Tri& tr = mesh.triangles[at(t)];
  return "triangle " + std::to_string(t) + " (" + input_face(mesh, mesh.facet_of_triangle[at(t)]) +
         "; vertices " + std::to_string(tr[0]) + " " + point(tr[0]) + ", " + std::to_string(tr[1]) + " " +
         point(tr[1]) + ", " + std::to_string(tr[2]) + " " + point(tr[2]) + ")";
}

}  // namespace panelrad::geometry::validation_detail

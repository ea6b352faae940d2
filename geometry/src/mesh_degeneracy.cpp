// Rules "structure", "non-empty", "finite" and "non-degenerate" of validate_closed_convex: indices
// in range, finite coordinates within the range double-precision geometry can measure, no
// zero-area triangle (exact collinearity), and an enclosed volume (exact sign).
#include "validation_internal.hpp"

#include <CGAL/Exact_rational.h>

#include <limits>

namespace panelrad::geometry::validation_detail {

namespace {

/// Structure (a mesh built in code can be inconsistent; files never are after read_mesh).
std::optional<Failure> check_structure(const TriangleMesh& mesh) {
  const Sz nv = mesh.vertices.size();
  const Sz nt = mesh.triangles.size();
  if (mesh.facet_of_triangle.size() != nt)
    return Failure{"structure", "facet_of_triangle has " + std::to_string(mesh.facet_of_triangle.size()) +
                                    " entries for " + std::to_string(nt) + " triangles"};
  for (Sz t = 0; t < nt; ++t) {
    for (Index v : mesh.triangles[t])
      if (v < 0 || at(v) >= nv)
        return Failure{"structure", "triangle " + std::to_string(t) + " refers to vertex " + std::to_string(v) +
                                        " but the mesh has " + std::to_string(nv) + " vertices"};
    const Index f = mesh.facet_of_triangle[t];
    if (f < 0 || f >= mesh.num_facets)
      return Failure{"structure", "triangle " + std::to_string(t) + " has facet id " + std::to_string(f) +
                                      " outside [0, " + std::to_string(mesh.num_facets) + ")"};
  }
  return std::nullopt;
}

}  // namespace

std::optional<Failure> check_well_formed(const TriangleMesh& mesh) {
  if (auto f = check_structure(mesh)) return f;
  // Rule 1: non-empty.
  if (mesh.vertices.empty() || mesh.triangles.empty()) return Failure{"non-empty", "the mesh has no triangles"};
  // Rule 2: finite coordinates.
  const Describe d{mesh};
  for (Sz v = 0; v < mesh.vertices.size(); ++v)
    if (!mesh.vertices[v].allFinite())
      return Failure{"finite", d.vertex(static_cast<Index>(v)) + " has a non-finite coordinate"};
  return std::nullopt;
}

std::optional<Failure> check_measurable(const TriangleMesh& mesh, const std::vector<Point>& pts) {
  const Describe d{mesh};
  const Sz nv = mesh.vertices.size();
  const Sz nt = mesh.triangles.size();
  // Rule 3: no zero-area triangle (exact collinearity; also catches a repeated vertex).
  for (Sz t = 0; t < nt; ++t) {
    const Tri& tr = mesh.triangles[t];
    if (CGAL::collinear(pts[at(tr[0])], pts[at(tr[1])], pts[at(tr[2])]))
      return Failure{"non-degenerate", d.triangle(static_cast<Index>(t)) + " has zero area (collinear vertices)"};
  }
  // Rule 2 continued: the exact predicates accept any finite doubles, but areas, normals and
  // distances are computed in double precision (products of two coordinates, squared): lengths from
  // 1e-75 to 1e75 keep those squares inside the double range (1e-308 .. 1e308). 1e308 coordinates
  // gave area NaN and an interior point at infinity, 1e-300 ones area 0. Found by fuzz/.
  for (Sz v = 0; v < nv; ++v)
    if (mesh.vertices[v].cwiseAbs().maxCoeff() > 1e75)
      return Failure{"finite", d.vertex(static_cast<Index>(v)) +
                                   " is beyond 1e75, outside the range double-precision geometry can measure"};
  for (Sz t = 0; t < nt; ++t) {
    const Tri& tr = mesh.triangles[t];
    const Vec3& a = mesh.vertices[at(tr[0])];
    const double area = 0.5 * (mesh.vertices[at(tr[1])] - a).cross(mesh.vertices[at(tr[2])] - a).stableNorm();
    if (!(area >= 1e-150))
      return Failure{"finite", d.triangle(static_cast<Index>(t)) +
                                   " is below 1e-150 in area, too small for double-precision geometry; rescale the mesh"};
  }
  return std::nullopt;
}

std::optional<std::array<Index, 4>> spanning_tetrahedron(const std::vector<Point>& p) {
  const Sz n = p.size();
  std::array<Index, 4> w{0, kNone, kNone, kNone};
  Sz i = 1;
  for (; i < n && w[1] == kNone; ++i)
    if (p[i] != p[0]) w[1] = static_cast<Index>(i);
  for (; i < n && w[2] == kNone; ++i)
    if (!CGAL::collinear(p[0], p[at(w[1])], p[i])) w[2] = static_cast<Index>(i);
  for (; i < n && w[3] == kNone; ++i)
    if (CGAL::orientation(p[0], p[at(w[1])], p[at(w[2])], p[i]) != CGAL::COPLANAR) w[3] = static_cast<Index>(i);
  if (w[3] == kNone) return std::nullopt;
  return w;
}

/// Double sum with a rigorous error bound; exact rational arithmetic only when the bound does not
/// decide the sign.
int volume_sign(const TriangleMesh& mesh, const Vec3& origin) {
  double sum = 0, magnitude = 0;
  for (const Tri& tr : mesh.triangles) {
    const Vec3 a = mesh.vertices[at(tr[0])] - origin, b = mesh.vertices[at(tr[1])] - origin,
               c = mesh.vertices[at(tr[2])] - origin;
    sum += a.dot(b.cross(c));
    magnitude += a.lpNorm<1>() * b.lpNorm<1>() * c.lpNorm<1>();
  }
  // Each term has relative error below 8 eps of its magnitude bound (three rounded differences, two
  // products and sums per term), and the sum adds at most n eps of the total: 16 + n is generous.
  const double eps = std::numeric_limits<double>::epsilon();
  const double bound = (16.0 + static_cast<double>(mesh.triangles.size())) * eps * magnitude;
  if (sum > bound) return 1;
  if (sum < -bound) return -1;
  using Q = CGAL::Exact_rational;
  Q exact(0);
  const Q ox(origin.x()), oy(origin.y()), oz(origin.z());
  for (const Tri& tr : mesh.triangles) {
    std::array<std::array<Q, 3>, 3> m;
    for (int r = 0; r < 3; ++r) {
      const Vec3& p = mesh.vertices[at(tr[at(r)])];
      m[at(r)] = {Q(p.x()) - ox, Q(p.y()) - oy, Q(p.z()) - oz};
    }
    exact += m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
             m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  }
  return CGAL::sign(exact);
}

}  // namespace panelrad::geometry::validation_detail

// Uniform 4-way midpoint subdivision through CGAL's PTQ refinement host with a custom geometry
// mask (a model of PTQMask_3: edge_node, vertex_node, border_node), as an independent check of
// ClusterTree. The refinement's connectivity (which vertices are joined, hence which four
// triangles replace one) is entirely CGAL's; only the positions of the nodes come from the mask.
#include <panelrad/geometry/oracles/cgal_subdivision.hpp>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/subdivision_method_3.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

namespace panelrad::geometry {

namespace {

using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using SurfaceMesh = CGAL::Surface_mesh<Point>;

/// PTQ geometry mask of plain midpoint subdivision: an edge node is the edge midpoint
/// (p + q) * 0.5 (componentwise in double, symmetric in p, q: the formula of ClusterTree), a
/// vertex node is the vertex itself. Border nodes (never met on a closed mesh) do the same.
class MidpointMask {
 public:
  using halfedge_descriptor = boost::graph_traits<SurfaceMesh>::halfedge_descriptor;
  using vertex_descriptor = boost::graph_traits<SurfaceMesh>::vertex_descriptor;

  explicit MidpointMask(const SurfaceMesh* mesh) : mesh_(mesh) {}

  void edge_node(halfedge_descriptor h, Point& pt) const {
    const Point& p = mesh_->point(mesh_->source(h));
    const Point& q = mesh_->point(mesh_->target(h));
    pt = Point((p.x() + q.x()) * 0.5, (p.y() + q.y()) * 0.5, (p.z() + q.z()) * 0.5);
  }
  void vertex_node(vertex_descriptor v, Point& pt) const { pt = mesh_->point(v); }
  void border_node(halfedge_descriptor h, Point& ept, Point& vpt) const {
    edge_node(h, ept);
    vpt = mesh_->point(mesh_->target(h));
  }

 private:
  const SurfaceMesh* mesh_;
};

Vec3 to_vec(const Point& p) { return Vec3(p.x(), p.y(), p.z()); }

/// An input triangle prepared for locating points: corner a, edges u = b - a, v = c - a, unit
/// normal, and the Gram matrix inverse for barycentric coordinates.
struct Root {
  Vec3 a, u, v, unit_normal;
  double uu = 0, uv = 0, vv = 0, det = 0;
  Index facet = 0;
};

}  // namespace

SubdividedTriangles subdivide_with_cgal(const TriangleMesh& mesh, int levels) {
  const std::string name = mesh.source.empty() ? std::string("mesh") : "mesh '" + mesh.source + "'";
  if (levels < 0)
    throw MeshError("CGAL subdivision of " + name + ": level " + std::to_string(levels) + " is negative");
  if (mesh.triangles.empty()) throw MeshError("CGAL subdivision of " + name + ": the mesh has no triangles");
  if (mesh.facet_of_triangle.size() != mesh.triangles.size())
    throw MeshError("CGAL subdivision of " + name + ": facet ids do not match the triangles");
  const long double n_out = std::ldexp(static_cast<long double>(mesh.triangles.size()), 2 * std::min(levels, 40));
  if (n_out > static_cast<long double>(std::numeric_limits<Index>::max()))
    throw MeshError("CGAL subdivision of " + name + ": level " + std::to_string(levels) +
                    " gives more triangles than 32-bit indices allow");

  // --- input as a CGAL Surface_mesh ----------------------------------------------------------------
  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> vid;
  vid.reserve(mesh.vertices.size());
  for (const Vec3& p : mesh.vertices) vid.push_back(sm.add_vertex(Point(p.x(), p.y(), p.z())));
  for (std::size_t k = 0; k < mesh.triangles.size(); ++k) {
    const auto& t = mesh.triangles[k];
    for (Index v : t)
      if (v < 0 || static_cast<std::size_t>(v) >= mesh.vertices.size())
        throw MeshError("CGAL subdivision of " + name + ": triangle " + std::to_string(k) + " uses vertex " +
                        std::to_string(v) + ", outside the vertex list");
    const auto f = sm.add_face(vid[static_cast<std::size_t>(t[0])], vid[static_cast<std::size_t>(t[1])],
                               vid[static_cast<std::size_t>(t[2])]);
    if (f == SurfaceMesh::null_face())
      throw MeshError("CGAL subdivision of " + name + ": Surface_mesh refuses triangle " + std::to_string(k) +
                      " (not a consistently oriented 2-manifold)");
  }
  if (!CGAL::is_closed(sm))
    throw MeshError("CGAL subdivision of " + name + ": the mesh is not closed");

  // --- refinement --------------------------------------------------------------------------------
  if (levels > 0)
    CGAL::Subdivision_method_3::PTQ(sm, MidpointMask(&sm),
                                    CGAL::parameters::number_of_iterations(static_cast<unsigned>(levels)));

  // --- input triangles for locating centroids ----------------------------------------------------
  std::vector<Root> roots(mesh.triangles.size());
  Vec3 lo = mesh.vertices.front(), hi = lo;
  for (const Vec3& p : mesh.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double diameter = (hi - lo).norm();
  for (std::size_t k = 0; k < roots.size(); ++k) {
    const auto& t = mesh.triangles[k];
    Root& r = roots[k];
    r.a = mesh.vertices[static_cast<std::size_t>(t[0])];
    r.u = mesh.vertices[static_cast<std::size_t>(t[1])] - r.a;
    r.v = mesh.vertices[static_cast<std::size_t>(t[2])] - r.a;
    r.unit_normal = r.u.cross(r.v).normalized();
    r.uu = r.u.dot(r.u);
    r.uv = r.u.dot(r.v);
    r.vv = r.v.dot(r.v);
    r.det = r.uu * r.vv - r.uv * r.uv;
    r.facet = mesh.facet_of_triangle[k];
    if (!(r.det > 0) || !r.unit_normal.allFinite())
      throw MeshError("CGAL subdivision of " + name + ": triangle " + std::to_string(k) + " is degenerate");
  }

  // --- output: corners, and the facet of the input triangle holding each centroid ----------------
  constexpr double plane_tol = 1e-12, bary_tol = 1e-12;
  SubdividedTriangles out;
  out.triangle.reserve(sm.number_of_faces());
  out.facet.reserve(sm.number_of_faces());
  for (const auto f : sm.faces()) {
    std::array<Vec3, 3> corners;
    std::size_t i = 0;
    for (const auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      if (i == 3) throw MeshError("CGAL subdivision of " + name + ": PTQ produced a face that is not a triangle");
      corners[i++] = to_vec(sm.point(v));
    }
    if (i != 3) throw MeshError("CGAL subdivision of " + name + ": PTQ produced a face that is not a triangle");
    const Vec3 g = (corners[0] + corners[1] + corners[2]) / 3.0;
    double best = -std::numeric_limits<double>::infinity();
    Index best_facet = -1;
    for (const Root& r : roots) {
      const Vec3 d = g - r.a;
      if (std::abs(d.dot(r.unit_normal)) > plane_tol * diameter) continue;
      const double du = d.dot(r.u), dv = d.dot(r.v);
      const double s = (r.vv * du - r.uv * dv) / r.det, t = (r.uu * dv - r.uv * du) / r.det;
      const double worst = std::min({1.0 - s - t, s, t});
      if (worst > best) {
        best = worst;
        best_facet = r.facet;
      }
    }
    if (best_facet < 0 || best < -bary_tol)
      throw MeshError("CGAL subdivision of " + name + ": subdivided triangle " + std::to_string(out.facet.size()) +
                      " lies in no input triangle");
    out.triangle.push_back(corners);
    out.facet.push_back(best_facet);
  }
  return out;
}

}  // namespace panelrad::geometry

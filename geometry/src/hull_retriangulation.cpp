// Step 1 of the convexity rule of validate_closed_convex: polygon faces whose rounded vertices are
// not exactly coplanar get a fan triangulation that is not exactly convex. CGAL's convex_hull_3
// (exact predicates) *proposes* a re-triangulation from the exact convex hull; the proposal is then
// proven closed and convex exactly like any input, so nothing rests on the hull code alone.
#include "validation_internal.hpp"

#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <utility>
#include <variant>

namespace panelrad::geometry::validation_detail {

namespace {

/// The exact convex hull of the vertices, as mesh vertex indices.
struct Hull {
  std::vector<Tri> triangles;
  std::vector<char> is_vertex;          // per mesh vertex
  std::vector<Index> offsets, facets;   // CSR: hull triangles incident to each mesh vertex
  Sz num_vertices = 0;
};

Hull exact_hull(const TriangleMesh& mesh, const std::vector<Point>& pts) {
  // The Surface_mesh overload picks CGAL's default hull traits for Epick (planes kept as point
  // triples, exact predicates). Note: the indexed-output overload passes the bare kernel as traits
  // and then constructs planes in double; it was seen to drop extreme points of thin inputs.
  CGAL::Surface_mesh<Point> sm;
  CGAL::convex_hull_3(pts.begin(), pts.end(), sm);
  std::vector<Point> hv;
  std::vector<std::array<Sz, 3>> hf;
  for (const auto v : sm.vertices()) hv.push_back(sm.point(v));
  for (const auto f : sm.faces()) {
    std::array<Sz, 3> tri{};
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(sm.halfedge(f), sm)) {
      if (k == 3) throw MeshError("internal error: convex hull face is not a triangle");
      tri[at(k++)] = static_cast<Sz>(v.idx());
    }
    if (k != 3) throw MeshError("internal error: convex hull face is not a triangle");
    hf.push_back(tri);
  }
  std::map<std::array<double, 3>, Index> index_of;  // vertices are pairwise distinct here
  for (Sz v = 0; v < mesh.vertices.size(); ++v) {
    const Vec3& p = mesh.vertices[v];
    index_of.emplace(std::array<double, 3>{p.x(), p.y(), p.z()}, static_cast<Index>(v));
  }
  Hull hull;
  hull.is_vertex.assign(mesh.vertices.size(), 0);
  std::vector<Index> mesh_id(hv.size(), kNone);
  for (Sz i = 0; i < hv.size(); ++i) {
    const auto it = index_of.find({hv[i].x(), hv[i].y(), hv[i].z()});
    if (it == index_of.end()) throw MeshError("internal error: convex hull vertex not found among the input vertices");
    mesh_id[i] = it->second;
    hull.is_vertex[at(it->second)] = 1;
  }
  hull.num_vertices = hv.size();
  for (const auto& f : hf) hull.triangles.push_back({mesh_id[f[0]], mesh_id[f[1]], mesh_id[f[2]]});
  hull.offsets.assign(mesh.vertices.size() + 1, 0);
  for (const Tri& f : hull.triangles)
    for (Index v : f) ++hull.offsets[at(v) + 1];
  std::partial_sum(hull.offsets.begin(), hull.offsets.end(), hull.offsets.begin());
  hull.facets.resize(at(hull.offsets.back()));
  std::vector<Index> fill(hull.offsets.begin(), hull.offsets.end() - 1);
  for (Sz f = 0; f < hull.triangles.size(); ++f)
    for (Index v : hull.triangles[f]) hull.facets[at(fill[at(v)]++)] = static_cast<Index>(f);
  return hull;
}

/// Largest distance of a vertex of a triangle's own input face outside that triangle's plane, over
/// the triangles `bad` (the non-planarity of rounded polygon faces).
double worst_within_faces(const TriangleMesh& mesh, const std::vector<Index>& bad, const Geometry& g) {
  std::vector<std::vector<Index>> face_vertices(at(mesh.num_facets));
  for (Sz t = 0; t < mesh.triangles.size(); ++t)
    for (Index v : mesh.triangles[t]) face_vertices[at(mesh.facet_of_triangle[t])].push_back(v);
  double worst = 0;
  for (Index t : bad) {
    const Tri& tr = mesh.triangles[at(t)];
    for (Index v : face_vertices[at(mesh.facet_of_triangle[at(t)])])
      if (g.side(tr, v) == CGAL::POSITIVE)
        worst = std::max(worst, plane_distance(mesh.vertices[at(tr[0])], mesh.vertices[at(tr[1])],
                                               mesh.vertices[at(tr[2])], mesh.vertices[at(v)]));
  }
  return worst;
}

/// The vertices of each input face (sorted, distinct), and the input faces of each vertex.
struct FaceVertices {
  std::vector<std::vector<Index>> of_face;
  std::vector<std::vector<Index>> faces_of_vertex;
};

FaceVertices vertices_of_faces(const TriangleMesh& mesh) {
  FaceVertices fv;
  fv.of_face.resize(at(mesh.num_facets));
  for (Sz t = 0; t < mesh.triangles.size(); ++t)
    for (Index v : mesh.triangles[t]) fv.of_face[at(mesh.facet_of_triangle[t])].push_back(v);
  fv.faces_of_vertex.resize(mesh.vertices.size());
  for (Sz f = 0; f < fv.of_face.size(); ++f) {
    auto& vs = fv.of_face[f];
    std::sort(vs.begin(), vs.end());
    vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
    for (Index v : vs) fv.faces_of_vertex[at(v)].push_back(static_cast<Index>(f));
  }
  return fv;
}

/// Per input face, its triangles as sorted vertex triples, in sorted order: equal for two
/// triangulations of a face exactly when they are the same triangulation.
std::vector<std::vector<Tri>> triangles_of_faces(const TriangleMesh& mesh) {
  std::vector<std::vector<Tri>> tris(at(mesh.num_facets));
  for (Sz t = 0; t < mesh.triangles.size(); ++t) {
    Tri s = mesh.triangles[t];
    std::sort(s.begin(), s.end());
    tris[at(mesh.facet_of_triangle[t])].push_back(s);
  }
  for (auto& f : tris) std::sort(f.begin(), f.end());
  return tris;
}

/// Each hull triangle with the input face whose vertices it lies on, oriented outward and ordered
/// by face (stable: in hull order within a face); or why there is no such assignment: a hull
/// triangle joins vertices of different faces, or a face with k vertices does not get k - 2.
std::variant<std::vector<std::pair<Index, Tri>>, std::string> hull_triangles_by_face(const TriangleMesh& mesh,
                                                                                     const Hull& hull,
                                                                                     const Geometry& g,
                                                                                     const FaceVertices& fv) {
  const Describe d{mesh};
  const Sz nf = fv.of_face.size();
  std::vector<std::pair<Index, Tri>> out;
  std::vector<Index> count(nf, 0);
  for (Tri h : hull.triangles) {
    Index facet = kNone;
    for (Index f : fv.faces_of_vertex[at(h[0])]) {
      const auto& vs = fv.of_face[at(f)];
      if (std::binary_search(vs.begin(), vs.end(), h[1]) && std::binary_search(vs.begin(), vs.end(), h[2])) {
        facet = f;
        break;
      }
    }
    if (facet == kNone)
      return "the hull triangle on " + d.vertex(h[0]) + ", " + d.vertex(h[1]) + " and " + d.vertex(h[2]) +
             " joins vertices of different input faces";
    if (g.facing(h) == CGAL::POSITIVE) std::swap(h[1], h[2]);  // outward
    ++count[at(facet)];
    out.emplace_back(facet, h);
  }
  for (Sz f = 0; f < nf; ++f)
    if (fv.of_face[f].size() < 3 || at(count[f]) != fv.of_face[f].size() - 2)
      return "input face " + std::to_string(f) + " with " + std::to_string(fv.of_face[f].size()) +
             " vertices gets " + std::to_string(count[f]) + " hull triangles";
  std::stable_sort(out.begin(), out.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  return out;
}

/// Replace the triangulation of every polygonal input face by the exact hull's when the
/// hull has exactly the input's vertices and each hull triangle lies on the vertices of one input
/// face. Returns the number of faces whose triangulation changed, or a reason why not.
std::variant<Sz, std::string> retriangulate_from_hull(TriangleMesh& mesh, const Hull& hull, const Geometry& g) {
  const Describe d{mesh};
  if (hull.num_vertices != mesh.vertices.size()) {
    for (Sz v = 0; v < mesh.vertices.size(); ++v)
      if (!hull.is_vertex[v])
        return d.vertex(static_cast<Index>(v)) + " is not a vertex of the exact convex hull";
  }
  auto by_face = hull_triangles_by_face(mesh, hull, g, vertices_of_faces(mesh));
  if (const auto* why = std::get_if<std::string>(&by_face)) return *why;
  const std::vector<std::vector<Tri>> old_tris = triangles_of_faces(mesh);
  mesh.triangles.clear();
  mesh.facet_of_triangle.clear();
  for (const auto& [f, h] : std::get<std::vector<std::pair<Index, Tri>>>(by_face)) {
    mesh.triangles.push_back(h);
    mesh.facet_of_triangle.push_back(f);
  }
  const std::vector<std::vector<Tri>> new_tris = triangles_of_faces(mesh);
  Sz changed = 0;
  for (Sz f = 0; f < old_tris.size(); ++f)
    if (old_tris[f] != new_tris[f]) ++changed;
  return changed;
}

/// Why the hull's triangulation (`candidate`, from `result`) does not prove the mesh convex; empty
/// when it does.
std::string hull_refusal(const std::variant<Sz, std::string>& result, const TriangleMesh& candidate,
                         const Geometry& g, const Vec3& inside) {
  if (std::holds_alternative<std::string>(result))
    return "the exact convex hull cannot replace the triangulation: " + std::get<std::string>(result);
  Adjacency hull_adj;
  if (auto f = build_adjacency(candidate, hull_adj)) return "the hull triangulation is not closed: " + f->message;
  if (!proven_convex(candidate, hull_adj, g, inside) && !unsupported_triangles(candidate, hull_adj, g, inside).empty())
    return "the hull's triangulation is not convex either";
  return {};
}

}  // namespace

std::optional<std::string> retriangulate_convex_from_hull(TriangleMesh& mesh, const std::vector<Point>& pts,
                                                          const std::vector<Index>& bad, const Geometry& g,
                                                          const Vec3& inside, double diam,
                                                          ValidationReport& report) {
  // Propose the exact hull's triangulation (CGAL convex_hull_3), then prove the result closed and
  // convex exactly, as for the input, so that nothing rests on the hull algorithm itself.
  const Hull hull = exact_hull(mesh, pts);
  TriangleMesh candidate = mesh;
  const auto result = retriangulate_from_hull(candidate, hull, g);
  std::string reason = hull_refusal(result, candidate, g, inside);
  if (!reason.empty()) return reason;
  const double before = worst_within_faces(mesh, bad, g) / diam;
  const Sz changed = std::get<Sz>(result);
  mesh = std::move(candidate);
  report.retriangulated_from_hull = true;
  report.notes.push_back("the fan triangulation was not exactly convex (" + sci(before) +
                         " of the diameter before, within its faces: polygon faces with rounded, not exactly "
                         "coplanar vertices); re-triangulated " + std::to_string(changed) +
                         " input faces with the exact convex hull, whose triangles each lie on one input face");
  report.valid = true;
  return std::nullopt;
}

}  // namespace panelrad::geometry::validation_detail

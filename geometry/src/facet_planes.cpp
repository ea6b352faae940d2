// Supporting planes of the facets (planar_facets.hpp): facets whose triangles lie in one plane,
// exactly or within the rounding of the input, share a plane id.
#include "validation_internal.hpp"

#include <panelrad/geometry/planar_facets.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace panelrad::geometry {

using namespace validation_detail;

namespace {

// The plane of a facet's first triangle, for bucketing: unit normal with a canonical sign (its
// largest component positive) and offset n.p, both rounded to a grid of `cell` (relative to the
// diameter for the offset). Coplanar facets have keys within one cell of each other in each of
// the four coordinates (their approximate planes differ by rounding only, far below the cell), so
// the 3^4 neighbouring cells hold every candidate.
struct PlaneKey {
  std::array<std::int64_t, 4> cell;
  bool operator==(const PlaneKey&) const = default;
};
struct PlaneKeyHash {
  std::size_t operator()(const PlaneKey& k) const {
    std::uint64_t h = 0x9e3779b97f4a7c15ULL;
    for (std::int64_t c : k.cell) h = (h ^ static_cast<std::uint64_t>(c)) * 0xbf58476d1ce4e5b9ULL;
    return static_cast<std::size_t>(h ^ (h >> 31));
  }
};

// Bucket size of the keys: far above the difference of two coplanar facets' normals and offsets
// (rounding: at six-digit input ~5e-6 over a triangle's relative size), and small enough that a
// bucket holds few planes on curved meshes (neighbouring facets' normals differ by their angle).
constexpr double kCell = 1e-3;

}  // namespace

std::vector<Index> facet_planes(const TriangleMesh& mesh, PlaneGrouping grouping) {
  const Sz nt = mesh.triangles.size();
  const Sz nf = static_cast<Sz>(std::max<Index>(mesh.num_facets, 0));
  if (mesh.facet_of_triangle.size() != nt) throw MeshError("facet_planes: facet_of_triangle has the wrong size");
  for (const Tri& tr : mesh.triangles)
    for (Index v : tr)
      if (v < 0 || at(v) >= mesh.vertices.size()) throw MeshError("facet_planes: vertex index out of range");
  for (const Vec3& p : mesh.vertices)
    if (!p.allFinite()) throw MeshError("facet_planes: non-finite vertex coordinate");
  std::vector<Index> first(nf, -1);  // a facet's first triangle: its plane's witness
  for (Sz t = 0; t < nt; ++t) {
    const Index f = mesh.facet_of_triangle[t];
    if (f < 0 || at(f) >= nf) throw MeshError("facet_planes: facet id out of range");
    if (first[at(f)] < 0) first[at(f)] = static_cast<Index>(t);
  }
  const double diam = diameter(mesh);
  const double unit = diam > 0 ? diam : 1.0;
  std::optional<InputRounding> rounding;  // computed on the first pair that is not exactly coplanar
  const auto corner = [&](Index t, int k) -> const Vec3& {
    return mesh.vertices[at(mesh.triangles[at(t)][at(k)])];
  };
  const auto point = [&](Index t, int k) {
    const Vec3& v = corner(t, k);
    return Point(v.x(), v.y(), v.z());
  };
  // The geometric normal (b - a) x (c - a) of triangle t with its edges scaled to O(1) first
  // (exactly, by a power of two), so that the cross product neither overflows nor underflows at
  // any coordinate magnitude validation accepts.
  const auto scaled_normal = [&](Index t) {
    Vec3 u = corner(t, 1) - corner(t, 0), v = corner(t, 2) - corner(t, 0);
    const double big = std::max(u.cwiseAbs().maxCoeff(), v.cwiseAbs().maxCoeff());
    if (big > 0 && std::isfinite(big)) {
      const double s = std::ldexp(1.0, -std::ilogb(big));
      u *= s;
      v *= s;
    }
    return Vec3(u.cross(v));
  };
  // The geometric normals of triangles w and g point the same way (both nearly in one plane here,
  // so the sign of their dot product is far from rounding).
  const auto same_orientation = [&](Index w, Index g) { return scaled_normal(w).dot(scaled_normal(g)) > 0; };
  // Facet g's triangle lies in the plane of the witness triangle w: each corner exactly coplanar
  // with w's corners, or, when both face the same way, within bound(w, v) of w's plane and
  // kMaxRoundingViolation of the diameter. Two faces of opposite orientation are joined only when
  // exactly coplanar: across any positive gap they face each other (or turn their backs to each
  // other) and G(P, Q) of (2) is not zero between them.
  const auto in_plane_of = [&](Index w, Index g) {
    const Point a = point(w, 0), b = point(w, 1), c = point(w, 2);
    for (int k = 0; k < 3; ++k) {
      if (CGAL::orientation(a, b, c, point(g, k)) == CGAL::COPLANAR) continue;
      if (grouping == PlaneGrouping::exact || !same_orientation(w, g)) return false;
      if (!rounding) rounding = input_rounding(mesh);
      const Vec3 &va = corner(w, 0), &vb = corner(w, 1), &vc = corner(w, 2), &v = corner(g, k);
      const double d = std::abs(plane_distance(va, vb, vc, v)), bound = rounding_bound(va, vb, vc, v, rounding->per_coordinate);
      if (!(bound >= 0 && d <= bound && d <= kMaxRoundingViolation * diam)) return false;
    }
    return true;
  };
  // Facets joined through planar neighbours (count_planar_facets' classes: adjacent triangles
  // coplanar exactly or within the rounding) are in one plane; their group is named by its
  // smallest facet.
  std::vector<Index> group(nf);
  for (Sz f = 0; f < nf; ++f) group[f] = static_cast<Index>(f);
  const auto find = [&](Index x) {
    while (group[at(x)] != x) x = group[at(x)] = group[at(group[at(x)])];
    return x;
  };
  if (grouping == PlaneGrouping::within_rounding) {
    const std::vector<Index> cls = planar_facet_classes(mesh);
    for (Sz t = 0; t < nt; ++t) {
      const Index a = find(mesh.facet_of_triangle[t]), b = find(mesh.facet_of_triangle[at(cls[t])]);
      if (a != b) group[at(std::max(a, b))] = std::min(a, b);
    }
  }
  // Groups that do not touch: bucketed by the plane of their first facet's first triangle, and
  // joined when that triangle lies in the plane of an earlier group's witness.
  std::unordered_map<PlaneKey, std::vector<Index>, PlaneKeyHash> buckets;  // cell -> plane ids
  std::vector<Index> witness;  // per plane id: the first facet's first triangle
  std::vector<Index> plane(nf, -1);
  for (Sz f = 0; f < nf; ++f) {
    const Index t = first[f];
    if (t < 0) continue;  // a facet id without triangles: no plane (-1)
    if (const Index g = find(static_cast<Index>(f)); g != static_cast<Index>(f)) {
      plane[f] = plane[at(g)];  // joined to a smaller facet through planar neighbours
      continue;
    }
    Vec3 n = scaled_normal(t);
    const double len = n.norm();
    if (!(len > 0) || !std::isfinite(len)) throw MeshError("facet_planes: triangle " + std::to_string(t) + " has no normal");
    n /= len;
    int big = 0;
    n.cwiseAbs().maxCoeff(&big);
    if (n[big] < 0) n = -n;
    const double offset = n.dot(corner(t, 0)) / unit;
    const std::array<double, 4> q = {n.x(), n.y(), n.z(), offset};
    PlaneKey key;
    for (int a = 0; a < 4; ++a) key.cell[at(a)] = static_cast<std::int64_t>(std::floor(q[at(a)] / kCell));
    Index found = -1;
    for (int m = 0; m < 81 && found < 0; ++m) {
      PlaneKey near = key;
      for (int a = 0, r = m; a < 4; ++a, r /= 3) near.cell[at(a)] += r % 3 - 1;
      const auto it = buckets.find(near);
      if (it == buckets.end()) continue;
      for (Index id : it->second)
        if (in_plane_of(witness[at(id)], t)) {
          found = id;
          break;
        }
    }
    if (found < 0) {
      found = static_cast<Index>(witness.size());
      witness.push_back(t);
      buckets[key].push_back(found);
    }
    plane[f] = found;
  }
  return plane;
}

std::vector<Index> triangle_planes(const TriangleMesh& mesh, PlaneGrouping grouping) {
  const std::vector<Index> facet_plane = facet_planes(mesh, grouping);
  const Sz nt = mesh.triangles.size();
  std::vector<Index> plane(nt);
  Index next = 0;
  for (Index p : facet_plane) next = std::max(next, p + 1);
  if (grouping != PlaneGrouping::exact) {  // within the rounding: the facet's plane throughout
    for (Sz t = 0; t < nt; ++t) plane[t] = facet_plane[at(mesh.facet_of_triangle[t])];
    return plane;
  }
  std::vector<Index> first(facet_plane.size(), -1);
  const std::vector<Point> pts = exact_points(mesh);
  for (Sz t = 0; t < nt; ++t) {
    const Index f = mesh.facet_of_triangle[t];
    plane[t] = facet_plane[at(f)];
    if (first[at(f)] < 0) {
      first[at(f)] = static_cast<Index>(t);
      continue;
    }
    const Tri& w = mesh.triangles[at(first[at(f)])];
    const Tri& tr = mesh.triangles[t];
    for (Index v : tr)
      if (CGAL::orientation(pts[at(w[0])], pts[at(w[1])], pts[at(w[2])], pts[at(v)]) != CGAL::COPLANAR) {
        plane[t] = next++;
        break;
      }
  }
  return plane;
}

}  // namespace panelrad::geometry

// Faces written rounded, moved back onto the planes they stand for (contact_removal.hpp:
// snap_to_common_planes).
//
// A scene rotated by its exporter and printed to 6 decimals (or any digits short of a double's)
// is no longer flat: the two triangles of a quad lie in planes an angle of about rounding / size
// apart, a box's bottom lies up to the rounding above or below the floor it stands on, and the
// corner where a table's leg meets its top and its side is a point that no two of those faces
// agree on. Deciding contacts pair by pair then closes the gap under one triangle and not under
// its neighbour. Instead, once for the whole scene:
//  1. Planes: pairs of triangles, the smaller's corners within the pair's tolerance of the larger's
//     plane (ContactTolerance: the rounding of their own corners as written), which touch or overlap
//     in projection within it, stand for one plane: the triangles of one face, flush sides of two
//     solids, and faces in contact. Each class with more than one triangle gets the least-squares
//     plane through its corners, kept when every corner lies within the class's tolerance of it.
//  2. Corners: each corner moves to the nearest point on the planes of its classes, the planes of
//     classes that span several input faces (contacts, flush sides) first and exactly, the others
//     in the freedom left. Planes meeting at less than about 6 degrees are one constraint there
//     (their intersection is ill-determined by the rounding), and a corner that would move more than
//     16 tolerances, or that lies within the visibility's resolution of all its planes already
//     (short decimals moved far from the origin look rounded), stays where it was written.
//  3. Corners on edges: a corner within the tolerance of an edge of its plane, inside the segment
//     (a box's corner written on the floor's diagonal), moves onto that edge's line first, so that
//     the triangles on both sides meet at it rather than a rounding apart; its own faces then bend
//     by no more than the rounding where their planes and the line disagree.
// All corners move at once, from their positions as written, so the result depends neither on the
// order of the faces nor on the vertex numbering. Only faces whose rounding exceeds the
// visibility's resolution take part: coordinates meant exactly (short decimals, a mesh built in
// code) and 17-digit ones keep their values bit for bit.
#include "contact_removal.hpp"
#include "t_junctions.hpp"

#include <CGAL/Bbox_3.h>
#include <CGAL/box_intersection_d.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <numeric>

namespace panelrad::geometry::validation_detail {

namespace {

/// Singular values below this (for unit normals) are planes meeting at less than about 6 degrees.
constexpr double kIndependentPlanes = 0.1;

struct Plane {
  Vec3 normal;    ///< unit
  double offset;  ///< normal . x = offset on the plane
  int tier;       ///< satisfied in this order: 0 a corner on an edge (the edge's line and its class's
                  ///< plane), 1 a plane of several input faces, 2 a plane of one face
  double tol;     ///< the tolerance of the triangles standing for it
};

/// A class of triangles standing for one plane: its triangles, their corners, its plane.
struct FlatClass {
  const std::vector<Index>* tris;
  std::vector<Index> corners;
  Plane plane;
};

/// Rounds of fitting and placing at most, and the weight of a corner held on an edge's line in the
/// refitted planes (its disagreement with the plane shrinks by about this factor a round).
constexpr int kRounds = 4;
constexpr double kOnLine = 1e6;

/// The weighted least-squares plane through `corners` (positions `x`, weights `w`, all 1 when
/// empty): normal the eigenvector of the weighted scatter with the smallest eigenvalue.
Plane fitted_plane(const std::vector<Index>& corners, const std::vector<Vec3>& x, const std::vector<double>& w,
                   int tier, double tol) {
  const auto weight = [&](Index v) { return w.empty() ? 1.0 : w[at(v)]; };
  Vec3 centre = Vec3::Zero();
  double total = 0;
  for (Index v : corners) {
    centre += weight(v) * x[at(v)];
    total += weight(v);
  }
  centre /= total;
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (Index v : corners) {
    const Vec3 d = x[at(v)] - centre;
    scatter += weight(v) * d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(scatter);
  const Vec3 n = eig.eigenvectors().col(0).normalized();  // smallest eigenvalue first
  return {n, n.dot(centre), tier, tol};
}

/// The largest distance of a class's corner (as moved) from its class's plane.
double largest_residual(const std::vector<FlatClass>& classes, const std::vector<Vec3>& x) {
  double r = 0;
  for (const FlatClass& c : classes)
    for (Index v : c.corners) r = std::max(r, std::abs(c.plane.normal.dot(x[at(v)]) - c.plane.offset));
  return r;
}

/// The move from x towards satisfying `rows` (unit normals, offsets) in the least-squares sense,
/// restricted to the span of `basis` (columns), directions where the rows are nearly dependent
/// left out; `null` receives the basis of the directions the rows leave free.
Vec3 constrained_move(const std::vector<Plane>& rows, const Vec3& x, const Eigen::Matrix3Xd& basis,
                      Eigen::Matrix3Xd& null) {
  if (rows.empty() || basis.cols() == 0) {
    null = basis;
    return Vec3::Zero();
  }
  Eigen::MatrixXd a(static_cast<Eigen::Index>(rows.size()), basis.cols());
  Eigen::VectorXd r(static_cast<Eigen::Index>(rows.size()));
  for (Sz k = 0; k < rows.size(); ++k) {
    a.row(static_cast<Eigen::Index>(k)) = rows[k].normal.transpose() * basis;
    r[static_cast<Eigen::Index>(k)] = rows[k].offset - rows[k].normal.dot(x);
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeThinU | Eigen::ComputeFullV);
  const Eigen::VectorXd& s = svd.singularValues();
  Eigen::VectorXd y = Eigen::VectorXd::Zero(basis.cols());
  std::vector<Eigen::Index> free;
  for (Eigen::Index k = 0; k < basis.cols(); ++k) {
    if (k < s.size() && s[k] > kIndependentPlanes)
      y += svd.matrixV().col(k) * (svd.matrixU().col(k).dot(r) / s[k]);
    else
      free.push_back(k);
  }
  null.resize(3, static_cast<Eigen::Index>(free.size()));
  for (Sz k = 0; k < free.size(); ++k) null.col(static_cast<Eigen::Index>(k)) = basis * svd.matrixV().col(free[k]);
  return basis * y;
}


/// x moved onto `planes`, tier after tier (Plane::tier), each exactly as far as its planes are
/// independent and in the freedom the earlier tiers leave; x itself when it lies within
/// `resolution` of every plane already (coordinates that only look rounded, such as short decimals
/// moved far from the origin, keep their values) or when the move would exceed 16 tolerances
/// (planes that do not meet near x).
Vec3 placed(const Vec3& x, const std::vector<Plane>& planes, double resolution) {
  std::array<std::vector<Plane>, 3> tiers;
  double tol = 0, off = 0;
  for (const Plane& p : planes) {
    tiers[at(p.tier)].push_back(p);
    tol = std::max(tol, p.tol);
    off = std::max(off, std::abs(p.normal.dot(x) - p.offset));
  }
  if (!(off > resolution)) return x;
  Eigen::Matrix3Xd free = Eigen::Matrix3d::Identity(), left;
  Vec3 y = x;
  for (const std::vector<Plane>& tier : tiers) {
    y += constrained_move(tier, y, free, left);
    free = left;
  }
  return y.allFinite() && (y - x).norm() <= 16 * tol ? y : x;
}

/// For the triangles `tris` of one class (its plane `plane`): each corner of them within the
/// class's tolerance of the open segment of an edge of another of them (further than the tolerance
/// from both ends, positions as written) receives in `lines_at` the plane through that edge's line
/// as `moved`, normal to the class's plane, and the class's plane, both of tier 0.
void corners_on_edges(const TriangleMesh& mesh, const std::vector<Index>& tris, const Plane& plane,
                      const std::vector<Vec3>& moved, std::vector<std::vector<Plane>>& lines_at) {
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, Index>;
  const double tol = plane.tol;
  std::vector<std::pair<Index, Index>> edges;
  std::vector<Index> corners;
  for (Index t : tris) {
    const Tri& tr = mesh.triangles[at(t)];
    for (int k = 0; k < 3; ++k) {
      edges.emplace_back(std::min(tr[at(k)], tr[at((k + 1) % 3)]), std::max(tr[at(k)], tr[at((k + 1) % 3)]));
      corners.push_back(tr[at(k)]);
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  const auto box_of = [&](const Vec3& lo, const Vec3& hi, Index info) {
    return Box(CGAL::Bbox_3(lo.x() - tol, lo.y() - tol, lo.z() - tol, hi.x() + tol, hi.y() + tol, hi.z() + tol), info);
  };
  std::vector<Box> corner_boxes, edge_boxes;
  for (Index v : corners) corner_boxes.push_back(box_of(mesh.vertices[at(v)], mesh.vertices[at(v)], v));
  for (Sz e = 0; e < edges.size(); ++e) {
    const Vec3 &a = mesh.vertices[at(edges[e].first)], &b = mesh.vertices[at(edges[e].second)];
    edge_boxes.push_back(box_of(a.cwiseMin(b), a.cwiseMax(b), static_cast<Index>(e)));
  }
  std::vector<std::pair<Index, Index>> hits;  // (corner, edge)
  CGAL::box_intersection_d(corner_boxes.begin(), corner_boxes.end(), edge_boxes.begin(), edge_boxes.end(),
                           [&](const Box& c, const Box& e) { hits.emplace_back(c.info(), e.info()); });
  std::sort(hits.begin(), hits.end());  // the same planes in the same order whatever the boxes' order
  for (const auto& [v, e] : hits) {
    const auto [ia, ib] = edges[at(e)];
    if (v == ia || v == ib) continue;
    if (!near_open_segment(mesh.vertices[at(ia)], mesh.vertices[at(ib)], mesh.vertices[at(v)], tol)) continue;
    const Vec3 m = (moved[at(ib)] - moved[at(ia)]).cross(plane.normal).normalized();
    if (!m.allFinite()) continue;
    lines_at[at(v)].push_back({m, m.dot(moved[at(ia)]), 0, tol});
    lines_at[at(v)].push_back({plane.normal, plane.offset, 0, tol});
  }
}

/// Corners whose moves would leave a triangle without area (collinear corners, exactly) or turned
/// over keep their positions as written, until every triangle is as proper as it was written: a
/// triangle smaller than the moves (16 tolerances at most) may otherwise be flattened by the planes
/// of its neighbours.
void keep_triangles_proper(const TriangleMesh& mesh, std::vector<Vec3>& moved) {
  const auto normal = [](const std::vector<Vec3>& x, const Tri& t) {
    return Vec3((x[at(t[1])] - x[at(t[0])]).cross(x[at(t[2])] - x[at(t[0])]));
  };
  const auto point = [&](Index v) { return Point(moved[at(v)].x(), moved[at(v)].y(), moved[at(v)].z()); };
  for (bool again = true; again;) {
    again = false;
    for (const Tri& t : mesh.triangles) {
      if (moved[at(t[0])] == mesh.vertices[at(t[0])] && moved[at(t[1])] == mesh.vertices[at(t[1])] &&
          moved[at(t[2])] == mesh.vertices[at(t[2])])
        continue;
      if (!CGAL::collinear(point(t[0]), point(t[1]), point(t[2])) &&
          normal(moved, t).dot(normal(mesh.vertices, t)) > 0)
        continue;
      for (Index v : t) moved[at(v)] = mesh.vertices[at(v)];
      again = true;
    }
  }
}

}  // namespace

Sz snap_to_common_planes(TriangleMesh& mesh, const ContactTolerance& tolerance) {
  const Sz nt = mesh.triangles.size();
  const double widest = largest_tolerance(tolerance, diameter(mesh));
  if (!(widest > tolerance.resolution) || nt < 2) return 0;
  // 1. Candidate pairs: triangles whose boxes, widened by the largest tolerance, intersect.
  const std::vector<std::pair<Index, Index>> candidates = nearby_triangle_pairs(mesh, widest);
  // Classes of triangles standing for one plane (union-find), with the largest tolerance joined.
  std::vector<Index> parent(nt);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<double> class_tol(nt, 0.0);
  const std::function<Index(Index)> root = [&](Index t) {
    while (parent[at(t)] != t) t = parent[at(t)] = parent[at(parent[at(t)])];
    return t;
  };
  for (const auto& [i, j] : candidates) {
    const Tri &ti = mesh.triangles[at(i)], &tj = mesh.triangles[at(j)];
    const double li = longest_edge(mesh, ti), lj = longest_edge(mesh, tj);
    const double tol =
        rounding_tolerance(tolerance, mesh.facet_of_triangle[at(i)], mesh.facet_of_triangle[at(j)], std::max(li, lj));
    if (!(tol > tolerance.resolution)) continue;
    // The smaller triangle within the tolerance of the larger one's plane: the plane of a small
    // triangle is tilted by up to about tol / its size, which its far neighbour's corners magnify.
    if (!(li >= lj ? corners_near_plane(mesh, ti, tj, tol) : corners_near_plane(mesh, tj, ti, tol))) continue;
    if (!projections_overlap(mesh, ti, tj, -tol)) continue;  // apart in their plane
    const Index ri = root(i), rj = root(j);
    const double joined = std::max({class_tol[at(ri)], class_tol[at(rj)], tol});
    if (ri != rj) parent[at(std::max(ri, rj))] = std::min(ri, rj);
    class_tol[at(std::min(ri, rj))] = joined;
  }
  // 2. The least-squares plane of each class of two or more triangles, kept when flat.
  std::map<Index, std::vector<Index>> members;
  for (Sz t = 0; t < nt; ++t) members[root(static_cast<Index>(t))].push_back(static_cast<Index>(t));
  std::vector<FlatClass> classes;
  for (const auto& [r, tris] : members) {
    if (tris.size() < 2) continue;
    FlatClass c{&tris, {}, {}};
    bool shared = false;
    for (Index t : tris) {
      for (Index v : mesh.triangles[at(t)]) c.corners.push_back(v);
      shared = shared || mesh.facet_of_triangle[at(t)] != mesh.facet_of_triangle[at(tris.front())];
    }
    std::sort(c.corners.begin(), c.corners.end());
    c.corners.erase(std::unique(c.corners.begin(), c.corners.end()), c.corners.end());
    c.plane = fitted_plane(c.corners, mesh.vertices, {}, shared ? 1 : 2, class_tol[at(r)]);
    const bool flat = std::all_of(c.corners.begin(), c.corners.end(), [&](Index v) {
      return std::abs(c.plane.normal.dot(mesh.vertices[at(v)]) - c.plane.offset) <= c.plane.tol;
    });
    if (flat && std::isfinite(c.plane.offset)) classes.push_back(std::move(c));  // else a curved chain
  }
  // 3. Each corner onto its planes; 4. a corner within the tolerance of an edge of its plane (inside
  // the segment, not at its ends) onto that edge's line first, as its ends were moved: a box's
  // corner written on the floor's diagonal. Such a corner has more constraints than freedom (the
  // line's two and its own three planes), which the rounding makes disagree; the planes are fitted
  // again through the corners as moved, those on lines weighing kOnLine, so that they pass through
  // them, and every corner is placed again, until every corner lies on its planes to within the
  // resolution (a few rounds: each shrinks the disagreement by about the weights' ratio).
  std::vector<Vec3> moved = mesh.vertices;
  std::vector<double> weight(mesh.vertices.size(), 1.0);
  for (int round = 0; round < kRounds; ++round) {
    std::vector<std::vector<Plane>> planes_at(mesh.vertices.size());
    for (FlatClass& c : classes) {
      if (round > 0) c.plane = fitted_plane(c.corners, moved, weight, c.plane.tier, c.plane.tol);
      for (Index v : c.corners) planes_at[at(v)].push_back(c.plane);
    }
    for (Sz v = 0; v < mesh.vertices.size(); ++v)
      if (!planes_at[v].empty()) moved[v] = placed(mesh.vertices[v], planes_at[v], tolerance.resolution);
    std::vector<std::vector<Plane>> lines_at(mesh.vertices.size());
    for (const FlatClass& c : classes) corners_on_edges(mesh, *c.tris, c.plane, moved, lines_at);
    bool any_line = false;
    for (Sz v = 0; v < mesh.vertices.size(); ++v) {
      if (lines_at[v].empty()) continue;
      any_line = true;
      weight[v] = kOnLine;
      std::vector<Plane> all = planes_at[v];
      all.insert(all.end(), lines_at[v].begin(), lines_at[v].end());
      moved[v] = placed(mesh.vertices[v], all, tolerance.resolution);
    }
    if (!any_line || largest_residual(classes, moved) <= tolerance.resolution) break;
  }
  keep_triangles_proper(mesh, moved);
  Sz count = 0;
  for (Sz v = 0; v < mesh.vertices.size(); ++v) count += moved[v] != mesh.vertices[v] ? 1 : 0;
  mesh.vertices = std::move(moved);
  return count;
}

}  // namespace panelrad::geometry::validation_detail

#pragma once
// The diagonals of a constrained triangulation chosen by the plane's own metric, with ties broken
// by the input's vertex numbers: the same triangles whatever frame the coordinates are written in.
//
// A constrained Delaunay triangulation built on coordinates projected to a coordinate plane (as the
// cut of faces in contact is, contact_removal.cpp) is Delaunay for the projected metric, which is
// the plane's own only when the plane is normal to that axis: the same scene rotated projects to
// a sheared copy, where the other diagonal of a quadrilateral can be the Delaunay one. And four
// corners on one circle (a rectangle: the corners of a leg's top and of a table's) are a tie that
// the rounding of the rotated coordinates breaks either way. This pass (Lawson's flips) makes
// every unconstrained edge locally Delaunay in the plane's orthonormal frame, and where the fourth
// corner lies within `tie` of the circle through the other three, takes the diagonal at the
// lowest-ranked corner (the input vertex numbers: the same in every writing of the scene).
#include <CGAL/enum.h>
#include <Eigen/Core>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

namespace panelrad::geometry::validation_detail {

/// The in-circle determinant of (a, b, c, d), coordinates relative to d: positive when d lies
/// inside the circle through a, b, c counter-clockwise (double precision).
inline double incircle_value(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                             const Eigen::Vector2d& d) {
  const Eigen::Vector2d p = a - d, q = b - d, r = c - d;
  return p.squaredNorm() * (q.x() * r.y() - q.y() * r.x()) - q.squaredNorm() * (p.x() * r.y() - p.y() * r.x()) +
         r.squaredNorm() * (p.x() * q.y() - p.y() * q.x());
}

/// Whether the diagonal (r, s) of the quadrilateral p, r, q, s (the edge (p, q) now) is the
/// canonical one: s inside the circle through p, q, r by more than the tie, or within it and the
/// lowest rank of the four at r or s. Coordinates in the plane's own (orthonormal) frame.
inline bool other_diagonal_wanted(const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r,
                                  const Eigen::Vector2d& s, std::int64_t rank_p, std::int64_t rank_q,
                                  std::int64_t rank_r, std::int64_t rank_s, double tie) {
  const double turn = (q - p).x() * (r - p).y() - (q - p).y() * (r - p).x();
  const double inside = turn > 0 ? incircle_value(p, q, r, s) : incircle_value(q, p, r, s);
  // |value| ~ 4 area(p, q, r) R |distance of s from the circle|, at most L^3 |distance| with L the
  // largest distance among the four: a tie is a distance within `tie`, measured the same way for
  // both diagonals (the value and L are those of the four points, whichever edge is tested).
  const double L = std::max({(p - q).norm(), (p - r).norm(), (p - s).norm(), (q - r).norm(), (q - s).norm(),
                             (r - s).norm()});
  const double bound = tie * L * L * L;
  if (inside > bound) return true;
  if (inside < -bound) return false;
  return std::min(rank_r, rank_s) < std::min(rank_p, rank_q);
}

/// Flips the unconstrained edges of `cdt` until each has its canonical diagonal
/// (other_diagonal_wanted), a flip being made only where the quadrilateral is strictly convex in
/// the triangulation's own coordinates (exact orientations). `place(v)` gives a vertex's
/// coordinates in the plane's orthonormal frame, `rank(v)` its rank (ties of ranks keep the edge).
/// At most a bounded number of passes (the tie's tolerance could make a cycle of flips).
template <class Cdt, class Place, class Rank>
void canonical_diagonals(Cdt& cdt, Place&& place, Rank&& rank, double tie) {
  using Face_handle = typename Cdt::Face_handle;
  using Vertex_handle = typename Cdt::Vertex_handle;
  const auto strictly_crosses = [&](const Vertex_handle& a, const Vertex_handle& b, const Vertex_handle& c,
                                    const Vertex_handle& d) {
    // The open segments ab and cd cross (exact, in the triangulation's coordinates).
    const CGAL::Orientation c_side = CGAL::orientation(a->point(), b->point(), c->point());
    const CGAL::Orientation d_side = CGAL::orientation(a->point(), b->point(), d->point());
    const CGAL::Orientation a_side = CGAL::orientation(c->point(), d->point(), a->point());
    const CGAL::Orientation b_side = CGAL::orientation(c->point(), d->point(), b->point());
    return c_side != CGAL::COLLINEAR && d_side != CGAL::COLLINEAR && c_side != d_side && a_side != CGAL::COLLINEAR &&
           b_side != CGAL::COLLINEAR && a_side != b_side;
  };
  constexpr int kMaxPasses = 64;
  for (int pass = 0; pass < kMaxPasses; ++pass) {
    bool flipped = false;
    std::vector<std::pair<Face_handle, int>> edges;
    for (auto e = cdt.finite_edges_begin(); e != cdt.finite_edges_end(); ++e) edges.emplace_back(e->first, e->second);
    for (auto [f, i] : edges) {
      if (cdt.is_constrained({f, i})) continue;
      const Face_handle g = f->neighbor(i);
      if (cdt.is_infinite(f) || cdt.is_infinite(g)) continue;
      const Vertex_handle p = f->vertex(Cdt::cw(i)), q = f->vertex(Cdt::ccw(i)), r = f->vertex(i);
      const Vertex_handle s = g->vertex(cdt.mirror_index(f, i));
      if (!other_diagonal_wanted(place(p), place(q), place(r), place(s), rank(p), rank(q), rank(r), rank(s), tie))
        continue;
      if (!strictly_crosses(p, q, r, s)) continue;
      cdt.flip(f, i);
      flipped = true;
    }
    if (!flipped) return;
  }
}

}  // namespace panelrad::geometry::validation_detail

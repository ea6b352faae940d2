// The visible part of tau in the line-of-sight function V of (1) is tau minus the union of the
// shadows; each shadow is convex, so a convex piece A minus a convex shadow S with edges e_1..e_m is
// the disjoint union of the convex pieces A cap H_1 cap ... cap H_{j-1} cap (outside of e_j's line)
// for j = 1..m (H_j the inner half-plane of e_j), and A cap S is what remains after the last edge.
#include "occluders_internal.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace panelrad::geometry::occluder_detail {

namespace {

void emit(const Vec2* p, int n, double min_area, Pieces& out) {
  if (n < 3) return;
  const double a = polygon_area(p, n);
  if (!(a > min_area)) return;
  out.pts.insert(out.pts.end(), p, p + n);
  out.end.push_back(static_cast<std::uint32_t>(out.pts.size()));
  out.area.push_back(a);
}

}  // namespace

void subtract_convex(const Pieces& in, const Vec2* poly, int n_poly, double tol, double min_area, Pieces& out,
                     Pieces* covered) {
  Vec2 slo = poly[0], shi = poly[0];
  for (int j = 1; j < n_poly; ++j) {
    slo = slo.cwiseMin(poly[j]);
    shi = shi.cwiseMax(poly[j]);
  }
  // The edge lines of the shadow, once for all pieces: a point and the unit normal on the inner
  // side of a counter-clockwise polygon; a degenerate edge (length at most tol) bounds nothing.
  std::array<Vec2, 12> line_at, line_in;
  int n_lines = 0;
  for (int j = 0; j < n_poly && n_lines < 12; ++j) {
    const Vec2& a = poly[j];
    const Vec2 d = poly[(j + 1) % n_poly] - a;
    const double len = d.norm();
    if (!(len > tol)) continue;
    line_at[n_lines] = a;
    line_in[n_lines++] = Vec2(-d.y() / len, d.x() / len);
  }
  subtract_convex(in, line_at.data(), line_in.data(), n_lines, slo, shi, tol, min_area, out, covered);
}

void subtract_convex(const Pieces& in, const Vec2* line_at, const Vec2* line_in, int n_lines, const Vec2& slo,
                     const Vec2& shi, double tol, double min_area, Pieces& out, Pieces* covered) {
  out.clear();
  std::uint32_t begin = 0;
  for (std::size_t k = 0; k < in.end.size(); ++k) {
    const std::uint32_t end = in.end[k];
    subtract_convex_from_piece(in.pts.data() + begin, static_cast<int>(end - begin), in.area[k], line_at, line_in,
                               n_lines, slo, shi, tol, min_area, out, covered);
    begin = end;
  }
}

void subtract_convex_from_piece(const Vec2* piece, int np, double piece_area, const Vec2* line_at,
                                const Vec2* line_in, int n_lines, const Vec2& slo, const Vec2& shi, double tol,
                                double min_area, Pieces& out, Pieces* covered) {
  thread_local std::vector<Vec2> cur, inner, outer;
  thread_local std::vector<double> dist;
  Vec2 lo = piece[0], hi = piece[0];
  for (int i = 1; i < np; ++i) {
    lo = lo.cwiseMin(piece[i]);
    hi = hi.cwiseMax(piece[i]);
  }
  if ((hi.array() <= slo.array() + tol).any() || (lo.array() >= shi.array() - tol).any()) {
    // Boxes apart: the shadow misses the piece, which is kept as it is.
    if (np >= 3 && piece_area > min_area) {
      out.pts.insert(out.pts.end(), piece, piece + np);
      out.end.push_back(static_cast<std::uint32_t>(out.pts.size()));
      out.area.push_back(piece_area);
    }
    return;
  }
  cur.assign(piece, piece + np);
  for (int j = 0; j < n_lines; ++j) {
    const Vec2& a = line_at[j];
    const Vec2& left = line_in[j];
    const int n = static_cast<int>(cur.size());
    dist.resize(cur.size());
    double dmin = 0, dmax = 0;
    for (int i = 0; i < n; ++i) {
      dist[i] = (cur[i] - a).dot(left);
      dmin = i == 0 ? dist[i] : std::min(dmin, dist[i]);
      dmax = i == 0 ? dist[i] : std::max(dmax, dist[i]);
    }
    if (dmax <= tol) {  // outside this edge's line: the shadow misses what is left
      emit(cur.data(), n, min_area, out);
      return;
    }
    if (dmin >= -tol) continue;  // inside this edge's line: on to the next edge
    // Split along the line; corners within tol of it belong to both sides (no slivers).
    inner.clear();
    outer.clear();
    for (int i = 0; i < n; ++i) {
      const int k2 = i + 1 < n ? i + 1 : 0;
      const double di = dist[i], dk = dist[k2];
      const int si = di > tol ? 1 : (di < -tol ? -1 : 0);
      const int sk = dk > tol ? 1 : (dk < -tol ? -1 : 0);
      if (si >= 0) inner.push_back(cur[i]);
      if (si <= 0) outer.push_back(cur[i]);
      if (si * sk < 0) {
        const Vec2 x = cur[i] + (di / (di - dk)) * (cur[k2] - cur[i]);
        inner.push_back(x);
        outer.push_back(x);
      }
    }
    emit(outer.data(), static_cast<int>(outer.size()), min_area, out);
    cur.swap(inner);
    if (cur.size() < 3) return;
  }
  // What is inside every edge line is covered by the shadow: dropped from the pieces, kept as
  // covered when asked for (whatever its area: the covered part is the complement of the pieces).
  if (covered) emit(cur.data(), static_cast<int>(cur.size()), 0, *covered);
}

}  // namespace panelrad::geometry::occluder_detail

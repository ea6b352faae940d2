// The shaft conv(P, tau) of the line-of-sight function V(P, Q) in (1), and the shadow an occluder
// casts on tau seen from P: the face clipped to the shaft's half-spaces (Sutherland-Hodgman on a
// fixed array: a triangle cut by 5 planes keeps at most 3 + 5 corners), then projected centrally
// from P onto tau's plane, X -> P + (X - P) h / (h - h(X)), h and h(X) the heights of P and X over
// tau's plane. Inside the shaft 0 <= h(X) < h, and the central projection of a convex polygon lying
// in front of P is a convex polygon of tau's plane inside tau.
#include "occluders_internal.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace panelrad::geometry::occluder_detail {

FaceData make_face(const std::array<Vec3, 3>& v) {
  FaceData f;
  f.v = v;
  f.lo = v[0].cwiseMin(v[1]).cwiseMin(v[2]);
  f.hi = v[0].cwiseMax(v[1]).cwiseMax(v[2]);
  f.n = (v[1] - v[0]).cross(v[2] - v[0]).normalized();
  for (int i = 0; i < 3; ++i) f.edge_in[i] = f.n.cross(v[(i + 1) % 3] - v[i]).normalized();
  return f;
}

bool make_shaft(const Vec3& P, const Vec3& nP, const std::array<Vec3, 3>& tau, const Vec3& nQ, double margin,
                Shaft& s) {
  s.P = P;
  s.margin = margin;
  const double nP_len = nP.norm();
  if (!(nP_len > 0)) return false;
  s.nP = nP / nP_len;
  const Vec3 cross = (tau[1] - tau[0]).cross(tau[2] - tau[0]);
  const double twice_area = cross.norm();
  if (!(twice_area > 0)) return false;
  if (cross.dot(nQ) >= 0) {
    s.t = tau;
    s.nQ = cross / twice_area;
  } else {
    s.t = {tau[0], tau[2], tau[1]};
    s.nQ = -cross / twice_area;
  }
  s.area = twice_area / 2;
  s.area_margin = kShadowMargin * s.area;
  s.height = (P - s.t[0]).dot(s.nQ);
  s.grazing = false;
  if (!(s.height > margin)) {
    // P on or behind tau's plane: cos theta_Q <= 0. Within the margin the sign is taken exactly:
    // a point a narrow gap h from a face, rounded to within d < margin in front of the plane of a
    // face across the gap (a collocation point above a box's edge, the box's side), sees it with
    // the factor d / 2h, which the face above the gap misses. Such a shaft is thinner than the
    // margin; no face is tested against it (a face crossing it could hide at most the factor of
    // tau, below margin / (2 dist(P, tau))).
    if (!(s.height > -margin) || !strictly_in_front(P, s.t)) return false;
    s.grazing = true;
  }
  double lo = 0, hi = 0;
  for (int i = 0; i < 3; ++i) {
    s.tP[i] = (s.t[i] - P).dot(s.nP);
    lo = i == 0 ? s.tP[i] : std::min(lo, s.tP[i]);
    hi = i == 0 ? s.tP[i] : std::max(hi, s.tP[i]);
  }
  if (!(hi > margin)) return false;  // tau on or behind P's plane: cos theta_P <= 0
  // A corner within the margin of P's plane counts as on it: cutting there removes no area.
  s.straddles = lo < -margin;
  return true;
}

void complete_shaft(Shaft& s) {
  const Vec3& P = s.P;
  for (int i = 0; i < 3; ++i) {
    const Vec3& a = s.t[i];
    const Vec3& b = s.t[(i + 1) % 3];
    const Vec3& c = s.t[(i + 2) % 3];
    Vec3 n = (a - P).cross(b - P);
    if (n.dot(c - P) < 0) n = -n;
    s.side_n[i] = n.normalized();
  }
  s.lo = P.cwiseMin(s.t[0]).cwiseMin(s.t[1]).cwiseMin(s.t[2]);
  s.hi = P.cwiseMax(s.t[0]).cwiseMax(s.t[1]).cwiseMax(s.t[2]);
  s.u = (s.t[1] - s.t[0]).normalized();
  s.w = s.nQ.cross(s.u);
}

namespace {

/// max over the face's corners of the signed distance from the plane through o with unit normal n.
double max_distance(const FaceData& f, const Vec3& o, const Vec3& n) {
  return std::max({(f.v[0] - o).dot(n), (f.v[1] - o).dot(n), (f.v[2] - o).dot(n)});
}

/// Sutherland-Hodgman: the part of the convex polygon in[0, n) where (x - o).m >= 0. At most n + 1
/// corners (a convex polygon crosses a plane at most twice, and a crossing drops a corner).
int clip(const Vec3* in, int n, const Vec3& o, const Vec3& m, Vec3* out) {
  int k = 0;
  double dc = (in[0] - o).dot(m);
  for (int i = 0; i < n; ++i) {
    const Vec3& c = in[i];
    const Vec3& x = in[i + 1 < n ? i + 1 : 0];
    const double dx = (x - o).dot(m);
    if (dc >= 0) out[k++] = c;
    if ((dc >= 0) != (dx >= 0)) out[k++] = c + (dc / (dc - dx)) * (x - c);
    dc = dx;
  }
  return k;
}

}  // namespace

bool may_meet(const FaceData& f, const Shaft& s) {
  const double m = s.margin;
  if ((f.hi.array() < s.lo.array() - m).any() || (f.lo.array() > s.hi.array() + m).any()) return false;
  if (max_distance(f, s.t[0], s.nQ) <= m) return false;  // on or behind tau's plane (tau's own face too)
  if (max_distance(f, s.P, s.nP) <= m) return false;     // on or behind P's plane (P's own face too)
  for (int i = 0; i < 3; ++i)
    if (max_distance(f, s.P, s.side_n[i]) <= m) return false;
  if (std::abs((s.P - f.v[0]).dot(f.n)) <= m) return false;  // P in the face's plane: seen edge-on
  return true;
}

bool covers_shaft(const FaceData& f, const Shaft& s) {
  if (s.straddles || s.grazing) return false;
  const double k = kCoverMargins * s.margin;
  const double dP = (s.P - f.v[0]).dot(f.n);
  if (!(std::abs(dP) > k)) return false;
  for (const Vec3& t : s.t) {
    const double dt = (t - f.v[0]).dot(f.n);
    if (!(dP > 0 ? dt < -k : dt > k)) return false;  // tau's corner beyond the face's plane
  }
  for (int e = 0; e < 3; ++e) {
    const Vec3 a = f.v[static_cast<std::size_t>(e)] - s.P, b = f.v[static_cast<std::size_t>((e + 1) % 3)] - s.P;
    Vec3 n = a.cross(b);
    if (n.dot(f.v[static_cast<std::size_t>((e + 2) % 3)] - s.P) < 0) n = -n;
    const double len = n.norm();
    if (!(len > 0)) return false;
    for (const Vec3& t : s.t)
      if (!((t - s.P).dot(n) > k * len)) return false;  // outside the cone over the face, or too near its side
  }
  return true;
}

double polygon_area(const Vec2* p, int n) {
  double a = 0;
  for (int i = 0; i < n; ++i) {
    const Vec2& x = p[i];
    const Vec2& y = p[i + 1 < n ? i + 1 : 0];
    a += x.x() * y.y() - x.y() * y.x();
  }
  return a / 2;
}

int convex_in_place(Vec2* p, int n) {
  bool dropped = true;
  while (dropped && n >= 3) {
    dropped = false;
    for (int i = 0; i < n && n >= 3; ++i) {
      const Vec2& a = p[i > 0 ? i - 1 : n - 1];
      const Vec2& b = p[i];
      const Vec2& c = p[i + 1 < n ? i + 1 : 0];
      const Vec2 ab = b - a, bc = c - b;
      if (ab.x() * bc.y() - ab.y() * bc.x() > 0) continue;  // a left turn: a convex corner
      std::copy(p + i + 1, p + n, p + i);
      --n;
      dropped = true;
    }
  }
  return n;
}

bool cast_shadow(const FaceData& f, const Shaft& s, Shadow& out) {
  std::array<Vec3, 9> buf_a, buf_b;
  Vec3* cur = buf_a.data();
  Vec3* nxt = buf_b.data();
  cur[0] = f.v[0];
  cur[1] = f.v[1];
  cur[2] = f.v[2];
  int n = 3;
  n = clip(cur, n, s.t[0], s.nQ, nxt);
  std::swap(cur, nxt);
  for (int i = 0; i < 3 && n >= 3; ++i) {
    n = clip(cur, n, s.P, s.side_n[i], nxt);
    std::swap(cur, nxt);
  }
  if (s.straddles && n >= 3) {
    n = clip(cur, n, s.P, s.nP, nxt);
    std::swap(cur, nxt);
  }
  if (n < 3) return false;
  // Central projection from P onto tau's plane, in the frame (u, w) at t[0]. The magnification
  // h / (h - h(X)) is bounded (X is farther than the margin from P, inside the shaft); the floor on
  // the denominator only keeps it finite under rounding.
  const Vec3 Pr = s.P - s.t[0];
  const double floor_denominator = kShadowMargin * s.height;
  const double tol2 = s.margin * s.margin;
  int k = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3 Y = cur[i] - s.t[0];
    const double denominator = std::max(s.height - Y.dot(s.nQ), floor_denominator);
    const Vec3 q = Pr + (Y - Pr) * (s.height / denominator);
    const Vec2 p(q.dot(s.u), q.dot(s.w));
    if (k > 0 && (p - out.p[k - 1]).squaredNorm() <= tol2) continue;  // repeated corner of the clipping
    out.p[k++] = p;
  }
  while (k > 1 && (out.p[k - 1] - out.p[0]).squaredNorm() <= tol2) --k;
  if (k < 3) return false;
  double a = polygon_area(out.p.data(), k);
  if (a < 0) {
    std::reverse(out.p.begin(), out.p.begin() + k);
    a = -a;
  }
  // The shadow of a convex polygon is convex, but a corner nearly in line with its neighbours (an
  // edge of the face seen almost end-on from P projects to a segment of a rounding's length) may
  // come out as a reflex turn. The subtraction uses the shadow as the intersection of its edges'
  // inner half-planes, which then loses a sliver of the shadow between the short edge's line and
  // the next: such corners are dropped, leaving the convex hull of the projected corners.
  k = convex_in_place(out.p.data(), k);
  if (k < 3) return false;
  out.n = k;
  out.area = a;
  return a > s.area_margin;
}

void front_part(const std::array<Vec2, 3>& c, const std::array<double, 3>& tP, bool straddles, Pieces& out) {
  out.clear();
  if (!straddles) {
    out.pts.assign(c.begin(), c.end());
  } else {
    // The distance from P's plane is affine along the triangle: cut where it changes sign.
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      const double di = tP[i], dj = tP[j];
      if (di >= 0) out.pts.push_back(c[i]);
      if ((di >= 0) != (dj >= 0)) out.pts.push_back(c[i] + (di / (di - dj)) * (c[j] - c[i]));
    }
  }
  out.end.push_back(static_cast<std::uint32_t>(out.pts.size()));
  out.area.push_back(polygon_area(out.pts.data(), static_cast<int>(out.pts.size())));
}

void front_part_of_tau(const Shaft& s, Pieces& out) {
  const Vec3 e1 = s.t[1] - s.t[0], e2 = s.t[2] - s.t[0];
  const std::array<Vec2, 3> c = {Vec2(0, 0), Vec2(e1.dot(s.u), e1.dot(s.w)), Vec2(e2.dot(s.u), e2.dot(s.w))};
  front_part(c, s.tP, s.straddles, out);
}

int clip_to_half_plane(const Vec2* in, int n, const Vec2& o, const Vec2& m, double enter_tol, Vec2* out) {
  std::array<double, 12> d;
  bool all_in = true;
  double d_max = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i) {
    d[i] = (in[i] - o).dot(m);
    all_in = all_in && d[i] >= 0;
    d_max = std::max(d_max, d[i]);
  }
  if (all_in) return -1;
  if (d_max <= enter_tol) return 0;
  int k = 0;
  for (int i = 0; i < n; ++i) {
    const int j = i + 1 < n ? i + 1 : 0;
    const double dc = d[i], dx = d[j];
    if (dc >= 0) out[k++] = in[i];
    if ((dc >= 0) != (dx >= 0)) out[k++] = in[i] + (dc / (dc - dx)) * (in[j] - in[i]);
  }
  return k;
}

}  // namespace panelrad::geometry::occluder_detail

// The shaft between two clusters (occluders_internal.hpp: ClusterShaft): the convex hull of two
// triangles, for the cluster-to-cluster visibility of the fast product. A face and the hull are
// convex; they are disjoint exactly when some axis separates them among the face's normal, the
// hull's face normals and the cross products of an edge of each (the separating axis theorem).
// A face separated (up to the margin) blocks no segment PQ, for any P of sigma and Q of tau; one
// not separated may block some.
#include "occluders_internal.hpp"

#include <algorithm>
#include <cmath>

namespace panelrad::geometry::occluder_detail {

namespace {

/// The largest and smallest signed distance of the points from the plane through o with normal n.
std::pair<double, double> extent(const Vec3* x, int count, const Vec3& o, const Vec3& n) {
  double lo = (x[0] - o).dot(n), hi = lo;
  for (int i = 1; i < count; ++i) {
    const double d = (x[i] - o).dot(n);
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
  return {lo, hi};
}

}  // namespace

ShaftClass make_cluster_shaft(const std::array<Vec3, 3>& sigma, const Vec3& nS, const std::array<Vec3, 3>& tau,
                              const Vec3& nT, double margin, ClusterShaft& s) {
  const Vec3 crossS = (sigma[1] - sigma[0]).cross(sigma[2] - sigma[0]);
  const Vec3 crossT = (tau[1] - tau[0]).cross(tau[2] - tau[0]);
  if (!(crossS.norm() > 0) || !(crossT.norm() > 0)) return ShaftClass::partial;
  const Vec3 uS = (crossS.dot(nS) >= 0 ? crossS : Vec3(-crossS)).normalized();
  const Vec3 uT = (crossT.dot(nT) >= 0 ? crossT : Vec3(-crossT)).normalized();
  // tau's corners from sigma's plane (P's plane for every P of sigma), sigma's from tau's plane
  // (the heights of the points of sigma over tau, affine along sigma).
  const auto [tau_lo, tau_hi] = extent(tau.data(), 3, sigma[0], uS);
  const auto [sig_lo, sig_hi] = extent(sigma.data(), 3, tau[0], uT);
  if (!(tau_hi > margin) || !(sig_hi > -margin)) return ShaftClass::hidden;
  // tau crossing sigma's plane (cut at it for some points), or sigma crossing tau's plane (some
  // points behind it): undecided. Corners within the margin of the other's plane count as on it,
  // as in the point shaft (a side face's cluster at the edge it shares with the floor).
  if (tau_lo < -margin || sig_lo < -margin) return ShaftClass::partial;
  for (int i = 0; i < 3; ++i) {
    s.x[static_cast<std::size_t>(i)] = sigma[static_cast<std::size_t>(i)];
    s.x[static_cast<std::size_t>(i) + 3] = tau[static_cast<std::size_t>(i)];
  }
  s.lo = s.hi = s.x[0];
  for (const Vec3& y : s.x) {
    s.lo = s.lo.cwiseMin(y);
    s.hi = s.hi.cwiseMax(y);
  }
  // Supporting planes: sigma's and tau's (the other triangle in front of each), then those through
  // an edge of one triangle and a corner of the other that leave all six corners on one side.
  s.planes = 0;
  const auto add = [&](const Vec3& n, const Vec3& o) {
    s.out_n[static_cast<std::size_t>(s.planes)] = n;
    s.out_d[static_cast<std::size_t>(s.planes)] = n.dot(o);
    ++s.planes;
  };
  add(-uS, sigma[0]);
  add(-uT, tau[0]);
  for (int side = 0; side < 2; ++side) {
    const std::array<Vec3, 3>& a = side == 0 ? sigma : tau;
    const std::array<Vec3, 3>& b = side == 0 ? tau : sigma;
    for (int e = 0; e < 3; ++e) {
      const Vec3& p = a[static_cast<std::size_t>(e)];
      const Vec3& q = a[static_cast<std::size_t>((e + 1) % 3)];
      for (int c = 0; c < 3 && s.planes < 20; ++c) {
        const Vec3 n = (q - p).cross(b[static_cast<std::size_t>(c)] - p);
        const double len = n.norm();
        if (!(len > 0)) continue;
        const Vec3 u = n / len;
        const auto [lo, hi] = extent(s.x.data(), 6, p, u);
        if (hi <= margin) add(u, p);
        else if (lo >= -margin) add(Vec3(-u), p);
      }
    }
  }
  return ShaftClass::full;
}

bool may_block(const FaceData& f, const ClusterShaft& s, double margin) {
  if ((f.hi.array() < s.lo.array() - margin).any() || (f.lo.array() > s.hi.array() + margin).any()) return false;
  const auto [lo, hi] = extent(s.x.data(), 6, f.v[0], f.n);
  if (lo >= -margin || hi <= margin) return false;  // no segment crosses the face's plane by more
  for (int k = 0; k < s.planes; ++k) {
    const Vec3& n = s.out_n[static_cast<std::size_t>(k)];
    const double d = s.out_d[static_cast<std::size_t>(k)];
    if (std::min({n.dot(f.v[0]), n.dot(f.v[1]), n.dot(f.v[2])}) - d >= -margin) return false;
  }
  // The other separating axes of two convex bodies: an edge of the face crossed with a segment
  // between two corners of the shaft (its edges are among these).
  for (int e = 0; e < 3; ++e) {
    const Vec3 fe = f.v[static_cast<std::size_t>((e + 1) % 3)] - f.v[static_cast<std::size_t>(e)];
    for (int i = 0; i < 6; ++i)
      for (int j = i + 1; j < 6; ++j) {
        const Vec3 axis = fe.cross(s.x[static_cast<std::size_t>(j)] - s.x[static_cast<std::size_t>(i)]);
        const double len = axis.norm();
        if (!(len > 0)) continue;
        const Vec3 u = axis / len;
        const auto [lo, hi] = extent(s.x.data(), 6, f.v[0], u);  // the face's corners at 0 and along fe
        const double a = (f.v[1] - f.v[0]).dot(u), b = (f.v[2] - f.v[0]).dot(u);
        const double flo = std::min({0.0, a, b}), fhi = std::max({0.0, a, b});
        if (flo >= hi - margin || fhi <= lo + margin) return false;
      }
  }
  return true;
}

bool may_enter(const FaceData& f, const ClusterShaft& s, double margin) {
  const double gap = 2 * margin;
  if ((f.hi.array() < s.lo.array() - gap).any() || (f.lo.array() > s.hi.array() + gap).any()) return false;
  const auto [lo, hi] = extent(s.x.data(), 6, f.v[0], f.n);
  if (lo > gap || hi < -gap) return false;  // the shaft on one side of the face's plane
  for (int k = 0; k < s.planes; ++k) {
    const Vec3& n = s.out_n[static_cast<std::size_t>(k)];
    const double d = s.out_d[static_cast<std::size_t>(k)];
    if (std::min({n.dot(f.v[0]), n.dot(f.v[1]), n.dot(f.v[2])}) - d > gap) return false;
  }
  return true;
}

bool covers_cluster_shaft(const FaceData& f, const ClusterShaft& s, double margin) {
  const double k = kCoverMargins * margin;
  std::array<double, 6> d{};
  for (std::size_t i = 0; i < 6; ++i) d[i] = (s.x[i] - f.v[0]).dot(f.n);
  const double side = d[0] > 0 ? 1.0 : -1.0;
  for (std::size_t i = 0; i < 6; ++i)
    if (!((i < 3 ? side : -side) * d[i] > k)) return false;  // sigma on one side, tau on the other
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 3; j < 6; ++j) {
      const Vec3 X = s.x[i] + (d[i] / (d[i] - d[j])) * (s.x[j] - s.x[i]);
      for (std::size_t e = 0; e < 3; ++e)
        if (!((X - f.v[e]).dot(f.edge_in[e]) > k)) return false;
    }
  return true;
}

}  // namespace panelrad::geometry::occluder_detail

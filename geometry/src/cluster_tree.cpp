// The cluster tree U = T_{n_0} u ... u T_{n_c} (39)-(40) of uniform 4-way midpoint subdivision,
// with the circumcircle centre A(tau) and radius R(tau) of (41) from exact constructions.
//
// Exactness: every double is a dyadic rational, so the circumcentre's numerator and denominator
// (polynomials in the corner coordinates) are evaluated without any rounding in CGAL::Mpzf
// (CGAL's multi-precision binary floating point: ring operations are exact and, unlike a rational
// type, need no gcd). Each result is then rounded once, to nearest (ties to even), by exact
// comparison with the midpoints between neighbouring doubles. Measured on this machine: a lazy
// Epeck circumcenter + squared_distance forced exact costs about 40 us per triangle (10 s for the
// 262k clusters of the cube's level 7); the Mpzf evaluation is more than ten times cheaper.
#include <panelrad/geometry/cluster_tree.hpp>
#include <panelrad/support/byte_size.hpp>
#include <panelrad/support/parallel_for.hpp>
#include <panelrad/geometry/planar_facets.hpp>
#include <panelrad/geometry/subdivision.hpp>

#include <panelrad/geometry/bounding_box.hpp>

#include <CGAL/Gmpq.h>
#include <CGAL/Mpzf.h>

#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <sstream>
#include <string>

namespace panelrad::geometry {

namespace {

using CGAL::Mpzf;

/// -1, 0, +1 for a < b, a == b, a > b (exact).
int compare(const Mpzf& a, const Mpzf& b) { return a < b ? -1 : (b < a ? 1 : 0); }

bool mantissa_even(double q) { return (std::bit_cast<std::uint64_t>(q) & 1u) == 0; }

/// Rounds a real x to the nearest double (ties to even), starting from an approximation and
/// moving by one ulp while x lies beyond the midpoint to a neighbour. side(lo, hi) must return the
/// exact sign of x - (lo + hi) / 2 for adjacent doubles lo < hi. NaN when x is out of range.
template <class Side>
double round_to_nearest(double approx, Side&& side) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  double q = approx;
  for (int step = 0; step < 256 && std::isfinite(q); ++step) {
    const double up = std::nextafter(q, inf);
    const double dn = std::nextafter(q, -inf);
    if (!std::isfinite(up) || !std::isfinite(dn)) break;
    const int above = side(q, up);
    if (above > 0) {
      q = up;
      continue;
    }
    if (above == 0) return mantissa_even(q) ? q : up;
    const int below = side(dn, q);
    if (below < 0) {
      q = dn;
      continue;
    }
    if (below == 0) return mantissa_even(q) ? q : dn;
    return q;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

/// num / den ~ m 2^e (m > 0 within a few ulps, any exponent), num != 0, den != 0, through GMP
/// integers: used when the quotient or the parts leave the range of a double.
void approximate_scaled(const Mpzf& num, const Mpzf& den, double& m, long& e) {
  const CGAL::Gmpq qn(num), qd(den);  // exact: num = a / b, den = c / d, num / den = a d / (b c)
  long ea = 0, eb = 0, ec = 0, ed = 0;
  const double a = mpz_get_d_2exp(&ea, mpq_numref(qn.mpq())), b = mpz_get_d_2exp(&eb, mpq_denref(qn.mpq()));
  const double c = mpz_get_d_2exp(&ec, mpq_numref(qd.mpq())), d = mpz_get_d_2exp(&ed, mpq_denref(qd.mpq()));
  m = std::abs((a * d) / (b * c));
  e = ea + ed - eb - ec;
}

double ldexp_long(double m, long e) {
  return std::ldexp(m, static_cast<int>(std::clamp(e, -100000L, 100000L)));
}

/// A double approximation of num / den (den != 0), within a few ulps when representable.
double approximate_quotient(const Mpzf& num, const Mpzf& den) {
  if (num.is_zero()) return 0;
  const double n = num.to_double(), d = den.to_double(), q = n / d;
  if (std::isnormal(n) && std::isnormal(d) && std::isnormal(q)) return q;
  double m = 0;
  long e = 0;
  approximate_scaled(num, den, m, e);
  const double r = ldexp_long(m, e);
  return (num.sign() == den.sign()) ? r : -r;
}

/// A double approximation of sqrt(num / den), num >= 0, den > 0.
double approximate_sqrt_quotient(const Mpzf& num, const Mpzf& den) {
  if (num.is_zero()) return 0;
  const double n = num.to_double(), d = den.to_double(), q = n / d;
  if (std::isnormal(n) && std::isnormal(d) && std::isnormal(q)) return std::sqrt(q);
  double m = 0;
  long e = 0;
  approximate_scaled(num, den, m, e);
  if (e % 2 != 0) {
    m *= 2;
    e -= 1;
  }
  return ldexp_long(std::sqrt(m), e / 2);
}

/// num / den rounded to nearest, den > 0.
double round_quotient(const Mpzf& num, const Mpzf& den) {
  const Mpzf twice_num = num + num;
  return round_to_nearest(approximate_quotient(num, den), [&](double lo, double hi) {
    return compare(twice_num, (Mpzf(lo) + Mpzf(hi)) * den);  // sign of num/den - (lo+hi)/2
  });
}

/// sqrt(num / den) rounded to nearest, num >= 0, den > 0.
double round_sqrt_quotient(const Mpzf& num, const Mpzf& den) {
  const Mpzf four_num = Mpzf(4) * num;
  return round_to_nearest(approximate_sqrt_quotient(num, den), [&](double lo, double hi) {
    if (lo < 0) return 1;  // sqrt >= 0 lies above any midpoint with a negative end
    const Mpzf m = Mpzf(lo) + Mpzf(hi);
    return compare(four_num, m * m * den);  // sign of sqrt(num/den) - (lo+hi)/2
  });
}

struct ExactVec {
  Mpzf x, y, z;
};

ExactVec exact(const Vec3& v) { return {Mpzf(v.x()), Mpzf(v.y()), Mpzf(v.z())}; }
ExactVec operator-(const ExactVec& a, const ExactVec& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
ExactVec cross(const ExactVec& a, const ExactVec& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Mpzf dot(const ExactVec& a, const ExactVec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

std::string describe(const Vec3& v) {
  std::ostringstream s;
  s.precision(17);
  s << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return s.str();
}

/// Circumcircle centre A and radius R (41) of the triangle (a, b, c), exact and rounded once.
/// With u = b - a, v = c - a, w = u x v: A = a + N / D, N = (|u|^2 v - |v|^2 u) x w, D = 2 |w|^2,
/// R = |N| / D. Throws MeshError (naming `where`) when the corners are collinear.
void circumcircle(const Vec3& a, const Vec3& b, const Vec3& c, Vec3& centre, double& radius, const char* where,
                  Index k) {
  const ExactVec ea = exact(a);
  const ExactVec u = exact(b) - ea, v = exact(c) - ea;
  const ExactVec w = cross(u, v);
  const Mpzf ww = dot(w, w);
  if (ww.is_zero()) {
    std::ostringstream msg;
    msg << "cluster tree: " << where << " triangle " << k << " has zero area (corners " << describe(a) << ", "
        << describe(b) << ", " << describe(c) << ")";
    throw MeshError(msg.str());
  }
  const Mpzf uu = dot(u, u), vv = dot(v, v);
  const ExactVec N = cross(ExactVec{uu * v.x - vv * u.x, uu * v.y - vv * u.y, uu * v.z - vv * u.z}, w);
  const Mpzf D = Mpzf(2) * ww;
  centre = Vec3(round_quotient(ea.x * D + N.x, D), round_quotient(ea.y * D + N.y, D),
                round_quotient(ea.z * D + N.z, D));
  radius = round_sqrt_quotient(dot(N, N), D * D);
  if (!centre.allFinite() || !std::isfinite(radius)) {
    std::ostringstream msg;
    msg << "cluster tree: " << where << " triangle " << k << ": circumcircle outside the double range (corners "
        << describe(a) << ", " << describe(b) << ", " << describe(c) << ")";
    throw MeshError(msg.str());
  }
}

/// v scaled by the power of two 2^-e that brings its largest component into [1, 2) (exact), so
/// that norms neither overflow nor underflow; e is returned. v must be non-zero and finite.
Vec3 scaled_to_unit_range(const Vec3& v, int& e) {
  e = std::ilogb(v.cwiseAbs().maxCoeff());
  return Vec3(std::ldexp(v.x(), -e), std::ldexp(v.y(), -e), std::ldexp(v.z(), -e));
}

/// |v| without overflow or underflow in the squares (and exactly scale-covariant by 2^k).
double length(const Vec3& v) {
  if ((v.array() == 0.0).all()) return 0;
  int e = 0;
  const Vec3 s = scaled_to_unit_range(v, e);
  return std::ldexp(s.norm(), e);
}

constexpr int max_level = 15;  // n0 * 4^16 > 2^31 - 1 for every n0 >= 1

/// The clusters on levels 0..level of n0 roots, n0 (4^(level+1) - 1) / 3, for level <= max_level
/// (below 2^63).
long long clusters_up_to(Index n0, int level) {
  long long clusters = 0;
  for (int l = 0; l <= level; ++l) clusters += static_cast<long long>(n0) << (2 * l);
  return clusters;
}

/// n0 4^level: exact below 2^63, else as "about 1.45e+25" (from its logarithm: any level).
std::string element_count(Index n0, int level) {
  if (level <= 30 && std::bit_width(static_cast<unsigned long long>(n0)) + 2 * level < 63)
    return std::to_string(static_cast<long long>(n0) << (2 * level));
  const double lg = std::log10(static_cast<double>(n0)) + static_cast<double>(level) * std::log10(4.0);
  const double exponent = std::floor(lg);
  char buf[48];
  std::snprintf(buf, sizeof buf, "about %.3ge+%.0f", std::pow(10.0, lg - exponent), exponent);
  return buf;
}

}  // namespace

std::string level_size_problem(Index n0, int level) {
  const long long index_max = std::numeric_limits<Index>::max();
  const auto fits = [&](int l) { return l <= max_level && clusters_up_to(n0, l) <= index_max; };
  if (n0 < 1 || level < 0 || fits(level)) return "";
  int largest = 0;  // level 0 has n0 <= index_max clusters
  while (fits(largest + 1)) ++largest;
  std::ostringstream msg;
  msg << "level " << level << " gives n = " << n0 << " * 4^" << level << " = " << element_count(n0, level)
      << " elements";
  const bool elements_fit = level <= max_level && (static_cast<long long>(n0) << (2 * level)) <= index_max;
  if (elements_fit) msg << " in " << clusters_up_to(n0, level) << " clusters on all levels";
  msg << ", more than the " << index_max << " that the 32-bit indices of the elements and clusters can number: level "
      << largest << " is the largest for " << n0 << " triangles";
  return msg.str();
}

namespace {

/// n0, the number of level-0 triangles, after checking the level and the mesh's sizes.
Index checked_root_count(const TriangleMesh& mesh, int finest_level, const std::string& name) {
  if (finest_level < 0)
    throw MeshError("cluster tree of " + name + ": level " + std::to_string(finest_level) + " is negative");
  if (mesh.triangles.empty()) throw MeshError("cluster tree of " + name + ": the mesh has no triangles");
  if (mesh.triangles.size() > static_cast<std::size_t>(std::numeric_limits<Index>::max()))
    throw MeshError("cluster tree of " + name + ": too many triangles for 32-bit indices");
  const Index n0 = static_cast<Index>(mesh.triangles.size());
  if (mesh.facet_of_triangle.size() != mesh.triangles.size())
    throw MeshError("cluster tree of " + name + ": " + std::to_string(mesh.facet_of_triangle.size()) +
                    " facet ids for " + std::to_string(n0) + " triangles");
  return n0;
}

/// Refuses a tree whose n = n0 4^L elements or whose clusters on all levels (< 4n/3) do not fit
/// Index (level_size_problem), and one whose estimated size exceeds memory_limit_bytes; before
/// any allocation.
void refuse_oversized_tree(Index n0, int finest_level, std::size_t memory_limit_bytes, const std::string& name) {
  if (const std::string problem = level_size_problem(n0, finest_level); !problem.empty())
    throw MeshError("cluster tree of " + name + ": " + problem);
  const std::size_t estimate = ClusterTree::estimate_bytes(n0, finest_level);
  if (estimate > memory_limit_bytes) {
    std::ostringstream msg;
    msg << "cluster tree of " << name << ": level " << finest_level << " (n = " << (static_cast<long long>(n0) << (2 * finest_level))
        << " elements) needs an estimated " << format_bytes(static_cast<double>(estimate)) << ", more than the "
        << format_bytes(static_cast<double>(memory_limit_bytes)) << " of memory available; choose a lower level";
    throw MeshError(msg.str());
  }
}

/// Every triangle's facet id lies in [0, num_facets), its vertex indices in the vertex list, and
/// the coordinates of those vertices are finite.
void check_triangle_references(const TriangleMesh& mesh, Index n0, const std::string& name) {
  for (Index k = 0; k < n0; ++k) {
    const Index f = mesh.facet_of_triangle[static_cast<std::size_t>(k)];
    if (f < 0 || f >= mesh.num_facets)
      throw MeshError("cluster tree of " + name + ": triangle " + std::to_string(k) + " has facet id " +
                      std::to_string(f) + " outside [0, " + std::to_string(mesh.num_facets) + ")");
    for (Index v : mesh.triangles[static_cast<std::size_t>(k)]) {
      if (v < 0 || static_cast<std::size_t>(v) >= mesh.vertices.size())
        throw MeshError("cluster tree of " + name + ": triangle " + std::to_string(k) + " uses vertex " +
                        std::to_string(v) + ", outside [0, " + std::to_string(mesh.vertices.size()) + ")");
      if (!mesh.vertices[static_cast<std::size_t>(v)].allFinite())
        throw MeshError("cluster tree of " + name + ": vertex " + std::to_string(v) + " " +
                        describe(mesh.vertices[static_cast<std::size_t>(v)]) + " is not finite");
    }
  }
}

/// Root cluster k of T_{n_0}: triangle k of the mesh with its facet, circumcircle (41), inner
/// normal (2) and area.
void make_root(Cluster& c, const TriangleMesh& mesh, Index k, const std::string& name) {
  const auto& t = mesh.triangles[static_cast<std::size_t>(k)];
  for (int i = 0; i < 3; ++i) c.vertex[static_cast<std::size_t>(i)] = mesh.vertices[static_cast<std::size_t>(t[static_cast<std::size_t>(i)])];
  c.facet = mesh.facet_of_triangle[static_cast<std::size_t>(k)];
  circumcircle(c.vertex[0], c.vertex[1], c.vertex[2], c.centre, c.radius, "level 0", k);
  // Outward normal w = (b - a) x (c - a) (counter-clockwise seen from outside): exact, each
  // component rounded once; the inner normal (2) is -w / |w|. Area |w| / 2 rounded once.
  const ExactVec ea = exact(c.vertex[0]);
  const ExactVec w = cross(exact(c.vertex[1]) - ea, exact(c.vertex[2]) - ea);
  const Vec3 wd(round_quotient(w.x, Mpzf(1)), round_quotient(w.y, Mpzf(1)), round_quotient(w.z, Mpzf(1)));
  c.area = round_sqrt_quotient(dot(w, w), Mpzf(4));
  if (!wd.allFinite() || (wd.array() == 0.0).all() || !(c.area > 0) || !std::isfinite(c.area))
    throw MeshError("cluster tree of " + name + ": triangle " + std::to_string(k) +
                    ": normal or area outside the double range (corners " + describe(c.vertex[0]) + ", " +
                    describe(c.vertex[1]) + ", " + describe(c.vertex[2]) + ")");
  int e = 0;
  const Vec3 ws = scaled_to_unit_range(wd, e);  // exact power-of-two scaling: no under/overflow
  c.normal = -ws / ws.norm();
}

/// Level l+1 from level l (39)-(40): children 4k .. 4k+3 of triangle k are its midpoint
/// subdivision, with the parent's plane, facet and a quarter of its area.
void subdivide_level(const UninitializedVector<Cluster>& parents, UninitializedVector<Cluster>& children, int child_level) {
  children.resize(parents.size() * 4);
  const std::string where = "level " + std::to_string(child_level);
  parallel_for(static_cast<Index>(parents.size()), [&](Index k) {
    const Cluster& p = parents[static_cast<std::size_t>(k)];
    const std::array<std::array<Vec3, 3>, 4> corners = midpoint_subdivision(p.vertex[0], p.vertex[1], p.vertex[2]);
    for (std::size_t j = 0; j < 4; ++j) {
      const Index id = 4 * k + static_cast<Index>(j);
      Cluster& child = children[static_cast<std::size_t>(id)];
      child.vertex = corners[j];
      child.normal = p.normal;
      child.area = p.area * 0.25;  // exact (no underflow for any area of a double triangle we accept)
      child.facet = p.facet;
      circumcircle(child.vertex[0], child.vertex[1], child.vertex[2], child.centre, child.radius, where.c_str(), id);
    }
  });
}

/// Collocation points P_k (22): the centroids (a + b + c) / 3 of the elements, exact and rounded once.
UninitializedVector<Vec3> element_centroids(const UninitializedVector<Cluster>& leaves) {
  const Index n = static_cast<Index>(leaves.size());
  UninitializedVector<Vec3> centroid(static_cast<std::size_t>(n));
  parallel_for(n, [&](Index k) {
    const Cluster& e = leaves[static_cast<std::size_t>(k)];
    const Mpzf three(3);
    Vec3 g;
    for (int i = 0; i < 3; ++i)  // (a + b + c) / 3, exact and rounded once
      g[i] = round_quotient(Mpzf(e.vertex[0][i]) + Mpzf(e.vertex[1][i]) + Mpzf(e.vertex[2][i]), three);
    centroid[static_cast<std::size_t>(k)] = g;
  });
  return centroid;
}

/// Mesh size h: the longest edge of the elements (section 3).
double longest_edge(const UninitializedVector<Cluster>& leaves) {
  const Index n = static_cast<Index>(leaves.size());
  double h = 0;
#pragma omp parallel for schedule(static) reduction(max : h)
  for (Index k = 0; k < n; ++k) {
    const auto& v = leaves[static_cast<std::size_t>(k)].vertex;
    h = std::max({h, length(v[1] - v[0]), length(v[2] - v[1]), length(v[0] - v[2])});
  }
  return h;
}

}  // namespace

std::size_t ClusterTree::default_memory_limit() {
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page_size = ::sysconf(_SC_PAGESIZE);
  if (pages <= 0 || page_size <= 0) return std::numeric_limits<std::size_t>::max();
  return static_cast<std::size_t>(pages) * static_cast<std::size_t>(page_size);
}

std::size_t ClusterTree::estimate_bytes(Index n0, int finest_level) {
  if (n0 <= 0 || finest_level < 0) return 0;
  // Clusters on all levels: n0 (4^(L+1) - 1) / 3; plus one centroid per element.
  long double clusters = 0, level_size = n0;
  for (int l = 0; l <= finest_level; ++l, level_size *= 4) clusters += level_size;
  const long double elements = level_size / 4;
  const long double bytes = clusters * sizeof(Cluster) + elements * sizeof(Vec3) +
                            (finest_level + 1.0L) * sizeof(UninitializedVector<Cluster>) + sizeof(ClusterTree);
  if (bytes >= static_cast<long double>(std::numeric_limits<std::size_t>::max()))
    return std::numeric_limits<std::size_t>::max();
  return static_cast<std::size_t>(bytes);
}

std::size_t ClusterTree::bytes() const {
  std::size_t total = sizeof(ClusterTree) + levels_.capacity() * sizeof(UninitializedVector<Cluster>);
  for (const auto& level : levels_) total += level.capacity() * sizeof(Cluster);
  return total + centroid_.capacity() * sizeof(Vec3) + root_plane_.capacity() * sizeof(Index);
}

ClusterTree::ClusterTree(const TriangleMesh& mesh, int finest_level)
    : ClusterTree(mesh, finest_level, default_memory_limit()) {}

ClusterTree::ClusterTree(const TriangleMesh& mesh, int finest_level, std::size_t memory_limit_bytes,
                         PlaneGrouping planes) {
  const std::string name = mesh.source.empty() ? std::string("mesh") : "mesh '" + mesh.source + "'";
  // --- checks before any allocation --------------------------------------------------------------
  const Index n0 = checked_root_count(mesh, finest_level, name);
  refuse_oversized_tree(n0, finest_level, memory_limit_bytes, name);
  check_triangle_references(mesh, n0, name);

  finest_level_ = finest_level;
  n0_ = n0;
  num_facets_ = mesh.num_facets;
  levels_.resize(static_cast<std::size_t>(finest_level) + 1);

  // --- level 0: the mesh's triangles, in mesh order ----------------------------------------------
  UninitializedVector<Cluster>& roots = levels_[0];
  roots.resize(static_cast<std::size_t>(n0));
  parallel_for(n0, [&](Index k) { make_root(roots[static_cast<std::size_t>(k)], mesh, k, name); });

  // --- level l+1 from level l, (39)-(40) ---------------------------------------------------------
  for (int l = 0; l < finest_level; ++l)
    subdivide_level(levels_[static_cast<std::size_t>(l)], levels_[static_cast<std::size_t>(l) + 1], l + 1);

  // --- collocation points (22), mesh size, diameter ----------------------------------------------
  centroid_ = element_centroids(levels_.back());
  mesh_size_ = longest_edge(levels_.back());
  std::vector<Vec3> corners;  // of the level-0 triangles: the surface's bounding box
  corners.reserve(3 * roots.size());
  for (const Cluster& root : roots) corners.insert(corners.end(), root.vertex.begin(), root.vertex.end());
  diameter_ = bounding_box_diameter(corners);

  // --- supporting planes of the roots (coplanar clusters, section 4.2 case (a)) -------------------
  root_plane_ = triangle_planes(mesh, planes);
  for (Index p : root_plane_) num_planes_ = std::max(num_planes_, p + 1);
}

}  // namespace panelrad::geometry

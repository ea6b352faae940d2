// Triangulation of one polygonal input face (polygon_triangulation.hpp).
//
// Distinctness, collinearity, simplicity and orientation are decided by exact predicates on the
// input coordinates (Epick: filtered double arithmetic with an exact fallback); only the plane
// (its normal, the distances from it, the projection axis) is computed in double precision, on
// coordinates scaled by a power of two (exact) so that no product overflows or underflows.
#include "polygon_triangulation.hpp"

#include "validation_internal.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numeric>
#include <optional>

namespace panelrad::geometry::polygon_detail {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point2 = K::Point_2;
using Point3 = K::Point_3;
using Sz = std::size_t;

// Vertices remember their corner number; faces their nesting level (number of polygon sides
// crossed from the unbounded face). Constraints may meet at existing vertices but never cross
// (a crossing would need a constructed point): a crossing raises
// Intersection_of_constraints_exception.
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<Index, K>;
using FaceBase = CGAL::Constrained_triangulation_face_base_2<K, CGAL::Triangulation_face_base_with_info_2<int, K>>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::No_constraint_intersection_requiring_constructions_tag>;

constexpr std::size_t kMaxDescribedCorners = 4096;  // above: the sides that meet are not searched for

/// "1st", "2nd", "3rd", "4th", ..., "11th", "21st".
std::string ordinal(Sz k) {
  const Sz mod100 = k % 100, mod10 = k % 10;
  const char* suffix = (mod100 >= 11 && mod100 <= 13) ? "th"
                       : mod10 == 1                     ? "st"
                       : mod10 == 2                     ? "nd"
                       : mod10 == 3                     ? "rd"
                                                        : "th";
  return std::to_string(k) + suffix;
}

std::string coordinates(const Vec3& p) {
  using validation_detail::num;
  std::string s(1, '(');
  s.append(num(p.x())).append(", ").append(num(p.y())).append(", ").append(num(p.z())).append(")");
  return s;
}

/// "its 3rd vertex (x, y, z)": corner m (0-based) by its position in the face's list.
std::string corner(const std::vector<Vec3>& c, Sz m) { return ordinal(m + 1) + " vertex " + coordinates(c[m]); }

/// The side from corner m to corner m + 1.
std::string side(const std::vector<Vec3>& c, Sz m) {
  const Sz n = c.size();
  return "side from its " + corner(c, m) + " to its " + corner(c, (m + 1) % n);
}

const char* const kSplitSimple = "; split it into simple polygons or triangles";

/// Two corners at the same point (exact comparison), the first pair in the face's order.
std::optional<std::string> repeated_corner(const std::vector<Vec3>& c) {
  std::vector<Sz> order(c.size());
  std::iota(order.begin(), order.end(), Sz{0});
  const auto less = [&](Sz a, Sz b) {
    return std::lexicographical_compare(c[a].data(), c[a].data() + 3, c[b].data(), c[b].data() + 3);
  };
  std::stable_sort(order.begin(), order.end(), less);  // equal points stay in face order
  std::optional<std::pair<Sz, Sz>> first;
  for (Sz k = 1; k < order.size(); ++k)
    if (c[order[k - 1]] == c[order[k]]) {
      const std::pair<Sz, Sz> pair{order[k - 1], order[k]};
      if (!first || pair < *first) first = pair;
    }
  if (!first) return std::nullopt;
  return "lists one vertex twice: its " + ordinal(first->first + 1) + " and " + ordinal(first->second + 1) +
         " vertices are both " + coordinates(c[first->first]) + " (a polygon passes each corner once)" + kSplitSimple;
}

/// Every corner on the line through the first two (which are distinct), exactly.
bool all_collinear(const std::vector<Vec3>& c) {
  const Point3 a(c[0].x(), c[0].y(), c[0].z()), b(c[1].x(), c[1].y(), c[1].z());
  for (Sz m = 2; m < c.size(); ++m)
    if (!CGAL::collinear(a, b, Point3(c[m].x(), c[m].y(), c[m].z()))) return false;
  return true;
}

/// The Newell plane of the polygon in coordinates scaled by `scale` (a power of two).
struct Plane {
  double scale = 1;
  Vec3 centroid = Vec3::Zero();  // scaled
  Vec3 normal = Vec3::Zero();    // Newell normal, scaled coordinates (not normalised)
  double size = 0;               // bounding-box diagonal, scaled
};

Plane newell_plane(const std::vector<Vec3>& c) {
  Plane pl;
  double largest = 0;
  for (const Vec3& p : c) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  int exponent = 0;
  std::frexp(largest, &exponent);
  pl.scale = std::ldexp(1.0, -exponent);  // largest * scale in [0.5, 1)
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Vec3& p : c) {
    const Vec3 q = p * pl.scale;
    pl.centroid += q;
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  pl.centroid /= static_cast<double>(c.size());
  pl.size = (hi - lo).norm();
  for (Sz m = 0; m < c.size(); ++m) {
    const Vec3 a = c[m] * pl.scale - pl.centroid, b = c[(m + 1) % c.size()] * pl.scale - pl.centroid;
    pl.normal += a.cross(b);
  }
  return pl;
}

/// Corners farther from the Newell plane than the flatness tolerance (polygon_triangulation.hpp):
/// the refusal when beyond kFlatnessLimit of the polygon's size, else the note.
struct Flatness {
  bool refused = false;
  std::string text;  ///< empty: planar within the tolerance
};
Flatness not_planar(const std::vector<Vec3>& c, const Plane& pl, double eta) {
  const Vec3 unit = pl.normal.normalized();
  const double tolerance = std::max(kFlatnessRelative * pl.size, kFlatnessRoundings * eta * pl.scale);
  Sz worst = 0;
  double farthest = -1;
  for (Sz m = 0; m < c.size(); ++m) {
    const double d = std::abs((c[m] * pl.scale - pl.centroid).dot(unit));
    if (d > farthest) {
      farthest = d;
      worst = m;
    }
  }
  if (farthest <= tolerance) return {};
  using validation_detail::num;
  using validation_detail::sci;
  const std::string where = "its " + corner(c, worst) + " lies " + sci(farthest / pl.scale) +
                            " from the plane through the centroid of its vertices with its Newell normal, more than "
                            "the tolerance " +
                            sci(tolerance / pl.scale) + " = max(" + num(kFlatnessRelative) + " x its size " +
                            sci(pl.size / pl.scale) + ", " + num(kFlatnessRoundings) + " x the rounding " + sci(eta) +
                            " of the file's coordinates)";
  if (farthest > kFlatnessLimit * pl.size)
    return {true, "is not planar: " + where + " and more than " + num(kFlatnessLimit) +
                      " of its size; split it into planar polygons or triangles" +
                      validation_detail::more_digits_hint(validation_detail::printed_rounding(c, pl.size / pl.scale), farthest / pl.scale,
                                                          kFlatnessRoundings, pl.size / pl.scale)};
  return {false, "is not exactly planar: " + where + "; it is triangulated as projected along its normal, each "
                 "triangle in its own plane"};
}

/// Two sides that meet other than at the corner they share, by exact predicates (O(n^2): only
/// to name them once the polygon is refused).
std::optional<std::pair<Sz, Sz>> sides_that_meet(const std::vector<Point2>& p) {
  const Sz n = p.size();
  if (n > kMaxDescribedCorners) return std::nullopt;
  for (Sz i = 0; i < n; ++i) {
    const Point2 &a = p[i], &b = p[(i + 1) % n], &c = p[(i + 2) % n];
    // Consecutive sides a-b, b-c overlap when c lies on the ray from b through a, or at b.
    if (CGAL::collinear(a, b, c) && !CGAL::collinear_are_strictly_ordered_along_line(a, b, c))
      return std::pair{i, (i + 1) % n};
  }
  for (Sz i = 0; i < n; ++i)
    for (Sz j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // consecutive through corner 0
      if (CGAL::do_intersect(K::Segment_2(p[i], p[(i + 1) % n]), K::Segment_2(p[j], p[(j + 1) % n])))
        return std::pair{i, j};
    }
  return std::nullopt;
}

std::string crosses_itself(const std::vector<Vec3>& c, const std::vector<Point2>& p) {
  if (const auto s = sides_that_meet(p))
    return "crosses or touches itself: its " + side(c, s->first) + " meets its " + side(c, s->second) +
           " (seen along its normal)" + kSplitSimple;
  return "crosses or touches itself (two of its sides meet other than at a shared corner)" + std::string(kSplitSimple);
}

/// The fan (p_0, p_k, p_{k+1}) is a triangulation of the polygon: every fan triangle has the same
/// strict orientation, and the directions p_k - p_0 turn monotonically by less than a full turn
/// (then the triangles lie in disjoint angular sectors at p_0 and the polygon is simple).
bool fan_is_triangulation(const std::vector<Point2>& p) {
  const Sz n = p.size();
  const CGAL::Orientation s = CGAL::orientation(p[0], p[1], p[2]);
  if (s == CGAL::COLLINEAR) return false;
  for (Sz k = 2; k + 1 < n; ++k)
    if (CGAL::orientation(p[0], p[k], p[k + 1]) != s) return false;
  // The angle from p_1 - p_0 to p_k - p_0, in the direction s, increases with k by less than pi per
  // step; it stays below 2 pi while it does not return to the side of the line (p_0, p_1) it started on.
  bool past_half_turn = false;
  for (Sz k = 2; k < n; ++k) {
    const CGAL::Orientation o = CGAL::orientation(p[0], p[1], p[k]);
    if (o == s) {
      if (past_half_turn) return false;
    } else if (o == CGAL::COLLINEAR) {
      // Direction of p_1 again (a full turn), or the opposite direction (a half turn).
      if (!CGAL::collinear_are_strictly_ordered_along_line(p[1], p[0], p[k])) return false;
      past_half_turn = true;
    } else {
      past_half_turn = true;
    }
  }
  return true;
}

/// Orientation of a simple polygon: the turn at its lexicographically smallest corner, a strictly
/// convex corner.
CGAL::Orientation simple_polygon_orientation(const std::vector<Point2>& p) {
  const Sz n = p.size();
  const Sz m = static_cast<Sz>(std::min_element(p.begin(), p.end()) - p.begin());
  return CGAL::orientation(p[(m + n - 1) % n], p[m], p[(m + 1) % n]);
}

/// Faces of `cdt` at odd nesting level: inside the polygon. The level of a face is the number of
/// constrained edges crossed on a path from the unbounded face (the fewest such, found by flooding
/// level by level).
std::vector<Cdt::Face_handle> inside_faces(Cdt& cdt) {
  for (const Cdt::Face_handle f : cdt.all_face_handles()) f->info() = -1;
  std::vector<Cdt::Face_handle> seeds{cdt.infinite_face()}, next, stack;
  std::vector<Cdt::Face_handle> inside;
  for (int level = 0; !seeds.empty(); ++level) {
    next.clear();
    for (const Cdt::Face_handle seed : seeds) {
      if (seed->info() != -1) continue;
      seed->info() = level;
      stack.assign(1, seed);
      while (!stack.empty()) {
        const Cdt::Face_handle f = stack.back();
        stack.pop_back();
        if (level % 2 == 1 && !cdt.is_infinite(f)) inside.push_back(f);
        for (int i = 0; i < 3; ++i) {
          const Cdt::Face_handle g = f->neighbor(i);
          if (g->info() != -1) continue;
          if (cdt.is_constrained(Cdt::Edge(f, i))) {
            next.push_back(g);
          } else {
            g->info() = level;
            stack.push_back(g);
          }
        }
      }
    }
    seeds.swap(next);
  }
  return inside;
}

/// The constrained Delaunay triangulation of the projected polygon, restricted to its inside.
PolygonTriangulation constrained_triangulation(const std::vector<Vec3>& c, const std::vector<Point2>& p) {
  const Sz n = p.size();
  PolygonTriangulation out;
  Cdt cdt;
  std::vector<Cdt::Vertex_handle> vertex(n);
  for (Sz m = 0; m < n; ++m) {
    const std::size_t before = cdt.number_of_vertices();
    vertex[m] = cdt.insert(p[m]);
    if (cdt.number_of_vertices() == before) {
      const auto other = static_cast<Sz>(vertex[m]->info());
      out.refusal = "touches itself: its " + corner(c, other) + " and its " + corner(c, m) +
                    " are at the same point seen along its normal" + kSplitSimple;
      return out;
    }
    vertex[m]->info() = static_cast<Index>(m);
  }
  if (cdt.dimension() < 2) {
    out.refusal = "has zero area: its vertices lie on one straight line seen along its normal";
    return out;
  }
  try {
    for (Sz m = 0; m < n; ++m) cdt.insert_constraint(vertex[m], vertex[(m + 1) % n]);
  } catch (const Cdt::Intersection_of_constraints_exception&) {
    out.refusal = crosses_itself(c, p);
    return out;
  }
  // Simple: every side is one edge of the triangulation (no corner lies on it: the constraint
  // would have been split there), and no two sides cross (that threw above).
  for (Sz m = 0; m < n; ++m) {
    Cdt::Face_handle f;
    int i = 0;
    if (!cdt.is_edge(vertex[m], vertex[(m + 1) % n], f, i)) {
      out.refusal = crosses_itself(c, p);
      return out;
    }
  }
  const CGAL::Orientation s = simple_polygon_orientation(p);
  const std::vector<Cdt::Face_handle> inside = inside_faces(cdt);
  if (s == CGAL::COLLINEAR || inside.size() != n - 2) {
    out.refusal = crosses_itself(c, p);
    return out;
  }
  out.triangles.reserve(n - 2);
  for (const Cdt::Face_handle f : inside) {
    // Triangulation faces are counter-clockwise in the projection plane.
    const Index a = f->vertex(0)->info(), b = f->vertex(1)->info(), d = f->vertex(2)->info();
    if (s == CGAL::COUNTERCLOCKWISE)
      out.triangles.push_back({a, b, d});
    else
      out.triangles.push_back({a, d, b});
  }
  return out;
}

}  // namespace

PolygonTriangulation triangulate_polygon(const std::vector<Vec3>& corners, double eta) {
  const Sz n = corners.size();
  PolygonTriangulation out;
  if (n == 3) {
    out.triangles.push_back({0, 1, 2});
    return out;
  }
  if (auto why = repeated_corner(corners)) {
    out.refusal = *why;
    return out;
  }
  if (all_collinear(corners)) {
    out.refusal = "has zero area: its " + std::to_string(n) + " vertices lie on one straight line";
    return out;
  }
  const Plane plane = newell_plane(corners);
  // Newell's sum carries a rounding error of a few n u size^2: a normal below that has no direction.
  const double noise = 8.0 * static_cast<double>(n) * std::numeric_limits<double>::epsilon() * plane.size * plane.size;
  if (!(plane.normal.norm() > noise)) {
    out.refusal =
        "has no plane: its vector area (Newell normal) is zero to double precision, so it crosses itself or "
        "folds back onto itself" +
        std::string(kSplitSimple);
    return out;
  }
  if (Flatness flat = not_planar(corners, plane, eta); flat.refused) {
    out.refusal = flat.text;
    return out;
  } else {
    out.note = std::move(flat.text);
  }
  // Projection onto the coordinate plane dropping the largest Newell component k, axes (k+1, k+2)
  // (a right-handed frame with e_k: counter-clockwise there is a positive N_k).
  int k = 0;
  plane.normal.cwiseAbs().maxCoeff(&k);
  const int i = (k + 1) % 3, j = (k + 2) % 3;
  std::vector<Point2> p;
  p.reserve(n);
  for (const Vec3& q : corners) p.emplace_back(q[i], q[j]);

  if (fan_is_triangulation(p)) {
    out.triangles.reserve(n - 2);
    for (Sz m = 1; m + 1 < n; ++m) out.triangles.push_back({0, static_cast<Index>(m), static_cast<Index>(m + 1)});
    return out;
  }
  return constrained_triangulation(corners, p);
}

}  // namespace panelrad::geometry::polygon_detail

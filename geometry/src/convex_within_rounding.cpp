// Steps 2 and 3 of the convexity rule of validate_closed_convex: a violation that is not exactly 0
// but within what the rounding of the input coordinates can produce (input_rounding.hpp, bound(t, v)
// in validation.hpp) is accepted with a note; the exact side test still decides which vertex-plane
// pairs are violations, the bound only how large one may be. Anything larger is refused, naming the
// first non-convex triangle and the worst violation relative to the diameter.
#include "validation_internal.hpp"

#include <panelrad/geometry/input_rounding.hpp>

#include <algorithm>
#include <limits>

namespace panelrad::geometry::validation_detail {

namespace {

/// Every vertex strictly outside a triangle's plane (exact side test), with its distance outside
/// and its rounding bound.
struct Violations {
  Index first_tri = kNone, first_vertex = kNone;  // first non-convex triangle and its farthest vertex
  double first_dist = 0;
  double worst = 0;                               // largest distance outside
  Index worst_tri = kNone, worst_vertex = kNone;
  Sz examined = 0, pairs = 0;                     // triangles measured, violating pairs
  double worst_ratio = 0;                         // max distance / bound
  Index ratio_tri = kNone, ratio_vertex = kNone;
  double ratio_dist = 0, ratio_bound = 0;
  Index small_tri = kNone;                        // a violated triangle too small for the bound
};

Violations measure_violations(const TriangleMesh& mesh, const std::vector<Index>& bad, const Geometry& g,
                              double eta) {
  const auto nv = static_cast<Index>(mesh.vertices.size());
  Violations out;
  const Sz budget = 200'000'000;  // exact tests; only a mesh that is not exactly convex gets here
  for (Index t : bad) {
    if (out.examined * static_cast<Sz>(nv) > budget) break;
    ++out.examined;
    const Tri& tr = mesh.triangles[at(t)];
    const Vec3 &a = mesh.vertices[at(tr[0])], &b = mesh.vertices[at(tr[1])], &c = mesh.vertices[at(tr[2])];
    double tri_worst = -1;
    Index tri_vertex = kNone;
    for (Index v = 0; v < nv; ++v) {
      if (g.side(tr, v) != CGAL::POSITIVE) continue;
      const Vec3& p = mesh.vertices[at(v)];
      ++out.pairs;
      const double bound = rounding_bound(a, b, c, p, eta);
      if (bound < 0 && out.small_tri == kNone) out.small_tri = t;
      // The accurate distance only where it can matter: the first non-convex triangle, a new worst
      // violation, a new worst ratio to the bound, or a bound it may exceed.
      const double hi = plane_distance_upper(a, b, c, p);
      if (out.first_tri != kNone && hi <= out.worst && bound >= 0 && hi <= bound && hi <= out.worst_ratio * bound)
        continue;
      // The exact side test says outside; the distance is accurate, hence positive.
      const double dist = std::max(plane_distance(a, b, c, p), std::numeric_limits<double>::denorm_min());
      if (dist > tri_worst) {
        tri_worst = dist;
        tri_vertex = v;
      }
      if (dist > out.worst) {
        out.worst = dist;
        out.worst_tri = t;
        out.worst_vertex = v;
      }
      if (bound < 0) continue;
      const double ratio = dist / bound;
      if (ratio > out.worst_ratio || out.ratio_tri == kNone) {
        out.worst_ratio = ratio;
        out.ratio_tri = t;
        out.ratio_vertex = v;
        out.ratio_dist = dist;
        out.ratio_bound = bound;
      }
    }
    if (tri_vertex != kNone && out.first_tri == kNone) {
      out.first_tri = t;
      out.first_vertex = tri_vertex;
      out.first_dist = tri_worst;
    }
  }
  return out;
}

/// The convexity report: first triangle with a vertex strictly outside its plane (exact), that
/// vertex, and the worst distance outside over the non-convex triangles, relative to the diameter.
Failure convexity_failure(const TriangleMesh& mesh, const std::vector<Index>& bad, const Violations& m, double diam) {
  const Describe d{mesh};
  std::string msg = d.vertex(m.first_vertex) + " lies outside the plane of " + d.triangle(m.first_tri) + " by " +
                    sci(m.first_dist) + " (" + relative(m.first_dist, diam) +
                    " of the mesh diameter); worst violation " + relative(m.worst, diam) + " of the diameter over " +
                    std::to_string(bad.size()) + " non-convex triangles";
  if (m.examined < bad.size()) msg += " (measured on the first " + std::to_string(m.examined) + ")";
  return Failure{"convex", msg};
}

/// Why the violations are not attributed to the rounding of the input; empty when they are.
std::string rounding_refusal(const TriangleMesh& mesh, const std::vector<Index>& bad, const Violations& viol,
                             const InputRounding& rounding, double diam, const Geometry& g, const Vec3& inside) {
  const Describe d{mesh};
  if (viol.examined < bad.size())
    return "only " + std::to_string(viol.examined) + " of the " + std::to_string(bad.size()) +
           " non-convex triangles could be measured, too few to attribute the violation to rounding";
  if (viol.small_tri != kNone)
    return "the rounding of the input (" + rounding.describe() + ", up to " + sci(rounding.per_coordinate) +
           " per coordinate) is not small against the heights of " + d.triangle(viol.small_tri) +
           ", so it cannot be bounded there";
  if (viol.worst_ratio > 1)
    return "more than the rounding of the input explains: " + d.vertex(viol.ratio_vertex) +
           " lies outside the plane of triangle " + std::to_string(viol.ratio_tri) + " by " + sci(viol.ratio_dist) +
           ", " + sci(viol.ratio_dist / viol.ratio_bound) + " times the bound " + sci(viol.ratio_bound) + " that " +
           rounding.describe() + " allow there";
  if (viol.worst > kMaxRoundingViolation * diam)
    return "the worst violation is above " + sci(kMaxRoundingViolation) +
           " of the diameter, more than is ever attributed to rounding (" + rounding.describe() + ")";
  if (!winds_once_around(mesh, g, inside)) return "the surface does not wind once around an interior point";
  return {};
}

/// The note of an acceptance within rounding: the worst violation and what V = 1 may then miss.
std::string within_rounding_note(const TriangleMesh& mesh, const std::vector<Index>& bad, const Violations& viol,
                                 const InputRounding& rounding, double diam) {
  const Describe d{mesh};
  return "convex within the rounding of the input: " + d.vertex(viol.worst_vertex) + " lies outside the plane of " +
         d.triangle(viol.worst_tri) + " by " + sci(viol.worst) + " (" + relative(viol.worst, diam) +
         " of the diameter), the worst of " + std::to_string(viol.pairs) + " vertex-plane violations over " +
         std::to_string(bad.size()) + " triangles, each within its bound for " + rounding.describe() + " (" +
         sci(rounding.per_coordinate) + " per coordinate; largest violation/bound " + sci(viol.worst_ratio) +
         "); accepted as convex. V = 1 (mutual visibility) may then miss, at grazing incidence, a configuration "
         "factor of order tau/rho (tau the violation, rho the distance from the off-plane vertices): " +
         relative(viol.worst, 0.01 * diam) + " at rho = 1% of the diameter";
}

}  // namespace

std::optional<Failure> accept_within_rounding(const TriangleMesh& mesh, const std::vector<Index>& bad,
                                              const Geometry& g, const Vec3& inside, double diam,
                                              const std::string& hull_reason, ValidationReport& report) {
  const InputRounding rounding = input_rounding(mesh);
  const Violations viol = measure_violations(mesh, bad, g, rounding.per_coordinate);
  report.worst_convexity_violation = std::max(viol.worst / diam, std::numeric_limits<double>::denorm_min());
  const std::string reason = rounding_refusal(mesh, bad, viol, rounding, diam, g, inside);
  if (!reason.empty()) {
    const Failure failure = convexity_failure(mesh, bad, viol, diam);
    return Failure{failure.rule, failure.message + "; " + hull_reason + "; " + reason};
  }
  report.convex_within_rounding = true;
  report.worst_rounding_ratio = viol.worst_ratio;
  report.notes.push_back(within_rounding_note(mesh, bad, viol, rounding, diam));
  return std::nullopt;
}

}  // namespace panelrad::geometry::validation_detail

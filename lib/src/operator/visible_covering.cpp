#include "visible_covering.hpp"

#include <panelrad/quadrature/exact_integrals.hpp>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace panelrad {

namespace {

/// Sum of the form factors of convex pieces (corners points[end[k-1], end[k])).
double pieces_form_factor(const Vec3& P, const Vec3& nP, const std::vector<Vec3>& points,
                          const std::vector<std::uint32_t>& piece_end, const Vec3& nQ) {
  double sum = 0;
  std::uint32_t begin = 0;
  for (const std::uint32_t end : piece_end) {
    // A convex piece: one contour sum over its edges (quadrature::convex_polygon_form_factor).
    sum += quadrature::convex_polygon_form_factor(P, nP, points.data() + begin, static_cast<int>(end - begin), nQ);
    begin = end;
  }
  return sum;
}

/// Some edge (a, b) of the pieces passes closer to P than R / kNearEdgeRatio, R the larger distance
/// of P from a and b (max norm): the distance from P to the segment.
bool edge_passes_close(const Vec3& P, const std::vector<Vec3>& points, const std::vector<std::uint32_t>& piece_end) {
  std::uint32_t begin = 0;
  for (const std::uint32_t end : piece_end) {
    for (std::uint32_t k = begin; k < end; ++k) {
      const Vec3 wa = points[k] - P, wb = points[k + 1 < end ? k + 1 : begin] - P;
      const Vec3 d = wb - wa;
      const double R = std::max(wa.cwiseAbs().maxCoeff(), wb.cwiseAbs().maxCoeff());
      const double t = -wa.dot(d), d2 = d.squaredNorm();  // the foot on the segment's line at wa + (t / d2) d
      double distance2;
      if (!(t > 0) || !(d2 > 0)) distance2 = wa.squaredNorm();
      else if (t >= d2) distance2 = wb.squaredNorm();
      else distance2 = wa.cross(wb).squaredNorm() / d2;
      if (distance2 * (quadrature::kNearEdgeRatio * quadrature::kNearEdgeRatio) < R * R) return true;
    }
    begin = end;
  }
  return false;
}

}  // namespace

double visible_form_factor(const Vec3& P, const Vec3& nP, const geometry::VisiblePart& part,
                           const std::array<Vec3, 3>& tau, const Vec3& nQ) {
  const double visible = pieces_form_factor(P, nP, part.points, part.piece_end, nQ);
  if (!part.whole_front || !edge_passes_close(P, part.points, part.piece_end) ||
      edge_passes_close(P, part.covered_points, part.covered_end))
    return visible;
  return quadrature::form_factor(P, nP, tau[0], tau[1], tau[2], nQ) -
         pieces_form_factor(P, nP, part.covered_points, part.covered_end, nQ);
}

}  // namespace panelrad

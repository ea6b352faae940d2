#include "visible_covering.hpp"

#include <panelrad/quadrature/exact_integrals.hpp>

namespace panelrad {

double visible_form_factor(const Vec3& P, const Vec3& nP, const geometry::VisiblePart& part, const Vec3& nQ) {
  double sum = 0;
  std::uint32_t begin = 0;
  for (const std::uint32_t end : part.piece_end) {
    // A convex piece (p_0 .. p_m-1) is the fan of triangles (p_0, p_k, p_k+1); the form factor is
    // additive over them, each by the contour formula of quadrature::form_factor.
    // A fan triangle of zero area (repeated or collinear corners of a clipped piece) adds nothing
    // and is skipped: the contour formula needs edges of positive length.
    for (std::uint32_t k = begin + 1; k + 1 < end; ++k) {
      const Vec3 &a = part.points[begin], &b = part.points[k], &c = part.points[k + 1];
      if ((b - a).cross(c - a).squaredNorm() == 0) continue;
      sum += quadrature::form_factor(P, nP, a, b, c, nQ);
    }
    begin = end;
  }
  return sum;
}

}  // namespace panelrad

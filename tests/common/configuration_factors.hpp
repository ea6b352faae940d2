#pragma once
// Closed-form point-to-rectangle configuration factors, for tests: truths independent of the
// contour-integral form factor (1/pi) Int G dS of quadrature/exact_integrals.hpp (paper (2)), with
// and without an occluder (the visibility V(P, Q) of the radiosity equation (1)).
//
// The classical factor from a differential element dA at the origin, its normal +z, to the
// rectangle [0, a] x [0, b] in the parallel plane z = c > 0 (one corner above dA; Siegel and
// Howell, "Thermal Radiation Heat Transfer"; e.g.
// http://naturalfrequency.com/Tregenza_Sharples/Daylight_Algorithms/algorithm_3_14.htm):
//   F(a, b) = (1/2pi) [ A/sqrt(1+A^2) atan(B/sqrt(1+A^2)) + B/sqrt(1+B^2) atan(A/sqrt(1+B^2)) ],
// A = a/c, B = b/c; it is (1/pi) Int Int c^2 / (x^2 + y^2 + c^2)^2 dx dy over the rectangle. The
// expression is odd in A and in B separately, as the integral over [0, a] x [0, b] is for signed
// a, b; so any rectangle [x0, x1] x [y0, y1] (offsets from the foot of dA) is the signed
// superposition F(x1, y1) - F(x0, y1) - F(x1, y0) + F(x0, y0).
#include <algorithm>
#include <cmath>

namespace panelrad::testing {

/// An axis-aligned rectangle [x0, x1] x [y0, y1] in a plane z = const (x0 <= x1, y0 <= y1 when not
/// empty).
struct AxisRectangle {
  double x0, x1, y0, y1;
  bool empty() const { return !(x0 < x1 && y0 < y1); }
};

/// The intersection of two rectangles; empty() when they do not overlap (or only touch).
inline AxisRectangle intersection(const AxisRectangle& r, const AxisRectangle& s) {
  return {std::max(r.x0, s.x0), std::min(r.x1, s.x1), std::max(r.y0, s.y0), std::min(r.y1, s.y1)};
}

/// The corner factor F(a, b) above, for signed corner offsets a, b and height c > 0.
inline double parallel_corner_factor(double a, double b, double c) {
  constexpr double inv_two_pi = 0.15915494309189533577;  // 1/(2 pi)
  const double A = a / c, B = b / c;
  const double sa = std::sqrt(1 + A * A), sb = std::sqrt(1 + B * B);
  return inv_two_pi * (A / sa * std::atan(B / sa) + B / sb * std::atan(A / sb));
}

/// The factor from the element at (px, py, 0), its normal +z, to the rectangle `r` in the plane
/// z = c > 0 (its front side facing the element): superposition of four signed corners. 0 for an
/// empty rectangle.
inline double parallel_rectangle_factor(double px, double py, const AxisRectangle& r, double c) {
  if (r.empty()) return 0;
  const double x0 = r.x0 - px, x1 = r.x1 - px, y0 = r.y0 - py, y1 = r.y1 - py;
  return parallel_corner_factor(x1, y1, c) - parallel_corner_factor(x0, y1, c) -
         parallel_corner_factor(x1, y0, c) + parallel_corner_factor(x0, y0, c);
}

/// The shadow scene of occluded_scenes.hpp (shadow_scene()): emitter [-0.5, 0.5]^2 at z = 1,
/// opaque blocker [-0.25, 0.25]^2 at z = 0.5, floor at z = 0.
inline constexpr double kShadowEmitterHalfWidth = 0.5, kShadowEmitterHeight = 1.0;
inline constexpr double kShadowBlockerHalfWidth = 0.25, kShadowBlockerHeight = 0.5;

/// The blocker's shadow on the emitter's plane seen from P = (px, py, 0): the central projection
/// from P of the blocker's square, Q = P + s (M - P) with s = emitter height / blocker height = 2,
/// i.e. [-0.5 - px, 0.5 - px] x [-0.5 - py, 0.5 - py].
inline AxisRectangle shadow_scene_shadow(double px, double py) {
  const double s = kShadowEmitterHeight / kShadowBlockerHeight;
  const double w = s * kShadowBlockerHalfWidth;
  return {-w + (1 - s) * px, w + (1 - s) * px, -w + (1 - s) * py, w + (1 - s) * py};
}

/// The emitter of the shadow scene as a rectangle.
inline AxisRectangle shadow_scene_emitter() {
  const double e = kShadowEmitterHalfWidth;
  return {-e, e, -e, e};
}

/// F_vis(P) = (1/pi) Int_emitter V(P, Q) G(P, Q) dS_Q for P = (px, py, 0) on the floor of the
/// shadow scene, its normal +z: the emitter's factor minus that of the part the blocker hides,
/// F(emitter) - F(emitter n shadow) (0 hidden when they do not overlap). Every point of the
/// emitter in the shadow is hidden (the blocker lies between the two planes), and no other.
inline double shadow_scene_visible_factor(double px, double py) {
  const AxisRectangle emitter = shadow_scene_emitter();
  const AxisRectangle hidden = intersection(emitter, shadow_scene_shadow(px, py));
  return parallel_rectangle_factor(px, py, emitter, kShadowEmitterHeight) -
         parallel_rectangle_factor(px, py, hidden, kShadowEmitterHeight);
}

}  // namespace panelrad::testing

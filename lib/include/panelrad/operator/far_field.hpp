#pragma once
// Far field of the fast product (paper section 4.1, (44)-(48)), in LOCAL coordinates of the
// cluster's plane centred at A(tau), so that nothing depends on where the scene sits in space.
//
// For Q = A + x e1 + y e2 in the plane of a cluster with inner unit normal nQ,
//   G(P,Q) = [(Q-P).nP] [(P-Q).nQ] / |P-Q|^4,
// where (P-Q).nQ = (P-A).nQ is constant over the plane and (Q-P).nP is linear in (x,y).
// We expand G(P, Q(x,y)) ~= sum_{p+q<=M} c_pq x^p y^q (Taylor in Q about A, (44)-(45)), and
//   Int_tau u_n(Q) G(P,Q) dS_Q ~= sum c_pq m_pq(tau),   m_pq(tau) = Int_tau u_n x^p y^q dS  (47)-(48).
#include <panelrad/geometry/mesh.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace panelrad {

using geometry::Vec3;

/// Largest Taylor degree M supported (stack arrays are sized for it).
inline constexpr int kMaxTaylorDegree = 12;

/// Number of coefficients of a bivariate polynomial of total degree <= M: (M+1)(M+2)/2.
constexpr int num_taylor_terms(int M) { return (M + 1) * (M + 2) / 2; }
/// Position of x^p y^q in the graded order (0,0),(1,0),(0,1),(2,0),(1,1),(0,2),(3,0),...
constexpr int taylor_index(int p, int q) { return (p + q) * (p + q + 1) / 2 + q; }

/// Orthonormal frame of a plane: origin (a cluster centre A(tau)), in-plane axes e1, e2 and the
/// inner unit normal. Clusters of one facet share e1, e2, so shifting moments between them is a
/// 2-D translation.
struct PlaneFrame {
  Vec3 origin, e1, e2, normal;
  /// Local coordinates (x, y) of a point of the plane.
  std::array<double, 2> local(const Vec3& Q) const { return {(Q - origin).dot(e1), (Q - origin).dot(e2)}; }
};

/// A cluster's frame as the fast product holds it: the origin A(tau) (in the far field's length
/// unit) and the index of its axes among the frames of the planes. Every cluster of a root
/// triangle has its root's normal, hence its axes (make_plane_frame): 32 bytes a cluster, against
/// 96 for a PlaneFrame of its own.
struct alignas(32) ClusterOrigin {
  double origin[3];
  std::int32_t axes;
};

/// A frame for a plane with unit normal n: e1, e2 chosen deterministically from n alone.
PlaneFrame make_plane_frame(const Vec3& origin, const Vec3& normal);

/// Taylor coefficients c_pq (graded order, num_taylor_terms(M) values) of G(P, Q(x,y)) about
/// (x,y) = (0,0) of `frame`, degree M in [0, 12]. Computed in the scaled variables (x,y)/|P-A|
/// by the Gegenbauer recurrence for |P-Q|^-4 (exact in exact arithmetic, forward-stable), free
/// of overflow and cancellation for admissible pairs; allocation-free. For |x|,|y| within a disc
/// of radius R = eta |P-A| the error is at most |h|/|P-A|^4 (|L0| T_M + |grad L| R T_{M-1}),
/// T_M = sum_{n>M} C(n+3,3) eta^n, h = (P-A).nQ, L0 = (A-P).nP (see tests/operator/test_far_field.cpp). `c` must hold num_taylor_terms(M) doubles. Throws std::invalid_argument when
/// M is outside [0, kMaxTaylorDegree] or P coincides with A(tau). The unscaled c_pq carry the
/// factor |P-A|^-(2+p+q), so |P-A| must exceed about 1e-300^(1/(M+2)) (1e-21 for M = 12).
void kernel_taylor_coefficients(const Vec3& P, const Vec3& nP, const PlaneFrame& frame, int M,
                                double* c);

/// Far pairs of one row whose coefficients the fast product computes at once, in SIMD lanes.
inline constexpr int kFarFieldLanes = 4;

/// The instruction set of the far-field lanes: `best`, the one the fast product uses (AVX2 +
/// FMA on an x86-64 CPU that has both, else the baseline), or the baseline one the build targets
/// (on x86-64: SSE2). The two differ by rounding: AVX2 + FMA fuses each multiply-add.
enum class FarFieldInstructions { best, baseline };

/// "avx2+fma" or "baseline": what `which` stands for on this CPU.
const char* far_field_instructions_name(FarFieldInstructions which = FarFieldInstructions::best);

/// `factor` times the Taylor coefficients of kernel_taylor_coefficients for `count` pairs
/// (P, *frames[w]), 1 <= count <= kFarFieldLanes, computed at once by the same recurrence run in
/// SIMD lanes (the fast product's recomputed far field): pair w's num_taylor_terms(M) values at
/// c[w * num_taylor_terms(M)]. Equal to kernel_taylor_coefficients up to rounding (the order and
/// fusion of the operations differ). Throws std::invalid_argument for M outside [0, 12], count
/// outside [1, kFarFieldLanes], or a P that coincides with some A(tau) or is not finite.
void kernel_taylor_coefficients_lanes(const Vec3& P, const Vec3& nP, const PlaneFrame* const* frames, int count,
                                      int M, double factor, double* c,
                                      FarFieldInstructions which = FarFieldInstructions::best);

/// Exact moments Int_Delta x^p y^q dS (graded order, p+q <= M) of the triangle (a,b,c) lying in
/// the plane of `frame`, in the frame's local coordinates. `m` holds num_taylor_terms(M) values.
void triangle_moments(const PlaneFrame& frame, const Vec3& a, const Vec3& b, const Vec3& c, int M,
                      double* m);

/// Re-centres moments: given m_pq about origin O_child, returns (adds into m_parent) the moments
/// about O_parent, where (dx, dy) = local coordinates of O_child - O_parent (binomial shift, (48)).
void shift_moments_add(const double* m_child, double dx, double dy, int M, double* m_parent);

}  // namespace panelrad

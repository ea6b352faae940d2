// The kernels of far_field_batch.hpp, written once over vectors of kLanes doubles (GCC/Clang
// vector extensions) and compiled by each instruction set's translation unit, which defines
// PANELRAD_LANES_FUSED (1: the multiply-add is the fused FMA instruction, 0: a rounded product
// then a rounded sum) and PANELRAD_LANES_NAME and includes this file once; kLaneKernels is the
// table of its kernels. Everything here has internal linkage.
// Include only from those translation units (no include guard on purpose: one inclusion each).
#include "far_field_batch.hpp"

#if PANELRAD_LANES_FUSED
#include <immintrin.h>
#endif

namespace panelrad::far_field_batch {
namespace {

using V = double __attribute__((vector_size(8 * kLanes)));
using VI = long long __attribute__((vector_size(8 * kLanes)));
static_assert(kLanes == 4, "the 4 x 4 transposes below assume 4 lanes");

constexpr int terms_of(int M) { return (M + 1) * (M + 2) / 2; }
constexpr int index_of(int p, int q) { return (p + q) * (p + q + 1) / 2 + q; }

[[gnu::always_inline]] inline V splat(double x) { return V{x, x, x, x}; }
[[gnu::always_inline]] inline V load(const double* p) {
  V v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
[[gnu::always_inline]] inline void store(double* p, V v) { __builtin_memcpy(p, &v, sizeof v); }

// a b + c: fused (one rounding) or product then sum (two roundings), see the file comment.
[[gnu::always_inline]] inline V madd(V a, V b, V c) {
#if PANELRAD_LANES_FUSED
  return _mm256_fmadd_pd(a, b, c);
#else
  return a * b + c;
#endif
}

[[gnu::always_inline]] inline V lane_sqrt(V x) {
#if PANELRAD_LANES_FUSED
  return _mm256_sqrt_pd(x);
#else
  return V{__builtin_sqrt(x[0]), __builtin_sqrt(x[1]), __builtin_sqrt(x[2]), __builtin_sqrt(x[3])};
#endif
}

// Rows r0..r3 -> columns: out[k] = (r0[k], r1[k], r2[k], r3[k]).
[[gnu::always_inline]] inline void transpose(V r0, V r1, V r2, V r3, V* out) {
  const V t0 = __builtin_shufflevector(r0, r1, 0, 4, 2, 6);
  const V t1 = __builtin_shufflevector(r0, r1, 1, 5, 3, 7);
  const V t2 = __builtin_shufflevector(r2, r3, 0, 4, 2, 6);
  const V t3 = __builtin_shufflevector(r2, r3, 1, 5, 3, 7);
  out[0] = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
  out[1] = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
  out[2] = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
  out[3] = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
}

// The Taylor coefficients of G(P, Q(x,y)) about A(tau_w), (44)-(45), times rho/pi, in lane w: the
// scaled Gegenbauer recurrence of kernel_taylor_coefficients (far_field.cpp), lane by lane.
// With d = P - A, r = |d|, X = x/r, Y = y/r: |P-Q|^2 = r^2 (1 - 2u + w), u = X a1 + Y a2,
// w = X^2 + Y^2, a_i = d.e_i / r, and (1 - 2u + w)^-2 = sum_n F_n,
//   n F_n = 2(n+1) u F_{n-1} - (n+2) w F_{n-2},  F_0 = 1, F_1 = 4u;
// then c_n = (l0 F_n + l1 X F_{n-1}/X + l2 Y F_{n-1}/Y) hn / r^(2+n), l0 = (A-P).nP / r,
// l_i = e_i.nP, hn = d.nQ / r. False when some lane's r is 0 or not finite.
// The point's side (P, n_P, factor) and the cluster's frame (A, e1, e2, n_Q) are given per lane:
// lane_coefficients (one point, kLanes clusters) and point_lane_coefficients (kLanes points, one
// cluster) load them and share this body, which computes the same operations in either case.
template <int M>
[[gnu::always_inline]] inline bool lane_coefficients_of(const V* P, const V* nP, V factor, const V* A, const V* e1,
                                                        const V* e2, const V* nq, V* c) {
  V dn[3];
  for (int k = 0; k < 3; ++k) dn[k] = P[k] - A[k];
  const V rho = lane_sqrt(madd(dn[2], dn[2], madd(dn[1], dn[1], dn[0] * dn[0])));
  const VI ok = (rho > 0.0) & (rho < __builtin_inf());  // false for NaN
  if (!(ok[0] & ok[1] & ok[2] & ok[3])) return false;
  const V inv = 1.0 / rho;
  for (int k = 0; k < 3; ++k) dn[k] *= inv;  // (P - A)/r
  const V a1 = madd(dn[2], e1[2], madd(dn[1], e1[1], dn[0] * e1[0]));
  const V a2 = madd(dn[2], e2[2], madd(dn[1], e2[1], dn[0] * e2[0]));
  const V hn = madd(dn[2], nq[2], madd(dn[1], nq[1], dn[0] * nq[0]));
  const V np0 = nP[0], np1 = nP[1], np2 = nP[2];
  const V l0 = -madd(dn[2], np2, madd(dn[1], np1, dn[0] * np0));
  const V l1 = madd(e1[2], np2, madd(e1[1], np1, e1[0] * np0));
  const V l2 = madd(e2[2], np2, madd(e2[1], np1, e2[0] * np0));

  V F[terms_of(M)];
  F[0] = splat(1.0);
  if constexpr (M >= 1) {
    F[1] = 4.0 * a1;
    F[2] = 4.0 * a2;
  }
  for (int n = 2; n <= M; ++n) {
    V* Fn = F + index_of(n, 0);
    const V* F1 = F + index_of(n - 1, 0);
    const V* F2 = F + index_of(n - 2, 0);
    const V ca = splat(2.0 * (n + 1) / n), cb = splat(static_cast<double>(n + 2) / n);
    // [X^(n-q) Y^q] of u F_{n-1} = a1 F1[q] + a2 F1[q-1]; of w F_{n-2} = F2[q] + F2[q-2].
    Fn[0] = madd(ca, a1 * F1[0], -(cb * F2[0]));
    Fn[n] = madd(ca, a2 * F1[n - 1], -(cb * F2[n - 2]));
    if (n >= 3) {
      Fn[1] = madd(ca, madd(a2, F1[0], a1 * F1[1]), -(cb * F2[1]));
      Fn[n - 1] = madd(ca, madd(a2, F1[n - 2], a1 * F1[n - 1]), -(cb * F2[n - 3]));
    } else {
      Fn[1] = ca * madd(a2, F1[0], a1 * F1[1]);  // n = 2: w F_0 has no X Y term
    }
    for (int q = 2; q <= n - 2; ++q) Fn[q] = madd(ca, madd(a2, F1[q - 1], a1 * F1[q]), -(cb * (F2[q] + F2[q - 2])));
  }

  // (l0 + l1 X + l2 Y) sum F_n truncated at degree M, times hn rho/pi, unscaled by r^-(2+n).
  V scale = hn * inv * inv * factor;
  c[0] = l0 * scale;
  for (int n = 1; n <= M; ++n) {
    scale *= inv;
    const V* Fn = F + index_of(n, 0);
    const V* F1 = F + index_of(n - 1, 0);
    V* cn = c + index_of(n, 0);
    cn[0] = madd(l1, F1[0], l0 * Fn[0]) * scale;
    for (int q = 1; q < n; ++q) cn[q] = madd(l2, F1[q - 1], madd(l1, F1[q], l0 * Fn[q])) * scale;
    cn[n] = madd(l2, F1[n - 1], l0 * Fn[n]) * scale;
  }
  return true;
}

template <int M>
[[gnu::always_inline]] inline bool lane_coefficients(const RowPoint& row, const FrameLanes& fr, V* c) {
  V P[3], nP[3], A[3], e1[3], e2[3], nq[3];
  for (int k = 0; k < 3; ++k) {
    P[k] = splat(row.P[k]);
    nP[k] = splat(row.nP[k]);
    A[k] = load(fr.v[k]);
    e1[k] = load(fr.v[3 + k]);
    e2[k] = load(fr.v[6 + k]);
    nq[k] = load(fr.v[9 + k]);
  }
  return lane_coefficients_of<M>(P, nP, splat(row.factor), A, e1, e2, nq, c);
}

template <int M>
[[gnu::always_inline]] inline bool point_lane_coefficients(const PointLanes& pts, const double* frame, V* c) {
  V P[3], nP[3], A[3], e1[3], e2[3], nq[3];
  for (int k = 0; k < 3; ++k) {
    P[k] = load(pts.P[k]);
    nP[k] = load(pts.nP[k]);
    A[k] = splat(frame[k]);
    e1[k] = splat(frame[3 + k]);
    e2[k] = splat(frame[6 + k]);
    nq[k] = splat(frame[9 + k]);
  }
  return lane_coefficients_of<M>(P, nP, load(pts.factor), A, e1, e2, nq, c);
}

// Column k, lane w, partial sum r: acc[(r kSeries + k) kLanes + w] += sum over the terms
// t = r mod kPartialSums of c[t][w] m[w][t C + k], t in order, one multiply-add each (the order
// of far_field_batch.hpp), in vectors over the lanes. The moments of the 4 lanes are read 4
// consecutive doubles at a time and transposed: 4 terms of all C columns are C such reads, whose
// columns and terms are known at compile time.
// Scaled (C = 1 only): lane w's moments are scale[w] m[w][t], each product rounded before its
// multiply-add, exactly as if they were stored (an element's v_e times its shape's moments).
template <int C, bool Scaled = false>
[[gnu::always_inline]] inline void add_terms(int T, const double* const* m, double* acc, const V* c,
                                             const double* scale = nullptr) {
  static_assert(!Scaled || C == 1, "scaled lanes hold one column");
  static_assert(kPartialSums == 4, "4 terms per group, one per partial sum");
  V a[kPartialSums][C];
  for (int r = 0; r < kPartialSums; ++r)
    for (int k = 0; k < C; ++k) a[r][k] = load(acc + (r * kSeries + k) * kLanes);
  const V S = Scaled ? load(scale) : splat(1.0);
  const int grouped = T - T % 4;
  for (int t = 0; t < grouped; t += 4) {
    const int base = t * C;
#pragma GCC unroll 4
    for (int g = 0; g < C; ++g) {
      V col[4];
      const int at = base + 4 * g;
      transpose(load(m[0] + at), load(m[1] + at), load(m[2] + at), load(m[3] + at), col);
#pragma GCC unroll 4
      for (int k = 0; k < 4; ++k) {
        const int f = 4 * g + k;  // (term - t) C + column
        if constexpr (Scaled) col[k] = col[k] * S;
        a[f / C][f % C] = madd(c[t + f / C], col[k], a[f / C][f % C]);
      }
    }
  }
  const auto tail = [&](int r) {
    const int t = grouped + r;
    for (int k = 0; k < C; ++k) {
      const int f = t * C + k;
      V mt = V{m[0][f], m[1][f], m[2][f], m[3][f]};
      if constexpr (Scaled) mt = mt * S;
      a[r][k] = madd(c[t], mt, a[r][k]);
    }
  };
  if (T - grouped > 0) tail(0);
  if (T - grouped > 1) tail(1);
  if (T - grouped > 2) tail(2);
  for (int r = 0; r < kPartialSums; ++r)
    for (int k = 0; k < C; ++k) store(acc + (r * kSeries + k) * kLanes, a[r][k]);
}

// The same sums with one cluster's moments m (term t of column k at m[t C + k]) for every lane.
template <int C>
[[gnu::always_inline]] inline void add_common_terms(int T, const double* m, double* acc, const V* c) {
  V a[kPartialSums][C];
  for (int r = 0; r < kPartialSums; ++r)
    for (int k = 0; k < C; ++k) a[r][k] = load(acc + (r * kSeries + k) * kLanes);
  for (int t = 0; t < T; ++t)
    for (int k = 0; k < C; ++k) a[t % kPartialSums][k] = madd(c[t], splat(m[t * C + k]), a[t % kPartialSums][k]);
  for (int r = 0; r < kPartialSums; ++r)
    for (int k = 0; k < C; ++k) store(acc + (r * kSeries + k) * kLanes, a[r][k]);
}

template <int M, int C>
[[gnu::always_inline]] inline bool points_columns(const PointLanes& pts, const double* frame, const double* m,
                                                  double* acc) {
  V c[terms_of(M)];
  if (!point_lane_coefficients<M>(pts, frame, c)) return false;
  add_common_terms<C>(terms_of(M), m, acc, c);
  return true;
}

template <int M>
bool points_of_degree(const PointLanes& pts, const double* frame, const double* m, int C, double* acc) {
  switch (C) {
    case 1: return points_columns<M, 1>(pts, frame, m, acc);
    case 2: return points_columns<M, 2>(pts, frame, m, acc);
    case 3: return points_columns<M, 3>(pts, frame, m, acc);
    default: return points_columns<M, 4>(pts, frame, m, acc);
  }
}

template <int M>
bool coefficients_of_degree(const RowPoint& row, const FrameLanes& frames, double* out) {
  V c[terms_of(M)];
  if (!lane_coefficients<M>(row, frames, c)) return false;
  for (int t = 0; t < terms_of(M); ++t) store(out + t * kLanes, c[t]);
  return true;
}

template <int M, int C, bool Scaled = false>
[[gnu::always_inline]] inline bool recomputed_columns(const RowPoint& row, const FrameLanes& frames,
                                                      const double* const* m, double* acc,
                                                      const double* scale = nullptr) {
  V c[terms_of(M)];
  if (!lane_coefficients<M>(row, frames, c)) return false;
  add_terms<C, Scaled>(terms_of(M), m, acc, c, scale);
  return true;
}

template <int M>
bool recomputed_of_degree(const RowPoint& row, const FrameLanes& frames, const double* const* m,
                          const double* scale, int C, double* acc) {
  if (scale) return recomputed_columns<M, 1, true>(row, frames, m, acc, scale);  // one column (Kernels)
  switch (C) {
    case 1: return recomputed_columns<M, 1>(row, frames, m, acc);
    case 2: return recomputed_columns<M, 2>(row, frames, m, acc);
    case 3: return recomputed_columns<M, 3>(row, frames, m, acc);
    default: return recomputed_columns<M, 4>(row, frames, m, acc);
  }
}

template <int... Ms>
constexpr Kernels make_kernels(const char* name) {
  return Kernels{name, {&coefficients_of_degree<Ms>...}, {&recomputed_of_degree<Ms>...}, {&points_of_degree<Ms>...}};
}

constexpr Kernels kLaneKernels = make_kernels<0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12>(PANELRAD_LANES_NAME);
static_assert(kMaxDegree == 12, "kLaneKernels lists the degrees 0..12");

}  // namespace
}  // namespace panelrad::far_field_batch

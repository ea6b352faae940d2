#pragma once
// The far field (44)-(48) of the fast product for kFarFieldLanes (point, cluster) pairs of one
// row at once, in SIMD lanes: lane w holds the pair (P_i, tau_w). P_i and n_P are common to the
// row; the frames of the clusters are gathered into lanes, the Gegenbauer recurrence of
// kernel_taylor_coefficients runs in the lanes, and each lane's Taylor terms are summed with the
// moments m_t(tau_w) of (47).
//
// The sums of a row. Partial sum r of lane w of accumulator set s holds the running sum, over
// the pairs of the row it is given, of the terms c_t m_t with t = r mod 4, in order of t, each
// term one multiply-add acc = c_t m_t + acc (4 partial sums: independent chains). The caller
// gives pair j of a row (in the row's far-field order) to lane j mod kFarFieldLanes of set
// (j / kFarFieldLanes) mod 2, and adds the 2 x 4 x kFarFieldLanes sums in a fixed order at the
// end (RowSums::total): every column of a block of C columns gets exactly the operations
// of the one-column product, in the same order, on any thread, so a block product's column is
// bit-identical to the product of that column alone, for any thread count.
//
// Instruction sets. The kernels are compiled twice: for baseline x86-64 (SSE2; the multiply-add
// is a product rounded, then a sum rounded) and, on x86-64, for AVX2 + FMA (the multiply-add is
// one fused, singly rounded operation), the latter chosen once at run time when the CPU has both.
// The two differ from each other by rounding (the fused operations); each is deterministic
// (floating-point contraction is off in both, every fusion is explicit). The kernels need only
// vectors of 4 doubles, shuffles, sqrt and FMA, which the GCC/Clang vector extensions give in one
// source for both builds; a build per translation unit and __builtin_cpu_supports do the
// dispatch without a SIMD library among the dependencies.
// This header is free of Eigen, of the standard library and of inline functions, so that the
// kernels' translation units, compiled for other instruction sets, share no inline function with
// the rest of the program (the linker keeps one copy of each, which must run on any x86-64).

#include <cstdint>

namespace panelrad {
struct PlaneFrame;
struct ClusterOrigin;
}

namespace panelrad::far_field_batch {

/// Pairs per batch (kFarFieldLanes of far_field.hpp), the largest Taylor degree
/// (kMaxTaylorDegree) and its number of terms.
inline constexpr int kLanes = 4;
inline constexpr int kMaxDegree = 12;
inline constexpr int kMaxTerms = (kMaxDegree + 1) * (kMaxDegree + 2) / 2;
/// Partial sums per lane (term t into partial sum t mod kPartialSums: independent chains of
/// multiply-adds), and columns (series) per partial sum.
inline constexpr int kPartialSums = 4;
inline constexpr int kSeries = 4;
/// Doubles of one accumulator set: kPartialSums x kSeries columns x kLanes lanes.
inline constexpr int kSetSize = kPartialSums * kSeries * kLanes;

/// The row's side of the pairs: P_i in the far field's length unit, n_P, and the factor rho_i/pi
/// that multiplies the Taylor coefficients of the product (the rho-scaled coefficients).
struct RowPoint {
  double P[3], nP[3], factor;
};

/// kLanes points of the row side, lane by lane (the interpolation points of a target cluster's
/// local expansion): P, n_P and the factor of lane w at P[k][w], nP[k][w], factor[w].
struct PointLanes {
  alignas(32) double P[3][kLanes], nP[3][kLanes], factor[kLanes];
};

/// The frames of kLanes clusters, lane by lane: component k of lane w at v[k][w], k = 0..2 the
/// origin A(tau), 3..5 e1, 6..8 e2, 9..11 the normal.
struct FrameLanes {
  alignas(32) double v[12][kLanes];
};

/// The frames of the clusters by global id. A cluster above the finest level (id < leaf_begin)
/// has its origin A(tau) at origin[id].origin and the axes e1, e2, n_Q of axes[origin[id].axes]
/// (whose own origin is not read). An element e = id - leaf_begin of the finest level L is its
/// root's shape scaled by s = +-2^-L and translated (uniform subdivision, see
/// FastOperator::element_moments), and circumcentre and centroid move with it:
/// A(e) - C(e) = s (A(root) - C(root)). Its origin is unit C(e) + shift[3 s_e .. 3 s_e + 2], with
/// C(e) at centroid[3 e .. 3 e + 2] (the tree's collocation points), s_e = element_shape(e, L)
/// and unit a power of two (an exact scaling); its axes are its root's, axes[e >> 2L].
struct ClusterFrames {
  const ClusterOrigin* origin;
  const PlaneFrame* axes;
  std::int64_t leaf_begin;
  int finest_level;
  const double* centroid;
  const double* shift;
  double unit;
};

/// The origin of element e of the finest level (ClusterFrames) and the index of its axes.
std::int32_t element_origin(const ClusterFrames& frames, std::int64_t e, double* origin);

/// The moments (47)-(48) of the clusters by global id, C columns interleaved (term t of column c
/// at t C + c). A cluster above the finest level (id < leaf_begin) has them stored, at
/// stored + id T C. An element of the finest level L (id = leaf_begin + e) has v_e times the
/// moments of its shape (uniform subdivision makes it a scaled copy of its root, see
/// FastOperator::element_moments): term t of column c is v[e C + c] shapes[s T + t], s =
/// element_shape(e, L). They are formed when read, so that a product never writes the n T C
/// finest ones.
struct ClusterMoments {
  const double* stored;
  std::int64_t leaf_begin;
  const double* v;
  const double* shapes;
  int finest_level;
};

/// The number of digits 3 in the path of cluster k of level l below its root (the base-4 digits
/// of k below the root's): each negates the triangle and turns its corners' labels by one.
int path_threes(std::int64_t k, int l);

/// The shape of element e of level L among the element moments by shape: at level 0 its root
/// e, above it 2 r + (the parity of the digits 3 of its path) for its root r (an even and an
/// odd shape per root).
std::int64_t element_shape(std::int64_t e, int L);

/// The moments of cluster id, T terms and C columns: a pointer into `moments.stored`, or, for an
/// element of the finest level, `buffer` (T C doubles) filled with v_e times its shape's moments
/// (the same products, rounded once, as stored ones would hold).
const double* cluster_moments(const ClusterMoments& moments, std::int32_t id, int T, int C, double* buffer);

/// The kernels of one instruction set. acc holds an accumulator set (kSetSize running sums):
/// partial sum r of column c of lane w at acc[(r kSeries + c) kLanes + w]; m[w] the moments of
/// lane w's cluster, C columns interleaved (term t of column c at m[w][t * C + c]). Lanes without a pair get the moments of zero (and any valid
/// frame or zero coefficients): they add +0 to their sums.
struct Kernels {
  const char* name;
  /// The rho-scaled Taylor coefficients of the kLanes pairs, c[t * kLanes + w], degree M; false
  /// (and c undefined) when some lane's P coincides with its A(tau) or is not finite.
  bool (*coefficients[kMaxDegree + 1])(const RowPoint& row, const FrameLanes& frames, double* c);
  /// The coefficients as above, summed with the moments into acc, C in 1..4. With `scale`
  /// (kLanes doubles, C = 1 only), lane w's moments are scale[w] m[w][t], each product rounded.
  bool (*recomputed[kMaxDegree + 1])(const RowPoint& row, const FrameLanes& frames, const double* const* m,
                                     const double* scale, int C, double* acc);
  /// kLanes points against one cluster: frame = its origin, e1, e2, normal (12 doubles), m its
  /// moments (term t of column c at m[t C + c]); lane w of acc sums point w's pairs, C in 1..4.
  /// False when some lane's P coincides with A(tau) or is not finite.
  bool (*points[kMaxDegree + 1])(const PointLanes& points, const double* frame, const double* m, int C, double* acc);
};

/// Baseline x86-64 (or whatever the build targets): always available.
const Kernels& baseline_kernels();
/// AVX2 + FMA: nullptr when not compiled in or when the CPU lacks either.
const Kernels* avx2_fma_kernels();
/// The kernels of this CPU, chosen once: AVX2 + FMA when available, else baseline.
const Kernels& kernels();

/// Zeros for kMaxTerms terms x 4 columns: the moments of a lane without a pair.
extern const double kZeroMoments[kMaxTerms * 4];

/// The far-field sums of one row for up to kSeries columns, in 2 accumulator sets.
struct RowSums {
  alignas(32) double v[2][kSetSize] = {};
  /// Column c's far field (47): the 2 x kPartialSums x kLanes sums added in a fixed order
  /// (out of line, like every function declared here: see the note at the top).
  double total(int c) const;
};

/// Point w's far field (47) in column c from an accumulator set of `kernels.points`: its
/// kPartialSums partial sums added in a fixed order.
double point_total(const double* acc, int c, int w);

/// The far field (47) of `count` clusters (ids clusters[j], in order) at each of `count_points`
/// points (P, n_P, factor of point q at points[q]), C columns: out[q C + c]. The points go
/// kLanes at a time into the lanes of `kernels.points`, every point's sum in the clusters' order,
/// so each value is independent of the others. False when some P coincides with an A(tau) or is
/// not finite.
bool add_points(const Kernels& kernels, int M, const RowPoint* points, int count_points, const ClusterFrames& frames,
                const std::int32_t* clusters, std::int64_t count, const ClusterMoments& moments, int C, double* out);

/// The rho-scaled Taylor coefficients of `count` pairs of a row, pair j with cluster clusters[j]
/// (its frame from `frames`), kLanes pairs at a time: pair j's T coefficients at out[j T ..], in
/// double or rounded once to float. Each pair's are the same bits in any batch (the lanes are
/// computed independently), so the same as the recomputing product's. False when some pair's P
/// coincides with its A(tau) or is not finite.
bool row_coefficients(const Kernels& kernels, int M, const RowPoint& row, const ClusterFrames& frames,
                      const std::int32_t* clusters, std::int64_t count, double* out);
bool row_coefficients(const Kernels& kernels, int M, const RowPoint& row, const ClusterFrames& frames,
                      const std::int32_t* clusters, std::int64_t count, float* out);

/// Adds the far field of `count` pairs of a row, pair j with cluster clusters[j] (its frame from
/// `frames`, moments by cluster_moments), coefficients recomputed at degree M
/// (T = (M+1)(M+2)/2 terms), pair j into lane j mod kLanes of set (j / kLanes) mod 2. False when
/// some pair's P coincides with its A(tau) or is not finite.
bool add_recomputed_row(const Kernels& kernels, int M, const RowPoint& row, const ClusterFrames& frames,
                        const std::int32_t* clusters, std::int64_t count, const ClusterMoments& moments, int C,
                        RowSums& sums);

}  // namespace panelrad::far_field_batch

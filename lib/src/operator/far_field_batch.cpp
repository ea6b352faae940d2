// The choice of the far-field kernels (far_field_batch.hpp) for this CPU, and the loops over the
// far pairs of a row that feed them kLanes pairs at a time.
#include "far_field_batch.hpp"

#include <panelrad/operator/far_field.hpp>

#include <algorithm>
#include <bit>
#include <stdexcept>
#include <string>

namespace panelrad::far_field_batch {

static_assert(kLanes == kFarFieldLanes && kMaxDegree == kMaxTaylorDegree &&
              kMaxTerms == num_taylor_terms(kMaxTaylorDegree));

#if PANELRAD_FAR_FIELD_AVX2
const Kernels& avx2_fma_kernel_table();  // far_field_batch_avx2.cpp
#endif

alignas(32) const double kZeroMoments[kMaxTerms * 4] = {};

const Kernels* avx2_fma_kernels() {
#if PANELRAD_FAR_FIELD_AVX2
  static const bool available = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  }();
  return available ? &avx2_fma_kernel_table() : nullptr;
#else
  return nullptr;
#endif
}

const Kernels& kernels() {
  static const Kernels* const chosen = avx2_fma_kernels() ? avx2_fma_kernels() : &baseline_kernels();
  return *chosen;
}

double RowSums::total(int c) const {
  double set[2];
  for (int s = 0; s < 2; ++s) {
    double partial[kPartialSums];
    for (int r = 0; r < kPartialSums; ++r) {
      const double* a = v[s] + (r * kSeries + c) * kLanes;
      partial[r] = (a[0] + a[1]) + (a[2] + a[3]);
    }
    set[s] = (partial[0] + partial[1]) + (partial[2] + partial[3]);
  }
  return set[0] + set[1];
}

namespace {

// Frame of lane w = frames[w] (w < count), the other lanes a copy of lane 0 (a valid frame).
void gather_frames(const PlaneFrame* const* frames, int count, FrameLanes& lanes) {
  for (int w = 0; w < kLanes; ++w) {
    const PlaneFrame& f = *frames[w < count ? w : 0];
    for (int k = 0; k < 3; ++k) {
      lanes.v[k][w] = f.origin[k];
      lanes.v[3 + k][w] = f.e1[k];
      lanes.v[6 + k][w] = f.e2[k];
      lanes.v[9 + k][w] = f.normal[k];
    }
  }
}

// The frame of cluster id: its origin, its plane's axes.
void frame_of(const ClusterFrames& frames, std::int32_t id, double* frame) {
  std::int32_t index;
  if (id >= frames.leaf_begin) {
    index = element_origin(frames, id - frames.leaf_begin, frame);
  } else {
    const ClusterOrigin& o = frames.origin[id];
    index = o.axes;
    for (int k = 0; k < 3; ++k) frame[k] = o.origin[k];
  }
  const PlaneFrame& axes = frames.axes[index];
  for (int k = 0; k < 3; ++k) {
    frame[3 + k] = axes.e1[k];
    frame[6 + k] = axes.e2[k];
    frame[9 + k] = axes.normal[k];
  }
}

// Frame of lane w = that of cluster ids[w] (w < count), the other lanes a copy of lane 0.
void gather_frames(const ClusterFrames& frames, const std::int32_t* ids, int count, FrameLanes& lanes) {
  double frame[kLanes][12];
  for (int w = 0; w < count; ++w) frame_of(frames, ids[w], frame[w]);
  for (int w = 0; w < kLanes; ++w)
    for (int k = 0; k < 12; ++k) lanes.v[k][w] = frame[w < count ? w : 0][k];
}

// The shape moments (T terms) of element e of the finest level (ClusterMoments).
inline const double* shape_moments(const ClusterMoments& moments, std::int64_t e, int T) {
  return moments.shapes + static_cast<std::size_t>(element_shape(e, moments.finest_level)) * static_cast<std::size_t>(T);
}

// The moments of the in_batch lanes of the batch starting at pair j0 (zeros beyond). One column:
// an element's lane points at its shape's moments with scale[w] = v_e (1 for the others), and the
// return is false when no lane needs scaling. Several columns: an element's moments are formed in
// buffer[w].
bool batch_moments(const std::int32_t* clusters, std::int64_t j0, int in_batch, const ClusterMoments& moments, int T,
                   int C, double (*buffer)[kMaxTerms * 4], const double** m, double* scale) {
  if (C > 1) {
    for (int w = 0; w < kLanes; ++w)
      m[w] = w < in_batch ? cluster_moments(moments, clusters[j0 + w], T, C, buffer[w]) : kZeroMoments;
    return false;
  }
  bool scaled = false;
  for (int w = 0; w < kLanes; ++w) {  // selects rather than branches: elements and clusters mix at random
    const std::int64_t id = w < in_batch ? clusters[j0 + w] : -1;
    const bool element = id >= moments.leaf_begin;
    const std::int64_t e = element ? id - moments.leaf_begin : 0;
    const std::int64_t held = id >= 0 && !element ? id : -1;
    const double* stored = held >= 0 ? moments.stored + static_cast<std::size_t>(held) * static_cast<std::size_t>(T) : kZeroMoments;
    m[w] = element ? shape_moments(moments, e, T) : stored;
    scale[w] = element ? moments.v[e] : 1.0;
    scaled |= element;
  }
  return scaled;
}

}  // namespace

int path_threes(std::int64_t k, int l) {
  const std::uint64_t path = static_cast<std::uint64_t>(k) & ((std::uint64_t{1} << (2 * l)) - 1);
  const std::uint64_t threes = path & (path >> 1) & 0x5555555555555555ULL;  // digit 3: both bits set
  return std::popcount(threes);
}

std::int64_t element_shape(std::int64_t e, int L) { return L == 0 ? e : 2 * (e >> (2 * L)) + (path_threes(e, L) & 1); }

std::int32_t element_origin(const ClusterFrames& frames, std::int64_t e, double* origin) {
  const double* c = frames.centroid + 3 * e;
  const double* shift = frames.shift + 3 * element_shape(e, frames.finest_level);
  for (int k = 0; k < 3; ++k) origin[k] = frames.unit * c[k] + shift[k];  // unit * c exact: one rounding
  return static_cast<std::int32_t>(e >> (2 * frames.finest_level));
}

const double* cluster_moments(const ClusterMoments& moments, std::int32_t id, int T, int C, double* buffer) {
  const std::size_t TC = static_cast<std::size_t>(T) * static_cast<std::size_t>(C);
  if (id < moments.leaf_begin) return moments.stored + static_cast<std::size_t>(id) * TC;
  const std::int64_t e = id - moments.leaf_begin;
  const double* g = shape_moments(moments, e, T);
  const double* ve = moments.v + static_cast<std::size_t>(e) * static_cast<std::size_t>(C);
  if (C == 1) {
    for (int t = 0; t < T; ++t) buffer[t] = ve[0] * g[t];
  } else {
    for (int t = 0; t < T; ++t)
      for (int c = 0; c < C; ++c) buffer[t * C + c] = ve[c] * g[t];
  }
  return buffer;
}

namespace {

template <class Coef>
bool row_coefficients_as(const Kernels& kernels, int M, const RowPoint& row, const ClusterFrames& frames,
                         const std::int32_t* clusters, std::int64_t count, Coef* out) {
  const int T = num_taylor_terms(M);
  const auto fn = kernels.coefficients[M];
  FrameLanes lanes;
  alignas(32) double lane_c[kLanes * kMaxTerms];
  for (std::int64_t j0 = 0; j0 < count; j0 += kLanes) {
    const int in_batch = static_cast<int>(std::min<std::int64_t>(kLanes, count - j0));
    gather_frames(frames, clusters + j0, in_batch, lanes);
    if (!fn(row, lanes, lane_c)) return false;
    Coef* c = out + j0 * T;
    for (int w = 0; w < in_batch; ++w)
      for (int t = 0; t < T; ++t) c[w * T + t] = static_cast<Coef>(lane_c[t * kLanes + w]);
  }
  return true;
}

}  // namespace

bool row_coefficients(const Kernels& kernels, int M, const RowPoint& row, const ClusterFrames& frames,
                      const std::int32_t* clusters, std::int64_t count, double* out) {
  return row_coefficients_as(kernels, M, row, frames, clusters, count, out);
}

bool row_coefficients(const Kernels& kernels, int M, const RowPoint& row, const ClusterFrames& frames,
                      const std::int32_t* clusters, std::int64_t count, float* out) {
  return row_coefficients_as(kernels, M, row, frames, clusters, count, out);
}

bool add_recomputed_row(const Kernels& kernels, int M, const RowPoint& row, const ClusterFrames& frames,
                        const std::int32_t* clusters, std::int64_t count, const ClusterMoments& moments, int C,
                        RowSums& sums) {
  const int T = num_taylor_terms(M);
  const auto fn = kernels.recomputed[M];
  int set = 0;
  FrameLanes lanes;
  alignas(32) double buffer[kLanes][kMaxTerms * 4];
  for (std::int64_t j0 = 0; j0 < count; j0 += kLanes, set ^= 1) {
    const double* m[kLanes];
    alignas(32) double scale[kLanes];
    const int in_batch = static_cast<int>(std::min<std::int64_t>(kLanes, count - j0));
    const bool scaled = batch_moments(clusters, j0, in_batch, moments, T, C, buffer, m, scale);
    gather_frames(frames, clusters + j0, in_batch, lanes);
    if (!fn(row, lanes, m, scaled ? scale : nullptr, C, sums.v[set])) return false;
  }
  return true;
}

double point_total(const double* acc, int c, int w) {
  static_assert(kPartialSums == 4);
  const auto at = [&](int r) { return acc[(r * kSeries + c) * kLanes + w]; };
  return (at(0) + at(1)) + (at(2) + at(3));
}

bool add_points(const Kernels& kernels, int M, const RowPoint* points, int count_points, const ClusterFrames& frames,
                const std::int32_t* clusters, std::int64_t count, const ClusterMoments& moments, int C, double* out) {
  const int T = num_taylor_terms(M);
  alignas(32) double buffer[kMaxTerms * 4];
  const auto fn = kernels.points[M];
  const int groups = (count_points + kLanes - 1) / kLanes;
  constexpr int kMaxGroups = 48;  // up to 192 points: (kMaxLocalDegree + 1)^2 = 169
  if (groups > kMaxGroups) return false;
  PointLanes lanes[kMaxGroups];
  alignas(32) double acc[kMaxGroups][kSetSize] = {};
  for (int g = 0; g < groups; ++g)
    for (int w = 0; w < kLanes; ++w) {
      const RowPoint& p = points[std::min(count_points - 1, g * kLanes + w)];  // a full last group: repeat the last point
      for (int k = 0; k < 3; ++k) {
        lanes[g].P[k][w] = p.P[k];
        lanes[g].nP[k][w] = p.nP[k];
      }
      lanes[g].factor[w] = p.factor;
    }
  for (std::int64_t j = 0; j < count; ++j) {
    double frame[12];
    frame_of(frames, clusters[j], frame);
    const double* m = cluster_moments(moments, clusters[j], T, C, buffer);
    for (int g = 0; g < groups; ++g)
      if (!fn(lanes[g], frame, m, C, acc[g])) return false;
  }
  for (int q = 0; q < count_points; ++q)
    for (int c = 0; c < C; ++c) out[q * C + c] = point_total(acc[q / kLanes], c, q % kLanes);
  return true;
}

}  // namespace panelrad::far_field_batch

namespace panelrad {

const char* far_field_instructions_name(FarFieldInstructions which) {
  return which == FarFieldInstructions::baseline ? far_field_batch::baseline_kernels().name
                                                 : far_field_batch::kernels().name;
}

void kernel_taylor_coefficients_lanes(const Vec3& P, const Vec3& nP, const PlaneFrame* const* frames, int count,
                                      int M, double factor, double* c, FarFieldInstructions which) {
  using namespace far_field_batch;
  if (M < 0 || M > kMaxTaylorDegree)
    throw std::invalid_argument("kernel_taylor_coefficients_lanes: Taylor degree M = " + std::to_string(M) +
                                " outside [0, " + std::to_string(kMaxTaylorDegree) + "]");
  if (count < 1 || count > kLanes)
    throw std::invalid_argument("kernel_taylor_coefficients_lanes: " + std::to_string(count) +
                                " pairs, outside [1, " + std::to_string(kLanes) + "]");
  const Kernels& k = which == FarFieldInstructions::baseline ? baseline_kernels() : kernels();
  const RowPoint row{{P[0], P[1], P[2]}, {nP[0], nP[1], nP[2]}, factor};
  FrameLanes lanes;
  gather_frames(frames, count, lanes);
  const int T = num_taylor_terms(M);
  alignas(32) double lane_c[kLanes * kMaxTerms];
  if (!k.coefficients[M](row, lanes, lane_c))
    throw std::invalid_argument("kernel_taylor_coefficients_lanes: P coincides with the expansion centre A(tau) of "
                                "one of the pairs or is not finite");
  for (int w = 0; w < count; ++w)
    for (int t = 0; t < T; ++t) c[w * T + t] = lane_c[t * kLanes + w];
}

}  // namespace panelrad

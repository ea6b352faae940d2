#include <panelrad/operator/fast_operator.hpp>

#include "far_field_batch.hpp"
#include "target_clusters.hpp"
#include "visible_covering.hpp"
#include <panelrad/geometry/admissibility.hpp>
#include <panelrad/operator/kernel.hpp>
#include <panelrad/quadrature/exact_integrals.hpp>
#include <panelrad/support/resources.hpp>

#include <omp.h>

#include <cstdint>
#include <cstdio>
#include <limits>

#include <algorithm>
#include <bit>
#include <cmath>
#include <exception>
#include <mutex>
#include <span>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace panelrad {

using geometry::Cluster;
using geometry::Index;

namespace {

/// Walks the cluster tree for collocation point P (in the plane planeP of the tree) and reports
/// the minimal admissible covering (42) of the subtrees of `starts` (count of them; nullptr: of
/// every root): admissible clusters (41) whole, non-admissible leaves as near field; clusters in
/// P's plane, of any facet, are coplanar with P (G = 0, section 4.2 case (a)) and skipped with
/// their subtree.
template <class Far, class Near, class Skip>
void cover(const geometry::ClusterTree& tree, const Vec3& P, Index planeP, double eta, const ClusterRef* starts,
           std::int64_t count, Far&& far, Near&& near, Skip&& skip) {
  const int L = tree.finest_level();
  ClusterRef stack[4 * 64 + 8];
  int top = 0;
  if (!starts) count = tree.num_roots();
  for (std::int64_t s = 0; s < count; ++s) {
    stack[top++] = starts ? starts[s] : ClusterRef{0, static_cast<Index>(count - 1 - s)};  // roots: last first
    while (top > 0) {
      const ClusterRef it = stack[--top];
      const Cluster& c = tree.cluster(it.level, it.k);
      if (tree.plane(it.level, it.k) == planeP) {
        skip();
      } else if (geometry::is_admissible(P, c.centre, c.radius, eta)) {
        far(it.level, it.k);
      } else if (it.level == L) {
        near(it.k);
      } else {
        for (Index child = 3; child >= 0; --child) stack[top++] = {it.level + 1, 4 * it.k + child};
      }
    }
  }
}

constexpr Index kRowBlock = 256;  // rows per block of the parallel covering traversal
// Indices per chunk of the loops whose bodies take nanoseconds (copies, frames). Every parallel
// loop of setup and product is scheduled dynamically: a virtual machine's processors do not run at
// one speed (a host's other tenants share their cores), and a static split waits for the slower.
constexpr Index kLightChunk = 8192;

/// [begin, end) of `rows`, end = -1 read as n; std::invalid_argument unless 0 <= begin <= end <= n.
std::pair<Index, Index> resolve_rows(const RowRange& rows, Index n) {
  const Index end = rows.end == -1 ? n : rows.end;
  if (rows.begin < 0 || rows.begin > end || end > n)
    throw std::invalid_argument("fast method: row range [" + std::to_string(rows.begin) + ", " +
                                std::to_string(rows.end) + ") is not within the rows [0, n) = [0, " +
                                std::to_string(n) + ") (need 0 <= begin <= end <= n; end -1 means n)");
  return {rows.begin, end};
}

}  // namespace

// Per (point, cluster) pair and core, measured on this machine (AMD EPYC at 2 GHz, AVX2 + FMA
// kernels of far_field_batch.hpp, 2 threads) with bench/product on the cube at n = 49,152, eta 0.5
// and 0.4, M = 6 and 7 (T = 28 and 36 terms; B = T x 8 or 4 bytes):
//   - recomputing in a product: 0.130 s and 0.242 s a product for 4.50 and 7.28 million pairs,
//     58 and 66 ns a pair: about 1.9 ns a term;
//   - reading stored coefficients: the product's multiply-adds, 1.3 ns a term (40 ns a pair at
//     T = 28, float or double), or the memory's bandwidth, 0.22 ns a byte over both cores
//     (double at T = 36: 2.17 GB in 0.229 s), whichever is slower;
//   - filling them at setup: the coefficients and the first touch of new memory, 2.2 ns a byte
//     (setup 1.46 s double and 0.64 s float against 0.095 s recomputing, at T = 28). The
//     coefficients took 3.5 ns a term one pair at a time; kLanes pairs at a time they take 0.39
//     and 0.48 of that (bench/threads --level 6 --single --keep-memory, one thread, M = 7 and 6:
//     0.112 s against 0.285 s and 0.173 s against 0.362 s, in one run), so 1.5 ns a term.
// So storing pays after about 17 products in single precision and almost never in double. The
// model is fixed (no timing at run time), so the choice, and with it the product's rounding,
// never varies between runs.
FarFieldCosts far_field_costs(int degree, std::size_t bytes_per_term) {
  constexpr double kRecomputeNsPerTerm = 1.9, kReadNsPerTerm = 1.3, kReadNsPerByte = 0.22;
  constexpr double kFillNsPerTerm = 1.5, kFirstTouchNsPerByte = 2.2;
  const double T = num_taylor_terms(degree);
  const double bytes = T * static_cast<double>(bytes_per_term);
  FarFieldCosts c;
  c.recompute_ns = kRecomputeNsPerTerm * T;
  c.read_ns = std::max(kReadNsPerTerm * T, kReadNsPerByte * bytes);
  c.fill_ns = kFillNsPerTerm * T + kFirstTouchNsPerByte * bytes;
  return c;
}

FastOperator::FastOperator(const Collocation& collocation, const FastOptions& options)
    : tree_(collocation.shared_tree()), options_(options) {
  check_options();
  n_ = tree_->num_elements();
  std::tie(row_begin_, row_end_) = resolve_rows(options_.rows, n_);
  terms_ = num_taylor_terms(options_.degree);
  Stopwatch clock;
  // The target clusters first (small: levels 0..lt), so that the memory gate counts the
  // per-point coverings that start below them.
  std::shared_ptr<TargetClusters> targets = make_target_clusters(*tree_, options_);
  stats_.targets_s = clock.seconds();
  if (options_.probe_samples > 0) {
    probed_.assign(static_cast<std::size_t>(row_end_ - row_begin_), 0);
    for (const Index i : self_check_rows(options_.probe_samples)) probed_[static_cast<std::size_t>(i - row_begin_)] = 1;
  } else {
    refuse_beyond_memory(collocation, targets.get());  // a probe holds a few rows beside the arrays of (48)
  }
  clock.restart();
  report_stage("fast operator, n = " + std::to_string(n_) + rows_note() + ": cluster frames and element moments");
  setup_cluster_frames();
  setup_element_data(collocation);
  stats_.geometry_s = clock.seconds();
  clock.restart();
  setup_target_clusters(std::move(targets));
  stats_.targets_s += clock.seconds();
  clock.restart();
  {
    char eta[32];
    std::snprintf(eta, sizeof eta, "%g", options_.eta);
    report_stage("fast operator: minimal admissible coverings (42) and near field (43), eta " + std::string(eta) +
                 ", M " + std::to_string(options_.degree));
  }
  cover_rows();
  store_coverings();
  stats_.covering_s = clock.seconds();  // covering (42) and near field (43)
  clock.restart();
  report_stage("fast operator: far field (44)-(45), " + std::to_string(stats_.far_pairs) + " (point, cluster) pairs, " +
               (stats_.far_stored ? "coefficients stored" : "coefficients recomputed per product (memory)"));
  setup_far_coefficients();
  stats_.far_s = clock.seconds();
  stats_.bytes = held_bytes();
}

void FastOperator::check_options() {
  if (!(options_.eta > 0 && options_.eta < 1))
    throw std::invalid_argument("fast method: eta = " + std::to_string(options_.eta) + " is outside (0, 1)");
  if (options_.degree < 0 || options_.degree > 12)
    throw std::invalid_argument("fast method: degree M = " + std::to_string(options_.degree) + " is outside [0, 12]");
  const LocalExpansionOptions& local = options_.local;
  if (local.degree < -1 || local.degree > kMaxLocalDegree)
    throw std::invalid_argument("fast method: local expansion degree d = " + std::to_string(local.degree) +
                                " is outside [0, " + std::to_string(kMaxLocalDegree) + "] (or -1: M)");
  if (!(local.eta >= 0 && local.eta <= 1))
    throw std::invalid_argument("fast method: target admissibility eta_t = " + std::to_string(local.eta) +
                                " is outside (0, 1] (or 0: eta)");
  if (local.min_points < 0)
    throw std::invalid_argument("fast method: local expansion min_points = " + std::to_string(local.min_points) +
                                " is negative");
}

// ", rows [begin, end)" when only some rows are held; empty for the whole operator.
std::string FastOperator::rows_note() const {
  if (holds_all_rows()) return "";
  return ", rows [" + std::to_string(row_begin_) + ", " + std::to_string(row_end_) + ")";
}

void FastOperator::report_stage(const std::string& what) const {
  if (options_.progress) options_.progress(what);
}

// Refuses what will not fit, before any large allocation.
void FastOperator::refuse_beyond_memory(const Collocation& collocation, const TargetClusters* targets) const {
  // What is available is read (files of /proc and the cgroup, serial) by one thread while the
  // others sample the coverings.
  std::size_t limit = options_.memory_limit;
  const MemoryEstimate est = estimate_memory(collocation, options_.eta, options_.degree, rows(), targets, [&] {
    if (!limit) limit = available_memory_bytes();
  });
  const std::size_t peak = est.bytes + est.list_bytes;
  if (peak > limit && !options_.memory_limit && ChunkPool::process().kept_bytes() > 0) {
    ChunkPool::process().release();  // the lists' chunks kept from earlier setups, before refusing
    limit = available_memory_bytes();
  }
  if (peak > limit)
    throw ResourceError("fast operator for n = " + std::to_string(n_) + rows_note() + " needs about " +
                        format_bytes(static_cast<double>(peak)) + " during setup (" +
                        format_bytes(static_cast<double>(est.list_bytes)) + " of near/far lists for about " +
                        std::to_string(est.far_pairs) + " far pairs), more than the " +
                        format_bytes(static_cast<double>(limit)) + " available; use fewer levels or a larger eta");
}

// Cluster ids, plane frames about A(tau) and the offsets of each A(tau) in its parent's frame
// (the shift of centre of (48)). A frame's axes depend on its normal alone (make_plane_frame),
// and every cluster has its root's normal (uniform subdivision), so the axes are held per root
// and each cluster above the finest level holds its origin (32 B); an element's origin is formed
// where it is read, from its centroid (the collocation point, held by the tree) and its shape.
void FastOperator::setup_cluster_frames() {
  const geometry::ClusterTree& tree = *tree_;
  const int L = tree.finest_level();
  unit_scale_ = far_field_unit(tree);
  level_offset_ = level_offsets(tree);
  root_axes_.resize(static_cast<std::size_t>(tree.num_roots()));
  for (Index r = 0; r < tree.num_roots(); ++r)
    root_axes_[static_cast<std::size_t>(r)] = make_plane_frame(unit_scale_ * tree.cluster(0, r).centre, tree.cluster(0, r).normal);
  // Held for the clusters above the finest level, a quarter of all: the elements' origins
  // follow from their centroids and their shapes (leaf_shift_, far_field_batch::ClusterFrames),
  // and the offsets are read by the shift of centre from level l + 1 to l, l <= L - 2 (compute_moments).
  const Index held = level_offset_[static_cast<std::size_t>(L)];
  cluster_origin_.resize(static_cast<std::size_t>(held));
  to_parent_.resize(static_cast<std::size_t>(held));
  // Per shape of the finest level (two per root, even and odd; one at level 0): s (A(root) - C(root))
  // in the far field's unit, s = +-2^-L, C(root) its centroid; the scalings by powers of two are
  // exact. An element's centroid lies in its root, so the root's corners in the unit bound it.
  const Index n0 = tree.num_roots();
  const int parities = L == 0 ? 1 : 2;
  leaf_shift_.resize(static_cast<std::size_t>(3 * parities * n0));
  bool finite = true;
  for (Index r = 0; r < n0; ++r) {
    const Cluster& root = tree.cluster(0, r);
    for (const Vec3& corner : root.vertex) finite = finite && (unit_scale_ * corner).allFinite();
    const Vec3 d = std::ldexp(unit_scale_, -L) * (root.centre - (root.vertex[0] + root.vertex[1] + root.vertex[2]) / 3.0);
    finite = finite && d.allFinite();
    for (int parity = 0; parity < parities; ++parity)
      for (int k = 0; k < 3; ++k)
        leaf_shift_[static_cast<std::size_t>(3 * (parities * r + parity) + k)] = parity ? -d[k] : d[k];
  }
#pragma omp parallel reduction(&& : finite)
  for (int l = 0; l < L; ++l) {  // no level waits for another: a child's offset forms its parent's origin anew
    const Index m = tree.level_size(l);
#pragma omp for schedule(dynamic, kLightChunk) nowait
    for (Index k = 0; k < m; ++k) {
      const Vec3 A = unit_scale_ * tree.cluster(l, k).centre;
      const Index id = cluster_id(l, k);
      finite = finite && A.allFinite();
      cluster_origin_[static_cast<std::size_t>(id)] = {{A[0], A[1], A[2]}, static_cast<std::int32_t>(k >> (2 * l))};
      to_parent_[static_cast<std::size_t>(id)] = l > 0 ? offset_in_parent(l, k, A) : std::array<double, 2>{0.0, 0.0};
    }
  }
  if (!finite) throw std::invalid_argument("fast operator: a cluster centre A(tau) is not finite in the far field's unit");
}

// A(tau) of cluster k of level l >= 1 (scaled: A) in its parent's frame, the parent's origin
// formed from the tree as setup_cluster_frames stores it (the same doubles as frame(parent)).
std::array<double, 2> FastOperator::offset_in_parent(int l, Index k, const Vec3& A) const {
  const Index parent = k / 4;
  PlaneFrame f = root_axes_[static_cast<std::size_t>(parent >> (2 * (l - 1)))];
  f.origin = unit_scale_ * tree_->cluster(l - 1, parent).centre;
  return f.local(A);
}

PlaneFrame FastOperator::frame(Index id) const {
  const Index leaf_begin = level_offset_[static_cast<std::size_t>(tree_->finest_level())];
  if (id >= leaf_begin) {  // an element: the same origin as the far-field kernels form
    double origin[3];
    PlaneFrame f = root_axes_[static_cast<std::size_t>(far_field_batch::element_origin(cluster_frames(), id - leaf_begin, origin))];
    f.origin = Vec3(origin[0], origin[1], origin[2]);
    return f;
  }
  const ClusterOrigin& o = cluster_origin_[static_cast<std::size_t>(id)];
  PlaneFrame f = root_axes_[static_cast<std::size_t>(o.axes)];
  f.origin = Vec3(o.origin[0], o.origin[1], o.origin[2]);
  return f;
}

Vec3 FastOperator::expansion_centre(Index id) const {
  if (id < 0 || id >= level_offset_.back())
    throw std::out_of_range("FastOperator::expansion_centre: cluster id " + std::to_string(id) + " is not in [0, " +
                            std::to_string(level_offset_.back()) + ")");
  return frame(id).origin;
}

far_field_batch::ClusterFrames FastOperator::cluster_frames() const {
  static_assert(sizeof(Vec3) == 3 * sizeof(double), "the collocation points are read as 3 doubles each");
  const int L = tree_->finest_level();
  return {cluster_origin_.data(), root_axes_.data(), level_offset_[static_cast<std::size_t>(L)], L,
          tree_->collocation_points().data()->data(), leaf_shift_.data(), unit_scale_};
}

far_field_batch::ClusterMoments FastOperator::cluster_moments(const double* moments, const double* v) const {
  const int L = tree_->finest_level();
  return {moments, level_offset_[static_cast<std::size_t>(L)], v, shape_moments_.data(), L};
}

// Element moments (48) Int_Delta x^p y^q dS about A(Delta), by shape, and rho(P_i) of every
// element (all n: the moments of a product and the self-check's vectors need the whole surface).
//
// Uniform midpoint subdivision makes every element of a root triangle Delta_0 congruent to it:
// children 0..2 of (a, b, c) are the parent scaled by 1/2 about a, b and c, child 3 (ab, bc, ca)
// is the parent scaled by -1/2 about its centroid. So element Delta of level L is
// s Delta_0 + t with s = (-1)^j 2^-L, j the number of digits 3 in its path from the root
// (element_parity), and its circumcentre is s A(Delta_0) + t. Its frame has the root's axes
// (e1, e2 depend on the normal alone), hence, in local coordinates about A,
//   Int_Delta x^p y^q dS = s^(p+q) |s|^2 Int_Delta0 x^p y^q dS
// (x = s x0, dS = s^2 dS0): two moment sets per root, the root's own scaled by the power of two
// 2^-L(p+q+2) (exact), with the odd degrees negated for odd j. They stand for the moments of the
// stored corners (midpoints rounded to double) up to that rounding: relative 2^-52 of the
// coordinates, i.e. 2^(L-52) of an element's size, far below the Taylor remainder (46).
void FastOperator::setup_element_data(const Collocation& collocation) {
  const geometry::ClusterTree& tree = *tree_;
  const int L = tree.finest_level();
  const int M = options_.degree;
  const std::size_t T = static_cast<std::size_t>(terms_);
  const Index n0 = tree.num_roots();
  shape_moments_.resize(static_cast<std::size_t>(n0) * (L == 0 ? 1 : 2) * T);  // level 0: every element is even
#pragma omp parallel for schedule(dynamic, 1)
  for (Index r = 0; r < n0; ++r) {
    const Cluster& root = tree.cluster(0, r);
    double* even = &shape_moments_[static_cast<std::size_t>(L == 0 ? r : 2 * r) * T];
    double* odd = L == 0 ? nullptr : even + T;
    triangle_moments(root_axes_[static_cast<std::size_t>(r)], unit_scale_ * root.vertex[0],
                     unit_scale_ * root.vertex[1], unit_scale_ * root.vertex[2], M, even);
    for (int k = 0; k <= M; ++k)
      for (int q = 0; q <= k; ++q) {
        const std::size_t t = static_cast<std::size_t>(taylor_index(k - q, q));
        even[t] = std::ldexp(even[t], -L * (k + 2));
        if (odd) odd[t] = k % 2 == 0 ? even[t] : -even[t];
      }
  }
  // Level L - 1: a cluster's four elements are placed about its A(tau) as those of any cluster
  // of its root congruent to it with the same labels: each digit 3 of its path below the root
  // negates it (the parity above) and turns its corners' labels by one (child 3 of (a, b, c) is
  // (ab, bc, ca), the images of (c, a, b)), so the number of digits 3 modulo 6 is its placement
  // class. Per class, the element moments shifted by the offsets of a representative cluster (the
  // path 0..03..3 with that many digits 3); other clusters' offsets differ from them by the
  // rounding of the centres (as for the element moments above).
  child_shape_moments_.clear();
  if (L >= 1) {
    const Index classes = placement_classes(L - 1);
    child_shape_moments_.assign(static_cast<std::size_t>(n0 * classes) * 4 * T, 0.0);
#pragma omp parallel for schedule(dynamic, 1)
    for (Index r = 0; r < n0; ++r)
      for (Index j = 0; j < classes; ++j) {
        const Index k = (r << (2 * (L - 1))) + ((Index{1} << (2 * j)) - 1);  // j trailing digits 3
        double* S = &child_shape_moments_[static_cast<std::size_t>((r * classes + j) * 4) * T];
        for (Index c = 0; c < 4; ++c) {
          const auto d = offset_in_parent(L, 4 * k + c, unit_scale_ * tree.cluster(L, 4 * k + c).centre);
          shift_moments_add(element_moments(4 * k + c).data(), d[0], d[1], M, S + static_cast<std::size_t>(c) * T);
        }
      }
  }
  rho_.resize(static_cast<std::size_t>(n_));
#pragma omp parallel for schedule(dynamic, kLightChunk)
  for (Index i = 0; i < n_; ++i) rho_[static_cast<std::size_t>(i)] = collocation.reflectivity()[i];
}

// The placement classes of the clusters of level l of a root: the number of digits 3 modulo 6,
// of which a path of l digits reaches min(l + 1, 6).
Index FastOperator::placement_classes(int l) { return std::min(l + 1, 6); }

std::span<const double> FastOperator::child_shape_moments(Index k) const {
  const int L = tree_->finest_level();
  if (L < 1 || k < 0 || k >= tree_->level_size(L - 1))
    throw std::out_of_range("FastOperator::child_shape_moments: cluster " + std::to_string(k) +
                            " is not one of level L - 1 = " + std::to_string(L - 1));
  const std::size_t T = static_cast<std::size_t>(terms_);
  const int P = L - 1;
  const std::size_t classes = static_cast<std::size_t>(placement_classes(P));
  const std::size_t shape = static_cast<std::size_t>(k >> (2 * P)) * classes + static_cast<std::size_t>(far_field_batch::path_threes(k, P) % 6);
  return {&child_shape_moments_[shape * 4 * T], 4 * T};
}

// The moments of element e's shape (setup_element_data): those of its root, even or odd.
std::span<const double> FastOperator::element_moments(Index e) const {
  if (e < 0 || e >= n_)
    throw std::out_of_range("FastOperator::element_moments: element " + std::to_string(e) + " is not in [0, " +
                            std::to_string(n_) + ")");
  const std::size_t T = static_cast<std::size_t>(terms_);
  const std::size_t shape = static_cast<std::size_t>(far_field_batch::element_shape(e, tree_->finest_level()));
  return {&shape_moments_[shape * T], T};
}

// The levels, degree and eta_t of the target clusters of an operator of `options` on a tree of
// finest level L: levels 0..lt, lt the finest level whose clusters hold at least min_points
// collocation points; lt = -1 when there are none (local expansions off, an occluded scene, or
// no level with that many points).
FastOperator::TargetPlan FastOperator::target_plan(const FastOptions& options, int L) {
  const LocalExpansionOptions& local = options.local;
  TargetPlan plan;
  plan.degree = local.degree >= 0 ? local.degree : default_local_degree(options.degree);
  plan.eta = local.eta > 0 ? local.eta : options.eta;
  const std::int64_t min_points = local.min_points > 0 ? local.min_points : num_local_points(plan.degree) + 1;
  if (!local.enabled || options.occluders) return plan;
  for (int l = 0; l <= L; ++l)
    if ((std::int64_t{1} << (2 * (L - l))) >= min_points) plan.level = l;
  return plan;
}

// The far field's length unit 2^k ~ diameter of the surface: G dS is invariant under scaling
// (G ~ length^-2), and scaling by a power of two is exact, so the Taylor coefficients
// (~ |P-A|^-(2+p+q)) and moments (~ R^(2+p+q)) stay far from overflow and underflow at any scene
// size that validation accepts (lengths 1e-75 .. 1e75), up to M = 12.
double FastOperator::far_field_unit(const geometry::ClusterTree& tree) { return std::ldexp(1.0, -std::ilogb(tree.diameter())); }

// Global cluster ids: the first id of each level l = 0..L+1 (the last: the number of clusters).
std::vector<Index> FastOperator::level_offsets(const geometry::ClusterTree& tree) {
  const int L = tree.finest_level();
  std::vector<Index> offset(static_cast<std::size_t>(L) + 2, 0);
  for (int l = 0; l <= L; ++l) offset[static_cast<std::size_t>(l) + 1] = offset[static_cast<std::size_t>(l)] + tree.level_size(l);
  return offset;
}

// The target clusters of target_plan with their sources (build_target_clusters), from the frames
// of the target levels (the same frames setup_cluster_frames makes); null when there are none.
std::shared_ptr<TargetClusters> FastOperator::make_target_clusters(const geometry::ClusterTree& tree,
                                                                   const FastOptions& options) {
  const TargetPlan plan = target_plan(options, tree.finest_level());
  if (plan.level < 0) return nullptr;
  const std::vector<Index> offset = level_offsets(tree);
  const double unit = far_field_unit(tree);
  // Written by the parallel loop below, not zeroed first by one thread; the levels are
  // independent, so no thread waits at the end of one.
  KeptVector<PlaneFrame> frames(static_cast<std::size_t>(offset[static_cast<std::size_t>(plan.level) + 1]));
#pragma omp parallel
  for (int l = 0; l <= plan.level; ++l) {
    const Index m = tree.level_size(l);
#pragma omp for schedule(dynamic, 256) nowait
    for (Index k = 0; k < m; ++k) {
      const Cluster& c = tree.cluster(l, k);
      frames[static_cast<std::size_t>(offset[static_cast<std::size_t>(l)] + k)] = make_plane_frame(unit * c.centre, c.normal);
    }
  }
  return std::make_shared<TargetClusters>(
      build_target_clusters(tree, frames.data(), offset, unit, options.eta, plan.eta, plan.level, plan.degree));
}

// The target clusters' slots: a target gets a slot for its values in a product when it holds a
// computed row and has sources of its own or a parent with a slot (whose expansion it inherits).
void FastOperator::setup_target_clusters(std::shared_ptr<TargetClusters> targets) {
  if (!targets) return;
  const geometry::ClusterTree& tree = *tree_;
  const int L = tree.finest_level();
  const int lt = targets->finest_level;
  report_stage("fast operator: target clusters of levels 0.." + std::to_string(lt) + " and their local expansions, d " +
               std::to_string(targets->degree));
  // Targets containing a computed row: marked on level lt, then up the tree.
  const Index num_targets = level_offset_[static_cast<std::size_t>(lt) + 1];
  std::vector<char> has_row(static_cast<std::size_t>(num_targets), 0);
  const Index first_target = row_begin_ >> (2 * (L - lt)), end_target = ((row_end_ - 1) >> (2 * (L - lt))) + 1;
#pragma omp parallel for schedule(dynamic, 64)
  for (Index k = first_target; k < std::max(first_target, end_target); ++k) {  // the targets of level lt: their rows
    const Index first = std::max(row_begin_, tree.first_element(lt, k)), end = std::min(row_end_, tree.end_element(lt, k));
    for (Index i = first; i < end && !has_row[static_cast<std::size_t>(cluster_id(lt, k))]; ++i)
      if (row_computed(i)) has_row[static_cast<std::size_t>(cluster_id(lt, k))] = 1;
  }
  for (int l = lt - 1; l >= 0; --l)
    for (Index k = 0; k < tree.level_size(l); ++k)
      for (Index c = 0; c < 4; ++c)
        has_row[static_cast<std::size_t>(cluster_id(l, k))] |= has_row[static_cast<std::size_t>(cluster_id(l + 1, 4 * k + c))];
  local_slot_.assign(static_cast<std::size_t>(num_targets), -1);
  for (int l = 0; l <= lt; ++l)
    for (Index k = 0; k < tree.level_size(l); ++k) {
      // A slot for every target with a computed row whose own or inherited expansion is not empty.
      const Index id = cluster_id(l, k);
      const bool inherits = l > 0 && local_slot_[static_cast<std::size_t>(cluster_id(l - 1, k / 4))] >= 0;
      if (!has_row[static_cast<std::size_t>(id)] || (targets->sources(id) == 0 && !inherits)) continue;
      local_slot_[static_cast<std::size_t>(id)] = static_cast<std::int64_t>(active_targets_.size());
      active_targets_.push_back(id);
      if (targets->sources(id) == 0) continue;
      ++stats_.target_clusters;
      stats_.target_pairs += static_cast<std::size_t>(targets->sources(id));
      stats_.target_point_pairs += static_cast<std::size_t>(targets->sources(id)) << (2 * (L - l));
    }
  stats_.target_level = lt;
  stats_.local_degree = targets->degree;
  targets_ = std::move(targets);
}

// Measured with bench/product on the cube at n = 49,152 (eta 0.5, M 6..8, 256 sampled rows): d = 4
// (25 points) adds no visible error to M <= 8 and is the fastest there (d = 3 gives 3e-4 at M 7,
// 13x the per-point error); above M = 7 the degree follows the Taylor degree, d = M - 3.
int default_local_degree(int M) { return M <= 4 ? M : std::max(4, M - 3); }

bool FastOperator::row_computed(Index i) const {
  return rho_[static_cast<std::size_t>(i)] != 0 && (probed_.empty() || probed_[static_cast<std::size_t>(i - row_begin_)]);
}

// One traversal per row held, in blocks of kRowBlock rows (dynamically scheduled): each thread
// gathers a block's coverings (42) (and the near-field integrals, (43) first sum) in lists of its
// own, reused from block to block, then writes them once into one piece of exactly their size in
// its own chunks (list_chunks_, kept by the process between operators: chunk_pool.hpp). Every
// block depends on its rows alone, so the lists are identical for any thread count.
void FastOperator::cover_rows() {
  const geometry::ClusterTree& tree = *tree_;
  const int L = tree.finest_level();
  const NearFieldIntegrator integrate_near(options_.near, tree.mesh_size());
  const Index num_blocks = (row_end_ - row_begin_ + kRowBlock - 1) / kRowBlock;
  blocks_.clear();
  blocks_.resize(static_cast<std::size_t>(num_blocks));
  list_chunks_.reset(omp_get_max_threads());
  std::size_t skipped = 0, skipped_rows = 0;
  std::size_t visible = 0, hidden = 0, partial = 0, clipped = 0;
  const geometry::Occluders* occluders = options_.occluders.get();
  bool out_of_memory = false, too_long = false;
#pragma omp parallel reduction(+ : skipped, skipped_rows, visible, hidden, partial, clipped)
  {
    std::vector<std::int64_t> near_count, far_count;  // the block being built, per row
    std::vector<Index> near_col, far_cluster;
    std::vector<double> near_val;
    VisibleCoveringScratch scratch;
#pragma omp for schedule(dynamic, 1)
    for (Index b = 0; b < num_blocks; ++b) try {
      const Index first = row_begin_ + b * kRowBlock, last = std::min(row_end_, first + kRowBlock);
      near_count.assign(static_cast<std::size_t>(last - first), 0);
      far_count.assign(static_cast<std::size_t>(last - first), 0);
      near_col.clear();
      near_val.clear();
      far_cluster.clear();
      VisibilityCounts counts;
      for (Index i = first; i < last; ++i) {
        const double rho = rho_[static_cast<std::size_t>(i)];
        if (rho == 0) {  // the row is zero: not computed
          ++skipped_rows;
          continue;
        }
        if (!probed_.empty() && !probed_[static_cast<std::size_t>(i - row_begin_)]) continue;  // a probe's row not sampled
        const Vec3& P = tree.collocation_point(i);
        const Vec3& nP = tree.cluster(L, i).normal;
        std::int64_t nn = 0, nf = 0;
        const auto add_far = [&](int l, Index k) {
          far_cluster.push_back(cluster_id(l, k));
          ++nf;
        };
        if (occluders) {
          cover_visible(
              tree, *occluders, P, nP, tree.plane(L, i), options_.eta, integrate_near, add_far,
              [&](Index e, double value) {
                near_col.push_back(e);
                near_val.push_back(rho * value);  // (43), first sum, over the visible part
                ++nn;
              },
              counts, scratch);
        } else {
          const ClusterRef* starts = nullptr;
          std::int64_t count = 0;
          if (targets_) {  // the clusters left by P's target cluster of level lt; its coplanar roots
            const std::size_t a = static_cast<std::size_t>(i >> (2 * (L - targets_->finest_level)));
            starts = targets_->start.data() + targets_->start_start[a];
            count = targets_->start_start[a + 1] - targets_->start_start[a];
            skipped += static_cast<std::size_t>(targets_->coplanar_roots[static_cast<std::size_t>(i >> (2 * L))]);
          }
          cover(
              tree, P, tree.plane(L, i), options_.eta, starts, count, add_far,
              [&](Index e) {
                near_col.push_back(e);
                near_val.push_back(rho * integrate_near(P, nP, tree.cluster(L, e)));  // (43), first sum
                ++nn;
              },
              [&]() { ++skipped; });
        }
        near_count[static_cast<std::size_t>(i - first)] = nn;
        far_count[static_cast<std::size_t>(i - first)] = nf;
      }
      skipped += counts.coplanar;
      visible += counts.visible;
      hidden += counts.hidden;
      partial += counts.partial;
      clipped += counts.clipped;
      if (std::max(near_col.size(), far_cluster.size()) > std::numeric_limits<std::uint32_t>::max()) {
#pragma omp atomic write
        too_long = true;
        continue;
      }
      RowBlock& blk = blocks_[static_cast<std::size_t>(b)];
      const std::size_t rows = near_count.size();
      blk.lists = list_chunks_.allocate(omp_get_thread_num(), RowBlock::list_bytes(rows, near_col.size(), far_cluster.size()));
      blk.rows = static_cast<std::uint32_t>(rows);
      blk.near = static_cast<std::uint32_t>(near_col.size());
      blk.far = static_cast<std::uint32_t>(far_cluster.size());
      std::uint32_t* near_start = blk.near_start();
      std::uint32_t* far_start = blk.far_start();
      std::uint32_t near = 0, far = 0;
      for (std::size_t r = 0; r < rows; ++r) {
        near_start[r] = near;
        far_start[r] = far;
        near += static_cast<std::uint32_t>(near_count[r]);
        far += static_cast<std::uint32_t>(far_count[r]);
      }
      near_start[rows] = near;
      far_start[rows] = far;
      std::copy(near_col.begin(), near_col.end(), blk.near_col());
      std::copy(near_val.begin(), near_val.end(), blk.near_val());
      std::copy(far_cluster.begin(), far_cluster.end(), blk.far_cluster());
    } catch (const std::bad_alloc&) {
#pragma omp atomic write
      out_of_memory = true;
    }
  }
  if (out_of_memory || too_long) {
    blocks_.clear();
    list_chunks_.clear();
    if (too_long)
      throw ResourceError("fast operator for n = " + std::to_string(n_) + rows_note() + ": a block of " +
                          std::to_string(kRowBlock) + " rows has more than 2^32 near or far pairs; use a larger eta");
    throw ResourceError("fast operator for n = " + std::to_string(n_) + rows_note() +
                        ": out of memory while building the near and far field lists (" + describe_available_memory() +
                        "); use fewer levels or a larger eta");
  }
  stats_.skipped_coplanar = skipped;
  stats_.skipped_rows = skipped_rows;
  stats_.occluded = occluders != nullptr;
  stats_.visible_pairs = visible;
  stats_.hidden_pairs = hidden;
  stats_.partial_pairs = partial;
  stats_.clipped_elements = clipped;
}

// The blocks' first far pairs among all (a short serial pass over the blocks), the pair counts,
// and whether the far coefficients are stored: only when they fit and storing pays for the
// products expected, else they are recomputed in each product.
void FastOperator::store_coverings() {
  std::int64_t near = 0, far = 0;
  for (RowBlock& blk : blocks_) {
    blk.far_first = far;
    near += blk.near;
    far += blk.far;
  }
  stats_.near_pairs = static_cast<std::size_t>(near);
  stats_.far_pairs = static_cast<std::size_t>(far);
  const std::size_t far_coef_bytes = stats_.far_pairs * static_cast<std::size_t>(terms_) * coefficient_bytes();
  const bool pays = options_.expected_products <= 0 ||
                    far_field_costs(options_.degree, coefficient_bytes()).store_pays(options_.expected_products);
  // The memory gate (files of /proc and the cgroup, serial) only when storing would pay and no
  // chunk kept by the process's pool can take the store (it then needs no new memory).
  const auto fits = [&] {
    if (options_.far_storage_limit) return far_coef_bytes <= options_.far_storage_limit;
    return ChunkPool::process().kept_for(far_coef_bytes) > 0 || far_coef_bytes <= available_memory_bytes() / 2;
  };
  stats_.far_stored = pays && fits();
}

FastOperator::RowLists FastOperator::row_lists(std::size_t r) const {
  const RowBlock& blk = blocks_[r / static_cast<std::size_t>(kRowBlock)];
  const std::size_t k = r % static_cast<std::size_t>(kRowBlock);
  const std::uint32_t* near_start = blk.near_start();
  const std::uint32_t* far_start = blk.far_start();
  const std::uint32_t near = near_start[k], far = far_start[k];
  return {blk.near_col() + near,  blk.near_val() + near, near_start[k + 1] - near,
          blk.far_cluster() + far, far_start[k + 1] - far, blk.far_first + far};
}

// The rho-scaled Taylor coefficients (44)-(45) of every far pair, when they are to be stored
// (rounded to float with single_precision_coefficients).
void FastOperator::setup_far_coefficients() {
  const std::size_t T = static_cast<std::size_t>(terms_);
  const bool single = options_.single_precision_coefficients;
  if (stats_.far_stored) {
    try {
      if (single) far_coef_single_ = LargeArray<float>(stats_.far_pairs * T);
      else far_coef_ = LargeBuffer(stats_.far_pairs * T);
    } catch (const std::bad_alloc&) {
      stats_.far_stored = false;  // could not have the memory after all: recompute per product
    }
  }
  if (!stats_.far_stored) return;
  const Index rows = row_end_ - row_begin_;
  const far_field_batch::Kernels& kernels = far_field_batch::kernels();
  const far_field_batch::ClusterFrames frames = cluster_frames();
  Index failed = rows;  // the first row whose coefficients could not be formed
#pragma omp parallel for schedule(dynamic, 64)
  for (Index r = 0; r < rows; ++r) {
    const RowLists row = row_lists(static_cast<std::size_t>(r));
    const std::size_t at = static_cast<std::size_t>(row.far_first) * T;
    const far_field_batch::RowPoint point = far_row_point(row_begin_ + r);
    const bool formed =
        single ? far_field_batch::row_coefficients(kernels, options_.degree, point, frames, row.far_cluster,
                                                   row.far_count, far_coef_single_.data() + at)
               : far_field_batch::row_coefficients(kernels, options_.degree, point, frames, row.far_cluster,
                                                   row.far_count, far_coef_.data() + at);
    if (!formed) {
#pragma omp critical(panelrad_far_coefficients_failed)
      failed = std::min(failed, r);
    }
  }
  if (failed < rows)
    throw std::invalid_argument("FastOperator: collocation point " + std::to_string(row_begin_ + failed) +
                                " coincides with the centre A(tau) of one of its far clusters or is not finite");
}

std::size_t FastOperator::held_bytes() const {
  const std::size_t num_clusters = static_cast<std::size_t>(level_offset_.back());
  std::size_t lists = 0;
  for (const RowBlock& blk : blocks_) lists += blk.bytes();
  return lists + far_coef_.bytes() + far_coef_single_.bytes() +
         cluster_origin_.size() * sizeof(ClusterOrigin) + root_axes_.size() * sizeof(PlaneFrame) + leaf_shift_.size() * sizeof(double) +
         to_parent_.size() * sizeof(to_parent_[0]) +
         (shape_moments_.size() + child_shape_moments_.size()) * sizeof(double) + rho_.size() * sizeof(double) +
         (num_clusters - static_cast<std::size_t>(n_)) * static_cast<std::size_t>(terms_) * sizeof(double) /* moments per product, above the finest level */ +
         (targets_ ? targets_->bytes() + local_slot_.size() * sizeof(std::int64_t) + active_targets_.size() * sizeof(Index) +
                         active_targets_.size() * static_cast<std::size_t>(num_local_points(targets_->degree)) *
                             sizeof(double) /* values per product */
                   : 0);
}

FastOperator::MemoryEstimate FastOperator::estimate_memory(const Collocation& collocation, double eta, int degree,
                                                           const RowRange& row_range) {
  return estimate_memory(collocation, eta, degree, row_range, nullptr);
}

FastOperator::MemoryEstimate FastOperator::estimate_memory(const Collocation& collocation, const FastOptions& options) {
  const std::shared_ptr<TargetClusters> targets = make_target_clusters(collocation.tree(), options);
  return estimate_memory(collocation, options.eta, options.degree, options.rows, targets.get());
}

FastOperator::MemoryEstimate FastOperator::estimate_memory(const Collocation& collocation, double eta, int degree,
                                                           const RowRange& row_range, const TargetClusters* targets,
                                                           const std::function<void()>& alongside) {
  const geometry::ClusterTree& tree = collocation.tree();
  const Index n = tree.num_elements();
  const auto [begin, end] = resolve_rows(row_range, n);
  const Index m = end - begin;
  const int L = tree.finest_level();
  const std::size_t T = static_cast<std::size_t>(num_taylor_terms(degree));
  std::size_t clusters = 0;
  for (int l = 0; l <= L; ++l) clusters += static_cast<std::size_t>(tree.level_size(l));
  const Index samples = std::min<Index>(m, 256);
  std::size_t near = 0, far = 0, sampled = 0, rows = 0;  // integer sums: the same for any thread count
  std::exception_ptr alongside_failed;
#pragma omp parallel reduction(+ : rows, near, far, sampled)
  {
    if (alongside) {
#pragma omp single nowait
      try {
        alongside();
      } catch (...) {
        alongside_failed = std::current_exception();
      }
    }
#pragma omp for schedule(dynamic, kLightChunk) nowait
    for (Index i = begin; i < end; ++i) rows += collocation.reflectivity()[i] != 0;
#pragma omp for schedule(dynamic, 1) nowait
    for (Index s = 0; s < samples; ++s) {
      const Index i = begin + static_cast<Index>((static_cast<std::int64_t>(s) * m + m / 2) / samples);
      if (collocation.reflectivity()[i] == 0) continue;
      ++sampled;
      const ClusterRef* starts = nullptr;  // the per-point covering from the roots, or below P's targets
      std::int64_t count = 0;
      if (targets) {
        const std::size_t a = static_cast<std::size_t>(i >> (2 * (L - targets->finest_level)));
        starts = targets->start.data() + targets->start_start[a];
        count = targets->start_start[a + 1] - targets->start_start[a];
      }
      cover(tree, collocation.collocation_point(i), tree.plane(L, i), eta, starts, count, [&](int, Index) { ++far; },
            [&](Index) { ++near; }, [] {});
    }
  }
  if (alongside_failed) std::rethrow_exception(alongside_failed);
  MemoryEstimate e;
  const double per_row = sampled ? 1.0 / static_cast<double>(sampled) : 0.0;
  const std::size_t near_pairs = static_cast<std::size_t>(static_cast<double>(near) * per_row * static_cast<double>(rows));
  e.far_pairs = static_cast<std::size_t>(static_cast<double>(far) * per_row * static_cast<double>(rows));
  e.near_pairs = near_pairs;
  e.list_bytes = near_pairs * (sizeof(Index) + sizeof(double)) + e.far_pairs * sizeof(Index);
  e.coefficient_bytes = e.far_pairs * T * sizeof(double);
  e.bytes = e.list_bytes + fixed_bytes(static_cast<std::size_t>(n), clusters, degree, static_cast<std::size_t>(m));
  if (targets) {  // the targets and their sources, a slot each and its values in a product (every target with one)
    const std::size_t num_targets = targets->box.size();
    e.bytes += targets->bytes() +
               num_targets * (sizeof(std::int64_t) + sizeof(Index) +
                              static_cast<std::size_t>(num_local_points(targets->degree)) * sizeof(double));
  }
  return e;
}

std::size_t FastOperator::fixed_bytes(std::size_t n, std::size_t clusters, int degree) {
  return fixed_bytes(n, clusters, degree, n);
}

std::size_t FastOperator::fixed_bytes(std::size_t n, std::size_t clusters, int degree, std::size_t rows) {
  const std::size_t T = static_cast<std::size_t>(num_taylor_terms(degree));
  // Per cluster above the finest level (clusters - n): frame, offset to the parent and moments
  // per product (an element's frame and moments are formed when read); per element: rho; per row
  // held: the near/far row starts; the element moments by shape, two per root (one at level 0:
  // n = n0), and four sets per placement class of level L - 1 (none at level 0);
  // n0 = 4 n - 3 clusters since clusters = n0 (4^(L+1) - 1) / 3 and n = n0 4^L.
  const std::size_t roots = 4 * n - 3 * clusters;
  const std::size_t shapes = std::min(n, 2 * roots);
  int L = 0;  // n = n0 4^L
  while (roots > 0 && L < 31 && (roots << (2 * L)) < n) ++L;
  const std::size_t parent_shapes = L >= 1 ? roots * static_cast<std::size_t>(placement_classes(L - 1)) : 0;  // 4 T each
  return (clusters - std::min(clusters, n)) * (sizeof(ClusterOrigin) + (T + 2) * sizeof(double)) +
         roots * (sizeof(PlaneFrame) + 6 * sizeof(double)) +
         n * sizeof(double) + (shapes + 4 * parent_shapes) * T * sizeof(double) + rows * 2 * sizeof(std::uint32_t) +
         (rows + static_cast<std::size_t>(kRowBlock) - 1) / static_cast<std::size_t>(kRowBlock) * (sizeof(RowBlock) + 2 * sizeof(std::uint32_t));
}

std::pair<int, Index> FastOperator::cluster_of_id(Index id) const {
  const auto it = std::upper_bound(level_offset_.begin(), level_offset_.end(), id);
  const int level = static_cast<int>(it - level_offset_.begin()) - 1;
  return {level, id - level_offset_[static_cast<std::size_t>(level)]};
}

// rho(P_i)/pi times the Taylor coefficients of G(P_i, .) about A(tau), (44)-(45): the stored
// coefficients, computed by the kernels of the recomputing product (far_field_batch.hpp), so that
// stored double and recomputed coefficients are the same numbers (their sums' order differs).
far_field_batch::RowPoint FastOperator::far_row_point(Index i) const {
  const Vec3 P = unit_scale_ * tree_->collocation_point(i);
  const Vec3& nP = tree_->elements()[static_cast<std::size_t>(i)].normal;
  return {{P[0], P[1], P[2]}, {nP[0], nP[1], nP[2]}, rho_[static_cast<std::size_t>(i)] / pi};
}

// Moments Int_tau v_n(Q) x^p y^q dS about A(tau) (48) of every cluster above the finest level:
// on level L - 1, sum_c v_c times the elements' moments about the cluster's A
// (child_shape_moments, shifted once per placement class at setup); then gathered up the tree
// with a shift of centre. An element's moments, v_e times those of its shape, are formed where
// the far field reads them (cluster_moments), never stored: three quarters of the clusters.
// O(n) per product.
void FastOperator::compute_moments(const Eigen::VectorXd& v, UninitializedVector<double>& moments) const {
  const geometry::ClusterTree& tree = *tree_;
  const int L = tree.finest_level();
  const std::size_t T = static_cast<std::size_t>(terms_);
  moments.resize(static_cast<std::size_t>(level_offset_[static_cast<std::size_t>(L)]) * T);  // every entry is written below
  if (L >= 1) {  // level L - 1: sum_c v_c times its elements' moments about its A (child_shape_moments)
    const Index size = tree.level_size(L - 1);
#pragma omp parallel for schedule(dynamic, kLightChunk / 8)
    for (Index k = 0; k < size; ++k) {
      double* m = &moments[static_cast<std::size_t>(cluster_id(L - 1, k)) * T];
      const double* S = child_shape_moments(k).data();
      for (std::size_t t = 0; t < T; ++t) m[t] = v[4 * k] * S[t];
      for (Index c = 1; c < 4; ++c) {
        const double vc = v[4 * k + c];
        const double* Sc = S + static_cast<std::size_t>(c) * T;
        for (std::size_t t = 0; t < T; ++t) m[t] += vc * Sc[t];
      }
    }
  }
  for (int l = L - 2; l >= 0; --l) {
    const Index size = tree.level_size(l);
#pragma omp parallel for schedule(dynamic, 64)
    for (Index k = 0; k < size; ++k) {
      double* m = &moments[static_cast<std::size_t>(cluster_id(l, k)) * T];
      std::fill(m, m + T, 0.0);
      for (Index c = 0; c < 4; ++c) {
        const Index child = cluster_id(l + 1, 4 * k + c);
        const auto& d = to_parent_[static_cast<std::size_t>(child)];
        shift_moments_add(&moments[static_cast<std::size_t>(child) * T], d[0], d[1], options_.degree, m);
      }
    }
  }
}

void FastOperator::append_target_ancestors(Index i, std::vector<Index>& out) const {
  if (!targets_) return;
  const int L = tree_->finest_level();
  for (int l = 0; l <= targets_->finest_level; ++l) {
    const Index id = cluster_id(l, i >> (2 * (L - l)));
    if (local_slot_[static_cast<std::size_t>(id)] >= 0) out.push_back(id);
  }
}

// Each target's values at its (d+1)^2 points: a far-field row (47) of the point (with the
// target's n_P and the factor 1/pi; rho_i multiplies the interpolant) over the target's sources,
// by the recomputing kernels of far_field_batch.hpp. Independent per target: any thread count
// gives the same values.
void FastOperator::evaluate_local_expansions(const double* moments, const double* v, int C,
                                             const std::vector<Index>& targets, std::vector<double>& values) const {
  const int d = targets_->degree;
  const int N = num_local_points(d);
  const std::size_t table = static_cast<std::size_t>(N) * static_cast<std::size_t>(C);
  values.assign(active_targets_.size() * table, 0.0);
  const far_field_batch::Kernels& kernels = far_field_batch::kernels();
  const Index count = static_cast<Index>(targets.size());
  const far_field_batch::ClusterMoments all_moments = cluster_moments(moments, v);
  bool failed = false;
#pragma omp parallel for schedule(dynamic, 1)
  for (Index t = 0; t < count; ++t) {
    const Index id = targets[static_cast<std::size_t>(t)];
    if (targets_->sources(id) == 0) continue;  // inherits its parent's expansion only
    const auto [l, k] = cluster_of_id(id);
    const Vec3& normal = tree_->cluster(l, k).normal;
    Vec3 points[num_local_points(kMaxLocalDegree)];
    targets_->box[static_cast<std::size_t>(id)].points(frame(id), d, points);
    far_field_batch::RowPoint rows[num_local_points(kMaxLocalDegree)];
    for (int q = 0; q < N; ++q)
      rows[q] = {{points[q][0], points[q][1], points[q][2]}, {normal[0], normal[1], normal[2]}, 1.0 / pi};
    const std::int64_t first = targets_->source_start[static_cast<std::size_t>(id)];
    double* out = values.data() + static_cast<std::size_t>(local_slot_[static_cast<std::size_t>(id)]) * table;
    if (!far_field_batch::add_points(kernels, options_.degree, rows, N, cluster_frames(), targets_->source.data() + first,
                                     targets_->sources(id), all_moments, C, out)) {
#pragma omp atomic write
      failed = true;
    }
  }
  if (failed)
    throw std::invalid_argument("FastOperator: an interpolation point of a target cluster coincides with the centre "
                                "A(tau) of one of its sources or is not finite");
  // Downward, level by level: each target adds its parent's expansion, evaluated at its own points
  // (the parent's interpolant, a tensor polynomial of degree d, is re-interpolated exactly up to
  // rounding: the child's rectangle lies in the parent's, in the same plane).
  const std::size_t C_ = static_cast<std::size_t>(C);
  for (int l = 1; l <= targets_->finest_level; ++l) {  // targets is ascending: level l's ids are one range
    const auto begin = std::lower_bound(targets.begin(), targets.end(), level_offset_[static_cast<std::size_t>(l)]);
    const auto end = std::lower_bound(begin, targets.end(), level_offset_[static_cast<std::size_t>(l) + 1]);
    const std::int64_t first = begin - targets.begin(), last = end - targets.begin();
#pragma omp parallel for schedule(dynamic, 16)
    for (std::int64_t t = first; t < last; ++t) {
      const Index id = targets[static_cast<std::size_t>(t)];
      const Index parent = cluster_id(l - 1, (id - cluster_id(l, 0)) / 4);
      const std::int64_t parent_slot = local_slot_[static_cast<std::size_t>(parent)];
      if (parent_slot < 0) continue;
      Vec3 points[num_local_points(kMaxLocalDegree)];
      targets_->box[static_cast<std::size_t>(id)].points(frame(id), d, points);
      const LocalBox& parent_box = targets_->box[static_cast<std::size_t>(parent)];
      const PlaneFrame parent_frame = frame(parent);
      const double* from = values.data() + static_cast<std::size_t>(parent_slot) * table;
      double* out = values.data() + static_cast<std::size_t>(local_slot_[static_cast<std::size_t>(id)]) * table;
      for (int q = 0; q < N; ++q) {
        double part[4];
        parent_box.interpolate(parent_frame, d, from, C, points[q], part);
        for (std::size_t c = 0; c < C_; ++c) out[static_cast<std::size_t>(q) * C_ + c] += part[c];
      }
    }
  }
}

template <int C>
void FastOperator::add_local_expansions(Index i, const double* values, double* sum) const {
  const int L = tree_->finest_level();
  const int d = targets_->degree;
  const std::size_t table = static_cast<std::size_t>(num_local_points(d)) * C;
  const Vec3 P = unit_scale_ * tree_->collocation_point(i);
  const int l = targets_->finest_level;  // its expansion holds those of its ancestors (evaluate_local_expansions)
  const Index id = cluster_id(l, i >> (2 * (L - l)));
  const std::int64_t slot = local_slot_[static_cast<std::size_t>(id)];
  if (slot < 0) return;
  double part[C];
  targets_->box[static_cast<std::size_t>(id)].interpolate(frame(id), d,
                                                           values + static_cast<std::size_t>(slot) * table, C, P, part);
  for (int c = 0; c < C; ++c) sum[c] += part[c];
}

namespace {

// sum[c] += sum_t coef[t] m[t C + c], (47), t in order for every column c; the stored coefficients
// in double or single precision (widened exactly to double before the product). Reading them is
// what a stored product costs; packets of columns keep the C sums in SIMD registers (Eigen's SIMD
// arithmetic is the scalar IEEE arithmetic, lane by lane, so each column's sum is the C = 1 sum).
template <int C, class Coef>
inline void add_far_terms(const Coef* coef, const double* m, std::size_t T, double* sum) {
  if constexpr (C % 2 == 0) {
    using Packet = Eigen::Array<double, C, 1>;
    Packet acc = Eigen::Map<const Packet>(sum);
    for (std::size_t t = 0; t < T; ++t) acc += static_cast<double>(coef[t]) * Eigen::Map<const Packet>(m + t * C);
    Eigen::Map<Packet> sums(sum);
    sums = acc;
  } else {
    for (std::size_t t = 0; t < T; ++t)
      for (int c = 0; c < C; ++c) sum[c] += static_cast<double>(coef[t]) * m[t * C + c];
  }
}

}  // namespace

// Row i (held) of the fast product (43) for C vectors, from their cluster moments: near field plus
// far field (47). v and moments hold the C columns interleaved (entry j of column c at j C + c), so
// that the C sums advance together; the lists and far coefficients are read once for all C.
// Recomputed coefficients: the far pairs go kFarFieldLanes at a time through the SIMD kernels of
// far_field_batch.hpp. Stored ones (double or float, widened exactly): pair by pair with
// add_far_terms. Both fix the order of every column's sums independently of C, so a column of a
// block product is bit-identical to the product of that column alone, for any thread count.
template <int C>
void FastOperator::apply_row_columns(Index i, const double* v, const double* moments, const double* local_values,
                                     double* /*scratch*/, double* out) const {
  const std::size_t r = static_cast<std::size_t>(i - row_begin_);
  double near[C], local[C];
  for (int c = 0; c < C; ++c) near[c] = local[c] = 0;
  if (targets_ && row_computed(i)) {
    add_local_expansions<C>(i, local_values, local);
    const double rho = rho_[static_cast<std::size_t>(i)];
    for (int c = 0; c < C; ++c) local[c] *= rho;
  }
  const RowLists row = row_lists(r);
  for (std::int64_t j = 0; j < row.near_count; ++j) {
    const double k = row.near_val[j];
    const double* vj = v + static_cast<std::size_t>(row.near_col[j]) * C;
    for (int c = 0; c < C; ++c) near[c] += k * vj[c];
  }
  const std::int64_t first = row.far_first, count = row.far_count;
  const Index* clusters = row.far_cluster;
  const far_field_batch::Kernels& kernels = far_field_batch::kernels();
  const std::size_t at = static_cast<std::size_t>(first) * static_cast<std::size_t>(terms_);  // pair's coefficients
  far_field_batch::RowSums sums;
  if (!stats_.far_stored) {
    if (!far_field_batch::add_recomputed_row(kernels, options_.degree, far_row_point(i), cluster_frames(), clusters,
                                             count, cluster_moments(moments, v), C, sums))
      throw std::invalid_argument("FastOperator: collocation point " + std::to_string(i) +
                                  " coincides with the centre A(tau) of a far cluster or is not finite");
  } else {
    // Stored: pair by pair, each column's sum in the same order for every C (the block products of
    // several channels read the coefficients once: measured faster than the lanes here).
    const std::size_t T = static_cast<std::size_t>(terms_);
    const far_field_batch::ClusterMoments all_moments = cluster_moments(moments, v);
    double far[C], buffer[far_field_batch::kMaxTerms * C];
    for (int c = 0; c < C; ++c) far[c] = 0;
    for (std::int64_t j = 0; j < count; ++j) {
      const double* m = far_field_batch::cluster_moments(all_moments, clusters[j], terms_, C, buffer);
      if (options_.single_precision_coefficients) add_far_terms<C>(far_coef_single_.data() + at + static_cast<std::size_t>(j) * T, m, T, far);
      else add_far_terms<C>(far_coef_.data() + at + static_cast<std::size_t>(j) * T, m, T, far);
    }
    for (int c = 0; c < C; ++c) out[c] = near[c] + far[c] + local[c];
    return;
  }
  for (int c = 0; c < C; ++c) out[c] = near[c] + sums.total(c) + local[c];
}

double FastOperator::apply_row(Index i, const Eigen::VectorXd& v, const UninitializedVector<double>& moments,
                               const std::vector<double>& local_values, double* scratch) const {
  double out;
  apply_row_columns<1>(i, v.data(), moments.data(), local_values.data(), scratch, &out);
  return out;
}

void FastOperator::apply(const Eigen::VectorXd& v, Eigen::VectorXd& y) const {
  if (!holds_all_rows())
    throw std::logic_error("FastOperator::apply: the operator holds only rows [" + std::to_string(row_begin_) + ", " +
                           std::to_string(row_end_) + ") of n = " + std::to_string(n_) +
                           "; apply_rows gives those rows");
  if (v.size() != n_) throw std::invalid_argument("FastOperator::apply: vector size differs from n");
  apply_rows(v, y);
}

FastOperator::ProductWorkspace& FastOperator::acquire_workspace(std::unique_lock<std::mutex>& lock,
                                                               ProductWorkspace& own) const {
  lock = std::unique_lock<std::mutex>(workspace_mutex_, std::try_to_lock);  // a concurrent product: its own
  return lock.owns_lock() ? workspace_ : own;
}

void FastOperator::apply_rows(const Eigen::VectorXd& v, Eigen::VectorXd& y_block) const {
  if (v.size() != n_) throw std::invalid_argument("FastOperator::apply_rows: vector size differs from n");
  std::unique_lock<std::mutex> lock;
  ProductWorkspace own;
  ProductWorkspace& w = acquire_workspace(lock, own);
  UninitializedVector<double>& moments = w.moments;
  std::vector<double>& local_values = w.local_values;
  compute_moments(v, moments);
  if (targets_) evaluate_local_expansions(moments.data(), v.data(), 1, active_targets_, local_values);
  const Index rows = row_end_ - row_begin_;
  y_block.resize(rows);
#pragma omp parallel
  {
    std::vector<double> scratch(static_cast<std::size_t>(terms_));
#pragma omp for schedule(dynamic, 256)
    for (Index r = 0; r < rows; ++r) y_block[r] = apply_row(row_begin_ + r, v, moments, local_values, scratch.data());
  }
}

void FastOperator::apply_block(const Eigen::MatrixXd& V, Eigen::MatrixXd& Y) const {
  if (!holds_all_rows())
    throw std::logic_error("FastOperator::apply_block: the operator holds only rows [" + std::to_string(row_begin_) +
                           ", " + std::to_string(row_end_) + ") of n = " + std::to_string(n_) +
                           "; apply_rows_block gives those rows");
  apply_rows_block(V, Y);
}

void FastOperator::apply_rows_block(const Eigen::MatrixXd& V, Eigen::MatrixXd& Y) const {
  if (V.rows() != n_) throw std::invalid_argument("FastOperator::apply_block: vector size differs from n");
  static_assert(kBlockColumns == 4, "apply_block dispatches on 1..4 columns");
  const Index columns = static_cast<Index>(V.cols());
  const Index rows = row_end_ - row_begin_;
  Y.resize(rows, columns);
  const std::size_t n = static_cast<std::size_t>(n_);
  std::unique_lock<std::mutex> lock;
  ProductWorkspace own;
  ProductWorkspace& w = acquire_workspace(lock, own);
  UninitializedVector<double>& moments = w.moments;
  UninitializedVector<double>& v_block = w.v_block;
  UninitializedVector<double>& m_block = w.m_block;
  std::vector<double>& local_values = w.local_values;
  for (Index first = 0; first < columns; first += kBlockColumns) {
    const int C = static_cast<int>(std::min<Index>(kBlockColumns, columns - first));
    // The group's columns and their moments (48), interleaved: entry j of column c at j C + c.
    v_block.resize(n * static_cast<std::size_t>(C));
    for (int c = 0; c < C; ++c) {
      const Eigen::VectorXd column = V.col(first + c);  // compute_moments reads a vector
      compute_moments(column, moments);
      if (c == 0) m_block.resize(moments.size() * static_cast<std::size_t>(C));
      const std::size_t M = moments.size();
#pragma omp parallel for schedule(dynamic, kLightChunk)
      for (std::size_t j = 0; j < std::max(n, M); ++j) {
        if (j < n) v_block[j * static_cast<std::size_t>(C) + static_cast<std::size_t>(c)] = column[static_cast<Index>(j)];
        if (j < M) m_block[j * static_cast<std::size_t>(C) + static_cast<std::size_t>(c)] = moments[j];
      }
    }
    if (targets_) evaluate_local_expansions(m_block.data(), v_block.data(), C, active_targets_, local_values);
    const double* lv = local_values.data();
#pragma omp parallel
    {
      std::vector<double> scratch(static_cast<std::size_t>(terms_));
      double out[kBlockColumns];
#pragma omp for schedule(dynamic, 256)
      for (Index r = 0; r < rows; ++r) {
        const Index i = row_begin_ + r;
        switch (C) {
          case 1: apply_row_columns<1>(i, v_block.data(), m_block.data(), lv, scratch.data(), out); break;
          case 2: apply_row_columns<2>(i, v_block.data(), m_block.data(), lv, scratch.data(), out); break;
          case 3: apply_row_columns<3>(i, v_block.data(), m_block.data(), lv, scratch.data(), out); break;
          default: apply_row_columns<4>(i, v_block.data(), m_block.data(), lv, scratch.data(), out); break;
        }
        for (int c = 0; c < C; ++c) Y(r, first + c) = out[c];
      }
    }
  }
}

std::vector<std::pair<std::string, Eigen::VectorXd>> FastOperator::self_check_vectors() const {
  std::vector<std::pair<std::string, Eigen::VectorXd>> out;
  if (n_ == 0) return out;
  const auto elements = tree_->elements();
  // Coordinates scaled to the bounding box of the collocation points: s in [0, 1]^3.
  const std::span<const Vec3> points = tree_->collocation_points();
  Vec3 lo = points.front(), hi = points.front();
  for (const Vec3& P : points) {
    lo = lo.cwiseMin(P);
    hi = hi.cwiseMax(P);
  }
  Vec3 inv_extent;
  for (int a = 0; a < 3; ++a) inv_extent[a] = hi[a] > lo[a] ? 1.0 / (hi[a] - lo[a]) : 0.0;
  const auto scaled = [&](Index j) -> Vec3 { return (points[static_cast<std::size_t>(j)] - lo).cwiseProduct(inv_extent); };
  const auto make = [&](const std::string& name, auto&& value) {
    Eigen::VectorXd v(n_);
#pragma omp parallel for schedule(static)
    for (Index j = 0; j < n_; ++j) v[j] = value(j);
    out.emplace_back(name, std::move(v));
  };
  make("1", [](Index) { return 1.0; });
  make("x", [&](Index j) { return scaled(j).x(); });
  make("x^2 + y^2 + z^2", [&](Index j) { return scaled(j).squaredNorm(); });
  make("cos 7x + sin(5y) z", [&](Index j) {
    const Vec3 s = scaled(j);
    return std::cos(7 * s.x()) + std::sin(5 * s.y()) * s.z();
  });
  // Sign per facet from a fixed 64-bit mix of the facet index (splitmix64's finalizer).
  const auto mix = [](std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  make("+-1 by facet", [&](Index j) {
    const auto f = static_cast<std::uint64_t>(elements[static_cast<std::size_t>(j)].facet);
    return (mix(f + 0x9e3779b97f4a7c15ULL) >> 63) ? 1.0 : -1.0;
  });
  make("random +-1", [&](Index j) {
    return (mix(static_cast<std::uint64_t>(j) * 0x9e3779b97f4a7c15ULL + 1) >> 63) ? 1.0 : -1.0;
  });
  return out;
}

// The rows of the self-check (FastSelfCheck in the header), among the rows held: every row, or
// half evenly spaced and half at corners of the input triangles; ascending.
std::vector<Index> FastOperator::self_check_rows(int samples) const {
  const geometry::ClusterTree& tree = *tree_;
  const auto elements = tree.elements();
  const int L = tree.finest_level();
  const Index m = row_end_ - row_begin_;
  std::vector<Index> rows;
  if (samples >= m) {
    rows.resize(static_cast<std::size_t>(m));
    for (Index r = 0; r < m; ++r) rows[static_cast<std::size_t>(r)] = row_begin_ + r;
    return rows;
  }
  samples = std::max(samples, 1);
  const Index even = std::max(1, samples - samples / 2);
  for (Index k = 0; k < even; ++k)
    rows.push_back(row_begin_ + static_cast<Index>((static_cast<std::int64_t>(k) * m) / even + (m / even) / 2));
  std::vector<Index> corners;  // elements sharing a vertex with their input triangle (level-0 ancestor)
  for (Index e = row_begin_; e < row_end_; ++e) {
    const Cluster& root = tree.cluster(0, e >> (2 * L));
    const Cluster& c = elements[static_cast<std::size_t>(e)];
    bool corner = false;
    for (const Vec3& p : c.vertex)
      for (const Vec3& q : root.vertex) corner = corner || p == q;
    if (corner) corners.push_back(e);
  }
  const Index at_corners = std::min<Index>(samples - even, static_cast<Index>(corners.size()));
  for (Index k = 0; k < at_corners; ++k)
    rows.push_back(corners[static_cast<std::size_t>((static_cast<std::int64_t>(k) * static_cast<std::int64_t>(corners.size())) / at_corners)]);
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  return rows;
}

// Per sampled row r and vector k (index r * V + k): (K v_k)_r and (K |v_k|)_r from the exact
// closed-form entries (one form factor per element, O(n) per row).
void FastOperator::exact_rows(FastSelfCheckReference& reference) const {
  const auto elements = tree_->elements();
  const int L = tree_->finest_level();
  const auto& rows = reference.rows;
  const auto& vectors = reference.vectors;
  const std::size_t V = vectors.size(), S = rows.size();
  // v_k(j) and |v_k(j)| interleaved per element: the exact rows' inner loop reads them in order.
  std::vector<double> values(static_cast<std::size_t>(n_) * 2 * V);
#pragma omp parallel for schedule(static)
  for (Index j = 0; j < n_; ++j)
    for (std::size_t k = 0; k < V; ++k) {
      values[(static_cast<std::size_t>(j) * V + k) * 2] = vectors[k].second[j];
      values[(static_cast<std::size_t>(j) * V + k) * 2 + 1] = std::abs(vectors[k].second[j]);
    }
  reference.exact.assign(S * V, 0.0);
  reference.scale.assign(S * V, 0.0);
  const geometry::Occluders* occluders = options_.occluders.get();
  const NearFieldIntegrator exact_near(NearFieldOptions{}, tree_->mesh_size());  // the closed form
#pragma omp parallel
  {
    VisibleCoveringScratch covering;
    // A row's sums are held by its thread until the row is done: the rows of neighbouring
    // entries of `exact` and `scale` share cache lines, and go to other threads.
    std::vector<double> sums(2 * V);
#pragma omp for schedule(dynamic, 1)
    for (std::size_t r = 0; r < S; ++r) {
      const Index i = rows[r];
      const double rho = rho_[static_cast<std::size_t>(i)];
      if (rho == 0) continue;
      double* ex = sums.data();
      double* sc = sums.data() + V;
      std::fill(sums.begin(), sums.end(), 0.0);
      const Vec3& P = tree_->collocation_point(i);
      const Vec3& nP = elements[static_cast<std::size_t>(i)].normal;
      const auto add = [&](Index j, double form_factor) {
        const double kij = rho * form_factor;
        const double* vj = &values[static_cast<std::size_t>(j) * 2 * V];
        for (std::size_t k = 0; k < V; ++k) {
          ex[k] += kij * vj[2 * k];
          sc[k] += kij * vj[2 * k + 1];
        }
      };
      if (occluders) {
        // The exact row with V: every element's closed-form form factor over its visible part,
        // by the walk with nothing admissible (eta = 0).
        VisibilityCounts counts;
        cover_visible(*tree_, *occluders, P, nP, tree_->plane(L, i), 0.0, exact_near, [](int, Index) {}, add, counts,
                      covering);
      } else {
        const Index plane = tree_->plane(L, i);
        for (Index j = 0; j < n_; ++j) {
          const Cluster& e = elements[static_cast<std::size_t>(j)];
          if (tree_->plane(L, j) == plane) continue;  // coplanar: G = 0
          add(j, quadrature::form_factor(P, nP, e.vertex[0], e.vertex[1], e.vertex[2], e.normal));
        }
      }
      std::copy(ex, ex + V, reference.exact.begin() + static_cast<std::ptrdiff_t>(r * V));
      std::copy(sc, sc + V, reference.scale.begin() + static_cast<std::ptrdiff_t>(r * V));
    }
  }
}

FastSelfCheckReference FastOperator::self_check_reference(int samples) const {
  FastSelfCheckReference reference;
  if (row_end_ == row_begin_) return reference;
  Stopwatch clock;
  reference.rows = self_check_rows(samples);
  reference.vectors = self_check_vectors();
  exact_rows(reference);
  reference.seconds = clock.seconds();
  return reference;
}

FastSelfCheck FastOperator::self_check(int samples) const {
  if (row_end_ == row_begin_) return {};
  return self_check(self_check_reference(samples));
}

// Exact entries of a row are cheap (one closed-form form factor per element, O(n)): compare the
// fast rows with them for every test vector (FastSelfCheck in the header).
FastSelfCheck FastOperator::self_check(const FastSelfCheckReference& reference) const {
  FastSelfCheck check;
  if (row_end_ == row_begin_) return check;
  Stopwatch clock;
  const auto& rows = reference.rows;
  const auto& vectors = reference.vectors;
  const std::size_t V = vectors.size(), S = rows.size();
  for (const Index i : rows)
    if (i < row_begin_ || i >= row_end_)
      throw std::invalid_argument("FastOperator::self_check: reference row " + std::to_string(i) +
                                  " is not among the rows held");
  for (const auto& v : vectors)
    if (v.second.size() != n_) throw std::invalid_argument("FastOperator::self_check: reference vector size differs from n");
  if (reference.exact.size() != S * V || reference.scale.size() != S * V)
    throw std::invalid_argument("FastOperator::self_check: reference rows and vectors do not match its values");
  std::vector<Index> targets;  // the sampled rows' target ancestors: only their local expansions are needed
  for (const Index i : rows) append_target_ancestors(i, targets);
  std::sort(targets.begin(), targets.end());
  targets.erase(std::unique(targets.begin(), targets.end()), targets.end());
  // One vector at a time through one array of cluster moments (48): the moments are the largest
  // array of a product (T doubles per cluster above the finest level, n/3 clusters), so holding
  // all V at once would take V times a product's memory.
  std::unique_lock<std::mutex> lock;
  ProductWorkspace own;
  ProductWorkspace& w = acquire_workspace(lock, own);
  UninitializedVector<double>& moments = w.moments;
  std::vector<double>& local_values = w.local_values;
  std::vector<double> fast(S * V, 0.0);
  for (std::size_t k = 0; k < V; ++k) {
    compute_moments(vectors[k].second, moments);
    if (targets_) evaluate_local_expansions(moments.data(), vectors[k].second.data(), 1, targets, local_values);
#pragma omp parallel
    {
      std::vector<double> scratch(static_cast<std::size_t>(terms_));
#pragma omp for schedule(dynamic, 1)
      for (std::size_t r = 0; r < S; ++r)
        fast[r * V + k] = apply_row(rows[r], vectors[k].second, moments, local_values, scratch.data());
    }
  }
  const auto& exact = reference.exact;
  const auto& scale = reference.scale;
  check.rows = static_cast<int>(S);
  check.sampled_rows = rows;
  for (std::size_t k = 0; k < V; ++k) {
    SelfCheckVector c;
    c.name = vectors[k].first;
    double err = 0, ref = 0;
    for (std::size_t r = 0; r < S; ++r) {
      // NaN-aware: a non-finite product is an infinite error, never ignored by max().
      double d = std::abs(fast[r * V + k] - exact[r * V + k]);
      if (!std::isfinite(d)) d = std::numeric_limits<double>::infinity();
      if (c.row < 0 || d > err) {
        err = d;
        c.row = rows[r];
      }
      ref = std::max(ref, scale[r * V + k]);
    }
    c.relative_error = ref > 0 ? err / ref : err;
    check.relative_error = std::max(check.relative_error, c.relative_error);
    check.vectors.push_back(std::move(c));
  }
  check.seconds = clock.seconds() + reference.seconds;
  return check;
}

// Position of row i in the arrays of the rows held; std::out_of_range for a row not held.
std::size_t FastOperator::local_row(Index i, const char* who) const {
  if (i < row_begin_ || i >= row_end_)
    throw std::out_of_range(std::string("FastOperator::") + who + ": row " + std::to_string(i) +
                            " is not among the rows held, [" + std::to_string(row_begin_) + ", " +
                            std::to_string(row_end_) + ")");
  return static_cast<std::size_t>(i - row_begin_);
}

std::vector<Index> FastOperator::far_clusters(Index i) const {
  const std::size_t r = local_row(i, "far_clusters");
  std::vector<Index> out, targets;
  if (row_computed(i)) append_target_ancestors(i, targets);
  for (const Index id : targets) {
    const std::int64_t first = targets_->source_start[static_cast<std::size_t>(id)];
    out.insert(out.end(), targets_->source.begin() + first, targets_->source.begin() + first + targets_->sources(id));
  }
  const RowLists row = row_lists(r);
  out.insert(out.end(), row.far_cluster, row.far_cluster + row.far_count);
  return out;
}

std::vector<Index> FastOperator::near_elements(Index i) const {
  const std::size_t r = local_row(i, "near_elements");
  const RowLists row = row_lists(r);
  return {row.near_col, row.near_col + row.near_count};
}

}  // namespace panelrad

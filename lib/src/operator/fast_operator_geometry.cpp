// The fast operator's cluster geometry: the frames of the clusters about their expansion centres
// A(tau), the offsets of the shift of centre, the element moments (48) by shape and the clusters'
// moments of a product (compute_moments).
#include <panelrad/operator/fast_operator.hpp>

#include "fast_operator_common.hpp"
#include "far_field_batch.hpp"
#include <panelrad/operator/kernel.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace panelrad {

using geometry::Cluster;
using geometry::Index;

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
  setup_shape_moments();
  setup_child_shape_moments();
  rho_.resize(static_cast<std::size_t>(n_));
#pragma omp parallel for schedule(dynamic, kLightChunk)
  for (Index i = 0; i < n_; ++i) rho_[static_cast<std::size_t>(i)] = collocation.reflectivity()[i];
}

// The element moments by shape: per root, its own moments about A(Delta_0) scaled by 2^-L(p+q+2),
// and (L >= 1) the odd elements' with the odd degrees negated.
void FastOperator::setup_shape_moments() {
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
}

// Level L - 1: a cluster's four elements are placed about its A(tau) as those of any cluster
// of its root congruent to it with the same labels: each digit 3 of its path below the root
// negates it (the parity above) and turns its corners' labels by one (child 3 of (a, b, c) is
// (ab, bc, ca), the images of (c, a, b)), so the number of digits 3 modulo 6 is its placement
// class. Per class, the element moments shifted by the offsets of a representative cluster (the
// path 0..03..3 with that many digits 3); other clusters' offsets differ from them by the
// rounding of the centres (as for the element moments above).
void FastOperator::setup_child_shape_moments() {
  const geometry::ClusterTree& tree = *tree_;
  const int L = tree.finest_level();
  const int M = options_.degree;
  const std::size_t T = static_cast<std::size_t>(terms_);
  const Index n0 = tree.num_roots();
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

}  // namespace panelrad

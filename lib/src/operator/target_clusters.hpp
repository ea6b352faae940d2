#pragma once
// The cluster-cluster part of the minimal admissible coverings (42): target clusters sigma of the
// levels 0..lt of the tree, each with the source clusters admissible for all of it (taken by its
// local expansion, local_expansion.hpp), and for each cluster of level lt the clusters where the
// per-point coverings of its collocation points start. For every collocation point P of sigma,
// the sources of P's ancestors of levels 0..lt, the clusters skipped as coplanar with P and P's
// per-point covering of the starts partition the surface, as the covering from the roots does.
//
// A pair (sigma, tau) is admissible when, with c and R_b the centre and half-diagonal of the
// rectangle bounding sigma (LocalBox) and D = |c - A(tau)|,
//   (i)  R(tau) <= eta (D - R_b):   every point of the rectangle satisfies (41) for tau, so the
//        Taylor far field (44)-(47) at the interpolation points has the per-point error bound;
//   (ii) R_b <= eta_t (D - R(tau)): the rectangle is small against its distance from tau, which
//        sets the interpolation's rate (local_expansion.hpp).
// Both are decided by the exact-on-doubles test of (41) (geometry::is_admissible) with the
// radius R(tau) + eta R_b (resp. R_b + eta_t R(tau)) rounded upward: conservative, never a pair
// that the exact condition would refuse. A non-admissible tau is split when it is not a leaf and
// at least as large as the rectangle (R(tau) >= R_b); otherwise it is handed to sigma's children,
// and from level lt to the per-point coverings.
//
// With the line-of-sight function V (occluders given), each pair is first classified for all of
// sigma at once (geometry::Occluders::classify_clusters): a pair hidden from every point of sigma
// by the planes alone is dropped (its integral is 0 for each); an admissible pair is a source only
// when tau is fully visible from all of sigma (no face may block a segment of conv(sigma, tau)),
// and otherwise it is handed down whole (not split: its parts would mostly be undecided too, and
// a point classifies a whole cluster once where it would classify each part), so that sigma's
// children, and from level lt the points, decide it (visible_covering.hpp).
#include <panelrad/geometry/cluster_tree.hpp>
#include <panelrad/geometry/occluders.hpp>
#include <panelrad/support/uninitialized_vector.hpp>
#include <panelrad/operator/local_expansion.hpp>
#include <panelrad/support/kept_vector.hpp>

#include <cstdint>
#include <vector>

namespace panelrad {

/// Cluster k of level l. Trivial (no member initializers): arrays of them, such as a
/// traversal's stack, are not written before use.
struct ClusterRef {
  int level;
  geometry::Index k;
};

struct TargetClusters {
  int finest_level = -1;  ///< lt; -1: no target clusters (per-point coverings from the roots)
  int degree = 0;         ///< d of the local expansions
  /// Per target cluster, by cluster id (ids of levels 0..lt): the rectangle in the cluster's
  /// frame, and the CSR of its sources (cluster ids).
  KeptVector<LocalBox> box;
  std::vector<std::int64_t> source_start;
  KeptVector<geometry::Index> source;
  /// Per cluster k of level lt: the CSR of the clusters where its points' coverings start.
  std::vector<std::int64_t> start_start;
  KeptVector<ClusterRef> start;
  /// Per root (level-0 cluster): the roots skipped as coplanar with it (each point of the root
  /// skips them too).
  std::vector<std::int32_t> coplanar_roots;
  /// With V: the (target, cluster) pairs dropped as hidden from the whole target, and the admissible
  /// ones not proven fully visible (handed down whole instead of taken as sources).
  std::size_t hidden_pairs = 0, undecided_pairs = 0;

  bool empty() const { return finest_level < 0; }
  std::int64_t sources(geometry::Index id) const {
    return source_start[static_cast<std::size_t>(id) + 1] - source_start[static_cast<std::size_t>(id)];
  }
  std::size_t bytes() const;
};

/// The target clusters of levels 0..lt of `tree` (lt in [0, finest level]) with local
/// expansions of degree d. `frames` are the clusters' frames by cluster id (level_offset's last entry of them) (origin A(tau) scaled
/// by unit_scale, a power of two), `level_offset` the first id of each level. Deterministic for
/// any thread count. `occluders`: V computed (see above); null on a convex surface (V = 1).
TargetClusters build_target_clusters(const geometry::ClusterTree& tree, const PlaneFrame* frames,
                                     const std::vector<geometry::Index>& level_offset, double unit_scale, double eta,
                                     double eta_t, int lt, int d, const geometry::Occluders* occluders = nullptr);

}  // namespace panelrad

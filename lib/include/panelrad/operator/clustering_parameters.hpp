#pragma once
// The parameters of the panel-clustering product of section 4: eta, M, and the target clusters'
// local expansions.
namespace panelrad {

/// The cluster-cluster far field (cluster-cluster interactions): target clusters with at least
/// `min_points` collocation points take the source clusters admissible for all of them through a
/// local expansion of degree `degree` (operator/local_expansion.hpp), (degree+1)^2 far-field evaluations per pair instead of one
/// per point; the finer levels keep the per-point coverings (42). With V a source is taken only
/// when it is fully visible from all of the target (a cluster-to-cluster shaft test); the rest is
/// left to the points.
struct LocalExpansionOptions {
  bool enabled = true;
  /// Interpolation degree d in each in-plane coordinate, 0..12; -1: default_local_degree(M).
  int degree = -1;
  /// eta_t of the target admissibility R(box) <= eta_t (|c - A(tau)| - R(tau)); 0: eta.
  double eta = 0;
  /// The fewest collocation points of a target cluster (4^(L - l) on level l); 0: automatic,
  /// (d+1)^2 + 1: more points than a pair's evaluations.
  int min_points = 0;
  bool operator==(const LocalExpansionOptions&) const = default;
};

/// The far-field approximation's parameters, shared by the fast operator's options and the
/// operator factory's.
struct ClusteringParameters {
  /// Admissibility parameter of (41): a cluster tau is far from P when
  /// diam(tau) <= eta dist(P, centre(tau)); in (0, 1).
  double eta = 0.2;
  /// Taylor degree M of the far-field expansion (44), 0..12.
  int degree = 2;
  /// Target clusters' local expansions (the cluster-cluster far field); off: the paper's
  /// per-point coverings (42) alone.
  LocalExpansionOptions local;
  bool operator==(const ClusteringParameters&) const = default;
};

}  // namespace panelrad

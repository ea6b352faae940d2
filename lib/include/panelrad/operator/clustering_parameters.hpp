#pragma once
// The two parameters of the panel-clustering product of section 4.
namespace panelrad {

/// The far-field approximation's parameters, shared by the fast operator's options and the
/// operator factory's.
struct ClusteringParameters {
  /// Admissibility parameter of (41): a cluster tau is far from P when
  /// diam(tau) <= eta dist(P, centre(tau)); in (0, 1).
  double eta = 0.2;
  /// Taylor degree M of the far-field expansion (44), 0..12.
  int degree = 2;
  bool operator==(const ClusteringParameters&) const = default;
};

}  // namespace panelrad

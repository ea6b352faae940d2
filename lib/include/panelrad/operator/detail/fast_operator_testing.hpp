#pragma once
// For the tests only, not the operator's interface: the fast operator's coverings (42), cluster
// ids, expansion centres and element moments as it holds them (FastOperator's private members,
// documented there), so that tests can check them against independent computations.
#include <panelrad/operator/fast_operator.hpp>

#include <span>
#include <utility>
#include <vector>

namespace panelrad::detail {

struct FastOperatorTesting {
  static std::vector<geometry::Index> far_clusters(const FastOperator& op, geometry::Index i) { return op.far_clusters(i); }
  static std::vector<geometry::Index> near_elements(const FastOperator& op, geometry::Index i) { return op.near_elements(i); }
  static std::span<const double> element_moments(const FastOperator& op, geometry::Index e) { return op.element_moments(e); }
  static std::span<const double> child_shape_moments(const FastOperator& op, geometry::Index k) {
    return op.child_shape_moments(k);
  }
  static Vec3 expansion_centre(const FastOperator& op, geometry::Index id) { return op.expansion_centre(id); }
  static geometry::Index cluster_id(const FastOperator& op, int level, geometry::Index k) { return op.cluster_id(level, k); }
  static std::pair<int, geometry::Index> cluster_of_id(const FastOperator& op, geometry::Index id) {
    return op.cluster_of_id(id);
  }
  static double far_field_unit(const geometry::ClusterTree& tree) { return FastOperator::far_field_unit(tree); }
  static geometry::Index placement_classes(int l) { return FastOperator::placement_classes(l); }
};

/// Cluster ids of the far field and element ids of the near field of row i: the covering plus
/// the skipped coplanar clusters partition the surface. The far field is the sources of the
/// local expansions of P_i's target ancestors (levels 0..target_level, coarse to fine), then
/// P_i's per-point covering; empty for a row not computed (rho = 0, or a probe's row not
/// sampled). Cluster id = level_offset(l) + k. Row i must be held (std::out_of_range otherwise).
inline std::vector<geometry::Index> far_clusters(const FastOperator& op, geometry::Index i) {
  return FastOperatorTesting::far_clusters(op, i);
}
inline std::vector<geometry::Index> near_elements(const FastOperator& op, geometry::Index i) {
  return FastOperatorTesting::near_elements(op, i);
}
/// The moments (48) of element e about A(Delta) in its plane's frame and the far field's unit.
inline std::span<const double> element_moments(const FastOperator& op, geometry::Index e) {
  return FastOperatorTesting::element_moments(op, e);
}
/// The moments of the four elements of cluster k of level L - 1 about its A(tau), child c's at c T.
inline std::span<const double> child_shape_moments(const FastOperator& op, geometry::Index k) {
  return FastOperatorTesting::child_shape_moments(op, k);
}
/// The centre A(tau) of the cluster of global id `id` as the far field expands about it.
inline Vec3 expansion_centre(const FastOperator& op, geometry::Index id) {
  return FastOperatorTesting::expansion_centre(op, id);
}
/// Global id of cluster k of level l, and its inverse.
inline geometry::Index cluster_id(const FastOperator& op, int level, geometry::Index k) {
  return FastOperatorTesting::cluster_id(op, level, k);
}
inline std::pair<int, geometry::Index> cluster_of_id(const FastOperator& op, geometry::Index id) {
  return FastOperatorTesting::cluster_of_id(op, id);
}

/// The far field's length unit: the power of two 2^-ilogb(diameter) (lengths are multiplied by it).
inline double far_field_unit(const geometry::ClusterTree& tree) { return FastOperatorTesting::far_field_unit(tree); }
/// The placement classes of the clusters of level l of a root: min(l + 1, 6).
inline geometry::Index placement_classes(int l) { return FastOperatorTesting::placement_classes(l); }

}  // namespace panelrad::detail

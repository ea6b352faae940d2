#pragma once
// What the collocation points of one cluster sigma see of each root, decided once for all of them
// (geometry::Occluders::cluster_candidates) and kept while the coverings (42) of sigma's points
// are walked (visible_covering.hpp): a root hidden from all of sigma (by the planes, or behind one
// face) is skipped by each point without a search; otherwise the faces near the shaft
// conv(sigma, root) are each point's candidates: they hold every face that meets its own shaft,
// so that its classification is the same bit for bit as against the candidates it would search
// the tree for. The points of a cluster are consecutive
// rows, walked one after the other by one thread: one cache per thread, keyed by the cluster.
// Private to lib/src/operator.
#include <panelrad/geometry/cluster_tree.hpp>
#include <panelrad/geometry/occluders.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace panelrad {

/// A root as seen from all of sigma: hidden; or listed, with `faces` every point's candidates; or
/// neither (each point searches for its own).
struct RootSight {
  bool hidden = false;
  bool listed = false;
  std::span<const geometry::Index> faces;
};

class ClusterSightCache {
 public:
  /// The cluster whose points are walked next (`key` its id among all clusters); a new key forgets
  /// the roots seen from the previous one. Null: no cluster (each point on its own).
  void begin(std::int64_t key, const geometry::Cluster* sigma, geometry::Index num_roots);
  bool active() const { return sigma_ != nullptr; }
  /// The root as seen from the current cluster, decided at its first request. The span is valid
  /// until the next call.
  RootSight of(const geometry::ClusterTree& tree, const geometry::Occluders& occluders, geometry::Index root);

 private:
  std::int64_t key_ = -1;
  const geometry::Cluster* sigma_ = nullptr;
  std::int64_t generation_ = 0;
  std::vector<std::int64_t> stamp_;  // per root: the generation in which it was decided
  std::vector<std::uint8_t> state_;  // per root: 0 hidden, 1 listed, 2 neither
  std::vector<std::uint32_t> begin_, end_;
  std::vector<geometry::Index> faces_, found_;
};

}  // namespace panelrad

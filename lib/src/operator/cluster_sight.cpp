#include "cluster_sight.hpp"

#include <stdexcept>
#include <string>

namespace panelrad {

using geometry::Index;

void ClusterSightCache::begin(std::int64_t key, const geometry::Cluster* sigma, Index num_roots) {
  if (!sigma) {
    sigma_ = nullptr;
    key_ = -1;
    return;
  }
  if (sigma == sigma_ && key == key_) return;
  sigma_ = sigma;
  key_ = key;
  ++generation_;
  if (stamp_.size() != static_cast<std::size_t>(num_roots)) {
    stamp_.assign(static_cast<std::size_t>(num_roots), 0);
    state_.assign(static_cast<std::size_t>(num_roots), 0);
    begin_.assign(static_cast<std::size_t>(num_roots), 0);
    end_.assign(static_cast<std::size_t>(num_roots), 0);
  }
  faces_.clear();
}

RootSight ClusterSightCache::of(const geometry::ClusterTree& tree, const geometry::Occluders& occluders, Index root) {
  if (root < 0 || static_cast<std::size_t>(root) >= stamp_.size())
    throw std::invalid_argument("ClusterSightCache: root " + std::to_string(root) + " is not in [0, " +
                                std::to_string(stamp_.size()) + ")");
  const auto r = static_cast<std::size_t>(root);
  if (stamp_[r] != generation_) {
    const geometry::Cluster& tau = tree.cluster(0, root);
    const geometry::ClusterSight sight =
        occluders.cluster_candidates(sigma_->vertex, sigma_->normal, tau.vertex, tau.normal, found_);
    stamp_[r] = generation_;
    state_[r] = sight.hidden ? 0 : sight.listed ? 1 : 2;
    begin_[r] = static_cast<std::uint32_t>(faces_.size());
    if (sight.listed) faces_.insert(faces_.end(), found_.begin(), found_.end());
    end_[r] = static_cast<std::uint32_t>(faces_.size());
  }
  RootSight out;
  out.hidden = state_[r] == 0;
  out.listed = state_[r] == 1;
  if (out.listed) out.faces = std::span<const Index>(faces_.data() + begin_[r], end_[r] - begin_[r]);
  return out;
}

}  // namespace panelrad

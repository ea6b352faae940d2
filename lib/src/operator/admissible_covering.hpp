#pragma once
// The walk of the cluster tree U (40) for one collocation point P: the minimal admissible
// covering (42) by the admissibility condition (41), without visibility (V = 1, a convex scene;
// with V: visible_covering.hpp). Used by the fast operator's coverings and its memory estimate.
#include <panelrad/geometry/admissibility.hpp>
#include <panelrad/geometry/cluster_tree.hpp>

#include "target_clusters.hpp"

#include <cstdint>

namespace panelrad {

/// Walks the cluster tree for collocation point P (in the plane planeP of the tree) and reports
/// the minimal admissible covering (42) of the subtrees of `starts` (count of them; nullptr: of
/// every root): admissible clusters (41) whole, non-admissible leaves as near field; clusters in
/// P's plane, of any facet, are coplanar with P (G = 0, section 4.2 case (a)) and skipped with
/// their subtree.
template <class Far, class Near, class Skip>
void cover(const geometry::ClusterTree& tree, const geometry::Vec3& P, geometry::Index planeP, double eta,
           const ClusterRef* starts, std::int64_t count, Far&& far, Near&& near, Skip&& skip) {
  using geometry::Index;
  const int L = tree.finest_level();
  ClusterRef stack[4 * 64 + 8];
  int top = 0;
  if (!starts) count = tree.num_roots();
  for (std::int64_t s = 0; s < count; ++s) {
    stack[top++] = starts ? starts[s] : ClusterRef{0, static_cast<Index>(count - 1 - s)};  // roots: last first
    while (top > 0) {
      const ClusterRef it = stack[--top];
      const geometry::Cluster& c = tree.cluster(it.level, it.k);
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

}  // namespace panelrad

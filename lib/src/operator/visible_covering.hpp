#pragma once
// The covering (42) of one collocation point P with the line-of-sight function V(P, Q) of (1):
// the walk of the cluster tree U (40) of the fast product, where each (P, cluster) pair is
// classified by the scene's occluders (geometry/occluders.hpp) before admissibility (41):
//   hidden   -> skipped with its subtree (its integral is 0);
//   full     -> the far field (44)-(48) when admissible, else refined; the elements, admissible
//               or not, and the admissible clusters of four elements by the near field (43) of
//               NearFieldIntegrator (an entry of one value costs a product one term where a far
//               pair costs T, and it is exact);
//   partial  -> refined, the faces that meet its shaft becoming its children's candidates; at
//               the elements the exact integral over the visible part: the closed-form
//               point-to-polygon form factor of each convex piece.
// A cluster is a sub-triangle of its level-0 root (the midpoint subdivision), in the root's plane:
// the shadows are cast once per (P, root) in 3-D (Occluders::classify with a ShadowPlane), and the
// clusters below the root are classified in 2-D against them (Occluders::classify_within), the
// candidates of a cluster being the root shadows that meet its parent. Below target clusters
// (target_clusters.hpp) the walk starts from the clusters P's target hands down instead of the
// roots: each start is classified in 2-D against the shadows cast on its root, as if reached
// from the root.
// With eta = 0 nothing is admissible: the walk gives every element's entry of the row, the dense
// matrix (33) with visibility. Private to lib/src/operator.
#include <panelrad/geometry/admissibility.hpp>
#include <panelrad/geometry/cluster_tree.hpp>
#include <panelrad/geometry/occluders.hpp>
#include <panelrad/operator/near_field.hpp>

#include "cluster_sight.hpp"
#include "target_clusters.hpp"

#include <array>
#include <cstddef>
#include <span>
#include <vector>

namespace panelrad {

/// Pairs classified (over the rows walked).
struct VisibilityCounts {
  std::size_t visible = 0;        ///< (P, cluster) pairs classified fully visible
  std::size_t hidden = 0;         ///< classified hidden, skipped with their subtrees
  std::size_t partial = 0;        ///< classified partly visible (refined, or clipped at the elements)
  std::size_t clipped = 0;        ///< elements integrated over their visible part
  std::size_t coplanar = 0;       ///< roots in P's plane, skipped unclassified (G = 0 there)
  VisibilityCounts& operator+=(const VisibilityCounts& o) {
    coplanar += o.coplanar;
    visible += o.visible;
    hidden += o.hidden;
    partial += o.partial;
    clipped += o.clipped;
    return *this;
  }
};

/// (1/pi) Int over the visible part of tau of G(P, Q) dS_Q, nQ tau's front normal: the sum of the
/// closed-form form factors of the convex pieces (fan triangles). The pieces' corners are rounded
/// (a few eps of the coordinates), and where pieces meet, a corner of one on an edge of another
/// is off it by that much: a sliver of width ~eps M left out or counted twice, harmless unless it
/// passes within the height h of P over tau's plane of P's foot, where it weighs eps M / h (a point
/// a narrow gap below a plane, an edge line of a distant shadow extended under it). So when an
/// edge of the pieces passes that close to P (the segment within R / kNearEdgeRatio of P, R the
/// distance of its ends, as in quadrature::form_factor) and tau lies wholly in front of P's plane, the factor is
/// taken as the complement, the factor of tau (its own corners) minus those of the covered pieces,
/// whose edges lie inside the shadows, unless those pass as close (P's foot at a shadow's edge).
double visible_form_factor(const Vec3& P, const Vec3& nP, const geometry::VisiblePart& part,
                           const std::array<Vec3, 3>& tau, const Vec3& nQ);

/// Reusable buffers of one thread's walks.
struct VisibleCoveringScratch {
  struct Item {
    int level;
    geometry::Index k;
    std::size_t among_begin, among_end;  // candidates in `pool`
    bool known_full;                     // an ancestor was fully visible
    bool start;                          // a root or a start of the walk
  };
  std::vector<Item> stack;
  std::vector<geometry::Index> pool, meeting;  // candidate faces of a root; below it, indices of plane.shadows
  geometry::VisiblePart part;
  geometry::ShadowPlane plane;  // the root being walked (depth first: its subtree before the next root)
  geometry::Index root = -1;    // the root of `plane` for starts below the roots
  geometry::ShaftClass root_class = geometry::ShaftClass::full;
  std::size_t root_shadows = 0;  // pool[0, root_shadows): all the root's shadows
  geometry::BlockerHints blockers;  // the faces that last hid a whole root (kept from row to row)
  ClusterSightCache sight;          // the roots as seen from P's sight cluster (inactive: none)
};

/// The candidate faces of root r for P, into `among`; false when r is hidden from P: from all of
/// P's sight cluster at once (s.sight, cluster_sight.hpp), or because one face alone hides it
/// (Occluders::hidden_by_a_face / hidden_by_one_of), before any shadow is cast. The candidates
/// are the sight cluster's list for r when it has one, else P's own (into s.meeting).
inline bool root_candidates(const geometry::ClusterTree& tree, const geometry::Occluders& occluders, const Vec3& P,
                            const Vec3& nP, geometry::Index r, VisibleCoveringScratch& s,
                            std::span<const geometry::Index>& among) {
  const geometry::Cluster& root = tree.cluster(0, r);
  if (s.sight.active()) {
    const RootSight sight = s.sight.of(tree, occluders, r);
    if (sight.hidden) return false;
    if (sight.listed) {
      among = sight.faces;
      return !occluders.hidden_by_one_of(P, nP, root.vertex, root.normal, among, &s.blockers);
    }
  }
  if (occluders.hidden_by_a_face(P, nP, root.vertex, root.normal, s.meeting, &s.blockers)) return false;
  among = s.meeting;
  return true;
}

/// The class of a start of the walk (a root, or a cluster below P's target clusters): a root by
/// its own shaft, its shadows cast into s.plane (its children meet at most those: s.meeting becomes
/// all of them); a start below a root against the shadows cast on its root, cast once for the
/// starts of that root (they come grouped by root; pool[0, root_shadows) lists them all). The
/// visible part into s.part at the elements. A root found hidden by root_candidates is hidden
/// with every start below it.
inline geometry::ShaftClass classify_start(const geometry::ClusterTree& tree, const geometry::Occluders& occluders,
                                           const Vec3& P, const Vec3& nP, int level, geometry::Index k,
                                           VisibleCoveringScratch& s) {
  using geometry::Index;
  using geometry::ShaftClass;
  const geometry::Cluster& c = tree.cluster(level, k);
  geometry::VisiblePart* part = level == tree.finest_level() ? &s.part : nullptr;
  std::span<const Index> among;
  if (level == 0) {
    s.root = -1;  // s.plane is this root's now, for its own subtree
    if (!root_candidates(tree, occluders, P, nP, k, s, among)) return ShaftClass::hidden;
    const ShaftClass cls = occluders.classify(P, nP, c.vertex, c.normal, among, s.plane, part);
    s.meeting.resize(s.plane.shadows.size());
    for (std::size_t j = 0; j < s.meeting.size(); ++j) s.meeting[j] = static_cast<Index>(j);
    return cls;
  }
  const Index root = k >> (2 * level);
  if (root != s.root) {
    s.root = root;
    if (!root_candidates(tree, occluders, P, nP, root, s, among)) {
      s.root_class = ShaftClass::hidden;  // and so is every start below it
      s.pool.clear();
      s.root_shadows = 0;
      return s.root_class;
    }
    const geometry::Cluster& r = tree.cluster(0, root);
    s.root_class = occluders.classify(P, nP, r.vertex, r.normal, among, s.plane, nullptr);
    s.pool.resize(s.plane.shadows.size());  // the subtrees of the previous root are done
    for (std::size_t j = 0; j < s.pool.size(); ++j) s.pool[j] = static_cast<Index>(j);
    s.root_shadows = s.pool.size();
  }
  if (s.root_class != ShaftClass::partial) return s.root_class;
  return occluders.classify_within(s.plane, c.vertex, std::span<const Index>(s.pool.data(), s.root_shadows), s.meeting,
                                   part);
}

/// Walks the tree for collocation point P (inner normal nP, in the tree's plane planeP; the roots
/// in that plane are coplanar with P, G = 0 on them, and are skipped before any classification,
/// counted in counts.coplanar): far(level, k) for the admissible,
/// fully visible clusters; near(element, value) for the elements reached, with value the
/// integral (1/pi) Int_Delta G V dS_Q (rho not applied). Deterministic: a fixed depth-first order.
/// `starts` (count of them): the clusters where the walk starts, below P's target clusters (none
/// coplanar with P); null: the roots.
template <class Far, class Near>
void cover_visible(const geometry::ClusterTree& tree, const geometry::Occluders& occluders, const Vec3& P,
                   const Vec3& nP, geometry::Index planeP, double eta, const NearFieldIntegrator& integrate_near, Far&& far, Near&& near,
                   VisibilityCounts& counts, VisibleCoveringScratch& s, const ClusterRef* starts = nullptr,
                   std::int64_t count = 0) {
  using geometry::Cluster;
  using geometry::Index;
  using geometry::ShaftClass;
  const int L = tree.finest_level();
  s.stack.clear();
  s.pool.clear();
  s.root = -1;
  if (starts) {
    for (std::int64_t j = count - 1; j >= 0; --j) s.stack.push_back({starts[j].level, starts[j].k, 0, 0, false, true});
  } else {
    for (Index root = tree.num_roots() - 1; root >= 0; --root) {
      if (tree.plane(0, root) == planeP) {
        ++counts.coplanar;
        continue;
      }
      s.stack.push_back({0, root, 0, 0, false, true});
    }
  }
  while (!s.stack.empty()) {
    const VisibleCoveringScratch::Item it = s.stack.back();
    s.stack.pop_back();
    const Cluster& c = tree.cluster(it.level, it.k);
    ShaftClass cls = ShaftClass::full;
    if (!it.known_full) {
      if (it.start) {
        cls = classify_start(tree, occluders, P, nP, it.level, it.k, s);
      } else {
        cls = occluders.classify_within(
            s.plane, c.vertex, std::span<const Index>(s.pool.data() + it.among_begin, it.among_end - it.among_begin),
            s.meeting, it.level == L ? &s.part : nullptr);
      }
      if (cls == ShaftClass::full) ++counts.visible;
      else if (cls == ShaftClass::hidden) ++counts.hidden;
      else ++counts.partial;
    }
    if (cls == ShaftClass::hidden) continue;
    if (cls == ShaftClass::full) {
      const bool admissible = eta > 0 && geometry::is_admissible(P, c.centre, c.radius, eta);
      if (admissible && it.level == L - 1) {
        // A cluster of four elements: their near entries (4 x 12 bytes, 4 products a row) cost
        // less than its far pair (an id and T coefficients, T terms a product) and are exact.
        for (Index child = 0; child < 4; ++child) near(4 * it.k + child, integrate_near(P, nP, tree.cluster(L, 4 * it.k + child)));
      } else if (admissible && it.level < L) {
        far(it.level, it.k);
      } else if (it.level == L) {
        // An element, admissible or not: its near entry (one value, one term a product) costs less
        // than a far pair and is exact.
        near(it.k, integrate_near(P, nP, c));
      } else {
        for (Index child = 3; child >= 0; --child) s.stack.push_back({it.level + 1, 4 * it.k + child, 0, 0, true, false});
      }
      continue;
    }
    // Partly visible.
    if (it.level == L) {
      ++counts.clipped;
      near(it.k, visible_form_factor(P, nP, s.part, c.vertex, c.normal));
      continue;
    }
    const std::size_t begin = s.pool.size();
    s.pool.insert(s.pool.end(), s.meeting.begin(), s.meeting.end());
    const std::size_t end = s.pool.size();
    for (Index child = 3; child >= 0; --child) s.stack.push_back({it.level + 1, 4 * it.k + child, begin, end, false, false});
  }
}

}  // namespace panelrad

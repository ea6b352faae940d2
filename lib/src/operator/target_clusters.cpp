// The target clusters of the cluster-cluster far field and their sources, from the roots down,
// each after its parent (target_clusters.hpp).
#include "target_clusters.hpp"

#include <panelrad/geometry/admissibility.hpp>

#include <omp.h>

#include <algorithm>
#include <span>
#include <stdexcept>
#include <string>

namespace panelrad {

using geometry::Cluster;
using geometry::Index;

namespace {

using Item = ClusterRef;

// x rounded upward past the rounding of the one or two operations that made it.
double round_up(double x) { return x * (1.0 + 0x1p-50); }

// What the traversal of one target cluster found: its sources and the clusters handed to its
// children (from level lt: to the per-point coverings), as ranges of its thread's lists. Trivial:
// a level's records are allocated unwritten, each then written once by its traversal.
struct Found {
  std::int64_t source_at, pass_at;
  std::int32_t sources, passes, thread, coplanar, hidden, undecided;
};

// The subtrees of the fused levels: at least this many a thread, for the dynamic schedule to
// even out processors of unequal speed.
constexpr Index kSubtreesPerThread = 32;
// Levels above the fused ones with fewer targets than this are traversed by one thread: each
// target takes microseconds, starting a team tens (two virtual processors).
constexpr Index kParallelLevel = 256;

// One thread's list, on a cache line of its own: the list's end changes with every cluster found.
template <class T>
struct alignas(64) ThreadList {
  KeptVector<T> items;
};

// The CSR of the ranges found on levels [0, found.size()) (Found) from the threads' lists, ids
// numbered level by level: the counts by a serial prefix sum into starts[1 ..], one resize of
// `out`, then the lists copied in target order, in parallel.
template <class T, class Count, class At, class ListOf>
void join_levels(std::span<const KeptVector<Found>> found, std::vector<std::int64_t>& starts, KeptVector<T>& out,
                 Count count, At at, ListOf list_of) {
  std::size_t id = 0;
  for (const KeptVector<Found>& level : found)
    for (const Found& f : level) {
      starts[id + 1] = starts[id] + count(f);
      ++id;
    }
  out.resize(static_cast<std::size_t>(starts[id]));
#pragma omp parallel
  {
    std::size_t first = 0;
    for (std::size_t l = 0; l < found.size(); ++l) {
      const KeptVector<Found>& level = found[l];
      const Index m = static_cast<Index>(level.size());
#pragma omp for schedule(dynamic, 256) nowait
      for (Index k = 0; k < m; ++k) {
        const Found& f = level[static_cast<std::size_t>(k)];
        const auto& list = list_of(l, f);
        std::copy_n(list.begin() + at(f), count(f), out.begin() + starts[first + static_cast<std::size_t>(k)]);
      }
      first += level.size();
    }
  }
}

// The construction of the target clusters of levels 0..lt (build_target_clusters). Each target's
// traversal starts from what its parent handed down and writes to its thread's lists of its level
// (no allocation per target). The top levels go level by level; from level l0 on, where there are
// enough clusters to share, one task takes the whole subtree of a cluster of level l0, parents
// before children, so that a parent's hand-down is read by the thread that wrote it and no level
// waits for the slowest processor. The sources of all levels join the CSR at the end, in one
// allocation.
class TargetBuilder {
 public:
  TargetBuilder(const geometry::ClusterTree& tree, const PlaneFrame* frames, const std::vector<Index>& level_offset,
                double unit_scale, double eta, double eta_t, int lt, const geometry::Occluders* occluders,
                TargetClusters& out)
      : tree_(tree), occluders_(occluders), frames_(frames), level_offset_(level_offset), unit_scale_(unit_scale),
        inv_scale_(1.0 / unit_scale),  // a power of two: exact
        eta_(eta), eta_t_(eta_t), lt_(lt), L_(tree.finest_level()), out_(out),
        threads_(std::max(1, omp_get_max_threads())), found_(static_cast<std::size_t>(lt) + 1),
        sources_(static_cast<std::size_t>(lt) + 1), passes_(static_cast<std::size_t>(lt) + 1) {
    for (int l = 0; l <= lt; ++l) {
      found_[static_cast<std::size_t>(l)].resize(static_cast<std::size_t>(tree.level_size(l)));  // each written below
      sources_[static_cast<std::size_t>(l)].resize(static_cast<std::size_t>(threads_));
      passes_[static_cast<std::size_t>(l)].resize(static_cast<std::size_t>(threads_));
    }
  }

  /// Every target's traversal: the top levels [0, l0) level by level, then the subtrees of l0.
  void traverse_all() {
    int l0 = 0;
    while (l0 <= lt_ && tree_.level_size(l0) < kSubtreesPerThread * threads_) ++l0;
    traverse_top_levels(l0);
    if (l0 <= lt_) traverse_subtrees(l0);
  }

  /// The coplanar roots, the sources' CSR and the starts of the per-point coverings.
  void join() {
    out_.coplanar_roots.resize(static_cast<std::size_t>(tree_.num_roots()));
    for (Index k = 0; k < tree_.num_roots(); ++k)
      out_.coplanar_roots[static_cast<std::size_t>(k)] = found_[0][static_cast<std::size_t>(k)].coplanar;
    for (const KeptVector<Found>& level : found_)
      for (const Found& f : level) {
        out_.hidden_pairs += static_cast<std::size_t>(f.hidden);
        out_.undecided_pairs += static_cast<std::size_t>(f.undecided);
      }
    join_levels(found_, out_.source_start, out_.source, [](const Found& f) { return std::int64_t{f.sources}; },
                [](const Found& f) { return f.source_at; },
                [&](std::size_t l, const Found& f) -> const KeptVector<Index>& {
                  return sources_[l][static_cast<std::size_t>(f.thread)].items;
                });
    // The starts of the per-point coverings: what the targets of level lt hand down.
    out_.start_start.assign(static_cast<std::size_t>(tree_.level_size(lt_)) + 1, 0);
    join_levels(std::span(found_).last(1), out_.start_start, out_.start,
                [](const Found& f) { return std::int64_t{f.passes}; }, [](const Found& f) { return f.pass_at; },
                [&](std::size_t, const Found& f) -> const KeptVector<Item>& {
                  return passes_[static_cast<std::size_t>(lt_)][static_cast<std::size_t>(f.thread)].items;
                });
    // Each target's starts grouped by root (stable: deterministic), so that a point's walk casts
    // the shadows on a root once for all its starts there (visible_covering.hpp).
    const Index m = tree_.level_size(lt_);
#pragma omp parallel for schedule(dynamic, 256)
    for (Index k = 0; k < m; ++k)
      std::stable_sort(out_.start.begin() + out_.start_start[static_cast<std::size_t>(k)],
                       out_.start.begin() + out_.start_start[static_cast<std::size_t>(k) + 1],
                       [](const Item& a, const Item& b) { return (a.k >> (2 * a.level)) < (b.k >> (2 * b.level)); });
  }

 private:
  Index id_of(int l, Index k) const { return level_offset_[static_cast<std::size_t>(l)] + k; }

  // Target k of level l, by thread `thread`, with `stack` its scratch: its rectangle, and the
  // clusters its parent handed down (from level 0: the roots) sorted into its sources, the
  // coplanar ones, and those handed to its children.
  void traverse(int l, Index k, int thread, std::vector<Item>& stack) {
    const Cluster& sigma = tree_.cluster(l, k);
    const Index id = id_of(l, k);
    const PlaneFrame& frame = frames_[static_cast<std::size_t>(id)];
    const LocalBox box = LocalBox::bounding(frame, unit_scale_ * sigma.vertex[0], unit_scale_ * sigma.vertex[1],
                                            unit_scale_ * sigma.vertex[2]);
    out_.box[static_cast<std::size_t>(id)] = box;
    const Vec3 c = inv_scale_ * box.centre(frame);
    const double Rb = inv_scale_ * box.half_diagonal();
    const Index plane = tree_.plane(l, k);
    KeptVector<Index>& my_sources = sources_[static_cast<std::size_t>(l)][static_cast<std::size_t>(thread)].items;
    KeptVector<Item>& my_pass = passes_[static_cast<std::size_t>(l)][static_cast<std::size_t>(thread)].items;
    Found f{};
    f.thread = thread;
    f.source_at = static_cast<std::int64_t>(my_sources.size());
    f.pass_at = static_cast<std::int64_t>(my_pass.size());
    stack.clear();
    const auto visit = [&](const Item& first) {
      stack.push_back(first);
      while (!stack.empty()) {
        const Item it = stack.back();
        stack.pop_back();
        const Cluster& tau = tree_.cluster(it.level, it.k);
        if (tree_.plane(it.level, it.k) == plane) {
          ++f.coplanar;
          continue;
        }
        const bool admissible =
            geometry::is_admissible(c, tau.centre, round_up(tau.radius + round_up(eta_ * Rb)), eta_) &&
            geometry::is_admissible(c, tau.centre, round_up(Rb + round_up(eta_t_ * tau.radius)), eta_t_);
        // With V: hidden from all of sigma by the planes, dropped; admissible, the faces looked at.
        geometry::ShaftClass seen = geometry::ShaftClass::full;
        if (occluders_) seen = occluders_->classify_clusters(sigma.vertex, sigma.normal, tau.vertex, tau.normal, admissible);
        if (seen == geometry::ShaftClass::hidden) {
          ++f.hidden;
          continue;
        }
        if (admissible && seen == geometry::ShaftClass::full) {
          my_sources.push_back(id_of(it.level, it.k));
          continue;
        }
        if (admissible) ++f.undecided;  // handed down whole (target_clusters.hpp)
        if (!admissible && it.level < L_ && tau.radius >= Rb) {
          for (Index child = 3; child >= 0; --child) stack.push_back({it.level + 1, 4 * it.k + child});
        } else {
          my_pass.push_back(it);
        }
      }
    };
    if (l == 0) {
      for (Index root = 0; root < tree_.num_roots(); ++root) visit({0, root});
    } else {
      const Found& parent = found_[static_cast<std::size_t>(l) - 1][static_cast<std::size_t>(k / 4)];
      const KeptVector<Item>& handed = passes_[static_cast<std::size_t>(l) - 1][static_cast<std::size_t>(parent.thread)].items;
      for (std::int32_t j = 0; j < parent.passes; ++j) visit(handed[static_cast<std::size_t>(parent.pass_at + j)]);
    }
    f.sources = static_cast<std::int32_t>(static_cast<std::int64_t>(my_sources.size()) - f.source_at);
    f.passes = static_cast<std::int32_t>(static_cast<std::int64_t>(my_pass.size()) - f.pass_at);
    found_[static_cast<std::size_t>(l)][static_cast<std::size_t>(k)] = f;
  }

  // The first failure of a traversal, kept to be thrown once the team is done.
  void fail(int l, const std::exception& e) {
#pragma omp critical(panelrad_target_clusters)
    if (!failed_) {
      failed_ = true;
      failure_ = "target clusters of level " + std::to_string(l) + ": " + e.what();
    }
  }

  // The top levels: few clusters each, too few to wake a team for.
  void traverse_top_levels(int l0) {
    for (int l = 0; l < l0; ++l) {
      const Index m = tree_.level_size(l);
#pragma omp parallel if (m >= kParallelLevel)
      {
        std::vector<Item> stack;
#pragma omp for schedule(dynamic, 1)
        for (Index k = 0; k < m; ++k) try {
          traverse(l, k, omp_get_thread_num(), stack);
        } catch (const std::exception& e) {
          fail(l, e);
        }
      }
      if (failed_) throw std::runtime_error(failure_);
    }
  }

  // The subtrees of the clusters of level l0, one task each, levels l0..lt.
  void traverse_subtrees(int l0) {
    const Index subtrees = tree_.level_size(l0);
#pragma omp parallel
    {
      const int thread = omp_get_thread_num();
      std::vector<Item> stack;
#pragma omp for schedule(dynamic, 1)
      for (Index r = 0; r < subtrees; ++r) {
        int l = l0;
        try {
          for (; l <= lt_; ++l) {
            const Index first = r << (2 * (l - l0)), end = (r + 1) << (2 * (l - l0));
            for (Index k = first; k < end; ++k) traverse(l, k, thread, stack);
          }
        } catch (const std::exception& e) {
          fail(l, e);
        }
      }
    }
    if (failed_) throw std::runtime_error(failure_);
  }

  const geometry::ClusterTree& tree_;
  const geometry::Occluders* occluders_;
  const PlaneFrame* frames_;
  const std::vector<Index>& level_offset_;
  double unit_scale_, inv_scale_, eta_, eta_t_;
  int lt_, L_;
  TargetClusters& out_;
  int threads_;
  std::vector<KeptVector<Found>> found_;
  std::vector<std::vector<ThreadList<Index>>> sources_;  // [level][thread]
  std::vector<std::vector<ThreadList<Item>>> passes_;    // [level][thread]
  bool failed_ = false;
  std::string failure_;
};

}  // namespace

std::size_t TargetClusters::bytes() const {
  return box.size() * sizeof(LocalBox) + (source_start.size() + start_start.size()) * sizeof(std::int64_t) +
         source.size() * sizeof(Index) + start.size() * sizeof(ClusterRef) + coplanar_roots.size() * sizeof(std::int32_t);
}

TargetClusters build_target_clusters(const geometry::ClusterTree& tree, const PlaneFrame* frames,
                                     const std::vector<Index>& level_offset, double unit_scale, double eta,
                                     double eta_t, int lt, int d, const geometry::Occluders* occluders) {
  const int L = tree.finest_level();
  if (lt < 0 || lt > L)
    throw std::invalid_argument("build_target_clusters: finest target level " + std::to_string(lt) + " outside [0, " +
                                std::to_string(L) + "]");
  TargetClusters out;
  out.finest_level = lt;
  out.degree = d;
  const Index targets = level_offset[static_cast<std::size_t>(lt) + 1];
  out.box.resize(static_cast<std::size_t>(targets));
  out.source_start.assign(static_cast<std::size_t>(targets) + 1, 0);
  TargetBuilder builder(tree, frames, level_offset, unit_scale, eta, eta_t, lt, occluders, out);
  builder.traverse_all();
  builder.join();
  return out;
}

}  // namespace panelrad

// The target clusters of the cluster-cluster far field and their sources, level by level from
// the roots (target_clusters.hpp).
#include "target_clusters.hpp"

#include <panelrad/geometry/admissibility.hpp>

#include <omp.h>

#include <algorithm>
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
// children (from level lt: to the per-point coverings), as ranges of its thread's lists.
struct Found {
  std::int64_t source_at = 0, pass_at = 0;
  std::int32_t sources = 0, passes = 0, thread = 0, coplanar = 0;
};

// One thread's sources and handed-down clusters for the targets of one level that it took, on a
// cache line of its own (the lists' ends change with every cluster found).
struct alignas(64) ThreadLists {
  std::vector<Index> source;
  std::vector<Item> pass;
};

// The CSR of one level's ranges (Found) from the threads' lists: the counts by a serial prefix
// sum into starts[first + 1 ..], the lists appended to `out` in target order, in parallel.
template <class T, class Count, class At, class ListOf>
void append_level(const std::vector<Found>& found, std::vector<std::int64_t>& starts, std::size_t first,
                  geometry::UninitializedVector<T>& out, Count count, At at, ListOf list_of) {
  const Index m = static_cast<Index>(found.size());
  for (Index k = 0; k < m; ++k)
    starts[first + static_cast<std::size_t>(k) + 1] = starts[first + static_cast<std::size_t>(k)] + count(found[static_cast<std::size_t>(k)]);
  out.resize(static_cast<std::size_t>(starts[first + static_cast<std::size_t>(m)]));
#pragma omp parallel for schedule(dynamic, 256)
  for (Index k = 0; k < m; ++k) {
    const Found& f = found[static_cast<std::size_t>(k)];
    const auto& list = list_of(f);
    std::copy_n(list.begin() + at(f), count(f), out.begin() + starts[first + static_cast<std::size_t>(k)]);
  }
}

}  // namespace

std::size_t TargetClusters::bytes() const {
  return box.size() * sizeof(LocalBox) + (source_start.size() + start_start.size()) * sizeof(std::int64_t) +
         source.size() * sizeof(Index) + start.size() * sizeof(ClusterRef) + coplanar_roots.size() * sizeof(std::int32_t);
}

TargetClusters build_target_clusters(const geometry::ClusterTree& tree, const PlaneFrame* frames,
                                     const std::vector<Index>& level_offset, double unit_scale, double eta,
                                     double eta_t, int lt, int d) {
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
  const auto id_of = [&](int l, Index k) { return level_offset[static_cast<std::size_t>(l)] + k; };
  const double inv_scale = 1.0 / unit_scale;  // a power of two: exact

  // Level by level: each target's traversal starts from what its parent handed down, and writes
  // to its thread's lists (no allocation per target); the level's sources then join the CSR.
  const std::size_t threads = static_cast<std::size_t>(std::max(1, omp_get_max_threads()));
  std::vector<ThreadLists> previous_lists(threads), current_lists(threads);
  std::vector<Found> previous, current;
  for (int l = 0; l <= lt; ++l) {
    const Index m = tree.level_size(l);
    current.assign(static_cast<std::size_t>(m), Found{});
    for (ThreadLists& lists : current_lists) {
      lists.source.clear();
      lists.pass.clear();
    }
    bool failed = false;
    std::string failure;
    // Targets in chunks: below the top levels a traversal takes under a microsecond (level 5 of
    // the cube at n = 786,432), as long as a shared counter.
    const int chunk = static_cast<int>(std::clamp<Index>(m / 256, 1, 16));
#pragma omp parallel
    {
      const int thread = omp_get_thread_num();
      ThreadLists& mine = current_lists[static_cast<std::size_t>(thread)];
      std::vector<Item> stack;
#pragma omp for schedule(dynamic, chunk)
      for (Index k = 0; k < m; ++k) try {
        const Cluster& sigma = tree.cluster(l, k);
        const Index id = id_of(l, k);
        const PlaneFrame& frame = frames[static_cast<std::size_t>(id)];
        const LocalBox box = LocalBox::bounding(frame, unit_scale * sigma.vertex[0], unit_scale * sigma.vertex[1],
                                                unit_scale * sigma.vertex[2]);
        out.box[static_cast<std::size_t>(id)] = box;
        const Vec3 c = inv_scale * box.centre(frame);
        const double Rb = inv_scale * box.half_diagonal();
        const Index plane = tree.plane(l, k);
        Found f;
        f.thread = thread;
        f.source_at = static_cast<std::int64_t>(mine.source.size());
        f.pass_at = static_cast<std::int64_t>(mine.pass.size());
        stack.clear();
        const auto visit = [&](const Item& first) {
          stack.push_back(first);
          while (!stack.empty()) {
            const Item it = stack.back();
            stack.pop_back();
            const Cluster& tau = tree.cluster(it.level, it.k);
            if (tree.plane(it.level, it.k) == plane) {
              ++f.coplanar;
            } else if (geometry::is_admissible(c, tau.centre, round_up(tau.radius + round_up(eta * Rb)), eta) &&
                       geometry::is_admissible(c, tau.centre, round_up(Rb + round_up(eta_t * tau.radius)), eta_t)) {
              mine.source.push_back(id_of(it.level, it.k));
            } else if (it.level < L && tau.radius >= Rb) {
              for (Index child = 3; child >= 0; --child) stack.push_back({it.level + 1, 4 * it.k + child});
            } else {
              mine.pass.push_back(it);
            }
          }
        };
        if (l == 0) {
          for (Index root = 0; root < tree.num_roots(); ++root) visit({0, root});
        } else {
          const Found& parent = previous[static_cast<std::size_t>(k / 4)];
          const std::vector<Item>& handed = previous_lists[static_cast<std::size_t>(parent.thread)].pass;
          for (std::int32_t j = 0; j < parent.passes; ++j) visit(handed[static_cast<std::size_t>(parent.pass_at + j)]);
        }
        f.sources = static_cast<std::int32_t>(static_cast<std::int64_t>(mine.source.size()) - f.source_at);
        f.passes = static_cast<std::int32_t>(static_cast<std::int64_t>(mine.pass.size()) - f.pass_at);
        current[static_cast<std::size_t>(k)] = f;
      } catch (const std::exception& e) {
#pragma omp critical(panelrad_target_clusters)
        if (!failed) {
          failed = true;
          failure = e.what();
        }
      }
    }
    if (failed) throw std::runtime_error("target clusters of level " + std::to_string(l) + ": " + failure);
    if (l == 0) {
      out.coplanar_roots.resize(static_cast<std::size_t>(m));
      for (Index k = 0; k < m; ++k) out.coplanar_roots[static_cast<std::size_t>(k)] = current[static_cast<std::size_t>(k)].coplanar;
    }
    append_level(current, out.source_start, static_cast<std::size_t>(id_of(l, 0)), out.source,
                 [](const Found& f) { return std::int64_t{f.sources}; }, [](const Found& f) { return f.source_at; },
                 [&](const Found& f) -> const std::vector<Index>& { return current_lists[static_cast<std::size_t>(f.thread)].source; });
    previous.swap(current);
    previous_lists.swap(current_lists);
  }
  // The starts of the per-point coverings: what the targets of level lt hand down.
  out.start_start.assign(static_cast<std::size_t>(tree.level_size(lt)) + 1, 0);
  append_level(previous, out.start_start, 0, out.start, [](const Found& f) { return std::int64_t{f.passes}; },
               [](const Found& f) { return f.pass_at; },
               [&](const Found& f) -> const std::vector<Item>& { return previous_lists[static_cast<std::size_t>(f.thread)].pass; });
  return out;
}

}  // namespace panelrad

// The target clusters of the cluster-cluster far field and their sources, level by level from
// the roots (target_clusters.hpp).
#include "target_clusters.hpp"

#include <panelrad/geometry/admissibility.hpp>

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

// What one target cluster found besides its sources: the clusters handed to its children.
struct TargetLists {
  std::vector<Item> pass;
  std::int32_t coplanar = 0;
};

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
  const auto id_of = [&](int l, Index k) { return level_offset[static_cast<std::size_t>(l)] + k; };

  std::vector<TargetLists> previous, current;
  std::vector<std::vector<Index>> sources(static_cast<std::size_t>(targets));
  for (int l = 0; l <= lt; ++l) {
    const Index m = tree.level_size(l);
    current.assign(static_cast<std::size_t>(m), TargetLists{});
    const double inv_scale = 1.0 / unit_scale;  // a power of two: exact
    bool failed = false;
    std::string failure;
    // Targets in chunks, and the traversal's lists reused from target to target (each target's
    // copied out once, at its size): below the top levels a traversal takes under a microsecond
    // (level 5 of the cube at n = 786,432), as long as a shared counter or a growing allocation.
    const int chunk = static_cast<int>(std::clamp<Index>(m / 256, 1, 16));
#pragma omp parallel
    {
      std::vector<Item> stack, pass;
      std::vector<Index> source;
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
        TargetLists& lists = current[static_cast<std::size_t>(k)];
        stack.clear();
        pass.clear();
        source.clear();
        const auto visit = [&](const Item& first) {
          stack.push_back(first);
          while (!stack.empty()) {
            const Item it = stack.back();
            stack.pop_back();
            const Cluster& tau = tree.cluster(it.level, it.k);
            if (tree.plane(it.level, it.k) == plane) {
              ++lists.coplanar;
            } else if (geometry::is_admissible(c, tau.centre, round_up(tau.radius + round_up(eta * Rb)), eta) &&
                       geometry::is_admissible(c, tau.centre, round_up(Rb + round_up(eta_t * tau.radius)), eta_t)) {
              source.push_back(id_of(it.level, it.k));
            } else if (it.level < L && tau.radius >= Rb) {
              for (Index child = 3; child >= 0; --child) stack.push_back({it.level + 1, 4 * it.k + child});
            } else {
              pass.push_back(it);
            }
          }
        };
        if (l == 0) {
          for (Index root = 0; root < tree.num_roots(); ++root) visit({0, root});
        } else {
          for (const Item& it : previous[static_cast<std::size_t>(k / 4)].pass) visit(it);
        }
        lists.pass.assign(pass.begin(), pass.end());
        sources[static_cast<std::size_t>(id)].assign(source.begin(), source.end());
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
    previous.swap(current);
  }
  // CSR of the sources (by target id) and of the starts (by cluster of level lt): the starts by
  // a serial prefix sum, the lists copied (and the per-target ones released) in parallel.
  out.source_start.assign(static_cast<std::size_t>(targets) + 1, 0);
  for (Index id = 0; id < targets; ++id)
    out.source_start[static_cast<std::size_t>(id) + 1] =
        out.source_start[static_cast<std::size_t>(id)] + static_cast<std::int64_t>(sources[static_cast<std::size_t>(id)].size());
  out.source.resize(static_cast<std::size_t>(out.source_start.back()));
#pragma omp parallel for schedule(dynamic, 256)
  for (Index id = 0; id < targets; ++id) {
    std::vector<Index>& s = sources[static_cast<std::size_t>(id)];
    std::copy(s.begin(), s.end(), out.source.begin() + out.source_start[static_cast<std::size_t>(id)]);
    std::vector<Index>().swap(s);
  }
  const Index m = tree.level_size(lt);
  out.start_start.assign(static_cast<std::size_t>(m) + 1, 0);
  for (Index k = 0; k < m; ++k)
    out.start_start[static_cast<std::size_t>(k) + 1] =
        out.start_start[static_cast<std::size_t>(k)] + static_cast<std::int64_t>(previous[static_cast<std::size_t>(k)].pass.size());
  out.start.resize(static_cast<std::size_t>(out.start_start.back()));
#pragma omp parallel for schedule(dynamic, 256)
  for (Index k = 0; k < m; ++k) {
    const std::vector<Item>& pass = previous[static_cast<std::size_t>(k)].pass;
    std::copy(pass.begin(), pass.end(), out.start.begin() + out.start_start[static_cast<std::size_t>(k)]);
  }
  return out;
}

}  // namespace panelrad

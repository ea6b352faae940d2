#include <panelrad/operator/far_field.hpp>
#include <panelrad/operator/row_costs.hpp>

#include "visible_covering.hpp"

#include <algorithm>
#include <cstdint>

namespace panelrad {

double occluded_row_work(const Collocation& collocation, const geometry::Occluders& occluders, double eta, int degree,
                         const NearFieldOptions& near, const RowRange& rows, int samples) {
  const geometry::ClusterTree& tree = collocation.tree();
  const int L = tree.finest_level();
  const Index m = rows.end - rows.begin;
  const Index count = std::min<Index>(m, std::max(samples, 1));
  if (count <= 0) return 0;
  const NearFieldIntegrator integrate_near(near, tree.mesh_size());
  const double terms = num_taylor_terms(degree);
  VisibleCoveringScratch scratch;
  double work = 0;
  for (Index s = 0; s < count; ++s) {
    const Index i = rows.begin + static_cast<Index>((static_cast<std::int64_t>(s) * m + m / 2) / count);
    if (collocation.reflectivity()[i] == 0) continue;
    std::size_t far = 0, near_pairs = 0;
    VisibilityCounts counts;
    cover_visible(tree, occluders, collocation.collocation_point(i), collocation.normal(i), tree.plane(L, i), eta,
                  integrate_near, [&](int, Index) { ++far; }, [&](Index, double) { ++near_pairs; }, counts, scratch);
    work += static_cast<double>(far + counts.visible + counts.hidden + counts.partial) * terms +
            static_cast<double>(near_pairs);
  }
  return work / static_cast<double>(count);
}

}  // namespace panelrad

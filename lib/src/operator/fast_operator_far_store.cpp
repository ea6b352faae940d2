// The fast operator's far store: the choice of storing the far coefficients (44)-(45) at setup
// or recomputing them in every product (the cost model far_field_costs, with the measured
// constants of far_store_tuning.hpp), and the stored coefficients themselves.
#include <panelrad/operator/fast_operator.hpp>

#include "far_field_batch.hpp"
#include "far_store_tuning.hpp"
#include <panelrad/support/chunk_pool.hpp>
#include <panelrad/support/resources.hpp>

#include <algorithm>
#include <new>
#include <stdexcept>

namespace panelrad {

using geometry::Index;

// Per (point, cluster) pair and core (far_store_tuning.hpp): recomputing T terms; reading them
// back, the slower of the multiply-adds and the memory's bandwidth; filling them, the terms and
// the first touch of their bytes.
FarFieldCosts far_field_costs(int degree, std::size_t bytes_per_term) {
  using namespace far_store_tuning;
  const double T = num_taylor_terms(degree);
  const double bytes = T * static_cast<double>(bytes_per_term);
  FarFieldCosts c;
  c.recompute_ns = kRecomputeNsPerTerm * T;
  c.read_ns = std::max(kReadNsPerTerm * T, kReadNsPerByte * bytes);
  c.fill_ns = kFillNsPerTerm * T + kFirstTouchNsPerByte * bytes;
  return c;
}

// Stored only when storing pays for the products expected (all products when unknown) and the
// coefficients fit.
bool FastOperator::far_storage_chosen() const {
  const std::size_t far_coef_bytes = stats_.far_pairs * static_cast<std::size_t>(terms_) * coefficient_bytes();
  const bool pays = options_.expected_products <= 0 ||
                    far_field_costs(options_.degree, coefficient_bytes()).store_pays(options_.expected_products);
  // The memory gate (files of /proc and the cgroup, serial) only when storing would pay and no
  // chunk kept by the process's pool can take the store (it then needs no new memory).
  const auto fits = [&] {
    if (options_.far_storage_limit) return far_coef_bytes <= options_.far_storage_limit;
    return ChunkPool::process().kept_for(far_coef_bytes) > 0 || far_coef_bytes <= available_memory_bytes() / 2;
  };
  return pays && fits();
}

// The rho-scaled Taylor coefficients (44)-(45) of every far pair, when they are to be stored
// (rounded to float with single_precision_coefficients).
void FastOperator::setup_far_coefficients() {
  const std::size_t T = static_cast<std::size_t>(terms_);
  const bool single = options_.single_precision_coefficients;
  if (stats_.far_stored) {
    try {
      if (single) far_coef_single_ = LargeArray<float>(stats_.far_pairs * T);
      else far_coef_ = LargeBuffer(stats_.far_pairs * T);
    } catch (const std::bad_alloc&) {
      stats_.far_stored = false;  // could not have the memory after all: recompute per product
    }
  }
  if (!stats_.far_stored) return;
  const Index rows = row_end_ - row_begin_;
  const far_field_batch::Kernels& kernels = far_field_batch::kernels();
  const far_field_batch::ClusterFrames frames = cluster_frames();
  Index failed = rows;  // the first row whose coefficients could not be formed
#pragma omp parallel for schedule(dynamic, 64)
  for (Index r = 0; r < rows; ++r) {
    const RowLists row = row_lists(static_cast<std::size_t>(r));
    const std::size_t at = static_cast<std::size_t>(row.far_first) * T;
    const far_field_batch::RowPoint point = far_row_point(row_begin_ + r);
    const bool formed =
        single ? far_field_batch::row_coefficients(kernels, options_.degree, point, frames, row.far_cluster,
                                                   row.far_count, far_coef_single_.data() + at)
               : far_field_batch::row_coefficients(kernels, options_.degree, point, frames, row.far_cluster,
                                                   row.far_count, far_coef_.data() + at);
    if (!formed) {
#pragma omp critical(panelrad_far_coefficients_failed)
      failed = std::min(failed, r);
    }
  }
  if (failed < rows)
    throw std::invalid_argument("FastOperator: collocation point " + std::to_string(row_begin_ + failed) +
                                " coincides with the centre A(tau) of one of its far clusters or is not finite");
}

}  // namespace panelrad

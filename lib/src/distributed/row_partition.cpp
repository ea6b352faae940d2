#include <panelrad/distributed/row_partition.hpp>
#include <panelrad/operator/row_costs.hpp>

#include <algorithm>
#include <stdexcept>

namespace panelrad {

RowRange RowPartition::rows(int part) const {
  if (part < 0 || part >= parts()) throw std::out_of_range("RowPartition::rows: no part " + std::to_string(part));
  return {begin[static_cast<std::size_t>(part)], begin[static_cast<std::size_t>(part) + 1]};
}

RowPartition partition_rows(geometry::Index n, const std::vector<double>& block_cost, int parts) {
  if (n < 0 || parts < 1) throw std::invalid_argument("partition_rows: needs n >= 0 and at least one part");
  const std::size_t blocks = static_cast<std::size_t>((n + kRowBlock - 1) / kRowBlock);
  if (block_cost.size() != blocks)
    throw std::invalid_argument("partition_rows: " + std::to_string(block_cost.size()) + " block costs for " +
                                std::to_string(blocks) + " blocks");
  std::vector<double> prefix(blocks + 1, 0.0);  // prefix[b]: the cost of blocks [0, b)
  for (std::size_t b = 0; b < blocks; ++b) {
    if (!(block_cost[b] >= 0)) throw std::invalid_argument("partition_rows: a block cost is negative or NaN");
    prefix[b + 1] = prefix[b] + block_cost[b];
  }
  const double total = prefix.back();
  RowPartition p;
  p.begin.assign(static_cast<std::size_t>(parts) + 1, n);
  p.begin[0] = 0;
  std::size_t b = 0;
  for (int r = 1; r < parts; ++r) {
    if (total > 0) {
      const double target = total * r / parts;
      while (b < blocks && prefix[b] < target) ++b;
      // The boundary nearer the target of the two around it.
      if (b > 0 && target - prefix[b - 1] < prefix[b] - target) --b;
    } else {
      b = blocks * static_cast<std::size_t>(r) / static_cast<std::size_t>(parts);
    }
    b = std::max<std::size_t>(b, static_cast<std::size_t>(p.begin[static_cast<std::size_t>(r) - 1] / kRowBlock));
    p.begin[static_cast<std::size_t>(r)] = std::min<geometry::Index>(n, static_cast<geometry::Index>(b) * kRowBlock);
  }
  return p;
}

std::vector<double> fast_product_block_costs(const Collocation& collocation, double eta, int degree,
                                             const geometry::Occluders* occluders, const NearFieldOptions& near) {
  const geometry::Index n = collocation.size();
  const std::size_t blocks = static_cast<std::size_t>((n + kRowBlock - 1) / kRowBlock);
  const std::size_t runs = std::min<std::size_t>(blocks, 256);
  const double terms = static_cast<double>(num_taylor_terms(degree));
  std::vector<double> cost(blocks, 0.0);
  for (std::size_t k = 0; k < runs; ++k) {
    const std::size_t first = blocks * k / runs, last = blocks * (k + 1) / runs;
    const RowRange rows{static_cast<geometry::Index>(first) * kRowBlock,
                        std::min(n, static_cast<geometry::Index>(last) * kRowBlock)};
    double work = 0;
    if (occluders) {
      work = occluded_row_work(collocation, *occluders, eta, degree, near, rows, 16) *
             static_cast<double>(rows.end - rows.begin);
    } else {
      const FastOperator::MemoryEstimate e = FastOperator::estimate_memory(collocation, eta, degree, rows);
      work = static_cast<double>(e.far_pairs) * terms + static_cast<double>(e.near_pairs);
    }
    for (std::size_t b = first; b < last; ++b) cost[b] = work / static_cast<double>(last - first);
  }
  return cost;
}

}  // namespace panelrad

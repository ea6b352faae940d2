#pragma once
// The rows of K_n spread over the processes of a solve: contiguous ranges of the element order,
// each a run of whole blocks of kRowBlock rows (subtrees of the cluster tree (40)), cut so that
// the measured cost of the fast product's rows is about equal on every process. Every process
// computes the same partition from the same data (no communication).
#include <panelrad/distributed/blocked_reductions.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/fast_operator.hpp>

#include <vector>

namespace panelrad {

/// Process r holds the rows [begin[r], begin[r + 1]); begin.front() = 0, begin.back() = n; every
/// begin[r] a multiple of kRowBlock (or n).
struct RowPartition {
  std::vector<geometry::Index> begin;
  int parts() const { return static_cast<int>(begin.size()) - 1; }
  RowRange rows(int part) const;
};

/// The blocks [0, ceil(n / kRowBlock)) cut into `parts` contiguous runs of nearly equal summed
/// `block_cost` (one entry per block): run r starts at the first block whose prefix sum of costs
/// reaches r / parts of the total. With no cost at all, equal numbers of blocks. Runs may be
/// empty (more parts than blocks).
RowPartition partition_rows(geometry::Index n, const std::vector<double>& block_cost, int parts);

/// The cost of the fast operator's rows per block of kRowBlock rows: far pairs x Taylor terms +
/// near pairs (the work of a row in a product, (43)-(48)), from the coverings (42) of sampled rows,
/// measured on up to 256 runs of consecutive blocks and spread evenly over the blocks of a run.
/// Without occluders (V = 1): the plain coverings of up to 256 rows a run
/// (FastOperator::estimate_memory). With them: the coverings with V of up to 16 rows a run, their
/// classified pairs counted too (occluded_row_work: the visibility work of setup, which differs
/// most from row to row). Deterministic.
std::vector<double> fast_product_block_costs(const Collocation& collocation, double eta, int degree,
                                             const geometry::Occluders* occluders = nullptr,
                                             const NearFieldOptions& near = {});

}  // namespace panelrad

#pragma once
// The processes that share one solve of (32): each holds a contiguous range of the rows of K_n
// (row_partition.hpp) and the same entries of every vector of the iteration. What they exchange
// goes through this interface, in plain C++ types: the vector of a product (its blocks gathered,
// since the cluster moments (48) integrate v over the whole surface) and the partial sums of the
// solvers' reductions (blocked_reductions.hpp). The default is one process holding every row;
// the MPI implementation (panelrad/mpi/, built with PANELRAD_MPI) runs one process per rank.
#include <Eigen/Core>

#include <cstddef>
#include <vector>

namespace panelrad {

class Communicator {
 public:
  virtual ~Communicator() = default;
  /// This process's number, 0 .. size() - 1; rank 0 writes the outputs and the progress.
  virtual int rank() const = 0;
  virtual int size() const = 0;
  /// Every process's `count` values, concatenated in rank order, into `all` (resized), on every
  /// process. A collective: every process calls it, in the same order as the others.
  virtual void all_gather(const double* local, std::size_t count, Eigen::VectorXd& all) const = 0;
  /// The largest of the processes' values (exact: max does not round). A collective.
  virtual double max(double local) const = 0;
};

/// One process: rank 0 of 1; all_gather copies, max returns its argument.
class SingleProcess final : public Communicator {
 public:
  int rank() const override { return 0; }
  int size() const override { return 1; }
  void all_gather(const double* local, std::size_t count, Eigen::VectorXd& all) const override;
  double max(double local) const override { return local; }
};

/// The one-process communicator (a shared constant: it has no state).
const Communicator& single_process();

/// Counts summed over the processes, entry by entry (each process gives the same number of
/// entries; exact below 2^53). A collective.
void sum_counts(const Communicator& communicator, std::vector<std::size_t*> counts);

}  // namespace panelrad

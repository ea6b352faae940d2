#pragma once
// The solvers' reductions (inner products, 2-norms, max-norms) over vectors whose rows are spread
// over the processes of a Communicator, with a result that does not depend on how many processes
// there are. Floating-point addition is not associative, and MPI_Allreduce fixes no order of
// summation; so a sum over the rows is taken in fixed blocks of kRowBlock rows (the blocks of
// row_partition.hpp: every process's rows start at a multiple of kRowBlock): each block's partial
// sum in a fixed pattern (eight running sums, added pairwise), the same whatever process holds the
// block, then the partials of all the blocks gathered and added pairwise in block order. One
// process adds the same partials in the same order, so 1 and K processes give the same bits. The
// max-norm needs no order (max does not round).
#include <panelrad/distributed/communicator.hpp>
#include <panelrad/geometry/mesh.hpp>

#include <Eigen/Core>

namespace panelrad {

/// Rows of a block: the unit of the row partition and of the reductions' partial sums. 4^4: at
/// refinement level L >= 4 a block aligned at a multiple of it is the elements of one cluster of
/// level L - 4 (a subtree of the cluster tree (40), whose elements are contiguous).
inline constexpr geometry::Index kRowBlock = 256;

class BlockedReductions {
 public:
  using Vector = Eigen::Ref<const Eigen::VectorXd>;
  /// nullptr: one process (single_process()).
  explicit BlockedReductions(const Communicator* communicator = nullptr);
  const Communicator& communicator() const { return *comm_; }
  /// sum_i a_i b_i over the rows of every process; a and b hold this process's rows, the first of
  /// them at a multiple of kRowBlock of the whole vector.
  double dot(Vector a, Vector b) const;
  /// sqrt(dot(a, a)).
  double norm(Vector a) const;
  /// max_i |a_i| over every process (0 for no rows).
  double inf_norm(Vector a) const;
  /// Whether every entry on every process is finite.
  bool all_finite(Vector a) const;
  /// The rows of all the processes together.
  geometry::Index total_rows(geometry::Index local_rows) const;

 private:
  const Communicator* comm_;
};

}  // namespace panelrad

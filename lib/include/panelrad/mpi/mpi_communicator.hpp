#pragma once
// The Communicator over MPI (MPI_COMM_WORLD), for the processes of `mpirun -np K`: one rank per
// process, the gathers MPI_Allgatherv, the max MPI_Allreduce(MPI_MAX) (exact, so its order does
// not matter; the sums of the solvers are added in block order by BlockedReductions, not by MPI).
// This header names no MPI type: only lib/src/mpi/ includes <mpi.h>.
#include <panelrad/distributed/communicator.hpp>

#include <string>

namespace panelrad {

/// MPI_Init on construction (MPI_THREAD_FUNNELED: OpenMP threads make no MPI calls), MPI_Finalize on
/// destruction. One per program, constructed before any MpiCommunicator is used.
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
};

/// Whether this process was started by an MPI launcher (mpirun, mpiexec: Open MPI's
/// OMPI_COMM_WORLD_SIZE, or PMI_SIZE / PMIX_RANK of a PMI launcher). A program not started so
/// runs alone without initializing MPI (an Open MPI singleton would start a helper daemon and
/// shared-memory files, which a restricted process, e.g. under a file-size limit, may not have).
bool started_by_mpi_launcher();

class MpiCommunicator final : public Communicator {
 public:
  MpiCommunicator();
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  void all_gather(const double* local, std::size_t count, Eigen::VectorXd& all) const override;
  double max(double local) const override;
  /// Ends the whole run: `message` (if any) on stderr, each line prefixed with this rank
  /// ("rank 1: ..."), then
  /// MPI_Abort(MPI_COMM_WORLD, exit_code), which ends every rank, also those waiting in a
  /// collective for this one, so that none is left hanging.
  [[noreturn]] void abort(const std::string& message, int exit_code) const;

 private:
  int rank_ = 0, size_ = 1;
};

}  // namespace panelrad

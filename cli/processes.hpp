#pragma once
// The processes of this run of the program: one (the default build, or an MPI build started
// without mpirun), or the ranks of `mpirun -np K panelrad ...` (an MPI build, PANELRAD_MPI), which
// share each solve's rows (SolveOptions::communicator). Rank 0 alone writes the outputs,
// the progress and the summary.
#include <panelrad/distributed/communicator.hpp>

namespace panelrad::cli {

/// The processes sharing the solves: nullptr when this process runs alone.
const Communicator* shared_solve();
/// Set once by main when the program runs on several processes.
void set_shared_solve(const Communicator* communicator);
/// Whether this process writes outputs, progress and the summary (rank 0, or the only process).
bool writes_outputs();

}  // namespace panelrad::cli

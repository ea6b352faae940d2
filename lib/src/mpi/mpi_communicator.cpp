#include <panelrad/mpi/mpi_communicator.hpp>

#include <mpi.h>

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <cstdio>
#include <stdexcept>
#include <vector>

namespace panelrad {

namespace {

void check(int status, const char* call) {
  if (status != MPI_SUCCESS) throw std::runtime_error(std::string("MPI: ") + call + " failed");
}

}  // namespace

bool started_by_mpi_launcher() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMI_SIZE") || std::getenv("PMIX_RANK");
}

MpiSession::MpiSession(int& argc, char**& argv) {
  int provided = 0;
  check(MPI_Init_thread(&argc, &argv, MPI_THREAD_FUNNELED, &provided), "MPI_Init_thread");
}

MpiSession::~MpiSession() { MPI_Finalize(); }

MpiCommunicator::MpiCommunicator() {
  check(MPI_Comm_rank(MPI_COMM_WORLD, &rank_), "MPI_Comm_rank");
  check(MPI_Comm_size(MPI_COMM_WORLD, &size_), "MPI_Comm_size");
}

void MpiCommunicator::all_gather(const double* local, std::size_t count, Eigen::VectorXd& all) const {
  // MPI-3 counts and displacements are int: up to 2^31 - 1 values in all.
  if (count > static_cast<std::size_t>(INT_MAX))
    throw std::length_error("MPI all_gather: " + std::to_string(count) + " values on one rank, more than 2^31 - 1");
  int mine = static_cast<int>(count);
  std::vector<int> counts(static_cast<std::size_t>(size_)), offsets(static_cast<std::size_t>(size_));
  check(MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD), "MPI_Allgather");
  long long total = 0;
  for (int r = 0; r < size_; ++r) {
    if (total > INT_MAX) break;
    offsets[static_cast<std::size_t>(r)] = static_cast<int>(total);
    total += counts[static_cast<std::size_t>(r)];
  }
  if (total > INT_MAX) throw std::length_error("MPI all_gather: more than 2^31 - 1 values in all");
  all.resize(static_cast<Eigen::Index>(total));
  check(MPI_Allgatherv(local, mine, MPI_DOUBLE, all.data(), counts.data(), offsets.data(), MPI_DOUBLE, MPI_COMM_WORLD),
        "MPI_Allgatherv");
}

double MpiCommunicator::max(double local) const {
  double out = 0;
  check(MPI_Allreduce(&local, &out, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD), "MPI_Allreduce");
  return out;
}

void MpiCommunicator::abort(const std::string& message, int exit_code) const {
  std::string said;  // every line prefixed with the rank
  for (std::size_t begin = 0; begin < message.size();) {
    const std::size_t end = std::min(message.find('\n', begin), message.size());
    said += "rank " + std::to_string(rank_) + ": " + message.substr(begin, end - begin) + "\n";
    begin = end + 1;
  }
  std::fputs(said.c_str(), stderr);
  std::fflush(stderr);
  MPI_Abort(MPI_COMM_WORLD, exit_code);
  std::_Exit(exit_code);  // MPI_Abort does not return; should it, this process still ends
}

}  // namespace panelrad

#pragma once
// The processes of a distributed solve played by threads of one test program: a Communicator
// whose collectives meet at a barrier (std::barrier) and exchange through shared slots. It lets
// the default build (no MPI) test that K processes give one process's bits; the MPI build tests
// the same over MPI_COMM_WORLD (tests/mpi/).
#include <panelrad/distributed/communicator.hpp>

#include <barrier>
#include <exception>
#include <functional>
#include <thread>
#include <vector>

namespace panelrad::testing {

class ThreadGroup {
 public:
  explicit ThreadGroup(int size) : slots_(static_cast<std::size_t>(size)), barrier_(size) {}
  int size() const { return static_cast<int>(slots_.size()); }

  /// Every thread's values, in rank order: each writes its slot, all wait, all read, all wait
  /// again (so that no slot is overwritten by the next collective while another thread reads).
  void all_gather(int rank, const double* local, std::size_t count, Eigen::VectorXd& all) {
    slots_[static_cast<std::size_t>(rank)].assign(local, local + count);
    barrier_.arrive_and_wait();
    std::size_t total = 0;
    for (const auto& s : slots_) total += s.size();
    all.resize(static_cast<Eigen::Index>(total));
    std::size_t at = 0;
    for (const auto& s : slots_)
      for (double x : s) all[static_cast<Eigen::Index>(at++)] = x;
    barrier_.arrive_and_wait();
  }

 private:
  std::vector<std::vector<double>> slots_;
  std::barrier<> barrier_;
};

class ThreadCommunicator final : public Communicator {
 public:
  ThreadCommunicator(ThreadGroup& group, int rank) : group_(group), rank_(rank) {}
  int rank() const override { return rank_; }
  int size() const override { return group_.size(); }
  void all_gather(const double* local, std::size_t count, Eigen::VectorXd& all) const override {
    group_.all_gather(rank_, local, count, all);
  }
  double max(double local) const override {
    Eigen::VectorXd all;
    group_.all_gather(rank_, &local, 1, all);
    return all.maxCoeff();
  }

 private:
  ThreadGroup& group_;
  int rank_;
};

/// Runs work(communicator) on `size` threads, one per rank, and rethrows the first exception.
/// (A thread that throws leaves the others at their next barrier: the test then times out.)
inline void run_ranks(int size, const std::function<void(const Communicator&)>& work) {
  ThreadGroup group(size);
  std::vector<std::exception_ptr> errors(static_cast<std::size_t>(size));
  std::vector<std::thread> threads;
  for (int r = 0; r < size; ++r)
    threads.emplace_back([&, r] {
      const ThreadCommunicator comm(group, r);
      try {
        work(comm);
      } catch (...) {
        errors[static_cast<std::size_t>(r)] = std::current_exception();
      }
    });
  for (std::thread& t : threads) t.join();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

}  // namespace panelrad::testing

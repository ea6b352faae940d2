#include <panelrad/distributed/communicator.hpp>

#include <algorithm>

namespace panelrad {

void SingleProcess::all_gather(const double* local, std::size_t count, Eigen::VectorXd& all) const {
  all.resize(static_cast<Eigen::Index>(count));
  std::copy(local, local + count, all.data());
}

void sum_counts(const Communicator& communicator, std::vector<std::size_t*> counts) {
  std::vector<double> mine;
  for (const std::size_t* c : counts) mine.push_back(static_cast<double>(*c));
  Eigen::VectorXd all;
  communicator.all_gather(mine.data(), mine.size(), all);
  const std::size_t k = counts.size();
  for (std::size_t j = 0; j < k; ++j) {
    double sum = 0;
    for (std::size_t at = j; at < static_cast<std::size_t>(all.size()); at += k) sum += all[static_cast<Eigen::Index>(at)];
    *counts[j] = static_cast<std::size_t>(sum);
  }
}

const Communicator& single_process() {
  static const SingleProcess one;
  return one;
}

}  // namespace panelrad

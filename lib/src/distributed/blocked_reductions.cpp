#include <panelrad/distributed/blocked_reductions.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace panelrad {

BlockedReductions::BlockedReductions(const Communicator* communicator)
    : comm_(communicator ? communicator : &single_process()) {}

namespace {

// sum_i a_i b_i over [begin, end) in a fixed pattern relative to `begin`: eight running sums
// (entry i into sum (i - begin) mod 8), added pairwise. Like a vectorized inner product it keeps
// the rounding error near that of pairwise summation, and its bits depend only on the values, not
// on where the block lies in memory or which process holds it (no reordering: -ffp-contract is off
// in ISO C++ mode and nothing here is vectorized across the sums).
double block_dot(const double* a, const double* b, Eigen::Index count) {
  double s[8] = {0, 0, 0, 0, 0, 0, 0, 0};
  Eigen::Index i = 0;
  for (; i + 8 <= count; i += 8)
    for (int k = 0; k < 8; ++k) s[k] += a[i + k] * b[i + k];
  for (int k = 0; i < count; ++i, ++k) s[k] += a[i] * b[i];
  return ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
}

// The partials [begin, end) added pairwise: halves split at the midpoint, recursively (the same
// tree for the same count).
double pairwise_sum(const double* x, Eigen::Index count) {
  if (count <= 2) return count == 0 ? 0.0 : count == 1 ? x[0] : x[0] + x[1];
  const Eigen::Index half = count / 2;
  return pairwise_sum(x, half) + pairwise_sum(x + half, count - half);
}

}  // namespace

double BlockedReductions::dot(Vector a, Vector b) const {
  if (a.size() != b.size()) throw std::invalid_argument("BlockedReductions::dot: the vectors differ in size");
  const Eigen::Index m = a.size();
  const Eigen::Index blocks = (m + kRowBlock - 1) / kRowBlock;
  std::vector<double> partial(static_cast<std::size_t>(blocks));
  for (Eigen::Index k = 0; k < blocks; ++k) {
    const Eigen::Index first = k * kRowBlock;
    partial[static_cast<std::size_t>(k)] = block_dot(a.data() + first, b.data() + first, std::min<Eigen::Index>(m - first, kRowBlock));
  }
  Eigen::VectorXd all;
  comm_->all_gather(partial.data(), partial.size(), all);  // every block's partial, in block order
  return pairwise_sum(all.data(), all.size());
}

double BlockedReductions::norm(Vector a) const { return std::sqrt(dot(a, a)); }

double BlockedReductions::inf_norm(Vector a) const {
  return comm_->max(a.size() ? a.lpNorm<Eigen::Infinity>() : 0.0);
}

bool BlockedReductions::all_finite(Vector a) const {
  return comm_->max(a.allFinite() ? 0.0 : 1.0) == 0.0;
}

geometry::Index BlockedReductions::total_rows(geometry::Index local_rows) const {
  if (comm_->size() == 1) return local_rows;
  const double rows = static_cast<double>(local_rows);
  Eigen::VectorXd all;
  comm_->all_gather(&rows, 1, all);
  return static_cast<geometry::Index>(all.sum());  // integers below 2^53: exact
}

}  // namespace panelrad

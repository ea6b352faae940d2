#include <panelrad/operator/collocation.hpp>
#include <panelrad/support/resources.hpp>
#include <panelrad/support/parallel_for.hpp>

#include <cmath>
#include <string>
#include <stdexcept>

namespace panelrad {

namespace {

// Runs row(i) for every element in parallel (each row is independent, and the values do not
// depend on the thread count); on bad data, rethrows the lowest failing row's error whatever the
// thread count (a deterministic message).
template <class Row>
void for_each_row(Index n, const Row& row) {
  parallel_for(n, row, 16);
}

}  // namespace

Collocation::Collocation(const Scene& scene, int level, std::size_t channel) {
  Stopwatch clock;
  // The tree is refused (with its estimate) when it exceeds what this process may still
  // allocate: MemAvailable, ulimit -v and the cgroup limit (available_memory_bytes).
  // Supporting planes: within the rounding of the input only for a closed convex surface (accepted
  // within rounding); a general scene's faces may face each other across any gap.
  const geometry::PlaneGrouping planes = scene.shape() == geometry::SceneShape::convex
                                             ? geometry::PlaneGrouping::within_rounding
                                             : geometry::PlaneGrouping::exact;
  tree_ = std::make_shared<const geometry::ClusterTree>(scene.mesh(), level, available_memory_bytes(), planes);
  shape_ = scene.shape();
  tree_s_ = clock.seconds();
  clock.restart();
  const Index n = tree_->num_elements();
  rho_.resize(n);
  E_.resize(n);
  const bool manufactured = scene.has_manufactured_solution();
  if (manufactured) true_u_.resize(n);
  for_each_row(n, [&](Index i) {
    const Vec3& P = collocation_point(i);
    const Index f = facet(i);
    rho_[i] = scene.reflectivity(P, f, channel);
    if (manufactured) {
      true_u_[i] = scene.manufactured_solution()(P, f);
      E_[i] = scene.manufactured_emissivity(P, f, normal(i));
    } else {
      E_[i] = scene.emissivity(P, f, channel);
    }
  });
  emissivity_s_ = clock.seconds();
}

Collocation::ChannelValues Collocation::channel_values(const Scene& scene, std::size_t channel) const {
  if (scene.has_manufactured_solution())
    throw std::logic_error("channel_values: a manufactured scene's E is the constructor's (emissivity())");
  ChannelValues v;
  const Index n = size();
  v.rho.resize(n);
  v.E.resize(n);
  for_each_row(n, [&](Index i) {
    const Vec3& P = collocation_point(i);
    const Index f = facet(i);
    v.rho[i] = scene.reflectivity(P, f, channel);
    v.E[i] = scene.emissivity(P, f, channel);
  });
  return v;
}

Collocation Collocation::with_row_weights(Eigen::VectorXd weights) const {
  if (weights.size() != size()) throw std::invalid_argument("with_row_weights: weights size differs from n");
  for (Index i = 0; i < size(); ++i)
    if (!(std::isfinite(weights[i]) && weights[i] >= 0))
      throw std::invalid_argument("with_row_weights: weight " + std::to_string(i) + " is not finite and >= 0");
  Collocation c;
  c.tree_ = tree_;
  c.shape_ = shape_;
  c.rho_ = std::move(weights);
  c.E_ = E_;
  c.true_u_ = true_u_;
  c.tree_s_ = tree_s_;
  c.emissivity_s_ = emissivity_s_;
  return c;
}

double Collocation::max_error(const Eigen::VectorXd& v) const {
  if (!has_true_solution()) throw std::logic_error("max_error: the scene has no manufactured solution");
  if (v.size() != size()) throw std::invalid_argument("max_error: vector size differs from n");
  return (true_u_ - v).lpNorm<Eigen::Infinity>();
}

}  // namespace panelrad

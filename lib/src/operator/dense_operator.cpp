#include <panelrad/operator/dense_operator.hpp>

#include "visible_covering.hpp"

#include <panelrad/support/resources.hpp>

#include <limits>
#include <sstream>
#include <stdexcept>

namespace panelrad {

std::size_t DenseOperator::matrix_bytes(geometry::Index n) {
  if (n <= 0) return 0;
  const auto m = static_cast<std::size_t>(n);
  // n^2 * 8 overflows size_t for n > 2^30.5: saturate, so that check_fits still refuses.
  if (m > std::numeric_limits<std::size_t>::max() / sizeof(double) / m) return std::numeric_limits<std::size_t>::max();
  return m * m * sizeof(double);
}

void DenseOperator::check_fits(geometry::Index n) {
  const std::size_t need = matrix_bytes(n);
  const MemoryAvailability available = memory_availability();
  const std::size_t avail = available.bytes();
  if (need > avail / 10 * 9) {
    std::ostringstream os;
    os << "dense matrix K_n for n = " << n << " needs " << format_bytes(static_cast<double>(need))
       << " but only " << format_bytes(static_cast<double>(avail)) << " of memory is available ("
       << available.binding() << "); use the fast method (section 4) or fewer levels";
    throw ResourceError(os.str());
  }
}

DenseOperator::DenseOperator(const Collocation& collocation, const NearFieldOptions& options,
                             std::shared_ptr<const geometry::Occluders> occluders) {
  const geometry::Index n = collocation.size();
  check_fits(n);
  K_.resize(n, n);
  const NearFieldIntegrator integrate(options, collocation.tree().mesh_size());
  const auto elements = collocation.tree().elements();
  if (occluders) {
    K_.setZero();  // hidden elements stay 0
    std::size_t visible = 0, hidden = 0, partial = 0, clipped = 0;
#pragma omp parallel reduction(+ : visible, hidden, partial, clipped)
    {
      VisibleCoveringScratch scratch;
      VisibilityCounts counts;
#pragma omp for schedule(dynamic, 8)
      for (geometry::Index i = 0; i < n; ++i) {
        const double rho = collocation.reflectivity()[i];
        if (rho == 0) continue;
        cover_visible(
            collocation.tree(), *occluders, collocation.collocation_point(i), collocation.normal(i),
            collocation.tree().plane(collocation.tree().finest_level(), i), 0.0, integrate,
            [](int, geometry::Index) {}, [&](geometry::Index j, double value) { K_(i, j) = rho * value; }, counts,
            scratch);
      }
      visible += counts.visible;
      hidden += counts.hidden;
      partial += counts.partial;
      clipped += counts.clipped;
    }
    occluded_ = true;
    visible_pairs_ = visible;
    hidden_pairs_ = hidden;
    partial_pairs_ = partial;
    clipped_elements_ = clipped;
    return;
  }
#pragma omp parallel for schedule(dynamic, 8)
  for (geometry::Index i = 0; i < n; ++i) {
    const Vec3& P = collocation.collocation_point(i);
    const Vec3& nP = collocation.normal(i);
    const geometry::ClusterTree& tree = collocation.tree();
    const int L = tree.finest_level();
    const geometry::Index plane = tree.plane(L, i);
    const double rho = collocation.reflectivity()[i];
    for (geometry::Index j = 0; j < n; ++j) {
      const auto& e = elements[static_cast<std::size_t>(j)];
      // In P_i's plane (any facet): coplanar, G = 0 exactly (section 4.2, case (a)); rho = 0: zero row.
      K_(i, j) = (tree.plane(L, j) == plane || rho == 0) ? 0.0 : rho * integrate(P, nP, e);
    }
  }
}

void DenseOperator::apply(const Eigen::VectorXd& v, Eigen::VectorXd& y) const {
  const geometry::Index n = size();
  if (v.size() != n) throw std::invalid_argument("DenseOperator::apply: vector size differs from n");
  y.resize(n);
  // One row per thread iteration, each dot product in a fixed order: thread-count independent.
#pragma omp parallel for schedule(static)
  for (geometry::Index i = 0; i < n; ++i) y[i] = K_.row(i).dot(v);
}

}  // namespace panelrad

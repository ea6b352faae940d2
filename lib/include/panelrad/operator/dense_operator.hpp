#pragma once
// The dense matrix K_n of (33): (K_n)_ij = rho(P_i)/pi Int_Delta_j G(P_i,Q) V(P_i,Q) dS_Q,
// assembled in parallel. The reference path: accurate, O(n^2) memory and time. With occluders,
// each entry is the closed-form form factor of the part of Delta_j that P_i sees
// (visible_covering.hpp, the walk with nothing admissible).
#include <panelrad/geometry/occluders.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/linear_operator.hpp>
#include <panelrad/operator/near_field.hpp>

#include <Eigen/Core>

#include <memory>

namespace panelrad {

class DenseOperator final : public RadiosityOperator {
 public:
  using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

  /// Refuses (ResourceError, a std::runtime_error, with the estimate) a matrix that would not fit in memory.
  /// `occluders` empty: V = 1 (a convex scene).
  DenseOperator(const Collocation& collocation, const NearFieldOptions& options,
                std::shared_ptr<const geometry::Occluders> occluders = {});

  /// Bytes needed for the matrix of order n.
  static std::size_t matrix_bytes(geometry::Index n);
  /// Throws ResourceError (with the estimate and what is available) when the matrix of
  /// order n would not fit in memory; called before anything is allocated or computed.
  static void check_fits(geometry::Index n);

  geometry::Index size() const override { return static_cast<geometry::Index>(K_.rows()); }
  void apply(const Eigen::VectorXd& v, Eigen::VectorXd& y) const override;
  std::string name() const override { return "dense"; }
  std::size_t bytes() const override { return matrix_bytes(size()); }
  const Matrix& matrix() const { return K_; }
  /// Occluders given: V computed, and the (P_i, cluster) pairs classified while assembling.
  bool occluded() const { return occluded_; }
  std::size_t visible_pairs() const { return visible_pairs_; }
  std::size_t hidden_pairs() const { return hidden_pairs_; }
  std::size_t partial_pairs() const { return partial_pairs_; }
  std::size_t clipped_elements() const { return clipped_elements_; }

 private:
  Matrix K_;
  bool occluded_ = false;
  std::size_t visible_pairs_ = 0, hidden_pairs_ = 0, partial_pairs_ = 0, clipped_elements_ = 0;
};

}  // namespace panelrad

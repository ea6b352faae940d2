#pragma once
// Centroid collocation (paper section 3): elements of the level-L uniform refinement, their
// centroids P_i as collocation points (22), and the data of the linear system (32):
// rho(P_i), (E_n)_i = E(P_i) and, for a manufactured scene, the true solution u(P_i).
#include <panelrad/geometry/cluster_tree.hpp>
#include <panelrad/scene/scene.hpp>

#include <Eigen/Core>

#include <memory>

namespace panelrad {

class Collocation {
 public:
  /// Refines the scene's mesh `level` times (n = 4^level n0) and evaluates rho, E (and u) of
  /// channel `channel` at the centroids, in parallel. Throws std::invalid_argument for bad rho/E
  /// (Scene's rule, naming the lowest failing point), geometry::MeshError for a size that does
  /// not fit in memory.
  Collocation(const Scene& scene, int level, std::size_t channel = 0);

  /// rho(P_i) and E(P_i) of one channel of `scene` (the scene this collocation was made from),
  /// checked by the scene's rule; the same evaluation as the constructor's.
  struct ChannelValues {
    Eigen::VectorXd rho, E;
  };
  ChannelValues channel_values(const Scene& scene, std::size_t channel) const;

  /// The scene's shape (Scene::shape): convex, where V = 1 is exact (the paper's setting), or
  /// general, where V(P, Q) must be computed (make_operator refuses V = 1 there).
  geometry::SceneShape shape() const { return shape_; }
  const geometry::ClusterTree& tree() const { return *tree_; }
  std::shared_ptr<const geometry::ClusterTree> shared_tree() const { return tree_; }
  Index size() const { return tree_->num_elements(); }
  int level() const { return tree_->finest_level(); }

  /// Collocation point P_i (centroid of element i, (22)) and its inner unit normal.
  const Vec3& collocation_point(Index i) const { return tree_->collocation_point(i); }
  const Vec3& normal(Index i) const { return tree_->elements()[static_cast<std::size_t>(i)].normal; }
  Index facet(Index i) const { return tree_->elements()[static_cast<std::size_t>(i)].facet; }

  const Eigen::VectorXd& reflectivity() const { return rho_; }   ///< rho(P_i)
  const Eigen::VectorXd& emissivity() const { return E_; }       ///< E_n, (32)
  bool has_true_solution() const { return true_u_.size() == size(); }
  const Eigen::VectorXd& true_solution() const { return true_u_; }  ///< u(P_i), manufactured scenes
  /// max_k |u(P_k) - v_k|, (51); requires a manufactured scene.
  double max_error(const Eigen::VectorXd& v) const;

  /// The same discretization with rho(P_i) replaced by `weights` (finite, >= 0; a weight of 0
  /// marks a row that is not needed): an operator built on it computes
  /// (W v)_i = w_i / pi Int_S v G(P_i, Q) dS_Q. With w = 1 it is the irradiance operator H of a
  /// multi-channel solve, K_n = diag(rho) H for every channel. Shares the cluster tree (and the
  /// scene's shape).
  Collocation with_row_weights(Eigen::VectorXd weights) const;

  double tree_seconds() const { return tree_s_; }
  double emissivity_seconds() const { return emissivity_s_; }

 private:
  Collocation() = default;
  std::shared_ptr<const geometry::ClusterTree> tree_;
  geometry::SceneShape shape_ = geometry::SceneShape::general;
  Eigen::VectorXd rho_, E_, true_u_;
  double tree_s_ = 0, emissivity_s_ = 0;
};

}  // namespace panelrad

#pragma once
// The self-check of an operator K_f ~ K_n: its product's real error on sampled rows, measured
// against the exact closed-form rows of K_n. For any RadiosityOperator (the fast operator of
// section 4, the dense matrix of (33), the rows of one process): the exact side (test vectors,
// sampled rows, exact rows) depends on the collocation and the occluders only.
//
// What it measures. The solution's error from the product's error: with (I - K) u = E and
// (I - K_f) u_f = E, (I - K)(u - u_f) = (K - K_f) u_f, so by (11)
//     ||u - u_f||_inf <= ||(K - K_f) u_f||_inf / (1 - rho_max).
// The check estimates delta = ||(K - K_f) v||_inf / ||K v||_inf for vectors v like the
// solution: smooth (constant, linear, quadratic in the coordinates scaled to the bounding box),
// oscillating (cos 7x + sin(5y) z, the same scaled coordinates), piecewise constant by facet
// (the solution jumps where rho or E changes from facet to facet) and rough (a random +-1
// vector with a fixed seed: the worst case of the row sums of |K - K_f|, the operator's
// inf-norm). The maximum over the vectors is the check value.
//
// Rows sampled: `samples` rows, half evenly spaced over the element order (which runs facet by
// facet), half among the elements at a corner of an input triangle (next to the surface's
// edges and corners, where the near field is largest and other facets are nearest); every row
// when samples >= n. Deterministic.
//
// Relative to max_k (K |v|)_k over the sampled rows k (inf-norm relative; K >= 0 entrywise, so
// this is max_k |(K v)_k| for v >= 0). For a sign-changing v it does not divide by the
// cancellations in K v (a random +-1 v has |K v| ~ n^-1/2 K|v|, which would make the check grow
// with n without any change in the solution's error); and it is the scale of the bound:
// ||(K - K_f) v||_inf <= delta max_k (K|v|)_k <= delta rho_max ||v||_inf, so with v = u_f
//     ||u - u_f||_inf / ||u_f||_inf <= delta rho_max / (1 - rho_max),
// delta the check value (an estimate: sampled rows and vectors like u_f, not a proof).
#include <panelrad/geometry/cluster_tree.hpp>
#include <panelrad/geometry/occluders.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/linear_operator.hpp>

#include <Eigen/Core>

#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace panelrad {

/// The named test vectors v of the self-check (values at the collocation points P_j).
using SelfCheckVectors = std::vector<std::pair<std::string, Eigen::VectorXd>>;

/// One test vector of the self-check and its worst error over the sampled rows.
struct SelfCheckVector {
  std::string name;            ///< what v is, e.g. "cos 7x + sin(5y) z"
  double relative_error = 0;   ///< max_k |(K_f v)_k - (K v)_k| / max_k (K |v|)_k over the sampled rows k
  geometry::Index row = -1;    ///< the row k where the maximum is attained
};

/// The exact side of the self-check: the sampled rows, the test vectors, and per row r and
/// vector k (index r * vectors + k) the exact (K v_k)_r and (K |v_k|)_r. It depends on the
/// collocation (rows and their weights) and the occluders only, not on the operator checked: one
/// reference serves every operator of the same rows and occluders.
struct SelfCheckReference {
  std::vector<geometry::Index> rows;
  SelfCheckVectors vectors;
  std::vector<double> exact, scale;
  double seconds = 0;
};

/// The measured error of an operator's product on the sampled rows.
struct SelfCheck {
  int rows = 0;                              ///< rows sampled
  double relative_error = 0;                 ///< max over `vectors` (+inf when a product is not finite)
  std::vector<SelfCheckVector> vectors;      ///< one entry per test vector, in self_check_vectors() order
  std::vector<geometry::Index> sampled_rows; ///< the rows compared, ascending
  double seconds = 0;                        ///< the products and comparison, plus the reference's
};

/// The test vectors: constant, linear and quadratic in the collocation points' coordinates scaled
/// to their bounding box, oscillating, +-1 by facet and random +-1 (fixed seed): deterministic
/// functions of the tree's collocation points and facets.
SelfCheckVectors self_check_vectors(const geometry::ClusterTree& tree);

/// The sampled rows among [first, end): every row when samples >= end - first, else half evenly
/// spaced and half at corners of the input triangles; ascending, without repeats.
std::vector<geometry::Index> self_check_rows(const geometry::ClusterTree& tree, geometry::Index first,
                                             geometry::Index end, int samples);

/// The exact rows of K_n, (K_n)_ij = w_i/pi Int_Delta_j G(P_i, Q) V(P_i, Q) dS_Q in closed form
/// (one form factor per element, O(n) per row), of the sampled rows of [first, end) (end = -1:
/// n) for every self_check_vectors(tree). `weights` are rho(P_i) (or the row weights of
/// Collocation::with_row_weights), all n; `occluders` null: V = 1 (a convex scene).
SelfCheckReference self_check_reference(const geometry::ClusterTree& tree, std::span<const double> weights,
                                        const geometry::Occluders* occluders, int samples,
                                        geometry::Index first = 0, geometry::Index end = -1);
/// The same for the rows of `collocation` (weights: its reflectivity), all of them.
SelfCheckReference self_check_reference(const Collocation& collocation, const geometry::Occluders* occluders,
                                        int samples = 32);

/// The product checked, on the sampled rows: out[r] = (K_f v)_{rows[r]} for every r.
using SampledProduct =
    std::function<void(const Eigen::VectorXd& v, std::span<const geometry::Index> rows, std::span<double> out)>;

/// Compares `product` with the reference's exact rows, vector by vector (std::invalid_argument
/// when the reference's values do not match its rows and vectors, or a vector is not of length n).
SelfCheck measure_self_check(const SelfCheckReference& reference, geometry::Index n, const SampledProduct& product);

/// The self-check of any operator of order n: its whole product apply(v), read on the sampled rows.
SelfCheck self_check(const RadiosityOperator& op, const SelfCheckReference& reference);
/// The same against the exact rows of `collocation` (self_check_reference): `samples` rows.
SelfCheck self_check(const RadiosityOperator& op, const Collocation& collocation,
                     const geometry::Occluders* occluders = nullptr, int samples = 32);

}  // namespace panelrad

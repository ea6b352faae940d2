#pragma once
// Builds the operator K_n of (32): the dense matrix (33) or the fast product of section 4, for a
// collocation (22) of a scene and a visibility policy.
#include <panelrad/geometry/occluders.hpp>
#include <panelrad/operator/clustering_parameters.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/operator/linear_operator.hpp>
#include <panelrad/operator/near_field.hpp>

#include <functional>
#include <memory>
#include <string>

namespace panelrad {

/// How K_n v is computed. automatic: the measured rule of auto_parameters.hpp (a solver
/// object's choice, SolveOptions); dense: the matrix (33); fast: section 4.
enum class OperatorMethod { automatic, dense, fast };
/// "auto" | "dense" | "fast".
const char* to_string(OperatorMethod method);
/// The inverse of to_string; anything else is a std::invalid_argument listing the valid names.
OperatorMethod parse_operator_method(const std::string& name);

/// Which pairs of points see each other. The kernel of (1) is G(P, Q) V(P, Q), V in {0, 1} the
/// line-of-sight function.
/// - unoccluded: V = 1 for every pair, exact on the surface of a convex solid (every segment
///   between two of its points lies inside it, so nothing occludes it); the paper's setting. The
///   scene's convexity is proven by the exact check geometry::validate_closed_convex when the
///   scene is made (geometry::SceneShape::convex).
/// - occluded: V computed from the scene's faces (geometry/occluders.hpp), with G clamped to the
///   front of both planes: each (P_i, cluster) pair of the covering (42) is fully visible (the
///   Taylor far field when admissible), hidden (skipped) or partly visible (refined; at the
///   elements, the closed-form form factor of the visible part).
/// - automatic: occluded unless the scene is proven convex (a solver's choice; not an operator).
enum class Visibility { automatic, unoccluded, occluded };
const char* to_string(Visibility visibility);  ///< "auto" | "unoccluded" | "occluded"
/// The inverse of to_string; anything else is a std::invalid_argument listing the valid names.
Visibility parse_visibility(const std::string& name);
/// Why `visibility` cannot build an operator on a scene of `shape`, or "" when it can: unoccluded
/// (V = 1) is the paper's convex assumption and exact only on a proven convex surface; on a
/// general scene it would let light through the faces that hide one part from another (entries
/// of K_n < 0 where a face is seen from its back), so it is refused there, naming the reason and
/// occluded instead. automatic is not an operator's (the solver resolves it).
std::string visibility_problem(Visibility visibility, geometry::SceneShape shape);

/// What the visibility computation of an occluded operator did: the (P_i, cluster) pairs of the
/// coverings (42) classified fully visible, hidden and partly visible, the elements integrated
/// over their visible part, and the rays cast. All 0 for an unoccluded operator, which does no
/// visibility work.
struct VisibilityWork {
  bool computed = false;  ///< the operator computes V
  std::size_t visible_pairs = 0, hidden_pairs = 0, partial_pairs = 0, clipped_elements = 0, rays_cast = 0;
};
/// The work of a DenseOperator or FastOperator (an unknown operator: none).
VisibilityWork visibility_work(const RadiosityOperator& op);

/// A concrete operator: method dense or fast, the near rule, and eta, M of the fast method
/// (ClusteringParameters; ignored by the dense method).
struct OperatorOptions : ClusteringParameters {
  OperatorMethod method = OperatorMethod::dense;  ///< dense | fast (automatic is not an operator)
  NearFieldOptions near;                          ///< near-field rule (dense: every entry)
  /// Products the solver expects (0: unknown): the fast operator stores its far coefficients only
  /// when they repay their writing (FastOptions::expected_products).
  int expected_products = 0;
  bool operator==(const OperatorOptions&) const = default;
};

/// Called when a setup stage starts ("dense matrix, n = 3072"; the fast operator's near field and
/// far field), e.g. for progress on stderr. May be empty.
using SetupProgress = std::function<void(const std::string&)>;

/// The scene's faces as occluders: the level-0 triangles of the cluster tree (the validated,
/// oriented input triangles; refinement adds no face).
std::shared_ptr<const geometry::Occluders> scene_occluders(const geometry::ClusterTree& tree);

/// Whether make_operator's fast operator stores its far coefficients in single precision
/// (FastOptions::single_precision_coefficients), with or without V: yes. Writing and reading the
/// stored coefficients dominate the setup and the products (a covering with V holds several times
/// the far pairs per row of a convex surface: bench/visibility, 2.9x on the Cornell box at
/// n = 49,152); in single precision they take half the memory, and storing them pays after about
/// 17 products instead of almost never (far_field_costs). The rounding, 6e-8 per coefficient,
/// stays two orders below the self-check's thresholds and is measured by it (bench/product: the
/// self-check errors of float and double agree to 3 digits on the cube at n = 49,152).
bool single_precision_far_field(Visibility visibility);

/// Whether make_operator's fast operator stores its near-field entries in single precision
/// (FastOptions::single_precision_near): with V only. A covering with V integrates the elements
/// along every shadow's edge one by one, so its near entries dominate the memory and a product's
/// reading (bench/visibility on the Cornell box at n = 245,760: 4,014 a row, 11.8 of the 12.8 GB
/// held in double; 8.9 GB held in all with them in single precision), at a rounding of 6e-8 per
/// entry that self_check includes. Without V the near field stays double: the convex path unchanged.
bool single_precision_near_field(Visibility visibility);

/// The operator with rows weighted by the collocation's reflectivity (33):
/// (K_n v)_i = rho(P_i)/pi Int_S v G(P_i, Q) V(P_i, Q) dS_Q. options.method automatic and
/// visibility automatic are std::invalid_argument (the solver resolves them), and so is
/// unoccluded on a scene that is not proven convex (visibility_problem; the collocation keeps the
/// scene's shape). With occluded, the occluders are the level-0 triangles of the collocation's
/// tree (the scene's faces).
///
/// The fast operator may hold some rows only (FastOptions::rows) or be a probe of the self-check's
/// sampled rows (FastOptions::probe_samples > 0); the dense operator always holds every row.
std::unique_ptr<RadiosityOperator> make_operator(const Collocation& collocation, const OperatorOptions& options,
                                                 Visibility visibility = Visibility::unoccluded,
                                                 const SetupProgress& progress = {}, const RowRange& rows = {},
                                                 int probe_samples = 0);

}  // namespace panelrad

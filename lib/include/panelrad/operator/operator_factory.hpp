#pragma once
// Builds the operator K_n of (32): the dense matrix (33) or the fast product of section 4, for a
// collocation (22) of a scene and a visibility policy.
#include <panelrad/operator/clustering_parameters.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/linear_operator.hpp>
#include <panelrad/operator/near_field.hpp>

#include <functional>
#include <memory>
#include <string>

namespace panelrad {

/// How K_n v is computed. automatic: the measured rule of auto_parameters.hpp (a solver
/// object's choice, RadiositySolverOptions); dense: the matrix (33); fast: section 4.
enum class OperatorMethod { automatic, dense, fast };
/// "auto" | "dense" | "fast".
const char* to_string(OperatorMethod method);
/// The inverse of to_string; anything else is a std::invalid_argument listing the valid names.
OperatorMethod parse_operator_method(const std::string& name);

/// Which pairs of points see each other. The kernel G(P, Q) of (2)-(3) carries the visibility
/// V(P, Q) in {0, 1}; the only policy today is `unoccluded` (V = 1 for every pair), which is exact
/// on the surface of a convex solid: every segment between two of its points lies inside it, so
/// nothing occludes it. The scene's convexity is proven by the exact check
/// geometry::validate_closed_convex when the scene is made.
enum class Visibility { unoccluded };
const char* to_string(Visibility visibility);  ///< "unoccluded"

/// A concrete operator: method dense or fast, the near rule, and eta, M of the fast method
/// (ClusteringParameters; ignored by the dense method).
struct OperatorOptions : ClusteringParameters {
  OperatorMethod method = OperatorMethod::dense;  ///< dense | fast (automatic is not an operator)
  NearFieldOptions near;                          ///< near-field rule (dense: every entry)
  bool operator==(const OperatorOptions&) const = default;
};

/// Called when a setup stage starts ("dense matrix, n = 3072"; the fast operator's near field and
/// far field), e.g. for progress on stderr. May be empty.
using SetupProgress = std::function<void(const std::string&)>;

/// The operator with rows weighted by the collocation's reflectivity (33):
/// (K_n v)_i = rho(P_i)/pi Int_S v G(P_i, Q) dS_Q. options.method automatic is a
/// std::invalid_argument (choose_parameters resolves it).
std::unique_ptr<RadiosityOperator> make_operator(const Collocation& collocation, const OperatorOptions& options,
                                                 Visibility visibility = Visibility::unoccluded,
                                                 const SetupProgress& progress = {});

}  // namespace panelrad

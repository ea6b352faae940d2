#pragma once
// View factors between groups of surfaces: F_IJ, the fraction of the radiation leaving surface I
// diffusely that reaches surface J directly (gray diffuse exchange),
//   F_IJ = (1 / A_I) Int_I (1/pi) Int_J G(P, Q) V(P, Q) dS_Q dS_P,
// with G and V those of equation (1). The inner integral is the operator H of (33) without rho,
// (H v)_i = (1/pi) Int_S v(Q) G(P_i, Q) V(P_i, Q) dS_Q, and the outer one its collocation (22):
//   F_IJ = (1 / A_I) sum_{i in I} A_i (H chi_J)_i,   A_I = sum_{i in I} A_i,
// chi_J the indicator of J's elements. Every group's indicator goes through H in block products
// (RadiosityOperator::apply_block: the fast operator's lists and far field read once for a block
// of columns), never as an n x n matrix. The part of P_i's hemisphere that no surface covers is
// 1 - (H 1)_i; over group I it is 1 - sum_J F_IJ: in an open scene the sky view factor, in an
// enclosed one the closure defect of the discretization (the exact factors close to 1).
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/radiosity_solver.hpp>

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace panelrad {

/// A partition of the scene's input facets into named groups (the surfaces of F_IJ).
struct SurfaceGroups {
  std::vector<std::string> names;        ///< one per group, distinct and non-empty
  std::vector<geometry::Index> of_facet;  ///< the group of each input facet, in [0, names.size())
};

/// Every input facet its own group, named "facet K" (K its index in the file's order).
SurfaceGroups groups_by_facet(const Scene& scene);
/// The facets of one material (OBJ usemtl) one group, named by it, in the order of first use; a
/// facet written before any usemtl is in the group "default". std::invalid_argument when the
/// scene has no materials (an OFF, or an OBJ read as geometry only).
SurfaceGroups groups_by_material(const Scene& scene);
/// The facets of one object one group: an OBJ's `o` or `g` name in force, an ASCII STL's `solid`
/// (TriangleMesh::facet_group), in the order of first use; a facet before any name is in the group
/// "default". std::invalid_argument when the file names no object.
SurfaceGroups groups_by_object(const Scene& scene);
/// One group per distinct name of `per_facet` (a name per input facet), in the order of first use;
/// an empty name is the group "default". groups_by_material and groups_by_object are this on the
/// file's names.
SurfaceGroups groups_by_name(const std::vector<std::string>& per_facet);
/// What is wrong with `groups` for `scene` ("" when nothing): a facet count that differs, a
/// group index out of range, a name empty or given twice, a group with no facet.
std::string groups_problem(const Scene& scene, const SurfaceGroups& groups);

/// A scene whose chosen groups are two-sided sheets, and its groups.
struct TwoSidedScene {
  Scene scene;
  SurfaceGroups groups;
};

/// Every facet of the groups named in `two_sided` (open sheets: a fin, a louvre, a pane) gets its
/// back side as a facet of its own: the same triangles wound the other way, on vertices of their
/// own, appended after the scene's facets (facet num_facets + k for the k-th facet so copied) in a
/// group "NAME (back)" after the scene's groups, so that each side radiates as its own elements;
/// two open sheets back to back are both kept (no contact is removed). The mesh is validated
/// anew as a geometry-only scene (rho and E are not carried: view factors do not use them), its
/// materials and object names copied to the back sides. std::invalid_argument for a name that
/// is no group or is given twice, or a group already ending in " (back)"; the validation's
/// MeshError when the back sides do not make a valid scene (a closed solid's faces: their backs
/// would lie inside it).
TwoSidedScene with_back_sides(const Scene& scene, const SurfaceGroups& groups, const std::vector<std::string>& two_sided);

struct ViewFactorOptions {
  /// The discretization and the operator, as a solve takes them (level or max_elements, method,
  /// accuracy, visibility, progress). Reflectivity plays no part: H carries none.
  SolveOptions solve;
  /// Also compute the factors one level coarser (when the level is at least 1) and report
  /// |F(level) - F(level - 1)| as the discretization's error estimate: at first order in h it is
  /// the error of the finer level, at higher order an overestimate.
  bool estimate_error = true;
  /// Group indicators per block product.
  int block_columns = 8;
  /// Make the matrix reciprocal (A_I F_IJ = A_J F_JI) and, in an enclosed scene, closed (rows
  /// summing to 1), as thermal network models need (reciprocal_and_closed); in an open one the sky
  /// takes what the rows leave. ViewFactors::correction says by how much F moved.
  bool reciprocal = false;
  /// Keep per element (level L) its group, centroid, area and sky view factor 1 - (H 1)_i
  /// (ViewFactors::elements): 1 - sum over every group's column, no extra product.
  bool elements = false;
  /// Groups, by name, whose factor from every element, F_iJ = (H chi_J)_i (the part of P_i's
  /// hemisphere, cosine-weighted, that J covers), is kept beside the sky (implies `elements`; no
  /// extra product: the columns of the block products). A name that is no group is a
  /// std::invalid_argument naming it.
  std::vector<std::string> element_targets;
};

/// Per element of the finest level: what ViewFactorOptions::elements keeps.
struct ElementSky {
  std::vector<geometry::Index> facet, group;
  std::vector<std::array<geometry::Vec3, 3>> triangle;  ///< corners, as ElementField::triangle
  std::vector<geometry::Vec3> centroid;  ///< the collocation point P_i
  Eigen::VectorXd area;
  Eigen::VectorXd sky;                   ///< 1 - (H 1)_i: what of P_i's hemisphere no surface covers
  std::vector<std::string> target_names;  ///< ViewFactorOptions::element_targets
  Eigen::MatrixXd to;                     ///< to(i, k) = F_iJ for J = target_names[k], n x targets
};

struct ViewFactors {
  std::vector<std::string> names;
  Eigen::VectorXd area;       ///< A_I
  Eigen::MatrixXd F;          ///< F(I, J) = F_IJ
  /// 1 - sum_J F_IJ: the sky view factor of I in an open scene, the closure defect in an
  /// enclosed one (Scene::enclosed).
  Eigen::VectorXd uncovered;
  bool enclosed = true;
  /// |F(level) - F(level - 1)| and the same for `uncovered` (estimate_error at level >= 1), else
  /// empty.
  Eigen::MatrixXd error;
  Eigen::VectorXd uncovered_error;
  /// max over pairs of |A_I F_IJ - A_J F_JI| / max(A_I F_IJ, A_J F_JI) (pairs where both are 0
  /// left out), and the pair (I, J) where it is reached (-1, -1 when no pair exchanges).
  double reciprocity_defect = 0;
  geometry::Index reciprocity_I = -1, reciprocity_J = -1;
  int level = 0;
  geometry::Index n = 0;
  std::string method;               ///< describe_parameters of the operator
  double self_check_error = -1;     ///< the fast operator's relative product error; -1: dense
  double seconds = 0;               ///< setup and products, both levels
  /// With ViewFactorOptions::reciprocal: max |F_IJ - F_IJ as computed|, else 0.
  double correction = 0;
  /// With ViewFactorOptions::elements, else empty.
  ElementSky elements;
};

/// F made reciprocal, and closed when `enclosed`: the exchange areas S = (A F + (A F)^T) / 2 made
/// symmetric; in an enclosure then scaled symmetrically, S_IJ d_I d_J, until every row sums to A_I
/// (Sinkhorn-Knopp's balancing of a symmetric matrix: zeros stay zeros, no entry turns negative);
/// F_IJ = S_IJ d_I d_J / A_I. In an open scene the rows' sums are left to the symmetrization (the
/// sky, 1 - sum_J F_IJ, takes the rest: reciprocity with the sky, whose area is not defined, is
/// not asked). Rows that exchange nothing stay 0. std::invalid_argument for sizes that differ or a
/// negative entry or area; a balance that does not reach 1e-13 in 10,000 sweeps (a pattern of
/// zeros that no scaling closes) is a std::runtime_error.
Eigen::MatrixXd reciprocal_and_closed(const Eigen::MatrixXd& F, const Eigen::VectorXd& area, bool enclosed);

/// The view factors between `groups` of `scene` (groups_problem must be ""; std::invalid_argument
/// naming the problem otherwise). The errors of the solver's setup pass through (ResourceError,
/// std::invalid_argument for bad options). One process (options.solve.communicator null).
ViewFactors compute_view_factors(const Scene& scene, const SurfaceGroups& groups, const ViewFactorOptions& options = {});

}  // namespace panelrad

#pragma once
// Automatic parameters: the method, near rule, eta of (41) and Taylor degree M
// of (44) for a scene of a given size, so that the solution stays within 5% of the
// discretization error at the least cost measured by bench/sweep (bench/results/sweep.csv).
//
// Criterion ("faithful"): with u_ref the dense solution with the exact near rule at the same n
// (the centroid method's own answer), a setting is accepted when
//     max_k |u_n(P_k) - u_ref(P_k)| <= 0.05 max_k |u(P_k) - u_ref(P_k)|,
// which implies error <= 1.05 x discretization error by the triangle inequality, without relying
// on a lucky cancellation of far-field and discretization errors (M = 1 runs often show a smaller
// error than the reference for that reason; cf. the paper's Table 2).
//
// The size is measured by the equivalent level lambda = log2(0.8165 / (h / diam)), h the mesh
// size (longest edge), diam the surface's diameter: the paper's cube at level l has
// h / diam = sqrt(2/3) 2^-l, so lambda = l; the hexagonal prism (r = 1, height 1) at level l has
// lambda = l + 0.21. The discretization error halves per level (Table 1) while the far-field
// error of a fixed (eta, M) does not, so the admissible settings tighten as lambda grows.
//
// The measurements behind the rule (deviations of each (eta, M) from the dense exact solution on
// the cube and the hexagonal prism, their costs, and the self-check values of each setting) are in
// bench/results/auto_parameters.md, from bench/sweep (bench/results/sweep.csv). In short: the
// deviation of a fixed (eta, M) does not shrink with n (it is the Taylor remainder, ~eta^(M+1)
// relative to |u|), while the discretization error halves per level, so each setting is good up
// to some level.
//
// The product's target. Those deviations are for the cube's smooth solution at rho_max 0.5; a
// scene's solution may oscillate, and its equation may be worse conditioned. The product's error
// reaches the solution amplified: with (I - K) u = E, (I - K_f) u_f = E and K = diag(rho) H,
//     u - u_f = (I - K)^-1 (K - K_f) u_f,   ||(I - K)^-1||_inf <= 1 / (1 - rho_max)   (11),
// and ||(K - K_f) v||_inf <= delta max_k (K|v|)_k <= delta rho_max ||v||_inf, delta the product's
// relative error (FastSelfCheck: the worst of smooth, oscillating, facet-wise and random vectors
// on sampled exact rows), so
//     ||u - u_f||_inf / ||u_f||_inf <= delta A(rho_max),   A(rho) = rho / (1 - rho).
// The target is 5% of the discretization error scale e_h = 0.025 (h/diam) ||u||_inf, the
// cube's measured error (Table 1: 3.77e-3 / 3 at h/diam 0.0510, 1.92e-3 / 3 at 0.0255; ||u|| = 3):
//     delta <= delta* = 0.05 * 0.025 (h/diam) / max(1, A(rho_max)) = 1.25e-3 (h/diam) / max(1, A).
// A scene's own discretization error need not grow with A (a constant solution on a closed
// surface is reproduced exactly: H_n 1 = 1), so the target does not count on it. For
// rho_max <= 0.5 the factor stays 1 (never looser than at the cube's rho_max 0.5). Example: an
// icosahedron with rho = 0.6, 0.3, 0.9 per channel at level 3 (h/diam 0.0446, lambda 4.19) was
// given eta 0.5, M 6 and deviated 9.4e-4 in the rho = 0.9 channel (|u| = 2), 8.4 times
// 0.05 e_h; with A(0.9) = 9 it now gets delta* = 6.2e-6.
//
// The rule. delta* halves per level and shrinks by A, so it is a level: the equivalent level of
// the target, lambda_eff = lambda + log2 max(1, A(rho_max)), and delta* = 1.02e-3 2^-lambda_eff.
// The self-check value of each setting does not depend on n (bench/results/auto_parameters.md);
// each setting is used while its check is below delta*, i.e. lambda_eff below:
//   n <= 768: dense, exact near field (whole solve < 0.1 s, no far-field error at all);
//   else, unless the dense matrix is the cheaper operator (W >= 11, below):
//   lambda_eff < 2.5:  fast, exact, eta 0.5, M 6  (delta* 1.8e-4 at 2.5);
//   lambda_eff < 5.5:  fast, exact, eta 0.4, M 6  (delta* 2.3e-5 at 5.5);
//   lambda_eff < 7.5:  fast, exact, eta 0.4, M 8  (5.6e-6);
//   lambda_eff < 10.5: fast, exact, eta 0.4, M 10 (7.0e-7);
//   otherwise:         fast, exact, eta 0.4, M 12 (valid to lambda_eff ~ 14.7; beyond it, and on
//     scenes whose product is less accurate than the cube's, the self-check tightens eta).
//   So the cube (rho_max 0.5) at levels 4-5 gets (0.4, 6) and at 6-7 (0.4, 8): one step stricter
//   than the deviations alone asked ((0.5, 6) and (0.4, 6)), since (0.5, 6) multiplies an
//   oscillating v by 1.5e-4 relative error, 4.7 times delta* at level 5.
//   Large eta with a higher M beats a small eta: far pairs fall like 1/eta^2 (89, 143, 258, 510
//   per row at eta 0.5, 0.4, 0.3, 0.2 for n = 12288) while the terms grow like M^2/2, and the
//   stored coefficients of eta 0.1 would need ~20 GB at n = 196,608.
// Dense or fast. The cluster tree (40) starts at the n0 input triangles: no cluster is larger than
// a root, so a row's covering (42) holds at least about every root that faces it, each a far pair
// of T(M) = (M+1)(M+2)/2 Taylor terms (44), while a dense row holds n entries. The fast method's
// work per row over the dense matrix's is estimated as
//     W = phi min(n, n0 + 20 / eta^2) T(M) / n,
// 20 / eta^2 the far pairs the refinement below the roots adds (cube, 12 roots: 134 per row at
// eta 0.4, n = 3072; 89 at eta 0.5, n = 12288, memory_plan.hpp), phi = 1 on a convex
// surface (V = 1: every pair interacts) and, on an occluded scene, the fraction of root pairs that
// face each other (each centroid strictly in front of the other's plane; ProblemSize::facing,
// sampled over 256 roots): a pair that does not is hidden, and so are all pairs of its elements.
// W is a work ratio for the far field's coefficients: they take the memory of W / 2 dense matrices
// when stored in single precision (the solver stores them when about 17 or more products are
// expected: rho_max near 1, or three channels), and about W / 100 of the dense setup's time per
// product when recomputed. The rule takes the dense matrix when W >= 11: at level 0 (W = phi T(M),
// at least 28 when the roots face each other) always, at level 1 from M = 8 (W ~ T(M) / 4),
// from level 2 on never above n ~ 2100 (M <= 12). Measured with the command line on this 2-core
// machine (wall time and peak memory of the whole solve, /usr/bin/time -v, the best of two runs
// with no compile running, 2026-12-06; bench/results/auto_method.md; scenes from
// bench/sphere_scene: an icosphere of n0 = 20 4^S facets, convex, in a cube room, or as a room
// around a box):
//   W      scene (n, n0, M)                           fast             dense
//   66     icosphere rho 0.9 (5120, 5120, 10)         13.3 s, 6.7 GB   2.3 s, 210 MB
//   45     icosphere rho 0.8 (5120, 5120, 8)          15.5 s, 4.6 GB   5.1 s, 210 MB
//   28     icosphere rho 0.5 (5120, 5120, 6)          3.5 s, 141 MB    2.3 s, 210 MB
//   28     sphere room around a box (5132, 5132, 6)   81 s, 166 MB     68 s, 213 MB
//   18.1   icosphere rho 0.9 (5120, 1280, 10)         2.2 s, 1.7 GB    2.3 s, 209 MB
//   12.35  icosphere rho 0.8 (5120, 1280, 8)          3.6 s, 1.2 GB    5.1 s, 210 MB
//   12.2   sphere room rho 0.9 (5168, 1292, 8)        14.0 s, 1.1 GB   13.2 s, 214 MB
//   9.7    icosphere rho 0.5 (1280, 320, 6)           0.10 s, 12 MB    0.15 s, 20 MB
//   7.7    icosphere rho 0.5 (5120, 1280, 6)          0.99 s, 53 MB    2.3 s, 209 MB
//   7.6    sphere room (5168, 1292, 6)                12.0 s, 59 MB    13.2 s, 214 MB
//   0.02   sphere in a cube room (5132, 5132, 6)      1.6 s, 21 MB     2.1 s, 216 MB
//   1.2    paper cube level 4 (3072, 12, 6)           0.14 s, 12 MB    0.62 s, 80 MB
//   0.31   paper cube level 5 (12288, 12, 6)          0.43 s, 19 MB    8.8 s, 1.16 GB
// With V both methods pay the line of sight per pair (the fast method per (point, cluster) pair,
// 1.5 to 4 times a dense pair's cost), which dominates both times: the times come close and the
// memory decides, as W says. The cube's levels keep the fast method (W <= 1.2 for n >= 3072).
// The two 5120-element rows at rho 0.8 ran while the machine was slower (dense 5.1 s, 2.3 s in
// the other rows).
//
// The exact near rule always: quadrature with mu = 2 deviates by 3e-5 (cube) to 1.4e-4 (prism),
// a third of the prism's margin at n = 5120 and growing relative to it with n; mu = 1 is never
// within 5% for n >= 192 (its dense deviation is 18-140% of the discretization error); mu = 3 was
// not reliably cheaper than the closed form in the measurements.
#include <panelrad/geometry/mesh.hpp>
#include <panelrad/operator/operator_factory.hpp>

#include <string>
#include <vector>

namespace panelrad {

/// What the rule needs to know about a discretized scene.
struct ProblemSize {
  geometry::Index n = 0;      ///< number of elements (collocation points)
  geometry::Index roots = 0;  ///< n0: input triangles, the roots of the cluster tree (n = n0 4^level)
  /// phi of the header: the fraction of pairs of distinct roots lying strictly in front of each
  /// other (front: the inner normal side of a validated mesh), sampled over 256 roots; 1 for a
  /// single root. Used on occluded scenes only.
  double facing = 1;
  double mesh_size = 0;   ///< h: longest element edge (section 3)
  double diameter = 0;    ///< diameter of the surface (bounding-box diagonal)
  /// lambda = log2(sqrt(2/3) diam / h): the paper cube's level for the same relative mesh size.
  double equivalent_level() const;
};

/// The size of `mesh` (validated: oriented, for the facing fraction) refined `level` times
/// (n = 4^level n0; midpoint subdivision halves every edge, so h = longest input edge / 2^level).
/// Throws std::invalid_argument for level < 0 or an empty mesh, ResourceError for a level whose
/// elements or clusters exceed the 32-bit index (geometry::level_size_problem).
ProblemSize problem_size(const geometry::TriangleMesh& mesh, int level);

/// max(1, A(rho_max)), A(rho) = rho / (1 - rho): the bound on the amplification of the
/// product's relative error into the solution's (header), never below its value 1 at the cube's
/// rho_max 0.5. rho_max is the largest reflectivity over all elements and channels; outside
/// [0, 1) (or NaN) it is a std::invalid_argument.
double conditioning_factor(double rho_max);

/// Largest reflectivity of the paper's cube (31): the default for callers that solve it.
inline constexpr double kPaperCubeMaxReflectivity = 0.5;

/// The rule above, at lambda_eff = lambda + log2 conditioning_factor(rho_max), for a scene whose
/// line of sight is `visibility` (the solver's, resolved: unoccluded or occluded). `margin` is the
/// accepted excess over the discretization error: delta* scales with it, so lambda_eff drops by
/// log2(margin / 0.05) (a looser margin takes the setting measured for a coarser level, whose
/// self-check against self_check_threshold(size, rho_max, margin) still decides); only margins
/// >= 0.05 were measured, and a smaller one, a size that is not finite and positive,
/// roots outside [1, n], rho_max outside [0, 1), or Visibility::automatic, is a
/// std::invalid_argument.
OperatorOptions choose_parameters(const ProblemSize& size, double margin = 0.05,
                                  double rho_max = kPaperCubeMaxReflectivity,
                                  Visibility visibility = Visibility::unoccluded);

/// W of the header: the fast method's estimated far-field work per row over the dense matrix's,
/// phi min(n, n0 + 20 / eta^2) (M + 1)(M + 2) / 2 / n (far pairs per row times Taylor terms over n
/// entries), phi = size.facing when occluded, 1 when unoccluded. std::invalid_argument for roots
/// outside [1, n], facing outside [0, 1], eta outside (0, 1), M < 0 or Visibility::automatic.
double fast_to_dense_work(const ProblemSize& size, double eta, int degree, Visibility visibility);

/// delta* of the header: the largest FastOperator::self_check relative product error accepted
/// for automatic parameters, margin * 0.025 (h/diam) / conditioning_factor(rho_max), so that the
/// bound delta A(rho_max) on the solution's relative deviation stays within `margin` (default
/// 5%) of the discretization error scale 0.025 h/diam. A check above it makes --accuracy auto
/// tighten. A margin below 0.05 or not finite is a std::invalid_argument.
double self_check_threshold(const ProblemSize& size, double rho_max = kPaperCubeMaxReflectivity,
                            double margin = 0.05);

/// One step stricter than `options` (for a self-check that failed): dense stays dense; the fast
/// method first raises M by one up to 6, then lowers eta along 0.5, 0.3, 0.2, 0.1 (keeping M).
/// Returns `options` unchanged when nothing is stricter (eta 0.1 and M >= 6).
OperatorOptions tighten_parameters(const OperatorOptions& options);

/// The settings to probe when the fast method's self-check fails on an occluded scene, where the
/// coverings are refined along the shadows whatever eta is, so that a smaller eta costs fewer
/// extra far pairs than on a convex surface and a rule of thumb cannot say which setting is the
/// cheapest: eta at options' value and the next two of 0.5, 0.3, 0.2, 0.1 below it, each with
/// M from options.degree - 2 to options.degree + 2 (within [1, 12]), and of those only the ones
/// stricter than options (a smaller eta, or the same eta and a larger M). In that order (eta
/// falling, M rising); empty for dense or when nothing is stricter.
std::vector<OperatorOptions> stricter_settings(const OperatorOptions& options);

/// "dense, exact near field" / "fast, exact near field, eta 0.3, M 4": for printing (compare
/// options with ==).
std::string describe_parameters(const OperatorOptions& options);

}  // namespace panelrad

#pragma once
// Automatic parameters (issue 5, point 2): the method, near rule, eta of (41) and Taylor degree M
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
// The rule, from bench/results/sweep.csv (bench/sweep --full: 2 cores, Intel Xeon, shared with
// other work, so timings are noisy; deviations are deterministic). Deviation of the fast method
// with the exact near field from the dense exact solution, cube (error: 3.77e-3 at n = 3072,
// 1.92e-3 at n = 12288, so the 5% margins are 1.9e-4 and 9.6e-5):
//     (eta, M)      n = 3072   n = 12288   total s (12288)   peak MB (12288)
//     (0.5, 4)      6.9e-4     6.9e-4      4.7               191     not within 5%
//     (0.5, 6)      5.5e-5     5.5e-5      5.9               299     within 5%
//     (0.3, 2)      3.6e-4     3.6e-4      5.0               223     not within 5%
//     (0.3, 4)      3.2e-5     3.2e-5      7.3               440     within 5%
//     (0.2, 2)      7.8e-5     8.5e-5      5.3               365     within 5%
//     (0.1, 2)      4.2e-6     4.7e-6      11.4              1218    within 5%
//     (0.4, 6)      1.3e-5     1.7e-5      0.9 (setup 0.52)  405     within 5% (prism 5120: 3.0e-5)
//     (0.4, 8)      1.8e-6     2.3e-6      2.0 (setup 1.45)  ~520    within 5% (prism 5120: 4.0e-6)
//   (the last two rows from a later, quieter run of bench/sweep --etas 0.5,0.4 --degrees 6,8)
//   dense exact: 3.0 s at n = 3072, 51 s at n = 12288 (1215 MB).
// The deviation of a fixed (eta, M) does not shrink with n (it is the Taylor remainder, ~eta^(M+1)
// relative to |u|), while the discretization error halves per level: each setting is good up to
// some level. The rule:
//   n <= 768: dense, exact near field (whole solve < 0.1 s, no far-field error at all);
//   lambda < 5.5: fast, exact, eta 0.5, M 6 (least memory among the settings within 5%; within 5%
//     at cube n = 768, 3072, 12288 and prism n = 1280 (2.2e-4 of 9.4e-4), 5120 (2.7e-4 of 4.9e-4));
//   lambda < 7.5: fast, exact, eta 0.4, M 6 (1.7e-5 <= 2.4e-5, the 5% margin at cube level 7);
//   otherwise:    fast, exact, eta 0.4, M 8 (2.3e-6: within 5% up to lambda ~ 10; extrapolated).
//   Large eta with a higher M beats a small eta: far pairs fall like 1/eta^2 (89, 143, 258, 510
//   per row at eta 0.5, 0.4, 0.3, 0.2 for n = 12288) while the terms grow like M^2/2, and the
//   stored coefficients of eta 0.1 would need ~20 GB at n = 196,608.
// The exact near rule always: quadrature with mu = 2 deviates by 3e-5 (cube) to 1.4e-4 (prism),
// a third of the prism's margin at n = 5120 and growing relative to it with n; mu = 1 is never
// within 5% for n >= 192 (its dense deviation is 18-140% of the discretization error); mu = 3 was
// not reliably cheaper than the closed form in the measurements.
#include <panelrad/geometry/mesh.hpp>
#include <panelrad/operator_factory.hpp>

#include <string>

namespace panelrad {

/// What the rule needs to know about a discretized scene.
struct ProblemSize {
  geometry::Index n = 0;  ///< number of elements (collocation points)
  double mesh_size = 0;   ///< h: longest element edge (section 3)
  double diameter = 0;    ///< diameter of the surface (bounding-box diagonal)
  /// lambda = log2(sqrt(2/3) diam / h): the paper cube's level for the same relative mesh size.
  double equivalent_level() const;
};

/// The size of `mesh` refined `level` times (n = 4^level n0; midpoint subdivision halves every
/// edge, so h = longest input edge / 2^level). Throws std::invalid_argument for level < 0 or an
/// empty mesh.
ProblemSize problem_size(const geometry::TriangleMesh& mesh, int level);

/// The measured rule above. `margin` is the accepted excess over the discretization error; only
/// margins >= 0.05 were measured (a looser margin gets the same, safe choice); a smaller one, or
/// a size that is not finite and positive, is a std::invalid_argument.
OperatorOptions choose_parameters(const ProblemSize& size, double margin = 0.05);

/// Largest FastOperator::self_check relative product error accepted for automatic parameters:
/// 8e-3 h/diam. Calibrated on the cube (bench/sweep + self_check): settings within 5% of the
/// discretization error measured <= 4e-3 h/diam ((0.5, 6): 5.1e-5 at n = 3072 and 12288;
/// (0.4, 6): 9.5e-6 at n = 49152), settings outside it >= 2.8e-2 h/diam ((0.5, 4): 3.6e-4 at
/// n = 12288, deviation 36% of the error). A check above it makes --accuracy auto tighten.
double self_check_threshold(const ProblemSize& size);

/// One step stricter than `options` (for a self-check that failed): dense stays dense; the fast
/// method first raises M by one up to 6, then lowers eta along 0.5, 0.3, 0.2, 0.1 (keeping M).
/// Returns `options` unchanged when nothing is stricter (eta 0.1 and M >= 6).
OperatorOptions tighten_parameters(const OperatorOptions& options);

/// "dense, exact near field" / "fast, exact near field, eta 0.3, M 4".
std::string describe_parameters(const OperatorOptions& options);

}  // namespace panelrad

// panelrad example: the paper's cube problem (Atkinson & Chien, section 3, example (31)) through the
// C++ API, checked against the paper's Table 1.
//
// The unit cube with rho = 0.5 on y = 0, 1; 0.4 on z = 0, 1; 0.3 on x = 0, 1 and the true solution
// u = x^2 + y^2 + z^2 (E manufactured as E = u - K u). The example discretizes it with centroid
// collocation at one level with one RadiositySolver, which picks the operator with the automatic
// rule (choose_parameters: dense up to n = 768, the fast method above, self-checked), solves to a
// tolerance tied to the discretization error; the example compares max_k |u(P_k) - u_n(P_k)|
// with the paper's value.
//   usage: paper_cube [level]   (default 3: n = 12 * 4^3 = 768; levels 0..5 have a paper value)
// Exit status 0 when the error is within 2% of Table 1, 1 otherwise (or on an error).
#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/radiosity_solver.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>

int main(int argc, char** argv) {
  using namespace panelrad;
  using Clock = std::chrono::steady_clock;
  const int level = argc > 1 ? std::atoi(argv[1]) : 3;
  // Paper, Table 1 (centroid method, max error (51) at the centroids), n = 12 * 4^level.
  constexpr double kPaperError[] = {7.61e-2, 2.58e-2, 1.37e-2, 7.28e-3, 3.77e-3, 1.92e-3};
  constexpr int kPaperLevels = static_cast<int>(sizeof kPaperError / sizeof kPaperError[0]);
  if (level < 0 || level > 8) {
    std::fprintf(stderr, "usage: paper_cube [level]   (0 <= level <= 8; Table 1 has levels 0..5)\n");
    return 2;
  }
  try {
    const auto start = Clock::now();
    // 1. The scene: the paper's cube with rho per facet and E manufactured from the true u.
    const Scene scene = make_paper_cube_scene();
    // 2. The solver object: the level-`level` refinement with collocation at the centroids (22)
    //    (rho, E and the true u evaluated there), the operator K_n (33) with rho in its rows, its
    //    parameters by the automatic rule, and a tolerance tied to the O(h) discretization error.
    SolveOptions options;
    options.level = level;
    options.fold_reflectivity = true;
    const RadiositySolver solver(scene, options);
    const Collocation& collocation = solver.collocation();
    const double h = solver.info().mesh_size, diam = solver.info().diameter;
    const double setup_s = solver.info().operator_s;
    // 3. Solve (I - K_n) u_n = E_n (32); result.u[i] is u_n at collocation.collocation_point(i).
    const ChannelSolve result = solver.solve(0);
    if (!result.converged()) throw SolverError(result.message);
    const double error = collocation.max_error(result.u);
    const double total_s = std::chrono::duration<double>(Clock::now() - start).count();

    std::printf("paper cube, level %d: n = %d, h/diam = %.4f\n", level, static_cast<int>(collocation.size()),
                h / diam);
    std::printf("operator: %s (setup %.2f s, %.1f MB)\n", describe_parameters(solver.parameters()).c_str(),
                setup_s, static_cast<double>(solver.operator_bytes()) / 1e6);
    std::printf("solver: %s, %d products, Neumann ratio %.4f, %.2f s\n",
                result.solver.c_str(), result.iterations,
                result.convergence_ratio, result.seconds);
    std::printf("max_k |u(P_k) - u_n(P_k)| = %.4e   (total %.2f s, E manufacturing %.2f s of it)\n", error,
                total_s, collocation.emissivity_seconds());
    if (level >= kPaperLevels) {
      std::printf("no paper value for level %d (Table 1 stops at n = 12288): nothing to compare\n", level);
      return std::isfinite(error) ? 0 : 1;
    }
    const double paper = kPaperError[level];
    const double deviation = std::abs(error - paper) / paper;
    const bool pass = deviation <= 0.02;
    std::printf("paper (Table 1): %.2e; relative deviation %.2f%% (accepted <= 2%%): %s\n", paper, 100 * deviation,
                pass ? "PASS" : "FAIL");
    return pass ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "paper_cube: %s\n", e.what());
    return 1;
  }
}

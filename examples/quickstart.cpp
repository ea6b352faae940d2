// panelrad quick start: a scene from the C++ API, solved with the fast method, with a known answer.
//
// A hexagonal prism with reflectivity 0.6 on its sides and 0.3 on its caps, emitting
// E = c (1 - rho): on a closed convex surface the radiosity is then exactly u = c everywhere
// (the rows of K sum to rho, paper Lemma 1), so the printed error is the fast method's own.
//   usage: quickstart [level]   (default 4: n = 20 * 4^4 = 5120 elements)
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/validation.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/radiosity_solver.hpp>

#include <cstdio>
#include <cstdlib>
#include <exception>

int main(int argc, char** argv) {
  using namespace panelrad;
  const int level = argc > 1 ? std::atoi(argv[1]) : 4;
  try {
    // 1. Geometry: a built-in prism (or geometry::read_mesh("my.off")), validated exactly.
    geometry::TriangleMesh mesh = geometry::make_prism(6, /*circumradius=*/1.0, /*height=*/2.0);
    const geometry::ValidationReport report = geometry::validate_closed_convex(mesh);
    if (!report.valid) {
      std::fprintf(stderr, "invalid mesh: %s\n", report.message.c_str());
      return 1;
    }
    // 2. Scene data per facet: prism facets are the 6 sides, then bottom and top caps.
    Scene scene(std::move(mesh));
    std::vector<double> rho(static_cast<std::size_t>(scene.num_facets()), 0.6), emission;
    rho[6] = rho[7] = 0.3;
    const double c = 2.0;
    for (double r : rho) emission.push_back(c * (1 - r));
    scene.set_reflectivity(rho);
    scene.set_emissivity(emission);
    // 3. The solver object: discretize (centroid collocation, n = 4^level n0) and build the fast
    //    operator (eta 0.2, M 2, exact near field), with rho in its rows.
    RadiositySolverOptions options;
    options.level = level;
    options.method = OperatorMethod::fast;
    options.fold_reflectivity = true;
    options.solver.tolerance = SolverOptions{}.tolerance;  // 1e-10, far below the far field's error
    const RadiositySolver solver(scene, options);
    // 4. Solve (I - K) u = E; the automatic solver says what it picked.
    const ChannelSolve result = solver.solve(0);
    if (!result.converged()) throw SolverError(result.message);
    // 5. Read the solution: u_i at collocation point P_i.
    double worst = 0;
    for (Index i = 0; i < solver.n(); ++i) worst = std::max(worst, std::abs(result.u[i] - c));
    std::printf("n = %d, %s, %d products, max |u - %g| = %.2e, fast operator %.1f MB\n", static_cast<int>(solver.n()),
                result.solver.c_str(), result.iterations, c, worst, static_cast<double>(solver.operator_bytes()) / 1e6);
    // The only error is the far field's Taylor truncation (eta 0.2, M 2: ~5e-5 relative per
    // product, amplified by at most 1/(1 - max rho) = 2.5): accept 1e-3 relative.
    return worst < 1e-3 * c ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "quickstart: %s\n", e.what());
    return 1;
  }
}

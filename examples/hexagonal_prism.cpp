// panelrad example: a scene loaded from a mesh file, with a manufactured solution, solved on a
// sequence of levels to show the centroid method's O(h) convergence (paper Theorem 5, Table 1).
//
// Loads examples/meshes/hexagonal_prism.off (a right prism over a regular hexagon, circumradius 1,
// height 1) with load_scene (geometry only), sets rho = 0.6 on the six sides and 0.3 on the two caps, and
// manufactures E = u - K u from the known solution u(Q) = 1 + 0.5 x - 0.25 y + 0.75 z^2. It then
// solves on levels 1, 2, 3 (n = 20 * 4^level), one RadiositySolver per level with the automatic
// parameters (choose_parameters at the scene's rho_max 0.6, self-checked), and prints max_k |u(P_k) - u_n(P_k)| per level and the ratio to the previous level.
//   usage: hexagonal_prism [mesh.off [max_level]]
//     mesh.off   default: the shipped examples/meshes/hexagonal_prism.off (PANELRAD_EXAMPLE_MESHES)
//     max_level  finest level, >= 2 (default 3)
// Exit status 0 when the error falls by a factor >= 1.6 per level, 1 otherwise (or on an error).
//
// Measured (Release, g++ 12, 2 cores, 2026-12-01): errors 3.359e-2 (n = 80, dense), 1.586e-2
// (n = 320, dense), 7.707e-3 (n = 1280, fast eta 0.4 M 6): ratios 2.12, 2.06 -- the O(h) halving
// per level of Table 1 (ratios ~1.9). The run to level 3 takes about 0.4 s.
// 1.6 leaves room for the fast method's small far-field error without accepting a method that
// does not converge at O(h).
#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/io/scene_file.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/radiosity_solver.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#ifndef PANELRAD_EXAMPLE_MESHES
#define PANELRAD_EXAMPLE_MESHES "examples/meshes"
#endif

int main(int argc, char** argv) {
  using namespace panelrad;
  using Clock = std::chrono::steady_clock;
  const std::string path = argc > 1 ? argv[1] : std::string(PANELRAD_EXAMPLE_MESHES) + "/hexagonal_prism.off";
  const int max_level = argc > 2 ? std::atoi(argv[2]) : 3;
  if (max_level < 2 || max_level > 7) {
    std::fprintf(stderr, "usage: hexagonal_prism [mesh.off [max_level]]   (2 <= max_level <= 7)\n");
    return 2;
  }
  try {
    // 1. Load and validate the mesh (closed, convex, exact predicates); notes say what was repaired.
    LoadOptions geometry_only;
    geometry_only.geometry_only = true;  // rho and E are set below
    Scene scene = load_scene(path, geometry_only);
    for (const std::string& note : scene.notes()) std::printf("note: %s\n", note.c_str());
    // 2. rho per facet. Facets are the OFF file's faces in order: 0-5 the rectangular sides, 6 the
    //    bottom and 7 the top hexagon. Check that numbering: caps have inner normal +-z.
    if (scene.num_facets() != 8) {
      std::fprintf(stderr, "%s: expected 8 facets (6 sides, 2 caps), got %d\n", path.c_str(),
                   static_cast<int>(scene.num_facets()));
      return 1;
    }
    const geometry::TriangleMesh& mesh = scene.mesh();
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      const bool cap = mesh.facet_of_triangle[t] >= 6;
      const double nz = std::abs(scene.triangle_inner_normal(static_cast<Index>(t)).z());
      if (cap ? nz < 1 - 1e-9 : nz > 1e-9) {
        std::fprintf(stderr, "%s: facet %d is not a %s\n", path.c_str(), static_cast<int>(mesh.facet_of_triangle[t]),
                     cap ? "cap" : "side");
        return 1;
      }
    }
    std::vector<double> rho(8, 0.6);  // sides
    rho[6] = rho[7] = 0.3;            // caps
    scene.set_reflectivity(rho);
    // 3. A known solution: E = u - K u is computed by integrating over the exact surface.
    scene.set_manufactured_solution(
        [](const Vec3& Q, Index /*facet*/) { return 1 + 0.5 * Q.x() - 0.25 * Q.y() + 0.75 * Q.z() * Q.z(); });

    // 4. Solve on each level with the automatic parameters and a tolerance tied to the
    //    discretization error; read the error at the collocation points.
    std::printf("%6s %8s %-40s %11s %7s %8s\n", "level", "n", "operator", "max error", "ratio", "time s");
    std::vector<double> errors;
    bool pass = true;
    for (int level = 1; level <= max_level; ++level) {
      const auto start = Clock::now();
      SolveOptions options;  // automatic parameters, tolerance tied to the discretization
      options.level = level;
      options.fold_reflectivity = true;
      const RadiositySolver solver(scene, options);
      const ChannelSolve result = solver.solve(0);
      if (!result.converged()) throw SolverError(result.message);
      const double error = solver.collocation().max_error(result.u);  // max_k |u(P_k) - result.u[k]|
      const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
      char ratio[32] = "";
      if (!errors.empty()) {
        const double r = errors.back() / error;
        std::snprintf(ratio, sizeof ratio, "%.2f", r);
        if (!(r >= 1.6)) pass = false;  // also fails on NaN
      } else if (!std::isfinite(error)) {
        pass = false;
      }
      errors.push_back(error);
      std::printf("%6d %8d %-40s %11.4e %7s %8.2f\n", level, static_cast<int>(solver.n()),
                  describe_parameters(solver.parameters()).c_str(), error, ratio, seconds);
    }
    std::printf("error ratio per level >= 1.6 (O(h) convergence): %s\n", pass ? "PASS" : "FAIL");
    return pass ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "hexagonal_prism: %s\n", e.what());
    return 1;
  }
}

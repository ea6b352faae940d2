// panelrad example: a colour (multi-channel) scene built in code, solved with solve_scene,
// written with the output API (CSV, PLY, VTK, PNG), with a known answer.
//
// A triangular prism (circumradius 1, height 2) with a different reflectivity on every facet in
// each of three channels R, G, B, emitting E = c_ch (1 - rho) with c = (1.0, 0.5, 2.0). On a
// closed convex surface the rows of K sum to rho (paper Lemma 1), so the exact solution is
// u = c_ch everywhere in every channel, whatever rho is: the printed error is the solver's own.
// One discretization and one operator H serve all channels (K_c = diag(rho_c) H, paper (33)).
//   usage: triangular_prism [level [prefix]]
//     level   refinement level (default 3: n = 8 * 4^3 = 512 elements)
//     prefix  output files PREFIX.csv, .ply, .vtk, .png (default "triangular_prism_radiosity" in
//             the current directory)
// Exit status 0 when max |u - c_ch| <= 1e-3 c_ch in every channel, 1 otherwise (or on an error).
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/validation.hpp>
#include <panelrad/io/scene_file.hpp>
#include <panelrad/io/scene_output.hpp>
#include <panelrad/solve/scene_solver.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  using namespace panelrad;
  const int level = argc > 1 ? std::atoi(argv[1]) : 3;
  const std::string prefix = argc > 2 ? argv[2] : "triangular_prism_radiosity";
  try {
    // 1. Geometry: a built-in prism over a triangle (or geometry::read_mesh("my.off")), validated
    //    exactly (closed, convex, non-degenerate) and oriented outward.
    geometry::TriangleMesh mesh = geometry::make_prism(3, /*circumradius=*/1.0, /*height=*/2.0);
    const geometry::ValidationReport report = geometry::validate_closed_convex(mesh);
    if (!report.valid) {
      std::fprintf(stderr, "invalid mesh: %s\n", report.message.c_str());
      return 1;
    }
    // 2. Per-facet data in each channel. Prism facets: the 3 sides, then bottom and top caps.
    Scene scene(std::move(mesh), {"R", "G", "B"});
    const std::vector<std::vector<double>> rho = {
        {0.80, 0.60, 0.40, 0.20, 0.85},  // R
        {0.10, 0.50, 0.70, 0.30, 0.00},  // G
        {0.45, 0.25, 0.65, 0.85, 0.55},  // B
    };
    const std::vector<double> c = {1.0, 0.5, 2.0};  // the exact radiosity per channel
    for (std::size_t ch = 0; ch < scene.num_channels(); ++ch) {
      std::vector<double> emission;
      for (double r : rho[ch]) emission.push_back(c[ch] * (1 - r));
      scene.set_reflectivity(rho[ch], ch);  // one value per facet, checked (0 <= rho < 1)
      scene.set_emissivity(emission, ch);
    }
    // 3. Solve: subdivision, one operator for all channels (automatic method), each channel solved
    //    to a tolerance tied to the discretization error, and the energy balance checked.
    SolveOptions options;
    options.level = level;
    const SceneSolution solution = solve_scene(scene, options);
    solution.require_converged();
    std::printf("triangular prism, level %d: n = %d, %s\n", solution.level, static_cast<int>(solution.n),
                solution.method.c_str());
    std::printf("times: subdivision %.3f s, operator %.3f s, solve %.3f s, total %.3f s\n", solution.subdivision_s,
                solution.operator_s, solution.solve_s, solution.total_s);
    // 4. Read the solution: channels[ch].radiosity[i] is u at element i's centroid
    //    (solution.field.centroid[i]), on input facet solution.field.facet[i].
    bool pass = true;
    for (std::size_t ch = 0; ch < solution.channels.size(); ++ch) {
      const ChannelSolution& s = solution.channels[ch];
      double worst = 0;
      for (Eigen::Index i = 0; i < s.radiosity.size(); ++i) worst = std::max(worst, std::abs(s.radiosity[i] - c[ch]));
      if (s.radiosity.size() != static_cast<Eigen::Index>(solution.n) || !std::isfinite(worst)) worst = std::numeric_limits<double>::infinity();
      const bool ok = worst <= 1e-3 * c[ch];
      pass = pass && ok;
      std::printf("channel %s: max |u - %g| = %.2e (%.1e relative), %s, %d products, energy mismatch %.2e "
                  "(expected <= %.2e): %s\n",
                  s.name.c_str(), c[ch], worst, worst / c[ch], s.solver.c_str(), s.iterations, s.energy_mismatch,
                  solution.expected_energy_mismatch, ok ? "ok" : "FAIL");
    }
    for (const std::string& w : solution.warnings) std::printf("warning: %s\n", w.c_str());
    // 5. Outputs: per-element CSV, PLY with face colours, VTK for ParaView, and a PNG picture.
    write_radiosity_csv(prefix + ".csv", solution.field);
    write_radiosity_ply(prefix + ".ply", solution.field);
    write_radiosity_vtk(prefix + ".vtk", solution.field);
    write_radiosity_png(prefix + ".png", solution.field);
    std::printf("wrote %s.csv, .ply, .vtk, .png\n", prefix.c_str());
    std::printf("%s\n", pass ? "PASS" : "FAIL");
    return pass ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "triangular_prism: %s\n", e.what());
    return 1;
  }
}

#include <panelrad/panelrad.hpp>
#include <cstdio>

int main() {
  const panelrad::Scene scene = panelrad::load_scene("examples/scenes/cornell_box.obj");
  panelrad::SolveOptions options;
  options.level = 3;  // n = 4^3 n0 elements
  const panelrad::SceneSolution solution = panelrad::solve_scene(scene, options);
  solution.require_converged();
  solution.require_energy_balance();
  panelrad::write_outputs(solution, "cornell", {"csv", "png"});
  std::printf("n = %lld, %s\n", static_cast<long long>(solution.n), solution.method.c_str());
}

// An outside program using the installed panelrad package: the umbrella header, the solver
// (panelrad::panelrad) and the file formats (panelrad::io).
#include <panelrad/panelrad.hpp>

#include <iostream>

int main() {
  std::cout << "panelrad " << panelrad::version() << "\n";
  try {
    (void)panelrad::load_scene("/nonexistent/scene.off");
    return 1;  // a missing file must be refused
  } catch (const panelrad::Error& e) {  // the root of the hierarchy catches a SceneFileError
    std::cout << "refused: " << e.what() << "\n";
  }
  const panelrad::Scene cube = panelrad::load_scene("builtin:cube");  // rho 0, E 1: u = E = 1
  panelrad::SolveOptions options;
  options.level = 1;
  const panelrad::SceneSolution solution = panelrad::solve_scene(cube, options);
  solution.require_converged();
  const std::vector<std::string> paths = panelrad::output_paths("cube", {"csv", "png"});  // from panelrad::io
  std::cout << "n = " << solution.n << ", u[0] = " << solution.channels[0].radiosity[0] << ", " << paths.size()
            << " outputs\n";
  return solution.n == 48 && solution.channels[0].radiosity[0] == 1.0 && paths.size() == 2 ? 0 : 1;
}

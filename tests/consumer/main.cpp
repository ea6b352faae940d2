// An outside program using the installed panelrad package: the umbrella header, the solver
// (panelrad::panelrad) and the file formats (panelrad::io).
#include <panelrad/panelrad.hpp>

#include <iostream>

int main() {
  std::cout << "panelrad " << panelrad::version() << "\n";
  panelrad::check_channel_names({"R", "G", "B"});  // from panelrad::io
  try {
    (void)panelrad::geometry::read_mesh("/nonexistent/scene.off");
    return 1;  // a missing file must be refused
  } catch (const panelrad::Error& e) {  // the root of the hierarchy catches a MeshError
    std::cout << "refused: " << e.what() << "\n";
  }
  return panelrad::version().empty() ? 1 : 0;
}

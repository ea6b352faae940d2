// panelrad check: validate a mesh file or a built-in scene (to be completed by the geometry work).
#include "commands.hpp"

#include <iostream>

namespace panelrad::cli {
int run_check(int, char**) {
  std::cerr << "panelrad check: not built yet\n";
  return 1;
}
}  // namespace panelrad::cli

// panelrad command-line program: dispatches sub-commands.
#include "commands.hpp"

#include <panelrad/support/version.hpp>

#include <cstring>
#include <iostream>
#include <string>

namespace {
void usage(std::ostream& os) {
  os << "usage: panelrad <command> [options]\n"
        "commands:\n"
        "  check MESH | check --builtin cube|prism:K|tetrahedron|octahedron\n"
        "      validate a closed convex polyhedral mesh (OFF or OBJ)\n"
        "  cube [options]   the paper's cube example (Table 1; --help for options)\n"
        "  solve SCENE [options]   solve an OBJ+MTL or OFF+JSON scene, write CSV/PLY/VTK/PNG (--help)\n"
        "  version\n";
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    usage(std::cerr);
    return 2;
  }
  const std::string cmd = argv[1];
  try {
    if (cmd == "check") return panelrad::cli::run_check(argc - 1, argv + 1);
    if (cmd == "cube") return panelrad::cli::run_cube(argc - 1, argv + 1);
    if (cmd == "solve") return panelrad::cli::run_solve(argc - 1, argv + 1);
    if (cmd == "version" || cmd == "--version") {
      std::cout << "panelrad " << panelrad::version() << "\n";
      return 0;
    }
    if (cmd == "help" || cmd == "--help" || cmd == "-h") {
      usage(std::cout);
      return 0;
    }
  } catch (const std::exception& e) {
    std::cerr << "panelrad " << cmd << ": error: " << e.what() << "\n";
    return 1;
  }
  std::cerr << "panelrad: unknown command '" << cmd << "'\n";
  usage(std::cerr);
  return 2;
}

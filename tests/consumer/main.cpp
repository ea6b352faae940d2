// An outside program using the installed panelrad package.
#include <panelrad/support/version.hpp>

#include <iostream>

int main() {
  std::cout << "panelrad " << panelrad::version() << "\n";
  return panelrad::version().empty() ? 1 : 0;
}

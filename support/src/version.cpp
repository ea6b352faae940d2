#include <panelrad/support/version.hpp>

namespace panelrad {
std::string version() { return "0.1.0"; }
}  // namespace panelrad

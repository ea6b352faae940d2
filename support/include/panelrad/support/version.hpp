#pragma once
#include <string>

namespace panelrad {
/// Library version "MAJOR.MINOR.PATCH".
std::string version();
}  // namespace panelrad

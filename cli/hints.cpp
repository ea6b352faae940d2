#include "hints.hpp"

#include <panelrad/scene/errors.hpp>

namespace panelrad::cli {

namespace {
bool says(const std::exception& error, const char* words) {
  return std::string(error.what()).find(words) != std::string::npos;
}
}  // namespace

std::string hint_for(const std::exception& error) {
  if (dynamic_cast<const ResourceError*>(&error)) {
    if (says(error, "the fast method")) return "hint: --method fast uses the fast operator (section 4); or fewer --levels";
    if (says(error, "Neumann or GMRES")) return "hint: --solver neumann or --solver gmres needs no matrix factorization";
    if (says(error, "level")) return "hint: fewer --levels";
  }
  if (dynamic_cast<const SolverError*>(&error) && says(error, "GMRES"))
    return "hint: --solver gmres";
  return "";
}

}  // namespace panelrad::cli

#include "options.hpp"

#include <cmath>
#include <cstdlib>

namespace panelrad::cli {

int parse_int(const std::string& option, const std::string& value, int lo, int hi) {
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(value.c_str(), &end, 10);
  if (value.empty() || *end != '\0' || errno != 0 || v < lo || v > hi)
    throw UsageError(option + " needs an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                     "], got '" + value + "'");
  return static_cast<int>(v);
}

double parse_double(const std::string& option, const std::string& value, double lo, double hi) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || !std::isfinite(v) || v < lo || v > hi)
    throw UsageError(option + " needs a number in [" + std::to_string(lo) + ", " + std::to_string(hi) +
                     "], got '" + value + "'");
  return v;
}

}  // namespace panelrad::cli

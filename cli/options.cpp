#include "options.hpp"

#include <panelrad/quadrature/triangle_rules.hpp>
#include <panelrad/support/resources.hpp>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace panelrad::cli {

namespace {
// Shortest round-trip-free form of a bound: 1e-15, 0.5, 0.001 (not std::to_string's fixed
// "0.000000", which hides small bounds).
std::string show_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}
}  // namespace

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
    throw UsageError(option + " needs a number in [" + show_number(lo) + ", " + show_number(hi) + "], got '" +
                     value + "'");
  return v;
}

int parse_threads(const std::string& option, const std::string& value) {
  const int limit = max_useful_threads();
  const int t = parse_int(option, value, 0, 1 << 20);
  if (t > limit)
    throw UsageError(option + " " + value + " is more than the " + std::to_string(limit) +
                     " threads that can help here (4 per processor available to this process, and at most "
                     "the OpenMP thread limit); 0 uses the default, " + std::to_string(max_threads()));
  return t;
}

void check_quadrature_rule(const std::string& option, const std::string& value) {
  try {
    (void)quadrature::rule_by_name(value);  // the parser the near-field integrator uses
  } catch (const std::invalid_argument& e) {
    throw UsageError(option + ": " + e.what());
  }
}

}  // namespace panelrad::cli

// The checks of a scene's rho and E (channel_scene.hpp).
#include <panelrad/scene/channel_scene.hpp>

#include <cfloat>
#include <charconv>
#include <cmath>
#include <string>

namespace panelrad {
namespace {

/// Shortest round-trip text of a number (inf, nan as such).
std::string number(double v) {
  char buf[40];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return ec == std::errc() ? std::string(buf, ptr) : std::to_string(v);
}

}  // namespace

std::string reflectivity_problem(double rho) {
  if (!std::isfinite(rho)) return "is not a finite number";
  if (!(rho >= 0.0 && rho < 1.0)) return "is outside [0, 1) (paper (7): 0 <= rho < 1)";
  if (rho > 0.0 && rho < DBL_MIN)
    return "is subnormal (below DBL_MIN = " + number(DBL_MIN) +
           "): it has lost precision and makes the solve compute with subnormal numbers; write 0";
  return "";
}

std::string emission_problem(double e) {
  if (!std::isfinite(e)) return "is not a finite number";
  if (e < 0.0) return "is negative (emission E must be >= 0)";
  if (e > 0.0 && e < DBL_MIN)
    return "is subnormal (below DBL_MIN = " + number(DBL_MIN) +
           "): it has lost precision already and the solve would lose the rest; scale all E up (the radiosity "
           "equation is linear in E) or write 0";
  if (e > 0.0 && e < kMinPositiveEmission)
    return "is below " + number(kMinPositiveEmission) +
           ", the smallest non-zero E accepted (products with areas and squared norms in the solve would "
           "underflow); scale all E up (the radiosity equation is linear in E) or write 0";
  if (e > kMaxEmission)
    return "is above " + number(kMaxEmission) +
           ", the largest E accepted (the radiosity u <= E / (1 - rho) and its squares and products with areas "
           "in the solve would overflow); scale all E down (the radiosity equation is linear in E)";
  return "";
}

}  // namespace panelrad

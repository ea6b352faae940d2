// The checks of the options of a solve, in one place: SolverOptions (the iteration (32)-(36) and
// GMRES) and SolveOptions (the level, the automatic parameters' accuracy, the operator's eta, M
// and mu of section 4). Each refusal names the option as the C++ field and the Python keyword
// call it, and the value given.
#include <panelrad/solve/radiosity_solver.hpp>
#include <panelrad/solve/solvers.hpp>

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace panelrad {

namespace {

std::string shown(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

[[noreturn]] void refuse(const std::string& option, const std::string& rule, const std::string& value) {
  throw std::invalid_argument(option + ": " + rule + ", got " + value);
}

// max_iterations and gmres_restart, shared by both validations.
void check_iteration_counts(const SolverOptions& o) {
  if (o.max_iterations < 1) refuse("max_iterations", "must be >= 1 (products with K_n)", std::to_string(o.max_iterations));
  if (o.gmres_restart < 1)
    refuse("gmres_restart", "must be >= 1 (the Krylov vectors kept between restarts)", std::to_string(o.gmres_restart));
}

}  // namespace

void SolverOptions::validate() const {
  // inf would stop at once, reporting convergence; 0 or less could never be reached.
  if (!(std::isfinite(tolerance) && tolerance > 0))
    refuse("tolerance", "must be finite and > 0 (the relative error at which the iteration stops)", shown(tolerance));
  check_iteration_counts(*this);
}

void SolveOptions::validate() const {
  if (level < -1)
    refuse("level", "must be >= 0, or -1 for the largest level with n <= max_elements", std::to_string(level));
  if (max_elements < 1) refuse("max_elements", "must be >= 1", std::to_string(max_elements));
  if (!(accuracy >= 0.05 && accuracy <= 1e6))
    refuse("accuracy",
           "the far field's error allowed as a fraction of the discretization error, in [0.05, 1e6] (0.05 is the "
           "tightest measured)",
           shown(accuracy));
  if (!(op.eta > 0 && op.eta < 1)) refuse("eta", "the admissibility (41) must be in (0, 1)", shown(op.eta));
  if (op.degree < 0 || op.degree > 12) refuse("degree", "the Taylor degree M (44) must be in 0..12", std::to_string(op.degree));
  if (op.near.mu < 0 || op.near.mu > 8)
    refuse("mu", "the near field's subdivision levels (section 4.2) must be in 0..8", std::to_string(op.near.mu));
  if (!(std::isfinite(solver.tolerance) && solver.tolerance >= 0))
    refuse("tolerance", "must be finite and > 0, or 0 to tie it to the discretization error", shown(solver.tolerance));
  check_iteration_counts(solver);
}

}  // namespace panelrad

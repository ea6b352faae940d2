#include "options.hpp"

#include "interrupt.hpp"

#include <panelrad/support/resources.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace panelrad::python {

SolverArguments solver_arguments(std::optional<int> level, long max_elements, double accuracy, std::string method,
                                 std::optional<double> eta, std::optional<int> degree, std::optional<std::string> near,
                                 std::optional<int> mu, std::string visibility, std::string solver,
                                 std::optional<double> tolerance, int max_iterations, std::optional<int> threads,
                                 py::object progress) {
  return SolverArguments{level,          max_elements,   accuracy, std::move(method), eta,     degree,
                         std::move(near), mu,            std::move(visibility), std::move(solver), tolerance,
                         max_iterations, threads,        std::move(progress)};
}

SolveOptions make_solve_options(const SolverArguments& a) {
  SolveOptions o;
  if (a.level) {
    if (*a.level < 0) throw std::invalid_argument("level: must be >= 0, got " + std::to_string(*a.level));
    o.level = *a.level;
  }
  if (a.max_elements < 1 || a.max_elements > std::numeric_limits<geometry::Index>::max())
    throw std::invalid_argument("max_elements: must be in [1, 2^31), got " + std::to_string(a.max_elements));
  o.max_elements = static_cast<geometry::Index>(a.max_elements);
  if (!(a.accuracy >= 0.05 && a.accuracy <= 1e6))
    throw std::invalid_argument("accuracy: the far field's error allowed as a fraction of the discretization error, "
                                "in [0.05, 1e6] (0.05 is the tightest measured), got " + std::to_string(a.accuracy));
  o.accuracy = a.accuracy;
  o.op.method = parse_operator_method(a.method);
  const bool manual = a.eta || a.degree || a.near || a.mu;
  if (manual && o.op.method == OperatorMethod::automatic)
    throw std::invalid_argument("eta, degree, near and mu need method=\"dense\" or \"fast\" (\"auto\" chooses them)");
  if (a.eta) {
    if (!(*a.eta > 0 && *a.eta < 1)) throw std::invalid_argument("eta: must be in (0, 1), got " + std::to_string(*a.eta));
    o.op.eta = *a.eta;
  }
  if (a.degree) {
    if (*a.degree < 0 || *a.degree > 12)
      throw std::invalid_argument("degree: must be in 0..12, got " + std::to_string(*a.degree));
    o.op.degree = *a.degree;
  }
  if (a.near) o.op.near.rule = parse_near_rule(*a.near);
  if (a.mu) {
    if (*a.mu < 0) throw std::invalid_argument("mu: must be >= 0, got " + std::to_string(*a.mu));
    o.op.near.mu = *a.mu;
  }
  o.visibility = parse_visibility(a.visibility);
  o.solver.kind = parse_solver(a.solver);
  if (a.tolerance) {
    if (!(std::isfinite(*a.tolerance) && *a.tolerance > 0))
      throw std::invalid_argument("tolerance: must be finite and > 0 (None ties it to the discretization error)");
    o.solver.tolerance = *a.tolerance;
  }
  if (a.max_iterations < 1)
    throw std::invalid_argument("max_iterations: must be >= 1, got " + std::to_string(a.max_iterations));
  o.solver.max_iterations = a.max_iterations;
  if (a.threads) {
    if (*a.threads < 0 || *a.threads > max_useful_threads())
      throw std::invalid_argument("threads: must be in 0.." + std::to_string(max_useful_threads()) + ", got " +
                                  std::to_string(*a.threads));
    set_threads(*a.threads);
  }
  if (!a.progress.is_none() && !PyCallable_Check(a.progress.ptr()))
    throw py::type_error("progress: expected a callable taking one str, or None");
  o.progress = interruptible_progress(a.progress);
  return o;
}

}  // namespace panelrad::python

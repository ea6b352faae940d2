#include "options.hpp"

#include "interrupt.hpp"

#include <panelrad/support/resources.hpp>

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
  // The values go into SolveOptions as given and are checked by the library's own rule
  // (SolveOptions::validate, the same as for C++ callers); only what is Python's is checked here:
  // None, a number beyond the C++ type, keywords that need each other, threads, progress.
  SolveOptions o;
  if (a.level) o.level = *a.level;  // None: -1, the largest level with n <= max_elements
  if (a.max_elements > std::numeric_limits<geometry::Index>::max() ||
      a.max_elements < std::numeric_limits<geometry::Index>::min())  // beyond the C++ type
    throw std::invalid_argument("max_elements: must be in [1, 2^31), got " + std::to_string(a.max_elements));
  o.max_elements = static_cast<geometry::Index>(a.max_elements);
  o.accuracy = a.accuracy;
  o.op.method = parse_operator_method(a.method);
  const bool manual = a.eta || a.degree || a.near || a.mu;
  if (manual && o.op.method == OperatorMethod::automatic)
    throw std::invalid_argument("eta, degree, near and mu need method=\"dense\" or \"fast\" (\"auto\" chooses them)");
  if (a.eta) o.op.eta = *a.eta;
  if (a.degree) o.op.degree = *a.degree;
  if (a.near) o.op.near.rule = parse_near_rule(*a.near);
  if (a.mu) o.op.near.mu = *a.mu;
  o.visibility = parse_visibility(a.visibility);
  o.solver.kind = parse_solver(a.solver);
  if (a.tolerance) {  // None: 0 in C++, tied to the discretization error
    if (*a.tolerance == 0)
      throw std::invalid_argument("tolerance: must be finite and > 0, got 0 (None ties it to the discretization error)");
    o.solver.tolerance = *a.tolerance;
  }
  o.solver.max_iterations = a.max_iterations;
  o.validate();  // before the process-wide thread count changes
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

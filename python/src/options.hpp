#pragma once
// The keyword arguments of panelrad.Solver and panelrad.solve_scene, as one SolveOptions.
#include <panelrad/solve/radiosity_solver.hpp>

#include <pybind11/pybind11.h>

#include <optional>
#include <string>

namespace panelrad::python {

namespace py = pybind11;

struct SolverArguments {
  std::optional<int> level;           ///< None: the largest with n <= max_elements (-1)
  long max_elements = 20000;
  double accuracy = 0.05;             ///< auto: the far field's error / the discretization error
  std::string method = "auto";        ///< auto | dense | fast
  std::optional<double> eta;          ///< fast: admissibility (41)
  std::optional<int> degree;          ///< fast: Taylor degree M (44)
  std::optional<std::string> near;    ///< exact | quadrature
  std::optional<int> mu;              ///< quadrature near rule: subdivision levels (section 4.2)
  std::string visibility = "auto";    ///< auto | occluded
  std::string solver = "auto";        ///< auto | neumann | gmres | lu
  std::optional<double> tolerance;    ///< None: tied to the discretization error (0)
  int max_iterations = 1000;
  std::optional<int> threads;         ///< None: keep the process's setting
  py::object progress = py::none();   ///< callable(str) or None
};

/// SolveOptions from the arguments, checked by SolveOptions::validate (ArgumentError naming the
/// argument and its value); sets the thread count when given (process-wide), once they pass. The
/// progress callback checks Python's signals.
SolveOptions make_solve_options(const SolverArguments& a);

/// The keyword arguments shared by Solver and solve_scene, declared once.
#define PANELRAD_SOLVER_KWARGS                                                                                  \
  py::kw_only(), py::arg("level") = py::none(), py::arg("max_elements") = 20000, py::arg("accuracy") = 0.05,  \
      py::arg("method") = "auto",                                                                            \
      py::arg("eta") = py::none(), py::arg("degree") = py::none(), py::arg("near") = py::none(),               \
      py::arg("mu") = py::none(), py::arg("visibility") = "auto", py::arg("solver") = "auto",                  \
      py::arg("tolerance") = py::none(), py::arg("max_iterations") = 1000, py::arg("threads") = py::none(),     \
      py::arg("progress") = py::none()

/// SolverArguments from the same parameters, in that order.
SolverArguments solver_arguments(std::optional<int> level, long max_elements, double accuracy, std::string method,
                                 std::optional<double> eta, std::optional<int> degree, std::optional<std::string> near,
                                 std::optional<int> mu, std::string visibility, std::string solver,
                                 std::optional<double> tolerance, int max_iterations, std::optional<int> threads,
                                 py::object progress);

}  // namespace panelrad::python

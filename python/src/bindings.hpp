#pragma once
// The parts of the module, one file each, registered in this order by module.cpp.
#include <pybind11/pybind11.h>

namespace panelrad::python {

namespace py = pybind11;

void bind_errors(py::module_& m);     // errors.cpp: panelrad.Error, the root of every exception raised
void bind_scene(py::module_& m);      // scene_binding.cpp: Scene, load_scene, paper_cube
void bind_operator(py::module_& m);   // operator_binding.cpp: Operator (H or K_n as a LinearOperator)
void bind_solver(py::module_& m);     // solver_binding.cpp: Solver, SolveResult
void bind_solution(py::module_& m);   // solution_binding.cpp: solve_scene, Solution, write_outputs
void bind_view_factors(py::module_& m);  // viewfactors_binding.cpp: view_factors, ViewFactors
void bind_thermal(py::module_& m);       // thermal_binding.cpp: thermal_solve, ThermalSolution

}  // namespace panelrad::python

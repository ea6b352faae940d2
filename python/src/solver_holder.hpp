#pragma once
// A RadiositySolver with the scene it refers to (the C++ solver keeps a reference: the holder
// keeps the scene alive as long as the solver and its operator are reachable from Python).
#include <panelrad/solve/radiosity_solver.hpp>

#include <memory>

namespace panelrad::python {

struct SolverHolder {
  std::shared_ptr<const Scene> scene;
  std::unique_ptr<RadiositySolver> solver;
};

}  // namespace panelrad::python

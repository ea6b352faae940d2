// The compiled module panelrad._panelrad (re-exported by the package panelrad).
#include "bindings.hpp"

#include <panelrad/support/resources.hpp>
#include <panelrad/support/version.hpp>

PYBIND11_MODULE(_panelrad, m) {
  m.doc() =
      "panelrad: the radiosity equation u - K u = E on polyhedral scenes, by centroid collocation and "
      "the fast matrix-vector product of Atkinson & Chien (Adv. Comput. Math. 12, 2000).";
  using namespace panelrad::python;
  bind_errors(m);
  bind_scene(m);
  bind_operator(m);
  bind_solver(m);
  bind_solution(m);
  bind_view_factors(m);
  bind_thermal(m);
  m.attr("__version__") = panelrad::version();
  m.def("max_threads", &panelrad::max_threads, "Threads used by panelrad's parallel regions (OpenMP).");
  m.def("set_threads", &panelrad::set_threads, py::arg("threads"),
        "Sets the threads of panelrad's parallel regions for the whole process (0 keeps the default).");
}

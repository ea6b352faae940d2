// panelrad's exceptions as Python classes under panelrad.Error (itself a RuntimeError), each
// carrying the C++ message: MeshError, SceneFileError, TextFileError, SolverError,
// EnergyBalanceError, ResourceError.
// A misuse of the API (std::invalid_argument in C++: an option out of range, rho >= 1, E < 0)
// arrives as ValueError, pybind11's translation, with the library's message.
#include "bindings.hpp"

#include <panelrad/scene/errors.hpp>

namespace panelrad::python {

void bind_errors(py::module_& m) {
  // pybind11 tries the translators last registered first: the base class goes first.
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  error.attr("__doc__") = "Any failure panelrad reports; the message names the data and the rule it breaks.";
  static py::exception<geometry::MeshError> mesh(m, "MeshError", error.ptr());
  mesh.attr("__doc__") = "A mesh that is malformed, degenerate, non-finite, or whose faces cross (names the face and rule).";
  static py::exception<TextFileError> text(m, "TextFileError", error.ptr());
  text.attr("__doc__") = "An input file that cannot be read as text (missing, not a regular file, too large, NUL byte).";
  static py::exception<SceneFileError> scene(m, "SceneFileError", error.ptr());
  scene.attr("__doc__") = "A scene file or its materials (names the file and line, facet or material).";
  static py::exception<SolverError> solver(m, "SolverError", error.ptr());
  solver.attr("__doc__") = "An iteration that did not reach its tolerance (says how far it got).";
  static py::exception<EnergyBalanceError> energy(m, "EnergyBalanceError", error.ptr());
  energy.attr("__doc__") =
      "A solution whose energy balance is far off its expected size (names the channel and both sizes).";
  static py::exception<ResourceError> resource(m, "ResourceError", error.ptr());
  resource.attr("__doc__") = "A size that cannot fit in memory (with the estimate), or an allocation that failed.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const ResourceError& e) {
      resource(e.what());
    } catch (const SolverError& e) {
      solver(e.what());
    } catch (const EnergyBalanceError& e) {
      energy(e.what());
    } catch (const SceneFileError& e) {
      scene(e.what());
    } catch (const TextFileError& e) {
      text(e.what());
    } catch (const geometry::MeshError& e) {
      mesh(e.what());
    } catch (const Error& e) {
      error(e.what());
    }
  });
}

}  // namespace panelrad::python

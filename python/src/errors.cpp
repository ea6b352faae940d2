// panelrad's exceptions as Python classes under panelrad.Error (itself a RuntimeError), each
// carrying the C++ message: every exception the module raises is a panelrad.Error.
//   MeshError, SceneFileError, TextFileError, SolverError, EnergyBalanceError, ResourceError: the
//     library's own
//     (ResourceError also for an allocation that failed, std::bad_alloc);
//   ArgumentError, also a ValueError: a misuse of the API (std::invalid_argument and the other
//     std::logic_error in C++: an option out of range, rho >= 1, E < 0; a wrong array shape);
//   ArgumentTypeError, also a TypeError: a wrong type (an array's dtype, a bool for a number) or
//     an unknown keyword (the package's wrappers, panelrad/__init__.py);
//   ChannelError, also a KeyError and an IndexError: an unknown channel name or index;
//   Error itself: anything else the library reports (a file that cannot be written, ...).
// An exception raised by Python code the module calls (a progress callable, Ctrl-C's
// KeyboardInterrupt) is passed on unchanged.
#include "bindings.hpp"

#include <panelrad/scene/errors.hpp>

#include <new>
#include <stdexcept>
#include <string>

namespace panelrad::python {

namespace {

/// A class `name` of the module deriving from `bases` (panelrad.Error and Python's own).
py::object error_class(py::module_& m, const char* name, const py::tuple& bases, const char* doc) {
  const std::string qualified = m.attr("__name__").cast<std::string>() + "." + name;
  py::object cls = py::reinterpret_steal<py::object>(PyErr_NewException(qualified.c_str(), bases.ptr(), nullptr));
  if (!cls) throw py::error_already_set();
  cls.attr("__doc__") = doc;
  m.attr(name) = cls;
  return cls;
}

}  // namespace

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
  // Held for the life of the process (handles: never released, even after the interpreter's end).
  static py::handle argument = error_class(
      m, "ArgumentError", py::make_tuple(error, py::handle(PyExc_ValueError)),
      "A value panelrad refuses (also a ValueError): an option out of range, rho outside [0, 1), E negative, a wrong "
      "array shape; the message names the argument and the rule.")
      .release();
  static py::handle argument_type = error_class(
      m, "ArgumentTypeError", py::make_tuple(error, py::handle(PyExc_TypeError)),
      "An argument of the wrong type (also a TypeError): an array's dtype, a bool for a number, or an unknown keyword "
      "(named, with the accepted ones).")
      .release();
  static py::handle channel =
      error_class(m, "ChannelError", py::make_tuple(error, py::handle(PyExc_KeyError), py::handle(PyExc_IndexError)),
                  "An unknown channel name or index (also a KeyError and an IndexError).")
          .release();
  py::register_exception_translator([](std::exception_ptr p) {
    const auto raise = [](py::handle cls, const char* what) { PyErr_SetString(cls.ptr(), what); };
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
    } catch (const py::value_error& e) {  // the bindings' own checks (shapes, entries)
      raise(argument, e.what());
    } catch (const py::type_error& e) {
      raise(argument_type, e.what());
    } catch (const py::cast_error& e) {
      raise(argument_type, e.what());
    } catch (const py::key_error& e) {
      raise(channel, e.what());
    } catch (const py::index_error& e) {
      raise(channel, e.what());
    } catch (const py::builtin_exception&) {
      throw;  // pybind11's own (StopIteration, BufferError, ...): its default translation
    } catch (const std::bad_alloc&) {
      resource("out of memory (an allocation failed)");
    } catch (const std::logic_error& e) {  // std::invalid_argument, std::out_of_range, ...: a misuse
      raise(argument, e.what());
    } catch (const std::exception& e) {  // std::runtime_error (a file that cannot be written), ...
      error(e.what());
    }
  });
}

}  // namespace panelrad::python

#pragma once
// Interrupting a setup or solve that runs with the GIL released. The library calls
// SolveOptions::progress at every stage line of the setup (subdivision, the operator's stages, the
// self-check) and after every product of the iteration; the callback made here takes the GIL for
// that moment, runs Python's signal handlers (PyErr_CheckSignals) and, when one raised (Ctrl-C:
// KeyboardInterrupt), throws it through the library as a C++ exception that pybind11 turns back
// into the Python one once the GIL is held again. Work between two calls (one stage of the setup,
// e.g. filling the dense matrix, or one product) is not interrupted: the signal is acted on at the
// next call. The user's own progress callable, if any, is called there too, with the line.
#include <pybind11/pybind11.h>

#include <functional>
#include <string>

namespace panelrad::python {

namespace py = pybind11;

/// The progress callback of SolveOptions: signals checked, then `user` (None: nothing) called
/// with the line. Must be called without the GIL held (the solver runs with it released).
std::function<void(const std::string&)> interruptible_progress(py::object user);

}  // namespace panelrad::python

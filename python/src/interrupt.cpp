#include "interrupt.hpp"

#include <memory>

namespace panelrad::python {

std::function<void(const std::string&)> interruptible_progress(py::object user) {
  // The callable is shared by the copies of the std::function; it is released with the GIL held.
  std::shared_ptr<py::object> callable(new py::object(std::move(user)), [](py::object* p) {
    py::gil_scoped_acquire gil;
    delete p;
  });
  return [callable](const std::string& line) {
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
    if (!callable->is_none()) (*callable)(line);
  };
}

}  // namespace panelrad::python

#pragma once
// numpy arrays in and out of the bindings. Out: the library's vectors either lent as read-only
// views (the array keeps the object that owns the memory alive) or, for a result the caller
// receives by value, moved into the array's own storage: no copy of a large array either way.
// In: any array-like of the right shape and kind is read through its strides (one pass into the
// C++ vector the library takes; a non-contiguous array costs no extra copy); a wrong shape is a
// ValueError, a wrong kind (complex, bool, text, object) a TypeError.
#include <panelrad/geometry/mesh.hpp>

#include <Eigen/Core>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <cstddef>
#include <vector>

namespace panelrad::python {

namespace py = pybind11;

/// The vector moved into a new float64 array that owns it (no copy).
py::array_t<double> take_vector(Eigen::VectorXd&& v);
/// A read-only float64 view of `v`, kept valid by `owner`.
py::array_t<double> view_vector(const Eigen::VectorXd& v, py::handle owner);
/// A read-only (n, 3) float64 view of n Vec3 starting at `first`, `stride` bytes apart.
py::array_t<double> view_points(const geometry::Vec3* first, std::size_t n, std::size_t stride, py::handle owner);
/// A read-only view of n values of type T starting at `first`, `stride` bytes apart.
template <class T>
py::array_t<T> view_values(const T* first, std::size_t n, std::size_t stride, py::handle owner);

/// The values of a 1-D array-like of real numbers (float or integer dtype) of length n, as float64;
/// `what` names it in the ValueError / TypeError.
Eigen::VectorXd read_vector(py::handle values, std::size_t n, const char* what);
/// A float64 array of shape (rows, cols) from a real array-like (float or integer dtype):
/// `rows` < 0 accepts any number of rows. Row-major values.
std::vector<double> read_matrix(py::handle values, long rows, long cols, const char* what, long& rows_read);
/// An integer array of shape (rows, cols) (rows < 0: any) with values in [0, 2^31): triangle
/// and facet indices. Row-major values.
std::vector<geometry::Index> read_indices(py::handle values, long rows, long cols, const char* what,
                                          long& rows_read);

}  // namespace panelrad::python

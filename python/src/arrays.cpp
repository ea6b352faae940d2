#include "arrays.hpp"

#include <limits>
#include <memory>
#include <string>

namespace panelrad::python {

namespace {

// np.asarray of any array-like; its dtype's kind checked against `kinds` (numpy's one-letter
// codes: f float, i signed, u unsigned).
py::array as_array(py::handle values, const std::string& kinds, const char* what, const char* expected) {
  py::array a = py::array::ensure(values);
  if (!a) {
    PyErr_Clear();
    throw py::type_error(std::string(what) + ": expected " + expected + ", got " +
                         std::string(py::str(py::type::handle_of(values).attr("__name__"))));
  }
  const char kind = a.dtype().kind();
  if (kinds.find(kind) == std::string::npos)
    throw py::type_error(std::string(what) + ": expected " + expected + ", got an array of dtype " +
                         std::string(py::str(a.dtype())));
  return a;
}

std::string shape_of(const py::array& a) {
  std::string s = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) s += (d ? ", " : "") + std::to_string(a.shape(d));
  return s + (a.ndim() == 1 ? ",)" : ")");
}

void check_shape(const py::array& a, long rows, long cols, const char* what) {
  const bool ok = a.ndim() == 2 && a.shape(1) == cols && (rows < 0 || a.shape(0) == rows);
  if (!ok)
    throw py::value_error(std::string(what) + ": expected shape (" + (rows < 0 ? "N" : std::to_string(rows)) +
                          ", " + std::to_string(cols) + "), got " + shape_of(a));
}

template <class T>
py::array_t<T> make_view(const T* first, std::vector<py::ssize_t> shape, std::vector<py::ssize_t> strides,
                         py::handle owner) {
  py::array_t<T> a(std::move(shape), std::move(strides), first, owner);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

}  // namespace

py::array_t<double> take_vector(Eigen::VectorXd&& v) {
  auto* owned = new Eigen::VectorXd(std::move(v));
  py::capsule free_when_done(owned, [](void* p) { delete static_cast<Eigen::VectorXd*>(p); });
  return py::array_t<double>(owned->size(), owned->data(), free_when_done);
}

py::array_t<double> view_vector(const Eigen::VectorXd& v, py::handle owner) {
  return make_view<double>(v.data(), {static_cast<py::ssize_t>(v.size())}, {sizeof(double)}, owner);
}

py::array_t<double> view_points(const geometry::Vec3* first, std::size_t n, std::size_t stride, py::handle owner) {
  static_assert(sizeof(geometry::Vec3) == 3 * sizeof(double), "Vec3 holds its 3 coordinates contiguously");
  return make_view<double>(first ? first->data() : nullptr, {static_cast<py::ssize_t>(n), 3},
                           {static_cast<py::ssize_t>(stride), sizeof(double)}, owner);
}

template <class T>
py::array_t<T> view_values(const T* first, std::size_t n, std::size_t stride, py::handle owner) {
  return make_view<T>(first, {static_cast<py::ssize_t>(n)}, {static_cast<py::ssize_t>(stride)}, owner);
}
template py::array_t<double> view_values<double>(const double*, std::size_t, std::size_t, py::handle);
template py::array_t<geometry::Index> view_values<geometry::Index>(const geometry::Index*, std::size_t, std::size_t,
                                                                   py::handle);

Eigen::VectorXd read_vector(py::handle values, std::size_t n, const char* what) {
  const py::array a = as_array(values, "fiu", what, "a 1-D array of real numbers");
  if (a.ndim() != 1 || static_cast<std::size_t>(a.shape(0)) != n)
    throw py::value_error(std::string(what) + ": expected shape (" + std::to_string(n) + ",), got " + shape_of(a));
  // float64 arrays are read in place through their strides; others are converted once.
  const auto d = py::array_t<double>::ensure(a);
  if (!d) throw py::error_already_set();
  const auto r = d.unchecked<1>();
  Eigen::VectorXd v(static_cast<Eigen::Index>(n));
  for (py::ssize_t i = 0; i < r.shape(0); ++i) v[i] = r(i);
  return v;
}

std::vector<double> read_matrix(py::handle values, long rows, long cols, const char* what, long& rows_read) {
  const py::array a = as_array(values, "fiu", what, "an array of real numbers");
  check_shape(a, rows, cols, what);
  const auto d = py::array_t<double>::ensure(a);
  if (!d) throw py::error_already_set();
  const auto r = d.unchecked<2>();
  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(r.shape(0) * r.shape(1)));
  for (py::ssize_t i = 0; i < r.shape(0); ++i)
    for (py::ssize_t j = 0; j < r.shape(1); ++j) out.push_back(r(i, j));
  rows_read = static_cast<long>(r.shape(0));
  return out;
}

std::vector<geometry::Index> read_indices(py::handle values, long rows, long cols, const char* what,
                                          long& rows_read) {
  const py::array a = as_array(values, "iu", what, "an array of integers");
  if (cols == 1 && a.ndim() == 1) {
    if (rows >= 0 && a.shape(0) != rows)
      throw py::value_error(std::string(what) + ": expected shape (" + std::to_string(rows) + ",), got " + shape_of(a));
  } else {
    check_shape(a, rows, cols, what);
  }
  // Every integer dtype fits in int64 except uint64 values above 2^63, which the range check
  // refuses anyway (astype wraps them to negative numbers).
  const auto d = py::array_t<std::int64_t>::ensure(a);
  if (!d) throw py::error_already_set();
  const py::ssize_t n = d.size();
  std::vector<geometry::Index> out;
  out.reserve(static_cast<std::size_t>(n));
  const auto flat = d.attr("reshape")(-1).cast<py::array_t<std::int64_t>>().unchecked<1>();
  constexpr std::int64_t kMax = std::numeric_limits<geometry::Index>::max();
  for (py::ssize_t i = 0; i < n; ++i) {
    const std::int64_t v = flat(i);
    if (v < 0 || v > kMax)
      throw py::value_error(std::string(what) + ": entry " + std::to_string(i) + " is " + std::to_string(v) +
                            ", outside [0, " + std::to_string(kMax) + "]");
    out.push_back(static_cast<geometry::Index>(v));
  }
  rows_read = a.ndim() >= 1 ? static_cast<long>(a.shape(0)) : 0;
  return out;
}

}  // namespace panelrad::python

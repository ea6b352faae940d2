// panelrad.Operator: the solver's irradiance operator H, (H v)_i = 1/pi Int_S v G(P_i, Q) V(P_i, Q)
// dS_Q, as a scipy.sparse.linalg.LinearOperator-compatible object (shape, dtype, matvec, matmat,
// @). K_c = diag(rho_c) H is the operator of channel c's equation (I - K_c) u = E_c, (32)-(33).
// The products are the library's own (dense matrix or fast method), with the GIL released.
#include "arrays.hpp"
#include "bindings.hpp"
#include "solver_holder.hpp"

#include <memory>
#include <string>

namespace panelrad::python {

namespace {

struct OperatorHandle {
  std::shared_ptr<const SolverHolder> holder;
  const RadiosityOperator& op() const { return holder->solver->op(); }
  py::ssize_t n() const { return holder->solver->op().size(); }
};

py::array product(const OperatorHandle& h, py::handle x) {
  const py::array a = py::array::ensure(x);
  const bool column = a && a.ndim() == 2 && a.shape(1) == 1;  // scipy passes (n, 1) as well as (n,)
  const py::object flat = column ? a.attr("reshape")(-1) : py::reinterpret_borrow<py::object>(x);
  Eigen::VectorXd v = read_vector(flat, static_cast<std::size_t>(h.n()), "x");
  Eigen::VectorXd y;
  {
    py::gil_scoped_release release;
    h.op().apply(v, y);
  }
  py::array out = take_vector(std::move(y));
  return column ? py::array(out.attr("reshape")(h.n(), 1)) : out;
}

py::array block_product(const OperatorHandle& h, py::handle X) {
  const py::array a = py::array::ensure(X);
  if (!a) throw py::error_already_set();
  if (a.ndim() == 1) return product(h, X);
  if (a.ndim() != 2 || a.shape(0) != h.n())
    throw py::value_error("X: expected shape (" + std::to_string(h.n()) + ", k)");
  // apply_block: column c is bit-identical to apply of that column.
  const auto d = py::array_t<double>::ensure(a);
  if (!d || a.dtype().kind() == 'c' || a.dtype().kind() == 'b' || a.dtype().kind() == 'O')
    throw py::type_error("X: expected an array of real numbers");
  const auto r = d.unchecked<2>();
  Eigen::MatrixXd V(r.shape(0), r.shape(1));
  for (py::ssize_t j = 0; j < r.shape(1); ++j)
    for (py::ssize_t i = 0; i < r.shape(0); ++i) V(i, j) = r(i, j);
  auto* Y = new Eigen::MatrixXd;
  {
    py::gil_scoped_release release;
    h.op().apply_block(V, *Y);
  }
  py::capsule owner(Y, [](void* p) { delete static_cast<Eigen::MatrixXd*>(p); });
  // Eigen is column-major: strides (8, 8 n).
  return py::array_t<double>({Y->rows(), Y->cols()},
                             {static_cast<py::ssize_t>(sizeof(double)), static_cast<py::ssize_t>(sizeof(double) * Y->rows())},
                             Y->data(), owner);
}

}  // namespace

py::object make_operator_handle(std::shared_ptr<const SolverHolder> holder) {
  return py::cast(OperatorHandle{std::move(holder)});
}

void bind_operator(py::module_& m) {
  py::class_<OperatorHandle>(m, "Operator", R"doc(
The irradiance operator H of a Solver: (H v)_i = 1/pi Int_S v(Q) G(P_i, Q) V(P_i, Q) dS_Q at the
collocation points P_i, the dense matrix (33) or the fast product of section 4 as the solver
built it. The operator of channel c's equation (32) is K_c = diag(rho_c) H.

Compatible with scipy.sparse.linalg.LinearOperator (shape, dtype, matvec, matmat, @):
scipy.sparse.linalg.aslinearoperator(op) wraps it, e.g. for gmres on I - diag(rho) H. H is not
symmetric, and there is no rmatvec. Each product runs with the GIL released and gives the same
bits as the solver's own products.
)doc")
      .def_property_readonly("shape", [](const OperatorHandle& h) { return py::make_tuple(h.n(), h.n()); })
      .def_property_readonly("dtype", [](const OperatorHandle&) { return py::dtype::of<double>(); })
      .def_property_readonly("name", [](const OperatorHandle& h) { return h.op().name(); })
      .def_property_readonly("nbytes", [](const OperatorHandle& h) { return h.op().bytes(); }, "Bytes the operator holds.")
      .def("matvec", &product, py::arg("x"), "H x for x of shape (n,) or (n, 1) (same shape returned).")
      .def("matmat", &block_product, py::arg("X"), "H X for X of shape (n, k): column j is bit-identical to matvec(X[:, j]).")
      .def("__matmul__", &block_product, py::arg("x"))
      .def("__repr__", [](const OperatorHandle& h) {
        return "<panelrad.Operator H: " + h.op().name() + ", shape (" + std::to_string(h.n()) + ", " +
               std::to_string(h.n()) + ")>";
      });
}

}  // namespace panelrad::python

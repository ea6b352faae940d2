// panelrad.Solver: RadiositySolver's setup once (level, operator, self-check) with the GIL
// released, then solves for the scene's channels or for any rho, E at the collocation points;
// the elements (centroids P_i, inner normals, areas, facets) as read-only views; panelrad.SolveResult.
#include "arrays.hpp"
#include "bindings.hpp"
#include "options.hpp"
#include "scene_access.hpp"
#include "solver_holder.hpp"

#include <pybind11/stl.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace panelrad::python {

py::object make_operator_handle(std::shared_ptr<const SolverHolder> holder);  // operator_binding.cpp

namespace {

// One solve's answer, with the channel it is for ("" for solve(rho, E) / solve(E)).
struct SolveResult {
  ChannelSolve solve;
  std::string channel;
};

py::object result_object(ChannelSolve&& s, std::string channel) {
  return py::cast(std::make_shared<SolveResult>(SolveResult{std::move(s), std::move(channel)}));
}

py::dict info_dict(const RadiositySolver& s) {
  const RadiositySolverInfo& i = s.info();
  py::dict d;
  d["level"] = i.level;
  d["n"] = i.n;
  d["mesh_size"] = i.mesh_size;
  d["diameter"] = i.diameter;
  d["conditioning_reflectivity"] = i.conditioning_reflectivity;
  d["method"] = std::string(to_string(i.parameters.method));
  d["eta"] = i.parameters.eta;
  d["degree"] = i.parameters.degree;
  d["near"] = std::string(to_string(i.parameters.near.rule));
  d["visibility"] = std::string(to_string(i.visibility));
  d["self_check_error"] = i.self_check ? py::cast(i.self_check->relative_error) : py::none();
  d["self_check_threshold"] = i.self_check_threshold;
  d["tightened"] = i.tightened;
  d["tolerance"] = i.tolerance;
  d["subdivision_s"] = i.subdivision_s;
  d["operator_s"] = i.operator_s;
  d["operator_bytes"] = i.operator_bytes;
  d["warnings"] = i.warnings;
  return d;
}

std::string scientific(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

const Collocation& collocation(const SolverHolder& h) { return h.solver->collocation(); }

// A field of the elements (the finest-level clusters), viewed with the clusters' stride.
template <class T>
py::array_t<T> element_field(py::object self, const T geometry::Cluster::*member) {
  const auto& h = self.cast<const SolverHolder&>();
  const auto elements = collocation(h).tree().elements();
  const T* first = elements.empty() ? nullptr : &(elements[0].*member);
  return view_values<T>(first, elements.size(), sizeof(geometry::Cluster), self);
}


void bind_solve_result(py::module_& m) {
  py::class_<SolveResult, std::shared_ptr<SolveResult>>(m, "SolveResult", R"doc(
One solve of (I - diag(rho) H) u = E, (32): the radiosity u at the collocation points and the
iteration's report. Arrays are read-only views owned by this object.
)doc")
      .def_property_readonly(
          "u", [](py::object self) { return view_vector(self.cast<const SolveResult&>().solve.u, self); },
          "Radiosity u_n at the collocation points (the last iterate when not converged).")
      .def_property_readonly(
          "radiosity", [](py::object self) { return view_vector(self.cast<const SolveResult&>().solve.u, self); },
          "The same array as u.")
      .def_property_readonly(
          "irradiance",
          [](py::object self) -> py::object {
            const auto& r = self.cast<const SolveResult&>();
            if (r.solve.irradiance.size() == 0) return py::none();
            return view_vector(r.solve.irradiance, self);
          },
          "H u (the light arriving at P_i), from Solver.solve() over the scene's channels; else None.")
      .def_property_readonly("channel", [](const SolveResult& r) { return r.channel; })
      .def_property_readonly("iterations", [](const SolveResult& r) { return r.solve.iterations; },
                             "Products with K_n.")
      .def_property_readonly("residual", [](const SolveResult& r) { return r.solve.residual; },
                             "||E - (I - K) u||_inf / ||E||_inf.")
      .def_property_readonly("error_estimate", [](const SolveResult& r) { return r.solve.error_estimate; },
                             "The iteration's bound on ||u_n - u||_inf.")
      .def_property_readonly("solver", [](const SolveResult& r) { return r.solve.solver; },
                             "The solver that ran, with the reason of an automatic choice.")
      .def_property_readonly("converged", [](const SolveResult& r) { return r.solve.converged(); })
      .def_property_readonly("message", [](const SolveResult& r) { return r.solve.message; })
      .def_property_readonly("convergence_ratio", [](const SolveResult& r) { return r.solve.convergence_ratio; },
                             "Neumann iteration: the ratio (36).")
      .def_property_readonly("seconds", [](const SolveResult& r) { return r.solve.seconds; })
      .def("require_converged", [](const SolveResult& r) { r.solve.require_converged(); },
           "Raises SolverError with the message when the iteration did not converge.")
      .def("__repr__", [](const SolveResult& r) {
        return "<panelrad.SolveResult" + (r.channel.empty() ? std::string() : " '" + r.channel + "'") + ": n " +
               std::to_string(r.solve.u.size()) + ", " + (r.solve.converged() ? "converged" : "not converged") +
               " after " + std::to_string(r.solve.iterations) + " products, residual " +
               scientific(r.solve.residual) + ">";
      });

}

// The elements of the level-L refinement as read-only views kept valid by the solver.
void add_element_views(py::class_<SolverHolder, std::shared_ptr<SolverHolder>>& cls) {
  cls
      .def_property_readonly(
          "centroids",
          [](py::object self) {
            const auto points = collocation(self.cast<const SolverHolder&>()).tree().collocation_points();
            return view_points(points.data(), points.size(), sizeof(geometry::Vec3), self);
          },
          "(n, 3) read-only view: the collocation points P_i, the elements' centroids (22).")
      .def_property_readonly(
          "normals",
          [](py::object self) {
            const auto elements = collocation(self.cast<const SolverHolder&>()).tree().elements();
            return view_points(elements.empty() ? nullptr : &elements[0].normal, elements.size(),
                               sizeof(geometry::Cluster), self);
          },
          "(n, 3) read-only view: the inner unit normals n (2), into the solid.")
      .def_property_readonly(
          "element_vertices",
          [](py::object self) {
            const auto elements = collocation(self.cast<const SolverHolder&>()).tree().elements();
            py::array_t<double> a({static_cast<py::ssize_t>(elements.size()), py::ssize_t{3}, py::ssize_t{3}},
                                  {static_cast<py::ssize_t>(sizeof(geometry::Cluster)),
                                   static_cast<py::ssize_t>(sizeof(geometry::Vec3)), py::ssize_t{sizeof(double)}},
                                  elements.empty() ? nullptr : elements[0].vertex[0].data(), self);
            a.attr("setflags")(py::arg("write") = false);
            return a;
          },
          "(n, 3, 3) read-only view: each element's corners, counter-clockwise seen from outside.")
      .def_property_readonly(
          "areas", [](py::object self) { return element_field<double>(self, &geometry::Cluster::area); },
          "(n,) read-only view: element areas.")
      .def_property_readonly(
          "facets", [](py::object self) { return element_field<geometry::Index>(self, &geometry::Cluster::facet); },
          "(n,) read-only view: the input facet of each element.");
}

void bind_solver_class(py::module_& m) {
  py::class_<SolverHolder, std::shared_ptr<SolverHolder>> cls(m, "Solver", R"doc(
Solver(scene, *, level=None, max_elements=20000, accuracy=0.05, method="auto", eta=None, degree=None, near=None,
       mu=None, visibility="auto", solver="auto", tolerance=None, max_iterations=1000,
       threads=None, progress=None)

The radiosity equation u - K u = E on one scene by centroid collocation (section 3): the setup
(level L, n = n0 4^L elements; the operator H, dense (33) or fast (section 4) with its
self-check) runs once here, with the GIL released; solve() then runs the iteration (32) for as
many right-hand sides as wanted.

level: refinement level (None: the largest with n <= max_elements). method: "auto" (the measured
rule picks dense or fast and their parameters so that the far field's error stays within
`accuracy` times the discretization error, tightened until the self-check passes), "dense"
or "fast" with eta (admissibility (41)), degree (Taylor degree M (44)), near ("exact" or
"quadrature") and mu as given. visibility: "auto" (V computed unless the scene is convex) or
"occluded". solver: "auto", "neumann", "gmres" or "lu". tolerance: relative stopping tolerance
(None: tied to the discretization error). threads: OpenMP threads for the whole process (None:
unchanged). progress: callable(str) called at every setup stage and product.

Ctrl-C (any Python signal handler that raises) interrupts the setup and the solves at the next
stage line or product: the exception (KeyboardInterrupt) is raised and the solver is not built.
The scene must not be modified from another thread while a solve runs.
)doc");
  cls.def(py::init([](std::shared_ptr<Scene> scene, std::optional<int> level, long max_elements, double accuracy, std::string method,
                       std::optional<double> eta, std::optional<int> degree, std::optional<std::string> near,
                       std::optional<int> mu, std::string visibility, std::string solver,
                       std::optional<double> tolerance, int max_iterations, std::optional<int> threads,
                       py::object progress) {
             if (!scene) throw py::type_error("scene: expected a panelrad.Scene, got None");
             const SolveOptions o = make_solve_options(solver_arguments(
                 level, max_elements, accuracy, std::move(method), eta, degree, std::move(near), mu, std::move(visibility),
                 std::move(solver), tolerance, max_iterations, threads, std::move(progress)));
             auto h = std::make_shared<SolverHolder>();
             h->scene = scene;
             py::gil_scoped_release release;
             h->solver = std::make_unique<RadiositySolver>(*h->scene, o);
             return h;
           }),
           py::arg("scene"), PANELRAD_SOLVER_KWARGS)
      .def_property_readonly("n", [](const SolverHolder& h) { return h.solver->n(); }, "Number of elements.")
      .def_property_readonly("level", [](const SolverHolder& h) { return h.solver->level(); })
      .def_property_readonly("tolerance", [](const SolverHolder& h) { return h.solver->tolerance(); },
                             "The iteration's relative tolerance.")
      .def_property_readonly("info", [](const SolverHolder& h) { return info_dict(*h.solver); },
                             "What the setup did (level, operator parameters, self-check, times), as a dict.")
      .def_property_readonly("scene", [](const SolverHolder& h) { return std::const_pointer_cast<Scene>(h.scene); });
  add_element_views(cls);
  cls
      .def_property_readonly(
          "true_solution",
          [](py::object self) -> py::object {
            const Collocation& c = collocation(self.cast<const SolverHolder&>());
            if (!c.has_true_solution()) return py::none();
            return view_vector(c.true_solution(), self);
          },
          "u(P_i) of a manufactured scene (paper_cube), else None.")
      .def(
          "max_error",
          [](const SolverHolder& h, py::handle u) {
            const Collocation& c = collocation(h);
            if (!c.has_true_solution()) throw py::value_error("max_error: the scene has no manufactured solution");
            return c.max_error(read_vector(u, static_cast<std::size_t>(h.solver->n()), "u"));
          },
          py::arg("u"), "max_k |u(P_k) - u_k|, the error (51) of Table 1, for a manufactured scene.")
      .def(
          "channel_values",
          [](const SolverHolder& h, py::handle channel) {
            Collocation::ChannelValues v = h.solver->channel_values(channel_index(*h.scene, channel));
            return py::make_tuple(take_vector(std::move(v.rho)), take_vector(std::move(v.E)));
          },
          py::arg("channel") = 0, "(rho, E) of a channel of the scene at the collocation points.")
      .def_property_readonly(
          "operator", [](std::shared_ptr<SolverHolder> h) { return make_operator_handle(h); },
          "The irradiance operator H (K_c = diag(rho_c) H) as a LinearOperator-compatible Operator.")
      .def(
          "irradiance",
          [](const SolverHolder& h, py::handle u) {
            Eigen::VectorXd v = read_vector(u, static_cast<std::size_t>(h.solver->n()), "u");
            Eigen::VectorXd y;
            {
              py::gil_scoped_release release;
              y = h.solver->irradiance(v);
            }
            return take_vector(std::move(y));
          },
          py::arg("u"), "H u: the light arriving at P_i (the product without rho).")
      .def(
          "solve",
          [](const SolverHolder& h) {
            std::vector<std::size_t> all;
            for (std::size_t c = 0; c < h.scene->num_channels(); ++c) all.push_back(c);
            std::vector<ChannelSolve> out;
            {
              py::gil_scoped_release release;
              out = h.solver->solve_channels(all);
            }
            py::list results;
            for (std::size_t c = 0; c < out.size(); ++c) results.append(result_object(std::move(out[c]), h.scene->channels()[c]));
            return results;
          },
          "Solves every channel of the scene (rho_c, E_c of the scene at P_i): a list of SolveResult, "
          "in channel order, each with its irradiance H u.")
      .def(
          "solve",
          [](const SolverHolder& h, py::handle E) {
            const auto n = static_cast<std::size_t>(h.solver->n());
            Eigen::VectorXd e = read_vector(E, n, "E");
            const Eigen::VectorXd& rho = collocation(h).reflectivity();
            ChannelSolve s;
            {
              py::gil_scoped_release release;
              s = h.solver->solve(rho, e);
            }
            return result_object(std::move(s), "");
          },
          py::arg("E"), "Solves with E per element (n,) and the rho of the scene's first channel at P_i.")
      .def(
          "solve",
          [](const SolverHolder& h, py::handle rho, py::handle E) {
            const auto n = static_cast<std::size_t>(h.solver->n());
            Eigen::VectorXd r = read_vector(rho, n, "rho");
            Eigen::VectorXd e = read_vector(E, n, "E");
            ChannelSolve s;
            {
              py::gil_scoped_release release;
              s = h.solver->solve(r, e);
            }
            return result_object(std::move(s), "");
          },
          py::arg("rho"), py::arg("E"),
          "Solves (I - diag(rho) H) u = E for rho, E per element, each of shape (n,); rho in [0, 1) "
          "(ArgumentError otherwise), E finite.")
      .def("__repr__", [](const SolverHolder& h) {
        const auto& i = h.solver->info();
        return "<panelrad.Solver: level " + std::to_string(i.level) + ", n " + std::to_string(i.n) + ", " +
               to_string(i.parameters.method) + " operator, visibility " + to_string(i.visibility) + ">";
      });
}

}  // namespace

void bind_solver(py::module_& m) {
  bind_solve_result(m);
  bind_solver_class(m);
}

}  // namespace panelrad::python

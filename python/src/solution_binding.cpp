// panelrad.solve_scene: discretize, build one operator H, solve every channel and check the
// energy balance, in one call with the GIL released; panelrad.Solution and its channels (views of
// the solution's arrays); panelrad.write_outputs (CSV, PLY, VTK, PNG).
#include "arrays.hpp"
#include "bindings.hpp"
#include "options.hpp"
#include "scene_access.hpp"

#include <panelrad/io/outputs.hpp>
#include <panelrad/solve/scene_solver.hpp>

#include <pybind11/stl.h>

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace panelrad::python {

namespace {

// One channel of a Solution: its arrays are views kept valid by the Solution object.
struct ChannelHandle {
  py::object owner;  // the Solution
  std::shared_ptr<const SceneSolution> solution;
  std::size_t index;
  const ChannelSolution& channel() const { return solution->channels[index]; }
  const ElementField& field() const { return solution->field; }
};

std::size_t channel_of(const SceneSolution& s, py::handle key) {
  if (py::isinstance<py::str>(key)) {
    const auto name = key.cast<std::string>();
    for (std::size_t c = 0; c < s.channels.size(); ++c)
      if (s.channels[c].name == name) return c;
    throw py::key_error("channel \"" + name + "\": not a channel of this solution");
  }
  const long c = key.cast<long>();
  if (c < 0 || static_cast<std::size_t>(c) >= s.channels.size())
    throw py::index_error("channel " + std::to_string(c) + " out of range");
  return static_cast<std::size_t>(c);
}

std::optional<geometry::Vec3> vec3(const std::optional<std::array<double, 3>>& v) {
  if (!v) return std::nullopt;
  return geometry::Vec3((*v)[0], (*v)[1], (*v)[2]);
}

}  // namespace

void bind_solution(py::module_& m) {
  py::class_<ChannelHandle>(m, "ChannelSolution", R"doc(
One channel of a Solution: radiosity u_n and irradiance H u_n per element, rho and E per
element, the iteration's report and the energy balance (emitted sum A_i E_i against absorbed
sum A_i (1 - rho_i) H_i plus the light no front side takes: equal up to the discretization).
Arrays are read-only views.
)doc")
      .def_property_readonly("name", [](const ChannelHandle& c) { return c.channel().name; })
      .def_property_readonly("radiosity", [](const ChannelHandle& c) { return view_vector(c.channel().radiosity, c.owner); })
      .def_property_readonly("irradiance", [](const ChannelHandle& c) { return view_vector(c.channel().irradiance, c.owner); })
      .def_property_readonly("rho", [](const ChannelHandle& c) { return view_vector(c.field().rho[c.index], c.owner); })
      .def_property_readonly("E", [](const ChannelHandle& c) { return view_vector(c.field().emission[c.index], c.owner); })
      .def_property_readonly("iterations", [](const ChannelHandle& c) { return c.channel().iterations; })
      .def_property_readonly("residual", [](const ChannelHandle& c) { return c.channel().residual; })
      .def_property_readonly("error_estimate", [](const ChannelHandle& c) { return c.channel().error_estimate; })
      .def_property_readonly("solver", [](const ChannelHandle& c) { return c.channel().solver; })
      .def_property_readonly("converged", [](const ChannelHandle& c) { return c.channel().converged(); })
      .def_property_readonly("message", [](const ChannelHandle& c) { return c.channel().message; })
      .def_property_readonly("shared_with", [](const ChannelHandle& c) { return c.channel().shared_with; },
                             "Non-empty: this channel's data equal that channel's, whose solution was copied.")
      .def_property_readonly("emitted", [](const ChannelHandle& c) { return c.channel().emitted; })
      .def_property_readonly("absorbed", [](const ChannelHandle& c) { return c.channel().absorbed; })
      .def_property_readonly(
          "environment_in", [](const ChannelHandle& c) { return c.channel().environment_in; },
          "The environment's power arriving, sum A_i u_env s_i (0 without an environment).")
      .def_property_readonly("energy_mismatch", [](const ChannelHandle& c) { return c.channel().energy_mismatch; })
      .def_property_readonly("escaped", [](const ChannelHandle& c) { return c.channel().escaped; },
                             "The fraction of the light that reaches no front side (leaves the scene, or falls on "
                             "a back side); 0 in a closed scene, never negative.")
      .def_property_readonly("energy_balanced", [](const ChannelHandle& c) { return c.channel().energy_balanced; },
                             "energy_mismatch is within 4 times its expected size (0.5 h/diam).")
      .def("__repr__", [](const ChannelHandle& c) {
        return "<panelrad.ChannelSolution '" + c.channel().name + "': " +
               (c.channel().converged() ? "converged" : "not converged") + ", " +
               std::to_string(c.channel().iterations) + " products>";
      });

  py::class_<SceneSolution, std::shared_ptr<SceneSolution>>(m, "Solution", R"doc(
A solved scene (solve_scene): every channel's radiosity on the elements, their geometry, the
operator that ran, times and warnings. solution[name or index] is a ChannelSolution.
)doc")
      .def_readonly("level", &SceneSolution::level)
      .def_readonly("n", &SceneSolution::n)
      .def_readonly("mesh_size", &SceneSolution::mesh_size)
      .def_readonly("diameter", &SceneSolution::diameter)
      .def_readonly("method", &SceneSolution::method, "The operator that ran, described.")
      .def_property_readonly("shape", [](const SceneSolution& s) { return std::string(geometry::to_string(s.shape)); })
      .def_readonly("closed", &SceneSolution::closed, "Every ray from a front side ends on a front side.")
      .def_readonly("enclosed", &SceneSolution::enclosed, "No light leaves the scene (it may fall on back sides).")
      .def_readonly("expected_energy_mismatch", &SceneSolution::expected_energy_mismatch,
                    "0.5 h/diam: the energy mismatch's expected size from the discretization.")
      .def_readonly("energy_balanced", &SceneSolution::energy_balanced,
                    "Every channel passed the energy check (mismatch within 4 times its expected size); "
                    "False: the solution is not to be trusted.")
      .def_property_readonly("visibility", [](const SceneSolution& s) { return std::string(to_string(s.visibility)); })
      .def_readonly("self_check_error", &SceneSolution::self_check_error, "Fast operator's measured product error; -1: dense.")
      .def_readonly("tightened", &SceneSolution::tightened)
      .def_readonly("subdivision_s", &SceneSolution::subdivision_s)
      .def_readonly("operator_s", &SceneSolution::operator_s)
      .def_readonly("solve_s", &SceneSolution::solve_s)
      .def_readonly("total_s", &SceneSolution::total_s)
      .def_readonly("operator_bytes", &SceneSolution::operator_bytes)
      .def_readonly("peak_rss_mb", &SceneSolution::peak_rss_mb)
      .def_readonly("warnings", &SceneSolution::warnings)
      .def_property_readonly("converged", &SceneSolution::converged)
      .def("require_converged", &SceneSolution::require_converged,
           "Raises SolverError with the message of the first channel that did not converge.")
      .def("require_energy_balance", &SceneSolution::require_energy_balance,
           "Raises EnergyBalanceError with the message of the first channel that failed the energy check.")
      .def_property_readonly("channel_names", [](const SceneSolution& s) { return s.field.channels; })
      .def_property_readonly("channels",
                             [](py::object self) {
                               auto s = self.cast<std::shared_ptr<SceneSolution>>();
                               py::list out;
                               for (std::size_t c = 0; c < s->channels.size(); ++c)
                                 out.append(py::cast(ChannelHandle{self, s, c}));
                               return out;
                             })
      .def("__getitem__",
           [](py::object self, py::handle key) {
             auto s = self.cast<std::shared_ptr<SceneSolution>>();
             return ChannelHandle{self, s, channel_of(*s, key)};
           })
      .def("__len__", [](const SceneSolution& s) { return s.channels.size(); })
      .def_property_readonly("centroids",
                             [](py::object self) {
                               const auto& p = self.cast<const SceneSolution&>().field.centroid;
                               return view_points(p.data(), p.size(), sizeof(geometry::Vec3), self);
                             },
                             "(n, 3) read-only view: the collocation points P_i (22).")
      .def_property_readonly("element_vertices",
                             [](py::object self) {
                               const auto& t = self.cast<const SceneSolution&>().field.triangle;
                               static_assert(sizeof(t[0]) == 3 * sizeof(geometry::Vec3));
                               py::array_t<double> a({static_cast<py::ssize_t>(t.size()), py::ssize_t{3}, py::ssize_t{3}},
                                                     {static_cast<py::ssize_t>(sizeof(t[0])),
                                                      static_cast<py::ssize_t>(sizeof(geometry::Vec3)),
                                                      py::ssize_t{sizeof(double)}},
                                                     t.empty() ? nullptr : t[0][0].data(), self);
                               a.attr("setflags")(py::arg("write") = false);
                               return a;
                             },
                             "(n, 3, 3) read-only view: element corners, counter-clockwise seen from outside.")
      .def_property_readonly("normals",
                             [](py::object self) {
                               const auto& p = self.cast<const SceneSolution&>().field.inner_normal;
                               return view_points(p.data(), p.size(), sizeof(geometry::Vec3), self);
                             },
                             "(n, 3) read-only view: inner unit normals (2).")
      .def_property_readonly("areas",
                             [](py::object self) {
                               const auto& a = self.cast<const SceneSolution&>().field.area;
                               return view_values<double>(a.data(), a.size(), sizeof(double), self);
                             })
      .def_property_readonly("facets",
                             [](py::object self) {
                               const auto& f = self.cast<const SceneSolution&>().field.facet;
                               return view_values<geometry::Index>(f.data(), f.size(), sizeof(geometry::Index), self);
                             })
      .def("__repr__", [](const SceneSolution& s) {
        return "<panelrad.Solution: level " + std::to_string(s.level) + ", n " + std::to_string(s.n) + ", " +
               std::to_string(s.channels.size()) + " channel(s), " + s.method + ", " +
               (s.converged() ? "converged" : "not converged") +
               (s.energy_balanced ? "" : ", energy check failed") + ">";
      });

  m.def(
      "solve_scene",
      [](std::shared_ptr<Scene> scene, std::optional<int> level, long max_elements, double accuracy, std::string method,
         std::optional<double> eta, std::optional<int> degree, std::optional<std::string> near, std::optional<int> mu,
         std::string visibility, std::string solver, std::optional<double> tolerance, int max_iterations,
         std::optional<int> threads, py::object progress) {
        if (!scene) throw py::type_error("scene: expected a panelrad.Scene, got None");
        const SolveOptions o = make_solve_options(solver_arguments(level, max_elements, accuracy, std::move(method), eta, degree,
                                                                   std::move(near), mu, std::move(visibility),
                                                                   std::move(solver), tolerance, max_iterations,
                                                                   threads, std::move(progress)));
        py::gil_scoped_release release;
        return std::make_shared<SceneSolution>(solve_scene(*scene, o));
      },
      py::arg("scene"), PANELRAD_SOLVER_KWARGS, R"doc(
Solves a scene in one call: one discretization and one operator H for every channel, each
channel (I - diag(rho_c) H) u_c = E_c (32), and the energy balance. Keyword arguments as Solver.
A channel that does not converge keeps its last iterate with a warning; call
solution.require_converged() to raise its SolverError. A channel that fails the energy check keeps
its solution with a warning; call solution.require_energy_balance() to raise its
EnergyBalanceError.
)doc");

  m.def(
      "write_outputs",
      [](const SceneSolution& solution, py::handle prefix, std::vector<std::string> formats,
         std::optional<std::array<double, 3>> view, std::optional<std::array<double, 3>> up) {
        OutputOptions o;
        o.view_direction = vec3(view);
        o.up = vec3(up);
        const std::string p = fspath(prefix);
        py::gil_scoped_release release;
        return write_outputs(solution, p, formats, o);
      },
      py::arg("solution"), py::arg("prefix"),
      py::arg("formats") = std::vector<std::string>{"csv", "ply", "vtk", "png"}, py::arg("view") = py::none(),
      py::arg("up") = py::none(), R"doc(
Writes PREFIX.csv (per-element radiosity), PREFIX.ply, PREFIX.vtk and PREFIX.png (the formats
asked for), all or none; view: direction from the scene's centre towards the viewer, up: the
direction shown upwards (None: chosen from the scene). Returns the paths written.
)doc");
}

}  // namespace panelrad::python

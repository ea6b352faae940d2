// panelrad.thermal_solve: temperatures and heat fluxes of gray diffuse surfaces (C++ solve_thermal,
// with the GIL released), SI units, as numpy arrays; ThermalSolution.write.
#include "bindings.hpp"
#include "options.hpp"
#include "scene_access.hpp"

#include <panelrad/io/thermal_output.hpp>
#include <panelrad/thermal/thermal_solve.hpp>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace panelrad::python {

namespace {

/// A number of `entry` at `key` (a float or an int, not a bool).
double number_at(const py::dict& entry, const char* key, const std::string& group) {
  const py::handle v = entry[key];
  if (py::isinstance<py::bool_>(v) || !(py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v)))
    throw py::type_error("conditions['" + group + "']['" + key + "']: expected a number");
  return v.cast<double>();
}

/// conditions: {group: {"T": K, "emissivity": e} or {"q": W/m^2, "emissivity": e}}, every group.
std::vector<SurfaceCondition> read_conditions(const py::dict& conditions, const SurfaceGroups& groups) {
  for (const auto& [key, value] : conditions) {
    const std::string name = py::str(key);
    if (std::find(groups.names.begin(), groups.names.end(), name) == groups.names.end())
      throw std::invalid_argument("conditions: '" + name + "' is not a group of the scene");
  }
  std::vector<SurfaceCondition> out;
  for (const std::string& name : groups.names) {
    if (!conditions.contains(name)) throw std::invalid_argument("conditions: group '" + name + "' has no condition");
    const py::handle h = conditions[py::str(name)];
    if (!py::isinstance<py::dict>(h)) throw py::type_error("conditions['" + name + "']: expected a dict");
    const py::dict entry = h.cast<py::dict>();
    for (const auto& [key, value] : entry) {
      const std::string k = py::str(key);
      if (k != "T" && k != "q" && k != "emissivity")
        throw std::invalid_argument("conditions['" + name + "']: unknown key '" + k + "' (expected 'T' or 'q', 'emissivity')");
    }
    if (entry.contains("T") == entry.contains("q"))
      throw std::invalid_argument("conditions['" + name + "']: needs exactly one of 'T' (K) and 'q' (W/m^2)");
    SurfaceCondition c;
    const bool hot = entry.contains("T");
    c.given = hot ? SurfaceCondition::Given::temperature : SurfaceCondition::Given::heat_flux;
    c.value = number_at(entry, hot ? "T" : "q", name);
    if (hot && !entry.contains("emissivity"))
      throw std::invalid_argument("conditions['" + name + "']: a temperature needs an 'emissivity' in (0, 1]");
    if (entry.contains("emissivity") && !py::isinstance<py::float_>(entry["emissivity"]) &&
        !py::isinstance<py::int_>(entry["emissivity"]) && py::isinstance<py::sequence>(entry["emissivity"])) {
      // One per wavelength band (band_edges_um): a list, a tuple or a 1-D array of numbers.
      for (const py::handle v : entry["emissivity"].cast<py::sequence>()) {
        double x = 0;
        try {
          if (py::isinstance<py::bool_>(v)) throw py::cast_error();
          x = v.cast<double>();
        } catch (const py::cast_error&) {
          throw py::type_error("conditions['" + name + "']['emissivity']: expected a number or one number per band");
        }
        c.band_emissivity.push_back(x);
      }
    } else {
      c.emissivity = entry.contains("emissivity") ? number_at(entry, "emissivity", name) : 1.0;
    }
    out.push_back(c);
  }
  return out;
}

}  // namespace

void bind_thermal(py::module_& m) {
  py::class_<ThermalSolution, std::shared_ptr<ThermalSolution>>(m, "ThermalSolution", R"doc(
A thermal solve (thermal_solve), SI units: per group (names) the area (m^2), the mean temperature
(K), the mean net flux (W/m^2) and the net rate leaving (W); per element J, H, q = J - H (W/m^2) and
T (K); the environment's net rate received and the energy balance's defect.
)doc")
      .def_property_readonly("names", [](const ThermalSolution& s) { return s.names; })
      .def_property_readonly("group_area", [](const ThermalSolution& s) { return s.group_area; })
      .def_property_readonly("group_T", [](const ThermalSolution& s) { return s.group_T; })
      .def_property_readonly("group_q", [](const ThermalSolution& s) { return s.group_q; })
      .def_property_readonly("group_Q", [](const ThermalSolution& s) { return s.group_Q; })
      .def_property_readonly("environment_Q", [](const ThermalSolution& s) { return s.environment_Q; },
                             "The net rate into the environment, W (0 when the scene is enclosed).")
      .def_property_readonly("balance_defect", [](const ThermalSolution& s) { return s.balance_defect; },
                             "|sum of the groups' Q - environment_Q| / (sum of |Q| + |environment_Q|).")
      .def_property_readonly("enclosed", [](const ThermalSolution& s) { return s.enclosed; })
      .def_property_readonly("J", [](const ThermalSolution& s) { return s.J; })
      .def_property_readonly("H", [](const ThermalSolution& s) { return s.H; })
      .def_property_readonly("q", [](const ThermalSolution& s) { return s.q; })
      .def_property_readonly("T", [](const ThermalSolution& s) { return s.T; })
      .def_property_readonly("areas", [](const ThermalSolution& s) { return s.area; })
      .def_property_readonly("groups", [](const ThermalSolution& s) { return s.group; },
                             "Each element's group (an index into names).")
      .def_property_readonly("converged", [](const ThermalSolution& s) { return s.iteration.converged(); })
      .def_property_readonly("iterations", [](const ThermalSolution& s) { return s.iteration.iterations; })
      .def_property_readonly("residual", [](const ThermalSolution& s) { return s.iteration.residual; })
      .def_property_readonly("level", [](const ThermalSolution& s) { return s.level; })
      .def_property_readonly("n", [](const ThermalSolution& s) { return s.n; })
      .def_property_readonly("method", [](const ThermalSolution& s) { return s.method; })
      .def_property_readonly("seconds", [](const ThermalSolution& s) { return s.seconds; })
      .def_property_readonly("warnings", [](const ThermalSolution& s) { return s.warnings; })
      .def_property_readonly("band_edges_um", [](const ThermalSolution& s) { return s.band_edges_um; },
                             "The band edges of a band model, micrometres (empty: gray).")
      .def_property_readonly("band_rounds", [](const ThermalSolution& s) { return s.band_rounds; },
                             "Rounds of the bands' split with the temperatures (0: gray, or no flux given).")
      .def_property_readonly("band_products", [](const ThermalSolution& s) { return s.band_products; },
                             "Block products of H over all rounds (0: gray).")
      .def(
          "write",
          [](const ThermalSolution& s, py::handle prefix) {
            const std::string p = fspath(prefix);
            py::gil_scoped_release release;
            return write_thermal(s, p);
          },
          py::arg("prefix"), "Writes PREFIX_groups.csv, PREFIX.csv, PREFIX.vtk, PREFIX.ply and PREFIX.png (T), all or none; returns the paths.")
      .def("__repr__", [](const ThermalSolution& s) {
        return "<panelrad.ThermalSolution: " + std::to_string(s.names.size()) + " groups, level " +
               std::to_string(s.level) + ", n " + std::to_string(s.n) + ", " + s.method + ">";
      });

  m.def(
      "thermal_solve",
      [](std::shared_ptr<Scene> scene, py::dict conditions, py::object groups, std::optional<double> environment,
         std::optional<std::vector<double>> band_edges_um, double tolerance, std::optional<int> level, long max_elements, double accuracy, std::string method,
         std::optional<double> eta, std::optional<int> degree, std::optional<std::string> near, std::optional<int> mu,
         std::string visibility, std::optional<int> threads, py::object progress) {
        if (!scene) throw py::type_error("scene: expected a panelrad.Scene, got None");
        ThermalOptions o;
        o.solve = make_solve_options(solver_arguments(level, max_elements, accuracy, std::move(method), eta, degree,
                                                      std::move(near), mu, std::move(visibility), "auto", std::nullopt,
                                                      1000, threads, std::move(progress)));
        o.environment_temperature = environment;
        o.band_edges_um = band_edges_um.value_or(std::vector<double>{});
        o.tolerance = tolerance;
        const SurfaceGroups g = surface_groups(*scene, groups);
        const std::vector<SurfaceCondition> c = read_conditions(conditions, g);
        py::gil_scoped_release release;
        return std::make_shared<ThermalSolution>(solve_thermal(*scene, g, c, o));
      },
      py::arg("scene"), py::arg("conditions"), py::arg("groups") = "object", py::kw_only(),
      py::arg("environment") = py::none(), py::arg("band_edges_um") = py::none(), py::arg("tolerance") = 1e-9, py::arg("level") = py::none(),
      py::arg("max_elements") = 20000, py::arg("accuracy") = 0.05, py::arg("method") = "auto",
      py::arg("eta") = py::none(), py::arg("degree") = py::none(), py::arg("near") = py::none(),
      py::arg("mu") = py::none(), py::arg("visibility") = "auto", py::arg("threads") = py::none(),
      py::arg("progress") = py::none(), R"doc(
Temperatures and net radiative heat fluxes of gray diffuse surfaces, SI units (docs/thermal.md):
conditions maps every group (groups as in view_factors, default 'object') to {'T': kelvin,
'emissivity': e} or {'q': W/m^2 leaving, 'emissivity': e} (q = 0: adiabatic); environment: the
temperature in K of an open scene's (black) environment. A band (non-gray) model: band_edges_um, the
wavelengths between the bands in micrometres ([3, 8]: [0, 3], [3, 8], [8, inf)), and an
emissivity per band where a group's differs (a list; a number is the same in every band). Solved by GMRES on the radiosity equation
with rho = 1 - eps where T is given and rho = 1, E = q where q is given. Raises ArgumentError for a
missing or unknown group, a value out of range, an open scene without an environment or a closed
one where no temperature is given. Returns a ThermalSolution.
)doc");
}

}  // namespace panelrad::python

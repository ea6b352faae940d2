// panelrad.Scene: a validated polyhedral scene with rho and E per facet in each channel, built from
// numpy arrays or loaded from a file; panelrad.load_scene; panelrad.paper_cube.
#include "arrays.hpp"
#include "bindings.hpp"
#include "scene_access.hpp"

#include <panelrad/io/scene_file.hpp>
#include <panelrad/scene/scene.hpp>

#include <pybind11/stl.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace panelrad::python {

std::size_t channel_index(const Scene& scene, py::handle channel) {
  const auto& names = scene.channels();
  if (py::isinstance<py::str>(channel)) {
    const auto name = channel.cast<std::string>();
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) throw py::key_error("channel \"" + name + "\": not a channel of this scene");
    return static_cast<std::size_t>(it - names.begin());
  }
  if (!py::isinstance<py::int_>(channel) || py::isinstance<py::bool_>(channel))
    throw py::type_error("channel: expected an int or a channel name");
  const long c = channel.cast<long>();
  if (c < 0 || static_cast<std::size_t>(c) >= names.size())
    throw py::index_error("channel " + std::to_string(c) + ": the scene has " + std::to_string(names.size()) +
                          " channel(s)");
  return static_cast<std::size_t>(c);
}

std::string fspath(py::handle path) {
  return py::module_::import("os").attr("fspath")(path).cast<std::string>();
}

namespace {

enum class Quantity { reflectivity, emission };

// values: a number (every facet), an array of num_facets (per facet), or, when `channel` is None,
// an array of shape (channels, num_facets). `channel` None: every channel.
void set_values(Scene& scene, Quantity q, py::handle values, py::handle channel) {
  const char* what = q == Quantity::reflectivity ? "rho" : "E";
  std::vector<std::size_t> targets;
  if (channel.is_none()) {
    for (std::size_t c = 0; c < scene.num_channels(); ++c) targets.push_back(c);
  } else {
    targets.push_back(channel_index(scene, channel));
  }
  const auto facets = static_cast<std::size_t>(scene.num_facets());
  auto set = [&](std::size_t c, std::vector<double> per_facet) {
    if (q == Quantity::reflectivity) scene.set_reflectivity(std::move(per_facet), c);
    else scene.set_emissivity(std::move(per_facet), c);
  };
  if (py::isinstance<py::float_>(values) || py::isinstance<py::int_>(values)) {
    if (py::isinstance<py::bool_>(values)) throw py::type_error(std::string(what) + ": expected a number, got bool");
    const double v = values.cast<double>();
    for (std::size_t c : targets) set(c, std::vector<double>(facets, v));
    return;
  }
  const py::array a = py::array::ensure(values);
  if (a && a.ndim() == 2) {
    if (!channel.is_none())
      throw py::value_error(std::string(what) + ": a 2-D array gives every channel; pass channel=None");
    long rows = 0;
    const std::vector<double> all =
        read_matrix(a, static_cast<long>(scene.num_channels()), static_cast<long>(facets), what, rows);
    for (std::size_t c = 0; c < scene.num_channels(); ++c)
      set(c, std::vector<double>(all.begin() + static_cast<long>(c * facets),
                                 all.begin() + static_cast<long>((c + 1) * facets)));
    return;
  }
  if (!a) PyErr_Clear();
  const Eigen::VectorXd v = read_vector(values, facets, what);
  for (std::size_t c : targets) set(c, std::vector<double>(v.data(), v.data() + v.size()));
}

py::object facet_values(const Scene& scene, Quantity q, py::handle channel) {
  const std::size_t c = channel_index(scene, channel);
  const std::vector<double>& v = q == Quantity::reflectivity ? scene.facet_reflectivity(c) : scene.facet_emissivity(c);
  if (v.empty()) return py::none();  // given as a function (the manufactured solution's E)
  return py::array_t<double>(static_cast<py::ssize_t>(v.size()), v.data());  // a copy: a later set replaces v
}

std::shared_ptr<Scene> scene_from_arrays(py::handle vertices, py::handle triangles, py::handle rho, py::handle E,
                                         py::handle facets, std::vector<std::string> channels, std::string source) {
  geometry::TriangleMesh mesh;
  long nv = 0, nt = 0;
  const std::vector<double> xyz = read_matrix(vertices, -1, 3, "vertices", nv);
  const std::vector<geometry::Index> tri = read_indices(triangles, -1, 3, "triangles", nt);
  mesh.vertices.reserve(static_cast<std::size_t>(nv));
  for (long i = 0; i < nv; ++i) mesh.vertices.emplace_back(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  mesh.triangles.reserve(static_cast<std::size_t>(nt));
  for (long t = 0; t < nt; ++t) mesh.triangles.push_back({tri[3 * t], tri[3 * t + 1], tri[3 * t + 2]});
  if (facets.is_none()) {
    mesh.facet_of_triangle.resize(static_cast<std::size_t>(nt));
    for (long t = 0; t < nt; ++t) mesh.facet_of_triangle[static_cast<std::size_t>(t)] = static_cast<geometry::Index>(t);
    mesh.num_facets = static_cast<geometry::Index>(nt);
  } else {
    long nf = 0;
    mesh.facet_of_triangle = read_indices(facets, nt, 1, "facets", nf);
    const auto top = std::max_element(mesh.facet_of_triangle.begin(), mesh.facet_of_triangle.end());
    mesh.num_facets = top == mesh.facet_of_triangle.end() ? 0 : *top + 1;
  }
  mesh.source = std::move(source);
  std::shared_ptr<Scene> scene;
  {
    py::gil_scoped_release release;  // validation: exact predicates over the whole mesh
    scene = std::make_shared<Scene>(std::move(mesh), std::move(channels));
  }
  set_values(*scene, Quantity::reflectivity, rho, py::none());
  set_values(*scene, Quantity::emission, E, py::none());
  return scene;
}

std::string scene_repr(const Scene& s) {
  std::string channels;
  for (const auto& c : s.channels()) channels += (channels.empty() ? "" : ", ") + ("'" + c + "'");
  return "<panelrad.Scene '" + s.mesh().source + "': " + std::to_string(s.mesh().triangles.size()) + " triangles, " +
         std::to_string(s.num_facets()) + " facets, " + geometry::to_string(s.shape()) +
         (s.closed() ? ", closed" : s.enclosed() ? ", enclosed" : ", open") + ", channels (" + channels + ")" +
         (s.has_manufactured_solution() ? ", manufactured solution" : "") + ">";
}

}  // namespace

void bind_scene(py::module_& m) {
  py::class_<Scene, std::shared_ptr<Scene>> scene(m, "Scene", R"doc(
A polyhedral scene of the radiosity equation u - K u = E (1): validated planar polygons with, in
each channel, the reflectivity rho (0 <= rho < 1) and the emission E (>= 0) per input facet.

Scene(vertices, triangles, rho=0.0, E=0.0, facets=None, channels=("value",), source="arrays")

vertices: (N, 3) real array; triangles: (M, 3) integer array of vertex indices; facets: (M,)
integer array, the input facet (maximal planar polygon) of each triangle, or None (each triangle
its own facet). rho and E: a number, a (num_facets,) array, or a (channels, num_facets) array; by
default nothing reflects and nothing emits (rho = 0, E = 0): give E where the light comes from.
The mesh is validated exactly as the C++ Scene does (convex: V = 1, the paper's setting; or a
general scene whose visibility V is computed): an invalid mesh, a NaN or infinite vertex included,
raises MeshError with the validator's message. Values of rho or E that break the rule
(rho outside [0, 1), E negative, not finite, subnormal) raise ArgumentError (a ValueError) naming
the facet and channel. Arrays of any strides are read in place (no extra copy); a wrong shape is
an ArgumentError, a wrong dtype (not a real number, or not an integer for indices) an
ArgumentTypeError (a TypeError).
)doc");
  scene
      .def(py::init(&scene_from_arrays), py::arg("vertices"), py::arg("triangles"), py::arg("rho") = 0.0,
           py::arg("E") = 0.0, py::kw_only(), py::arg("facets") = py::none(),
           py::arg("channels") = std::vector<std::string>{"value"}, py::arg("source") = "arrays")
      .def_property_readonly("num_facets", &Scene::num_facets)
      .def_property_readonly("num_triangles", [](const Scene& s) { return s.mesh().triangles.size(); })
      .def_property_readonly("channels", &Scene::channels, "Channel names, e.g. ['R', 'G', 'B'].")
      .def_property_readonly("shape", [](const Scene& s) { return std::string(geometry::to_string(s.shape())); },
                             "'convex' (proven: V = 1) or 'general' (V(P, Q) is computed).")
      .def_property_readonly("closed", &Scene::closed,
                             "Every ray from a front side ends on a front side: emitted = absorbed.")
      .def_property_readonly("enclosed", &Scene::enclosed,
                             "No light leaves the scene (closed, or one-sided surfaces in a room, whose back "
                             "sides take light).")
      .def_property_readonly("notes", &Scene::notes, "What loading and validation did.")
      .def_property_readonly("facet_material", &Scene::facet_material, "Material name per facet (OBJ scenes).")
      .def_property_readonly("source", [](const Scene& s) { return s.mesh().source; })
      .def_property_readonly("has_manufactured_solution", &Scene::has_manufactured_solution)
      .def_property_readonly(
          "vertices",
          [](py::object self) {
            const auto& v = self.cast<const Scene&>().mesh().vertices;
            return view_points(v.data(), v.size(), sizeof(geometry::Vec3), self);
          },
          "(N, 3) read-only view of the validated mesh's vertices.")
      .def_property_readonly(
          "triangles",
          [](py::object self) {
            const auto& t = self.cast<const Scene&>().mesh().triangles;
            static_assert(sizeof(t[0]) == 3 * sizeof(geometry::Index));
            py::array_t<geometry::Index> a({static_cast<py::ssize_t>(t.size()), py::ssize_t{3}},
                                           {static_cast<py::ssize_t>(sizeof(t[0])), py::ssize_t{sizeof(geometry::Index)}},
                                           t.empty() ? nullptr : t[0].data(), self);
            a.attr("setflags")(py::arg("write") = false);
            return a;
          },
          "(M, 3) read-only view of the validated (oriented) triangles.")
      .def_property_readonly(
          "facets",
          [](py::object self) {
            const auto& f = self.cast<const Scene&>().mesh().facet_of_triangle;
            return view_values<geometry::Index>(f.data(), f.size(), sizeof(geometry::Index), self);
          },
          "(M,) read-only view: the input facet of each triangle.")
      .def(
          "set_reflectivity",
          [](Scene& s, py::handle rho, py::handle channel) { set_values(s, Quantity::reflectivity, rho, channel); },
          py::arg("rho"), py::arg("channel") = py::none(),
          "rho per facet: a number, (num_facets,) or (channels, num_facets); channel None sets every channel. "
          "ArgumentError naming the facet, channel and rule for a value outside [0, 1).")
      .def(
          "set_emission",
          [](Scene& s, py::handle e, py::handle channel) { set_values(s, Quantity::emission, e, channel); },
          py::arg("E"), py::arg("channel") = py::none(),
          "The emission E per facet (the light a surface gives off itself, the E of u - K u = E), as "
          "set_reflectivity; ArgumentError for E negative, not finite or subnormal.")
      .def(
          "set_environment",
          [](Scene& s, double radiosity, py::handle channel) {
            if (channel.is_none()) {
              for (std::size_t c = 0; c < s.num_channels(); ++c) s.set_environment(radiosity, c);
            } else {
              s.set_environment(radiosity, channel_index(s, channel));
            }
          },
          py::arg("radiosity"), py::arg("channel") = py::none(),
          "The environment's radiosity (the sky of an open scene), seen where no front side covers a point's "
          "hemisphere: u - K u = E + rho u_env s. channel None sets every channel; 0 (the default) is black. "
          "Not seen in an enclosed scene. ArgumentError as for E.")
      .def(
          "environment", [](const Scene& s, py::handle c) { return s.environment(channel_index(s, c)); },
          py::arg("channel") = 0, "The environment's radiosity in the channel.")
      .def(
          "reflectivity", [](const Scene& s, py::handle c) { return facet_values(s, Quantity::reflectivity, c); },
          py::arg("channel") = 0, "rho per facet of the channel (a copy), or None when given as a function.")
      .def(
          "emission", [](const Scene& s, py::handle c) { return facet_values(s, Quantity::emission, c); },
          py::arg("channel") = 0, "E per facet of the channel (a copy), or None when manufactured.")
      .def("__repr__", &scene_repr);

  m.def(
      "load_scene",
      [](py::handle path, py::handle materials, bool geometry_only) {
        LoadOptions o;
        if (!materials.is_none()) o.materials_path = fspath(materials);
        o.geometry_only = geometry_only;
        const std::string p = fspath(path);
        py::gil_scoped_release release;
        return std::make_shared<Scene>(load_scene(p, o));
      },
      py::arg("path"), py::arg("materials") = py::none(), py::arg("geometry_only") = false, R"doc(
Loads a validated scene: "builtin:NAME" (cube, prism:K, tetrahedron, octahedron; geometry only),
SCENE.obj with its MTL files (Kd -> rho, Ke -> E, channels R, G, B), SCENE.off with its JSON
sidecar (materials: the sidecar's path; default SCENE.json), or with geometry_only=True the mesh
alone (one channel 'value', rho = 0, E = 1). Raises SceneFileError, MeshError or TextFileError.
)doc");

  m.def(
      "paper_cube",
      [](double scale, std::array<double, 3> offset) {
        return std::make_shared<Scene>(make_paper_cube_scene(scale, geometry::Vec3(offset[0], offset[1], offset[2])));
      },
      py::arg("scale") = 1.0, py::arg("offset") = std::array<double, 3>{0, 0, 0}, R"doc(
The paper's cube example (31): the unit cube (or offset + scale [0,1]^3), rho = 0.5 on y = 0, 1;
0.4 on z = 0, 1; 0.3 on x = 0, 1; true solution u = x^2 + y^2 + z^2 with E manufactured as
u - K u. Solver.true_solution and Solver.max_error then give the error (51) of Table 1.
)doc");
}

}  // namespace panelrad::python

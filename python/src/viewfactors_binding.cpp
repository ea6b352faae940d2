// panelrad.view_factors: the view factors between groups of a scene's surfaces (C++
// compute_view_factors, with the GIL released), as numpy arrays; ViewFactors.write.
#include "bindings.hpp"
#include "options.hpp"
#include "scene_access.hpp"

#include <panelrad/io/view_factor_output.hpp>
#include <panelrad/viewfactors/view_factors.hpp>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace panelrad::python {

/// groups: "facet", "object", "material", or a sequence of one name per input facet
/// (groups_by_name).
SurfaceGroups surface_groups(const Scene& scene, py::handle groups) {
  if (py::isinstance<py::str>(groups)) {
    const std::string how = groups.cast<std::string>();
    if (how == "facet") return groups_by_facet(scene);
    if (how == "object") return groups_by_object(scene);
    if (how == "material") return groups_by_material(scene);
    throw std::invalid_argument("groups: '" + how + "' is not 'facet', 'object', 'material' or a name per facet");
  }
  if (!py::isinstance<py::sequence>(groups))
    throw py::type_error("groups: expected 'facet', 'object', 'material' or a sequence of one name per facet");
  std::vector<std::string> names;
  for (const py::handle item : groups.cast<py::sequence>()) {
    if (!py::isinstance<py::str>(item)) throw py::type_error("groups: every entry must be a str (a group's name)");
    names.push_back(item.cast<std::string>());
  }
  return groups_by_name(names);
}

namespace {

/// `value` when the elements were kept (ViewFactorOptions::elements), else None.
template <class T>
std::optional<T> if_elements(const ViewFactors& v, T value) {
  if (v.elements.sky.size() == 0) return std::nullopt;
  return value;
}

}  // namespace

void bind_view_factors(py::module_& m) {
  py::class_<ViewFactors, std::shared_ptr<ViewFactors>>(m, "ViewFactors", R"doc(
The view factors between groups of a scene's surfaces (view_factors): F[I, J] is the fraction of
the radiation leaving group I diffusely that reaches group J directly.
)doc")
      .def_property_readonly("names", [](const ViewFactors& v) { return v.names; }, "The groups, in the order of F's rows.")
      .def_property_readonly("area", [](const ViewFactors& v) { return v.area; }, "A_I, the groups' areas.")
      .def_property_readonly("F", [](const ViewFactors& v) { return v.F; }, "The matrix F[I, J].")
      .def_property_readonly("uncovered", [](const ViewFactors& v) { return v.uncovered; },
                             "1 - sum_J F[I, J]: the sky view factor (open scene) or the closure defect (enclosed).")
      .def_property_readonly("enclosed", [](const ViewFactors& v) { return v.enclosed; },
                             "Whether the scene is enclosed: `uncovered` is then the closure defect.")
      .def_property_readonly(
          "error",
          [](const ViewFactors& v) -> std::optional<Eigen::MatrixXd> {
            if (v.error.size() == 0) return std::nullopt;
            return v.error;
          },
          "|F(L) - F(L-1)|, the error estimate (None when not computed).")
      .def_property_readonly(
          "uncovered_error",
          [](const ViewFactors& v) -> std::optional<Eigen::VectorXd> {
            if (v.uncovered_error.size() == 0) return std::nullopt;
            return v.uncovered_error;
          },
          "The same for `uncovered` (None when not computed).")
      .def_property_readonly("reciprocity_defect", [](const ViewFactors& v) { return v.reciprocity_defect; },
                             "max |A_I F_IJ - A_J F_JI| / max(A_I F_IJ, A_J F_JI) over the pairs that exchange.")
      .def_property_readonly(
          "reciprocity_pair",
          [](const ViewFactors& v) -> std::optional<std::pair<std::string, std::string>> {
            if (v.reciprocity_I < 0) return std::nullopt;
            return std::make_pair(v.names[static_cast<std::size_t>(v.reciprocity_I)],
                                  v.names[static_cast<std::size_t>(v.reciprocity_J)]);
          },
          "The pair (I, J) of the worst reciprocity defect (None when no pair exchanges).")
      .def_property_readonly("level", [](const ViewFactors& v) { return v.level; })
      .def_property_readonly("n", [](const ViewFactors& v) { return v.n; })
      .def_property_readonly("method", [](const ViewFactors& v) { return v.method; })
      .def_property_readonly(
          "self_check_error",
          [](const ViewFactors& v) -> std::optional<double> {
            if (v.self_check_error < 0) return std::nullopt;
            return v.self_check_error;
          },
          "The fast operator's measured relative product error (None: dense).")
      .def_property_readonly("seconds", [](const ViewFactors& v) { return v.seconds; })
      .def_property_readonly(
          "element_sky",
          [](const ViewFactors& v) { return if_elements(v, v.elements.sky); },
          "With elements=True: per element of the finest level, 1 - (H 1)_i, its sky view factor (else None).")
      .def_property_readonly(
          "element_groups",
          [](const ViewFactors& v) { return if_elements(v, v.elements.group); },
          "With elements=True: each element's group (an index into names), else None.")
      .def_property_readonly(
          "element_centroids",
          [](const ViewFactors& v) {
            Eigen::MatrixX3d c(static_cast<Eigen::Index>(v.elements.centroid.size()), 3);
            for (std::size_t i = 0; i < v.elements.centroid.size(); ++i) c.row(static_cast<Eigen::Index>(i)) = v.elements.centroid[i];
            return if_elements(v, c);
          },
          "With elements=True: each element's collocation point (n x 3), else None.")
      .def_property_readonly(
          "element_areas",
          [](const ViewFactors& v) { return if_elements(v, v.elements.area); },
          "With elements=True: each element's area, else None.")
      .def_property_readonly(
          "element_factors",
          [](const ViewFactors& v) { return if_elements(v, v.elements.to); },
          "With elements_to: per element its view factor to each of those groups (n x len(elements_to), "
          "columns in their order), else None.")
      .def_property_readonly("correction", [](const ViewFactors& v) { return v.correction; },
                             "With reciprocal=True, max |F - F as computed|; else 0.")
      .def(
          "write",
          [](const ViewFactors& v, py::handle prefix) {
            const std::string p = fspath(prefix);
            py::gil_scoped_release release;
            return write_view_factors(v, p);
          },
          py::arg("prefix"),
          "Writes PREFIX.csv, PREFIX_error.csv (with the estimates), PREFIX.npy and, with the elements kept, "
          "PREFIX_elements.csv, PREFIX_elements.vtk and PREFIX_elements.ply, all or none; returns the paths.")
      .def("__repr__", [](const ViewFactors& v) {
        return "<panelrad.ViewFactors: " + std::to_string(v.names.size()) + " groups, level " + std::to_string(v.level) +
               ", n " + std::to_string(v.n) + ", " + v.method + ">";
      });

  m.def(
      "view_factors",
      [](std::shared_ptr<Scene> scene, py::object groups, bool estimate_error, bool reciprocal, bool elements,
         std::vector<std::string> elements_to, std::vector<std::string> two_sided, int block_columns,
         std::optional<int> level,
         long max_elements, double accuracy, std::string method, std::optional<double> eta, std::optional<int> degree,
         std::optional<std::string> near, std::optional<int> mu, std::string visibility, std::optional<int> threads,
         py::object progress) {
        if (!scene) throw py::type_error("scene: expected a panelrad.Scene, got None");
        ViewFactorOptions o;
        o.solve = make_solve_options(solver_arguments(level, max_elements, accuracy, std::move(method), eta, degree,
                                                      std::move(near), mu, std::move(visibility), "auto", std::nullopt,
                                                      1000, threads, std::move(progress)));
        o.estimate_error = estimate_error;
        o.reciprocal = reciprocal;
        o.elements = elements;
        o.element_targets = std::move(elements_to);
        o.block_columns = block_columns;
        const SurfaceGroups g = surface_groups(*scene, groups);
        py::gil_scoped_release release;
        if (two_sided.empty()) return std::make_shared<ViewFactors>(compute_view_factors(*scene, g, o));
        const TwoSidedScene two = with_back_sides(*scene, g, two_sided);
        return std::make_shared<ViewFactors>(compute_view_factors(two.scene, two.groups, o));
      },
      py::arg("scene"), py::arg("groups") = "facet", py::kw_only(), py::arg("estimate_error") = true,
      py::arg("reciprocal") = false, py::arg("elements") = false,
      py::arg("elements_to") = std::vector<std::string>{}, py::arg("two_sided") = std::vector<std::string>{},
      py::arg("block_columns") = 8, py::arg("level") = py::none(), py::arg("max_elements") = 20000,
      py::arg("accuracy") = 0.05, py::arg("method") = "auto", py::arg("eta") = py::none(), py::arg("degree") = py::none(),
      py::arg("near") = py::none(), py::arg("mu") = py::none(), py::arg("visibility") = "auto",
      py::arg("threads") = py::none(), py::arg("progress") = py::none(), R"doc(
The view factors between groups of the scene's surfaces: groups 'facet' (every input face),
'object' (an OBJ's o or g, an ASCII STL's solid), 'material' (the faces of one OBJ material) or a
sequence of one group name per input facet.
F[I, J] = (1 / A_I) sum_{i in I} A_i (H chi_J)_i with the solver's operator H (the line of sight
computed unless the scene is proven convex), every group's indicator in block products of
block_columns columns. With estimate_error the factors are also computed one level coarser and
|F(L) - F(L-1)| is the error estimate. With reciprocal the matrix is made reciprocal and closed
(ViewFactors.correction: by how much it moved); with elements, every element's sky view factor
(element_sky, element_groups, element_centroids, element_areas), and with elements_to (group
names) every element's view factor to each of them (element_factors). two_sided: group names
whose back sides radiate too, each as a group 'NAME (back)' after the others. The other keywords as Solver's. Returns a
ViewFactors.
)doc");
}

}  // namespace panelrad::python

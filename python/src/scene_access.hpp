#pragma once
// Small helpers shared by the scene, solver and solution bindings.
#include <panelrad/scene/scene.hpp>
#include <panelrad/viewfactors/view_factors.hpp>

#include <pybind11/pybind11.h>

#include <cstddef>
#include <string>

namespace panelrad::python {

namespace py = pybind11;

/// A channel given by index or name: IndexError / KeyError when the scene has no such channel.
std::size_t channel_index(const Scene& scene, py::handle channel);
/// os.fspath(path): a str or an os.PathLike.
std::string fspath(py::handle path);
/// groups: "facet", "object", "material", or a sequence of one name per input facet
/// (groups_by_name).
SurfaceGroups surface_groups(const Scene& scene, py::handle groups);

}  // namespace panelrad::python

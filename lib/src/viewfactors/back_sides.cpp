// Two-sided sheets for view factors (view_factors.hpp, with_back_sides): the back side of every
// facet of the chosen groups as a facet of its own, the same triangles wound the other way.
#include <panelrad/viewfactors/view_factors.hpp>

#include <algorithm>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace panelrad {

using geometry::Index;

namespace {

constexpr const char* kBackSuffix = " (back)";

bool ends_with_back(const std::string& name) {
  const std::string suffix = kBackSuffix;
  return name.size() >= suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// The group index of every name of `two_sided` (std::invalid_argument for a name that is no
/// group, one given twice, or a back side already).
std::vector<Index> chosen_groups(const SurfaceGroups& groups, const std::vector<std::string>& two_sided) {
  std::vector<Index> chosen;
  for (const std::string& name : two_sided) {
    const auto it = std::find(groups.names.begin(), groups.names.end(), name);
    if (it == groups.names.end()) throw std::invalid_argument("two-sided: '" + name + "' is not a group");
    if (ends_with_back(name)) throw std::invalid_argument("two-sided: '" + name + "' is a back side already");
    const auto g = static_cast<Index>(it - groups.names.begin());
    if (std::find(chosen.begin(), chosen.end(), g) != chosen.end())
      throw std::invalid_argument("two-sided: '" + name + "' is given twice");
    chosen.push_back(g);
  }
  return chosen;
}

}  // namespace

TwoSidedScene with_back_sides(const Scene& scene, const SurfaceGroups& groups, const std::vector<std::string>& two_sided) {
  if (const std::string why = groups_problem(scene, groups); !why.empty()) throw std::invalid_argument(why);
  const std::vector<Index> chosen = chosen_groups(groups, two_sided);
  geometry::TriangleMesh mesh = scene.mesh();
  std::vector<std::string> material = scene.facet_material();
  SurfaceGroups out = groups;
  std::map<Index, Index> back_group;  // chosen group -> its back side's group
  for (const Index g : chosen) {
    back_group[g] = static_cast<Index>(out.names.size());
    out.names.push_back(groups.names[static_cast<std::size_t>(g)] + kBackSuffix);
  }
  // The back facets, in facet order: facet f's copy is the next new facet id.
  std::map<Index, Index> back_facet;
  for (Index f = 0; f < scene.num_facets(); ++f) {
    const auto it = back_group.find(groups.of_facet[static_cast<std::size_t>(f)]);
    if (it == back_group.end()) continue;
    back_facet[f] = mesh.num_facets++;
    out.of_facet.push_back(it->second);
    if (!material.empty()) material.push_back(material[static_cast<std::size_t>(f)]);
    if (!mesh.facet_group.empty()) mesh.facet_group.push_back(mesh.facet_group[static_cast<std::size_t>(f)]);
    if (!mesh.facet_line.empty()) mesh.facet_line.push_back(mesh.facet_line[static_cast<std::size_t>(f)]);
  }
  // The back sides on copies of their corners, shared among them as among the front triangles:
  // a sheet and its back share no vertex, so they are two open surfaces back to back (both kept),
  // not one closed surface of no volume.
  // A scene's mesh is wound counter-clockwise seen from outside (Scene::triangle_inner_normal),
  // against the front side: it is wound as a file is (counter-clockwise seen from the front) to be
  // validated again, and a back side is the stored triangle.
  const std::size_t triangles = mesh.triangles.size();
  for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  std::map<Index, Index> copy;  // a front corner -> its copy
  for (std::size_t t = 0; t < triangles; ++t) {
    const auto it = back_facet.find(mesh.facet_of_triangle[t]);
    if (it == back_facet.end()) continue;
    std::array<Index, 3> back = {mesh.triangles[t][0], mesh.triangles[t][2], mesh.triangles[t][1]};
    for (Index& v : back) {
      const auto [c, added] = copy.try_emplace(v, static_cast<Index>(mesh.vertices.size()));
      if (added) mesh.vertices.push_back(mesh.vertices[static_cast<std::size_t>(v)]);
      v = c->second;
    }
    mesh.triangles.push_back(back);
    mesh.facet_of_triangle.push_back(it->second);
  }
  mesh.source += " (two-sided: " + std::to_string(chosen.size()) + " group" + (chosen.size() == 1 ? "" : "s") + ")";
  TwoSidedScene result{Scene(std::move(mesh)), std::move(out)};
  result.scene.set_facet_material(std::move(material));
  for (const std::string& note : scene.notes()) result.scene.add_note(note);
  return result;
}

}  // namespace panelrad

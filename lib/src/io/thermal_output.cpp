// A thermal solve as CSV, VTK, PLY and PNG files, written as one set (thermal_output.hpp).
#include "csv_fields.hpp"

#include <panelrad/io/scene_output.hpp>
#include <panelrad/io/text_output.hpp>
#include <panelrad/io/thermal_output.hpp>

#include <sstream>

namespace panelrad {

using io_detail::csv_field;
using io_detail::g17;

std::vector<std::string> thermal_paths(const std::string& prefix) {
  return {prefix + "_groups.csv", prefix + ".csv", prefix + ".vtk", prefix + ".ply", prefix + ".png"};
}

std::string thermal_groups_csv(const ThermalSolution& s) {
  std::ostringstream out;
  out << "group,area_m2,T_K,q_W_m2,Q_W\n";
  for (std::size_t g = 0; g < s.names.size(); ++g) {
    const auto k = static_cast<Eigen::Index>(g);
    out << csv_field(s.names[g]) << ',' << g17(s.group_area[k]) << ',' << g17(s.group_T[k]) << ','
        << g17(s.group_q[k]) << ',' << g17(s.group_Q[k]) << '\n';
  }
  out << "environment,,,," << (s.enclosed ? std::string() : g17(-s.environment_Q)) << '\n';
  return out.str();
}

std::string thermal_elements_csv(const ThermalSolution& s) {
  std::ostringstream out;
  out << "element,facet,group,x,y,z,area_m2,J_W_m2,H_W_m2,q_W_m2,T_K\n";
  for (std::size_t i = 0; i < s.facet.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    out << i << ',' << s.facet[i] << ',' << csv_field(s.names[static_cast<std::size_t>(s.group[i])]);
    for (int c = 0; c < 3; ++c) out << ',' << g17(s.centroid[i][c]);
    out << ',' << g17(s.area[k]) << ',' << g17(s.J[k]) << ',' << g17(s.H[k]) << ',' << g17(s.q[k]) << ','
        << g17(s.T[k]) << '\n';
  }
  return out.str();
}

namespace {

/// The per-element values of PREFIX.vtk and PREFIX.ply.
std::vector<CellValues> thermal_cells(const ThermalSolution& s) {
  const auto at = [](const Eigen::VectorXd& v) {
    return [&v](std::size_t i) { return v[static_cast<Eigen::Index>(i)]; };
  };
  return {
      {"group", [&s](std::size_t i) { return static_cast<double>(s.group[i]); }},
      {"area_m2", at(s.area)},
      {"J_W_m2", at(s.J)},
      {"H_W_m2", at(s.H)},
      {"q_W_m2", at(s.q)},
      {"T_K", at(s.T)}};
}

}  // namespace

std::string thermal_vtk(const ThermalSolution& s) {
  return cells_vtk("panelrad thermal solve", s.triangle, s.facet, thermal_cells(s));
}

std::string thermal_ply(const ThermalSolution& s) {
  return cells_ply("panelrad thermal solve", s.triangle, s.facet, thermal_cells(s));
}

std::string thermal_png(const ThermalSolution& s) {
  // The temperature as a scalar field of one channel, T_K: the picture's colour map runs from its
  // lowest to its highest value, and the view is chosen from the scene (no light: z up).
  ElementField f;
  f.triangle = s.triangle;
  f.inner_normal = s.inner_normal;
  f.centroid = s.centroid;
  f.area.assign(s.area.data(), s.area.data() + s.area.size());
  f.facet = s.facet;
  f.channels = {"T_K"};
  f.rho = {Eigen::VectorXd::Zero(s.area.size())};
  f.emission = {Eigen::VectorXd::Zero(s.area.size())};
  f.radiosity = {s.T};
  RenderOptions view;
  view.view_from_scene = true;
  view.up_from_scene = true;
  return radiosity_png(f, view);
}

std::vector<std::string> write_thermal(const ThermalSolution& s, const std::string& prefix) {
  const std::vector<std::string> paths = thermal_paths(prefix);
  OutputSet set;
  set.add(paths[0], thermal_groups_csv(s));
  set.add(paths[1], thermal_elements_csv(s));
  set.add(paths[2], thermal_vtk(s));
  set.add(paths[3], thermal_ply(s));
  set.add(paths[4], thermal_png(s));
  set.commit();
  return paths;
}

}  // namespace panelrad

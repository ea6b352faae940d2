#pragma once
// A thermal solve (thermal/thermal_solve.hpp) written as one set of files, all or none
// (text_output.hpp's OutputSet), SI units, 17 significant digits:
//   PREFIX_groups.csv  one row per group: group,area_m2,T_K,q_W_m2,Q_W (area-weighted mean
//                      temperature and net flux, the net heat rate leaving), then a row
//                      "environment" with the net rate leaving it (minus what it receives), so
//                      that Q_W sums to 0 up to the energy balance's defect (empty when the
//                      scene is enclosed);
//   PREFIX.csv         per element: element,facet,group,x,y,z,area_m2,J_W_m2,H_W_m2,q_W_m2,T_K;
//   PREFIX.vtk         the same per element on its triangle (legacy VTK cell data, ParaView);
//   PREFIX.ply         the same as face properties (ASCII PLY, MeshLab and ParaView);
//   PREFIX.png         a picture of T (radiosity_png's view chosen from the scene, its colour
//                      map from the lowest to the highest temperature, with a colour bar).
#include <panelrad/thermal/thermal_solve.hpp>

#include <string>
#include <vector>

namespace panelrad {

/// The paths write_thermal writes for `prefix`.
std::vector<std::string> thermal_paths(const std::string& prefix);

/// The texts of PREFIX_groups.csv, PREFIX.csv, PREFIX.vtk and PREFIX.ply, and the bytes of
/// PREFIX.png.
std::string thermal_groups_csv(const ThermalSolution& s);
std::string thermal_elements_csv(const ThermalSolution& s);
std::string thermal_vtk(const ThermalSolution& s);
std::string thermal_ply(const ThermalSolution& s);
std::string thermal_png(const ThermalSolution& s);

/// Writes the set; a failure leaves the previous files in place and throws std::runtime_error
/// naming the path. Returns the paths written.
std::vector<std::string> write_thermal(const ThermalSolution& s, const std::string& prefix);

}  // namespace panelrad

#pragma once
// The boundary conditions of `panelrad thermal` (thermal/thermal_solve.hpp), a JSON object:
//   { "groups": { "floor":   { "T": 600, "emissivity": 0.9 },       a temperature, K
//                 "walls":   { "q": 0, "emissivity": 0.8 },         a net flux leaving, W/m^2
//                 "ceiling": { "T": 300, "emissivity": 1 } },        (0: adiabatic, re-radiating)
//     "environment": { "T": 290 } }                                 or "none" (the default)
// A band (non-gray) model adds "band_edges_um": [3, 8] (the bands [0, 3], [3, 8], [8, inf) um), and
// a group's "emissivity" may then be one value per band, each in [0, 1] ([0.9, 0.2, 0.6]); a
// number is the same in every band.
// Every group of the scene (as --groups makes them) must be given, exactly one of "T" or "q" and
// an "emissivity" in (0, 1] (optional where "q" is given: it only enters the temperature there,
// default 1). Errors name the
// file, the line and the group: a missing or unknown group (with the groups there are), an unknown
// key, a value that is not a number or out of range, a key given twice. Read by the bounded reader
// (support/text_file.hpp).
#include <panelrad/thermal/thermal_solve.hpp>
#include <panelrad/viewfactors/view_factors.hpp>

#include <optional>
#include <string>
#include <vector>

namespace panelrad {

struct ThermalConditions {
  std::vector<SurfaceCondition> conditions;       ///< one per group, in the groups' order
  std::optional<double> environment_temperature;  ///< K; none when "none" or not given
  std::vector<double> band_edges_um;              ///< "band_edges_um"; empty: a gray model
};

/// Reads `path` for `groups`; SceneFileError "file:line: what" on any error.
ThermalConditions read_thermal_conditions(const std::string& path, const SurfaceGroups& groups);

}  // namespace panelrad

#pragma once
// The band model of a thermal solve (thermal_solve.hpp: Bands): the coupled band equations and the
// alternation of the emission's split among the bands with the unknown temperatures.
#include <panelrad/solve/radiosity_solver.hpp>
#include <panelrad/thermal/thermal_solve.hpp>

#include <Eigen/Core>

#include <string>
#include <vector>

namespace panelrad::thermal_detail {

/// One thermal problem on the solver's elements: per element its group's condition.
struct BandProblem {
  const RadiositySolver* solver = nullptr;
  const std::vector<SurfaceCondition>* conditions = nullptr;
  const std::vector<geometry::Index>* group = nullptr;  ///< per element
  Eigen::VectorXd area;                                 ///< per element
  Eigen::VectorXd sky;                                  ///< per element: s = 1 - H 1 (0 when enclosed)
  double environment_temperature = 0;                   ///< K; 0: none
};

struct BandAnswer {
  Eigen::VectorXd J, H, T;  ///< summed over the bands, per element; T given or found
  IterationReport iteration;
  int rounds = 0;
  double change = 0;
  int products = 0;  ///< block products of H (one per GMRES step and one per round), all rounds
  std::vector<std::string> warnings;
};

BandAnswer solve_bands(const BandProblem& problem, const ThermalOptions& options);

}  // namespace panelrad::thermal_detail

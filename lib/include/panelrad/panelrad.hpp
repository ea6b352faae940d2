#pragma once
// panelrad: the radiosity equation (1) on polyhedral scenes, by centroid collocation (section 3)
// and the fast matrix-vector product of section 4. Equation, table and section numbers in
// panelrad's comments refer to K. Atkinson and D. Chien, "A fast matrix-vector multiplication
// method for solving the radiosity equation", Advances in Computational Mathematics 12 (2000).
//
// The common path: a mesh (geometry/: read, validate exactly), a scene (scene/), its solution
// (solve/), and its files (io/, target panelrad::io). Link panelrad::panelrad and panelrad::io.
#include <panelrad/scene/errors.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/scene_solver.hpp>
#include <panelrad/io/scene_file.hpp>
#include <panelrad/io/outputs.hpp>
#include <panelrad/io/view_factor_output.hpp>
#include <panelrad/viewfactors/view_factors.hpp>
#include <panelrad/thermal/thermal_solve.hpp>
#include <panelrad/support/version.hpp>

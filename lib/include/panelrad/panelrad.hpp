#pragma once
// panelrad: the radiosity equation (1) on polyhedral scenes, by centroid collocation (section 3)
// and the fast matrix-vector product of section 4. Equation, table and section numbers in
// panelrad's comments refer to K. Atkinson and D. Chien, "A fast matrix-vector multiplication
// method for solving the radiosity equation", Advances in Computational Mathematics 12 (2000).
//
// The common path: a mesh (geometry/: read, validate exactly), a scene (scene/), its solution
// (solve/), and its files (io/, target panelrad::io). Link panelrad::panelrad and panelrad::io.
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/mesh_io.hpp>
#include <panelrad/geometry/occluders.hpp>
#include <panelrad/geometry/scene_validation.hpp>
#include <panelrad/geometry/validation.hpp>

#include <panelrad/support/chunk_pool.hpp>
#include <panelrad/support/kept_vector.hpp>
#include <panelrad/scene/errors.hpp>
#include <panelrad/support/resources.hpp>
#include <panelrad/support/version.hpp>

#include <panelrad/scene/scene.hpp>

#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/operator/clustering_parameters.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/operator/operator_factory.hpp>

#include <panelrad/solve/memory_plan.hpp>
#include <panelrad/solve/radiosity_solver.hpp>
#include <panelrad/solve/scene_solver.hpp>
#include <panelrad/solve/solvers.hpp>

#include <panelrad/io/scene_file.hpp>
#include <panelrad/io/scene_output.hpp>
#include <panelrad/io/text_output.hpp>

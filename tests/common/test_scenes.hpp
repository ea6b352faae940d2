#pragma once
// Scenes with data for the operator and solver tests (a built-in convex solid, or a general
// (non-convex) mesh after validate_scene, with rho and E the same on every facet), and operator
// options.
#include <panelrad/geometry/scene_validation.hpp>
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/scene/scene.hpp>

#include "validated_meshes.hpp"

#include <gtest/gtest.h>

#include <string>
#include <utility>

namespace panelrad::testing {

/// make_builtin(spec), validated, with rho and E on every facet (a scene's default rho is 0, and
/// the fast method does not compute the rows with rho = 0).
inline Scene reflecting_builtin(const std::string& spec, double rho = 0.5, double E = 1.0) {
  Scene scene(validated_builtin(spec));
  scene.set_reflectivity(rho);
  scene.set_emissivity(E);
  return scene;
}

/// A general scene (validate_scene must accept it, and not as convex) with the given channels and
/// rho and E on every facet of every channel (set per facet afterwards where a test needs it).
inline Scene general_scene(geometry::ValidatedMesh mesh, std::vector<std::string> channels = {"value"}, double rho = 0.5,
                           double E = 1.0) {
  EXPECT_EQ(mesh.shape(), geometry::SceneShape::general) << mesh.mesh().source;
  Scene scene(std::move(mesh), std::move(channels));
  for (std::size_t c = 0; c < scene.num_channels(); ++c) {
    scene.set_reflectivity(rho, c);
    scene.set_emissivity(E, c);
  }
  return scene;
}

/// As above, for a mesh as read (validated here: geometry::validate_mesh).
inline Scene general_scene(geometry::TriangleMesh mesh, std::vector<std::string> channels = {"value"}, double rho = 0.5,
                           double E = 1.0) {
  return general_scene(geometry::validate_mesh(std::move(mesh)), std::move(channels), rho, E);
}

/// The fast operator (section 4) with admissibility eta (41) and Taylor degree M (44).
inline OperatorOptions fast_options(double eta, int degree) {
  OperatorOptions o;
  o.method = OperatorMethod::fast;
  o.eta = eta;
  o.degree = degree;
  return o;
}

}  // namespace panelrad::testing

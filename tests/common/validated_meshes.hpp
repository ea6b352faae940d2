#pragma once
// Built-in meshes (geometry/builtin_scenes.hpp) after the exact validation that every scene's
// mesh passes (geometry::validate_closed_convex: closed, convex, oriented outward), for tests.
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/validation.hpp>

#include <gtest/gtest.h>

#include <string>

namespace panelrad::testing {

/// make_builtin(spec) ("cube", "prism:K", "tetrahedron", ...), validated; a failure is reported.
inline geometry::TriangleMesh validated_builtin(const std::string& spec) {
  geometry::TriangleMesh mesh = geometry::make_builtin(spec);
  const geometry::ValidationReport report = geometry::validate_closed_convex(mesh);
  EXPECT_TRUE(report.valid) << spec << ": " << report.message;
  return mesh;
}

}  // namespace panelrad::testing

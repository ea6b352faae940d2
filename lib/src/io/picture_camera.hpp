#pragma once
// The picture's camera (internal to panelrad_io): orthographic along a direction, or a pinhole
// eye chosen from the scene; the projection of a point and the test of which side of an element
// the camera sees.
#include <panelrad/geometry/mesh.hpp>
#include <panelrad/io/scene_output.hpp>
#include <panelrad/solve/element_field.hpp>

namespace panelrad::io_detail {

/// d is the unit direction from the scene towards the viewer; r and u are the screen's right and
/// up, with r x u = d. A perspective camera sits at `eye` and looks along -d.
struct Camera {
  bool perspective = false;
  geometry::Vec3 eye = geometry::Vec3::Zero();
  geometry::Vec3 d, r, u;
};

/// A point on the screen plane (x right, y up) and its depth, larger = nearer the viewer.
/// Orthographic: x = p.r, y = p.u, depth = p.d. Perspective: with q = p - eye and the distance
/// in front of the eye z = -q.d > 0, x = q.r / z, y = q.u / z and depth = 1 / z (linear across a
/// triangle's image, so that the depth test compares exact planes).
struct Projection {
  double x, y, depth;
};

Camera orthographic_camera(const geometry::Vec3& view_direction, const geometry::Vec3& up);

Projection project(const Camera& camera, const geometry::Vec3& p);

/// The front side (inner normal n) of the plane through `point` faces the camera.
bool sees_front(const Camera& camera, const geometry::Vec3& point, const geometry::Vec3& n);

/// The scene's upward direction when the options leave it to the scene (RenderOptions).
geometry::Vec3 scene_up(const ElementField& field);

/// The camera the options ask for: view_direction and up, or chosen from the (validated) field.
Camera picture_camera(const ElementField& field, const RenderOptions& options);

/// brightest_view_direction() in the frame whose third axis is `up` (z: the fixed diagonals).
geometry::Vec3 brightest_diagonal(const ElementField& field, const geometry::Vec3& up);

}  // namespace panelrad::io_detail

// The picture's viewpoint. A room (a surface whose front sides, the inner normals n, face inward)
// is shown as the Cornell box is in the literature: a pinhole eye in front of its open side,
// level with its centre, looking in, the scene's up upwards; a closed room from outside one of
// its walls, which the eye sees from behind and so leaves out. Any other scene (bodies seen from
// outside) is shown orthographically along the diagonal that sees the most light.
#include "picture_camera.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace panelrad::io_detail {

using geometry::Vec3;

namespace {

/// The light the viewer sees along the unit direction `towards_viewer` in an orthographic
/// cut-away view: sum over the elements whose front side faces the viewer of
/// area (n . d) sum_c u_c.
double light_towards(const ElementField& field, const Vec3& towards_viewer) {
  double light = 0;
  for (std::size_t i = 0; i < field.size(); ++i) {
    const double facing = field.inner_normal[i].dot(towards_viewer);
    if (facing <= 0) continue;  // not visible in the cut-away view
    double u = 0;
    for (const Eigen::VectorXd& r : field.radiosity) u += r[static_cast<Eigen::Index>(i)];
    light += field.area[i] * facing * u;
  }
  return light;
}

/// Two unit directions a, b across the unit `up`, with a x b = up: a is the coordinate axis least
/// along up (the first of x, y, z on a tie) made orthogonal to it; for up = z, a = x and b = y.
void across(const Vec3& up, Vec3* a, Vec3* b) {
  int k = 0;
  up.cwiseAbs().minCoeff(&k);
  const Vec3 e = Vec3::Unit(k);
  *a = (e - e.dot(up) * up).normalized();
  *b = up.cross(*a);
}

Vec3 box_centre(const ElementField& field) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& t : field.triangle)
    for (const Vec3& p : t) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  return 0.5 * (lo + hi);
}

/// A room: the front sides face the scene's centre m more than away from it,
/// sum area (n . (m - P)) / |m - P| > 0 over the elements (collocation points P). The walls of a
/// room face inward; a body's faces, and a room's own bodies, face outward.
bool is_room(const ElementField& field) {
  const Vec3 m = box_centre(field);
  double inward = 0;
  for (std::size_t i = 0; i < field.size(); ++i) {
    const Vec3 to_centre = m - field.centroid[i];
    const double dist = to_centre.norm();
    if (dist > 0) inward += field.area[i] * field.inner_normal[i].dot(to_centre) / dist;
  }
  return inward > 0;
}

/// The direction from a room towards the eye. A closed surface has sum area n = 0; a room with
/// an open side (the Cornell box's front) lacks the opening's face, whose inner normal points
/// into the room, so sum area n points out through the opening: the eye goes there, level with
/// the room's centre unless the opening faces up or down. A closed room (the sum below 2% of the
/// area) is seen through one of its walls: the eye goes along the one of the four directions
/// across up whose far walls (front sides towards the eye) show the most light (ties: the first
/// of -b, -a, b, a).
Vec3 room_view(const ElementField& field, const Vec3& up) {
  Vec3 open = Vec3::Zero();
  double area = 0;
  for (std::size_t i = 0; i < field.size(); ++i) {
    open += field.area[i] * field.inner_normal[i];
    area += field.area[i];
  }
  if (open.norm() > 0.02 * area) {
    const Vec3 level = open - open.dot(up) * up;
    return level.norm() > 0.5 * open.norm() ? level.normalized() : open.normalized();
  }
  Vec3 a, b;
  across(up, &a, &b);
  Vec3 best = -b;
  double best_light = -1;
  for (const Vec3& d : {Vec3(-b), Vec3(-a), b, a}) {
    const double light = light_towards(field, d);
    if (light > best_light * (1 + 1e-12)) {
      best_light = light;
      best = d;
    }
  }
  return best;
}

/// A pinhole eye on the line from the scene's centre m along the unit v, outside the scene: beyond
/// its farthest point along v by its width across v (about 40 degrees of view, as the Cornell box's
/// camera), so that every point lies in front of the eye.
Camera eye_camera(const ElementField& field, const Vec3& v, const Vec3& up) {
  const Vec3 m = box_centre(field);
  double ahead = 0, across_v = 0;
  for (const auto& t : field.triangle)
    for (const Vec3& p : t) {
      const Vec3 q = p - m;
      ahead = std::max(ahead, q.dot(v));
      across_v = std::max(across_v, (q - q.dot(v) * v).norm());
    }
  const double distance = across_v > 0 ? 2 * across_v : 1.0;
  Camera c = orthographic_camera(v, up);
  c.perspective = true;
  c.eye = m + (ahead + distance) * v;
  return c;
}

}  // namespace

Camera orthographic_camera(const Vec3& view_direction, const Vec3& up) {
  const Vec3 d = view_direction.normalized();
  const Vec3 w = up.normalized();
  // Along `up` itself the screen's up is the next axis after up's largest component.
  int k = 0;
  w.cwiseAbs().maxCoeff(&k);
  const Vec3 up0 = std::abs(d.dot(w)) > 1.0 - 1e-9 ? Vec3::Unit((k + 2) % 3) : w;
  const Vec3 r = up0.cross(d).normalized();
  const Vec3 u = d.cross(r);
  Camera c;
  c.d = d;
  c.r = r;
  c.u = u;
  return c;
}

Projection project(const Camera& camera, const Vec3& p) {
  if (!camera.perspective) return Projection{p.dot(camera.r), p.dot(camera.u), p.dot(camera.d)};
  const Vec3 q = p - camera.eye;
  const double z = -q.dot(camera.d);
  return Projection{q.dot(camera.r) / z, q.dot(camera.u) / z, 1.0 / z};
}

bool sees_front(const Camera& camera, const Vec3& point, const Vec3& n) {
  if (!camera.perspective) return n.dot(camera.d) > 0.0;
  return n.dot(camera.eye - point) > 0.0;
}

Vec3 scene_up(const ElementField& field) {
  // The lights hang from the ceiling facing down: their front sides, weighted by what they emit,
  // point against up. Data are written y up (OBJ, the Cornell box) or z up; x is never up.
  Vec3 down = Vec3::Zero();
  for (std::size_t i = 0; i < field.size(); ++i) {
    double e = 0;
    for (const Eigen::VectorXd& c : field.emission) e += c[static_cast<Eigen::Index>(i)];
    if (e > 0) down += field.area[i] * e * field.inner_normal[i];
  }
  const double cos15 = std::cos(15.0 * 3.14159265358979323846 / 180.0);
  if (down.norm() > 0 && std::abs(down.y()) >= cos15 * down.norm())
    return down.y() < 0 ? Vec3::UnitY() : Vec3(-Vec3::UnitY());
  if (down.norm() > 0 && std::abs(down.z()) >= cos15 * down.norm())
    return down.z() < 0 ? Vec3::UnitZ() : Vec3(-Vec3::UnitZ());
  return Vec3::UnitZ();
}

Vec3 brightest_diagonal(const ElementField& field, const Vec3& up) {
  Vec3 a, b;
  across(up, &a, &b);
  Vec3 best = -1.0 * a - 1.7 * b + 1.2 * up;
  double best_light = -1;
  for (int k = 0; k < 8; ++k) {
    const Vec3 d = ((k & 1) ? 1.0 : -1.0) * a + ((k & 2) ? 1.7 : -1.7) * b + ((k & 4) ? -1.2 : 1.2) * up;
    const double light = light_towards(field, d.normalized());
    if (light > best_light * (1 + 1e-12)) {
      best_light = light;
      best = d;
    }
  }
  return best;
}

Camera picture_camera(const ElementField& field, const RenderOptions& options) {
  const Vec3 up = options.up_from_scene ? scene_up(field) : options.up;
  if (!options.view_from_scene) return orthographic_camera(options.view_direction, up);
  const Vec3 w = up.normalized();
  if (!is_room(field)) return orthographic_camera(brightest_diagonal(field, w), w);
  return eye_camera(field, room_view(field, w), w);
}

}  // namespace panelrad::io_detail

// The picture's default viewpoint (RenderOptions::view_from_scene, up_from_scene), checked on the
// frame the picture is made of (which element is seen at each sample) and on the frame's own
// projection of the elements: a room shows its light and the walls the light shines on, inside
// the frame and not hidden; a body seen from outside shows only front sides, and its light.
#include "../../lib/src/io/picture_frame.hpp"

#include <panelrad/io/scene_file.hpp>
#include <panelrad/io/scene_output.hpp>
#include <panelrad/solve/scene_solver.hpp>

#include "unit_cube_elements.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <array>
#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace {

using panelrad::ElementField;
using panelrad::geometry::Vec3;
using panelrad::io_detail::Frame;
using panelrad::io_detail::kSamples;

ElementField solved(const std::string& scene_file, int level) {
  const panelrad::Scene scene =
      panelrad::load_scene(std::string(PANELRAD_SOURCE_DIR) + "/examples/scenes/" + scene_file);
  panelrad::SolveOptions o;
  o.level = level;
  return panelrad::solve_scene(scene, o).field;
}

Frame default_frame(const ElementField& field) {
  panelrad::RenderOptions o;
  o.view_from_scene = true;
  o.up_from_scene = true;
  return panelrad::io_detail::draw_frame(field, o);
}

bool emits(const ElementField& f, std::size_t i) {
  for (const Eigen::VectorXd& e : f.emission)
    if (e[static_cast<Eigen::Index>(i)] > 0) return true;
  return false;
}

/// What the frame shows of a set of elements: the area of their images (in samples, from the
/// frame's projection), the samples where they are seen, and whether every corner lies in the
/// plot area.
struct Seen {
  double projected = 0;
  double samples = 0;
  bool in_frame = true;
};

Seen seen(const Frame& frame, const ElementField& f, const std::vector<std::size_t>& elements) {
  Seen s;
  std::map<std::int32_t, int> count;
  for (const std::int32_t e : frame.element) ++count[e];
  for (const std::size_t i : elements) {
    std::array<std::array<double, 2>, 3> p;
    for (int k = 0; k < 3; ++k) {
      p[static_cast<std::size_t>(k)] = panelrad::io_detail::frame_position(frame, f.triangle[i][static_cast<std::size_t>(k)]);
      const auto& q = p[static_cast<std::size_t>(k)];
      s.in_frame = s.in_frame && q[0] >= 0 && q[0] <= kSamples * frame.plot_w && q[1] >= 0 && q[1] <= frame.h;
    }
    s.projected += 0.5 * std::abs((p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[1][1] - p[0][1]) * (p[2][0] - p[0][0]));
    s.samples += count[static_cast<std::int32_t>(i)];
  }
  return s;
}

/// The camera sees the front side (inner normal n) of element i.
bool front_faces_camera(const Frame& frame, const ElementField& f, std::size_t i) {
  const Vec3& n = f.inner_normal[i];
  return frame.camera.perspective ? n.dot(frame.camera.eye - f.centroid[i]) > 0 : n.dot(frame.camera.d) > 0;
}

/// A room's checks: its lights (E > 0) are in the frame and at least 90% visible; each large
/// facet the light shines on (at least 5% of the area, every element's front side facing the
/// lights' centre) is in the frame and at least 30% visible (the blocks hide part of a floor or a
/// wall), except at most `through` of them (the wall a closed room is seen through); the floor
/// (the lit facet whose front side faces the lights' most directly) is never one of those.
void expect_room_shows_its_light(const ElementField& f, const std::string& name, int through) {
  const Frame frame = default_frame(f);
  std::vector<std::size_t> lights;
  Vec3 light_centre = Vec3::Zero(), light_normal = Vec3::Zero();
  double light_area = 0, total_area = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    total_area += f.area[i];
    if (!emits(f, i)) continue;
    lights.push_back(i);
    light_centre += f.area[i] * f.centroid[i];
    light_normal += f.area[i] * f.inner_normal[i];
    light_area += f.area[i];
  }
  ASSERT_FALSE(lights.empty()) << name;
  light_centre /= light_area;
  const Seen light = seen(frame, f, lights);
  EXPECT_TRUE(light.in_frame) << name << ": the light leaves the frame";
  EXPECT_GE(light.samples, 0.9 * light.projected) << name << ": the light is hidden or turned away";

  std::map<panelrad::geometry::Index, std::vector<std::size_t>> facets;
  std::map<panelrad::geometry::Index, bool> lit;
  std::map<panelrad::geometry::Index, double> area;
  for (std::size_t i = 0; i < f.size(); ++i) {
    const auto facet = f.facet[i];
    facets[facet].push_back(i);
    area[facet] += f.area[i];
    const bool faces_light = !emits(f, i) && f.inner_normal[i].dot(light_centre - f.centroid[i]) > 0;
    lit[facet] = (lit.count(facet) ? lit[facet] : true) && faces_light;
  }
  int checked = 0, hidden = 0;
  double floor_facing = 0;
  bool floor_seen = false;
  for (const auto& [facet, elements] : facets) {
    if (!lit[facet] || area[facet] < 0.05 * total_area) continue;
    ++checked;
    const Seen wall = seen(frame, f, elements);
    const bool shown = wall.in_frame && wall.samples >= 0.3 * wall.projected;
    if (!shown) ++hidden;
    const double facing = -f.inner_normal[elements[0]].dot(light_normal.normalized());
    if (facing > floor_facing) {
      floor_facing = facing;
      floor_seen = shown;
    }
  }
  EXPECT_GE(checked, 4) << name << ": the floor and the walls around it";
  EXPECT_LE(hidden, through) << name << ": lit walls hidden or out of the frame";
  EXPECT_TRUE(floor_seen) << name << ": the floor under the light is hidden or out of the frame";
}

TEST(DefaultView, CornellBoxIsSeenThroughItsOpenSideWithTheLight) {
  const ElementField f = solved("cornell_box.obj", 1);
  expect_room_shows_its_light(f, "cornell_box", 0);
  const Frame frame = default_frame(f);
  // The data's y is up on the screen; the eye is in front of the open side z = 0.
  EXPECT_GT(frame.camera.u.y(), 0.99);
  EXPECT_TRUE(frame.camera.perspective);
  EXPECT_LT(frame.camera.eye.z(), 0.0);
}

TEST(DefaultView, ClosedRoomIsSeenThroughAWall) {
  expect_room_shows_its_light(solved("convex_box.obj", 1), "convex_box", 1);
}

/// The unit cube seen from outside (front sides outward), each face split into m x m squares of
/// two triangles; the face x = 1 is a lamp.
ElementField lit_body(int m) {
  ElementField f;
  f.channels = {"u"};
  std::vector<double> u, e;
  panelrad::testing::for_each_unit_cube_triangle(m, [&](int facet, const Vec3& outward, const std::array<Vec3, 3>& t) {
    f.triangle.push_back(t);
    f.inner_normal.push_back(outward);
    f.centroid.push_back((t[0] + t[1] + t[2]) / 3.0);
    f.area.push_back(0.5 * (t[1] - t[0]).cross(t[2] - t[0]).norm());
    f.facet.push_back(facet);
    e.push_back(facet == 1 ? 1.0 : 0.0);
    u.push_back(facet == 1 ? 1.0 : 0.1 + 0.01 * facet);
  });
  const auto vec = [](const std::vector<double>& v) { return Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()))); };
  f.rho = {Eigen::VectorXd::Constant(static_cast<Eigen::Index>(u.size()), 0.5)};
  f.emission = {vec(e)};
  f.radiosity = {vec(u)};
  return f;
}

TEST(DefaultView, BodyIsSeenFromOutsideShowingFrontSidesAndItsLight) {
  const ElementField f = lit_body(3);
  const Frame frame = default_frame(f);
  std::size_t drawn = 0;
  for (const std::int32_t e : frame.element) {
    if (e < 0) continue;
    ++drawn;
    ASSERT_TRUE(front_faces_camera(frame, f, static_cast<std::size_t>(e))) << "element " << e << " is a back side";
  }
  EXPECT_GT(drawn, static_cast<std::size_t>(frame.w) * static_cast<std::size_t>(frame.h) / 10);
  std::vector<std::size_t> lamp;
  for (std::size_t i = 0; i < f.size(); ++i)
    if (emits(f, i)) lamp.push_back(i);
  const Seen s = seen(frame, f, lamp);
  EXPECT_TRUE(s.in_frame);
  EXPECT_GE(s.samples, 0.9 * s.projected) << "the lamp is hidden or turned away";
  EXPECT_GT(s.projected, 0.0);
}

}  // namespace

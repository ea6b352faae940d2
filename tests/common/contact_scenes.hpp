#pragma once
// Scenes of solids in contact, written as an exporter would write them: OBJ text whose quads start
// at any corner (so that the reader's fan takes either diagonal), over shared or separate vertex
// lines (the reader merges coincident vertices), in 6 decimals, 9 or 17 significant digits, moved
// and scaled. Each scene is closed (a room [0, 1]^3 wound inward with closed bodies inside, wound
// outward), so that the closed-scene oracle u = c of oracle_scenes.hpp applies whatever the
// contacts: where two solids touch, the touching parts are inside matter and leave the scene.
#include "oracle_scenes.hpp"

#include <panelrad/geometry/mesh_io.hpp>

#include <Eigen/Geometry>

#include <array>
#include <cstdio>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace panelrad::testing {

/// A planar polygon, its corners counter-clockwise seen from its front side (local coordinates).
using Polygon = std::vector<Vec3>;

/// The six faces of the axis box [lo, hi], counter-clockwise seen from outside (`outward`) or from
/// inside.
inline std::vector<Polygon> box_polygons(const Vec3& lo, const Vec3& hi, bool outward) {
  const double x0 = lo.x(), y0 = lo.y(), z0 = lo.z(), x1 = hi.x(), y1 = hi.y(), z1 = hi.z();
  std::vector<Polygon> faces = {
      {{x0, y0, z0}, {x0, y1, z0}, {x1, y1, z0}, {x1, y0, z0}},  // z = z0
      {{x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}},  // z = z1
      {{x0, y0, z0}, {x1, y0, z0}, {x1, y0, z1}, {x0, y0, z1}},  // y = y0
      {{x0, y1, z0}, {x0, y1, z1}, {x1, y1, z1}, {x1, y1, z0}},  // y = y1
      {{x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0}},  // x = x0
      {{x1, y0, z0}, {x1, y1, z0}, {x1, y1, z1}, {x1, y0, z1}},  // x = x1
  };
  if (!outward)
    for (Polygon& f : faces) std::reverse(f.begin() + 1, f.end());
  return faces;
}

/// A scene of polygons and its name.
struct PolygonScene {
  std::string name;
  std::vector<Polygon> faces;
  void add(const std::vector<Polygon>& more) { faces.insert(faces.end(), more.begin(), more.end()); }
};

/// The room [0, 1]^3 wound inward (its front sides face the room).
inline PolygonScene room_scene(std::string name) {
  return {std::move(name), box_polygons(Vec3(0, 0, 0), Vec3(1, 1, 1), false)};
}

/// A closed room with bodies that touch each other or the room: the families of contacts.
inline std::vector<PolygonScene> contact_families() {
  std::vector<PolygonScene> out;
  const auto body = [](PolygonScene& s, Vec3 lo, Vec3 hi) { s.add(box_polygons(lo, hi, true)); };
  {
    PolygonScene s = room_scene("two boxes stacked in mid-air, one footprint");
    body(s, {0.3, 0.3, 0.2}, {0.6, 0.6, 0.4});
    body(s, {0.3, 0.3, 0.4}, {0.6, 0.6, 0.6});
    out.push_back(s);
  }
  {
    PolygonScene s = room_scene("a stack of three boxes of one footprint on the floor");
    body(s, {0.3, 0.3, 0.0}, {0.6, 0.6, 0.2});
    body(s, {0.3, 0.3, 0.2}, {0.6, 0.6, 0.4});
    body(s, {0.3, 0.3, 0.4}, {0.6, 0.6, 0.6});
    out.push_back(s);
  }
  {
    PolygonScene s = room_scene("steps: a box on a longer box on the floor, flush on three sides");
    body(s, {0.2, 0.3, 0.0}, {0.7, 0.6, 0.2});
    body(s, {0.2, 0.3, 0.2}, {0.45, 0.6, 0.4});
    out.push_back(s);
  }
  {
    PolygonScene s = room_scene("a shelf against the wall x = 0, under a shelf flush with it");
    body(s, {0.0, 0.3, 0.5}, {0.25, 0.7, 0.55});
    body(s, {0.0, 0.3, 0.55}, {0.25, 0.7, 0.65});
    out.push_back(s);
  }
  {
    PolygonScene s = room_scene("a table: four legs on the floor, a top on the legs");
    for (const auto& [x, y] : std::vector<std::array<double, 2>>{{0.2, 0.2}, {0.65, 0.2}, {0.2, 0.65}, {0.65, 0.65}})
      body(s, {x, y, 0.0}, {x + 0.05, y + 0.05, 0.4});
    body(s, {0.2, 0.2, 0.4}, {0.7, 0.7, 0.45});
    out.push_back(s);
  }
  {
    PolygonScene s = room_scene("two boxes face to face in mid-air");
    body(s, {0.2, 0.3, 0.25}, {0.5, 0.6, 0.55});
    body(s, {0.5, 0.3, 0.25}, {0.8, 0.6, 0.55});
    out.push_back(s);
  }
  {
    // The floor as a 3 x 3 grid of tiles, a box exactly on the middle tile.
    PolygonScene s{"a box exactly on one floor tile", {}};
    std::vector<Polygon> room = box_polygons(Vec3(0, 0, 0), Vec3(1, 1, 1), false);
    const double g[4] = {0.0, 0.3, 0.6, 1.0};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        s.faces.push_back({{g[i], g[j], 0}, {g[i + 1], g[j], 0}, {g[i + 1], g[j + 1], 0}, {g[i], g[j + 1], 0}});
    s.faces.insert(s.faces.end(), room.begin() + 1, room.end());
    body(s, {0.3, 0.3, 0.0}, {0.6, 0.6, 0.3});
    out.push_back(s);
  }
  {
    PolygonScene s = room_scene("a box in the room's corner, against two walls and the floor");
    body(s, {0.0, 0.0, 0.0}, {0.3, 0.3, 0.3});
    out.push_back(s);
  }
  for (int walls = 1; walls <= 3; ++walls) {
    // 1e-13 of the room: far below the visibility's resolution (1e-12 of the scene plus 64 eps
    // of its coordinates, times four), so the bodies are in contact for it.
    const double h = 1e-13;
    PolygonScene s = room_scene("a box a hair (1e-13) from " + std::to_string(walls) + (walls == 1 ? " wall" : " walls"));
    body(s, {h, walls >= 2 ? h : 0.2, walls >= 3 ? h : 0.2}, {0.3, 0.5, 0.5});
    out.push_back(s);
  }
  return out;
}

/// How a scene is written.
struct Writing {
  int first_corner = 0;   ///< each quad starts at this corner; -1: a random corner per quad
  bool separate = false;  ///< each face its own vertex lines (the reader merges them)
  int digits = 17;        ///< 6: six decimals (%.6f); otherwise significant digits (%.<d>g)
  Frame frame{"origin", 1.0, Vec3::Zero()};
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  ///< about the room's centre, before the frame
  std::uint64_t seed = 1;

  std::string describe() const {
    char s[1024];
    const Eigen::Quaterniond q(rotation);
    char r[256] = "";
    if (!rotation.isIdentity())
      std::snprintf(r, sizeof r, ", rotated by the quaternion (%.17g, %.17g, %.17g, %.17g)", q.w(), q.x(), q.y(), q.z());
    std::snprintf(s, sizeof s, "%s, %s vertices, %s, %s%s", first_corner < 0 ? "random first corners"
                                                         : ("quads from corner " + std::to_string(first_corner)).c_str(),
                  separate ? "separate" : "shared", digits == 6 ? "6 decimals" : (std::to_string(digits) + " digits").c_str(),
                  frame.describe().c_str(), r);
    return s;
  }
};

/// A rotation drawn uniformly (a normalized Gaussian quaternion) from `rng`.
inline Eigen::Matrix3d random_rotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  q.normalize();
  return q.toRotationMatrix();
}

/// The scene as OBJ text.
inline std::string obj_text(const PolygonScene& scene, const Writing& w) {
  std::mt19937_64 rng(w.seed);
  std::ostringstream obj;
  std::map<std::string, long> index;
  long count = 0;
  const auto text = [&](const Vec3& local) {
    const Vec3 centre(0.5, 0.5, 0.5);
    const Vec3 p = w.frame.place(centre + w.rotation * (local - centre));
    char s[160];
    if (w.digits == 6)
      std::snprintf(s, sizeof s, "%.6f %.6f %.6f", p.x(), p.y(), p.z());
    else
      std::snprintf(s, sizeof s, "%.*g %.*g %.*g", w.digits, p.x(), w.digits, p.y(), w.digits, p.z());
    return std::string(s);
  };
  std::ostringstream faces;
  for (const Polygon& f : scene.faces) {
    const std::size_t n = f.size();
    const std::size_t k = w.first_corner >= 0 ? static_cast<std::size_t>(w.first_corner) % n
                                              : static_cast<std::size_t>(rng() % n);
    faces << "f";
    for (std::size_t c = 0; c < n; ++c) {
      const std::string v = text(f[(k + c) % n]);
      auto it = index.find(v);
      if (w.separate || it == index.end()) {
        obj << "v " << v << "\n";
        it = index.insert_or_assign(v, ++count).first;
      }
      faces << " " << it->second;
    }
    faces << "\n";
  }
  return obj.str() + faces.str();
}

/// The scene read back as a user's file is read.
inline TriangleMesh read_scene(const PolygonScene& scene, const Writing& w) {
  std::istringstream in(obj_text(scene, w));
  return geometry::read_obj(in, scene.name + ", " + w.describe());
}

}  // namespace panelrad::testing

#pragma once
// Scenes whose discrete radiosity solution is known exactly (oracles), for tests of the occluded
// radiosity equation (1) on general scenes, and the runner that checks the first kind.
//
// Closed scenes: every ray leaving a front side ends on a front side, so at every collocation
// point P_i the visible form factors of the surface sum to 1 and (K 1)_i = rho_i. With
// E = c (1 - rho), the collocation system (I - K) u = E then has the solution u = c 1 exactly, for
// any rho per facet: rho varies by facet so that a wrong row cannot hide behind a constant.
// Where the orientation rule reads closed pieces as a solid (its outer surface an object facing the
// unbounded air), the same system says more: an element in bounded air (a room, a closed cavity)
// still has u = c exactly, its row being a closed scene's; an element in the unbounded air that
// sees nothing (no vertex of the scene in front of its plane) has a zero row, so u = E exactly;
// any other element in the unbounded air has E <= u <= c: K >= 0 entrywise with rows summing to
// at most rho <= 0.7, so (I - K)^-1 = sum_k K^k >= 0; then u = c - w with w = (I - K)^-1 c (rho -
// K 1) >= 0, and u = E + K u >= E as u = (I - K)^-1 E >= 0.
//
// Open scenes with direct lighting (a lamp above a receiving face that sees nothing else lit):
// u_i = rho_i F_vis(P_i -> lamp), checked against the closed-form rectangle factor of
// configuration_factors.hpp.
//
// Every scene is described in local coordinates and placed by a Frame, x -> offset + scale x,
// each coordinate rounded to double once. A coordinate that several faces share (a box standing on
// the floor shares the floor's z) is one Coord, placed once, so that the faces meet on the same
// double wherever the scene sits. A gap from a shared coordinate is added after placing it, and is
// at least four spacings of the doubles there: representable at any magnitude (at 1e8 doubles are
// 2^-26 ~ 1.5e-8 apart), and wider than the rounding of a face's centroid (about one spacing), so
// that every collocation point stays on its own side of the gap.
#include <panelrad/geometry/mesh.hpp>
#include <panelrad/geometry/mesh_io.hpp>
#include <panelrad/geometry/occluders.hpp>
#include <panelrad/geometry/scene_validation.hpp>
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/radiosity_solver.hpp>

#include "configuration_factors.hpp"
#include "occluded_scenes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <functional>
#include <limits>
#include <ostream>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace panelrad::testing {

// ------------------------------------------------------------------------------------------------
// Frames and coordinates

/// Where a scene sits: the local point x becomes offset + scale x.
struct Frame {
  std::string name;  ///< letters only (a test-name suffix)
  double scale = 1;
  Vec3 offset = Vec3::Zero();

  double place(int axis, double local) const { return offset[axis] + scale * local; }
  Vec3 place(const Vec3& local) const { return Vec3(place(0, local.x()), place(1, local.y()), place(2, local.z())); }
  std::string describe() const {
    char s[160];
    std::snprintf(s, sizeof s, "frame %s (x -> (%.17g, %.17g, %.17g) + %.17g x)", name.c_str(), offset.x(),
                  offset.y(), offset.z(), scale);
    return s;
  }
};

/// gtest's printer for test parameters.
inline void PrintTo(const Frame& frame, std::ostream* os) { *os << frame.describe(); }

/// The frames every deterministic oracle scene is checked in: at the origin, moved to 1e8 (both
/// signs), scaled down by 1e3 and up by 1e3.
inline std::vector<Frame> oracle_frames() {
  return {{"origin", 1.0, Vec3::Zero()},
          {"far", 1.0, Vec3(1e8, -1e8, 1e8)},
          {"small", 1e-3, Vec3::Zero()},
          {"large", 1e3, Vec3::Zero()}};
}

/// A coordinate along one axis: `base` (local), shared by every face that uses the same Coord,
/// followed by signed gaps (local units). Placed in a frame, the base is placed first and each gap
/// is then added, widened to four spacings of the doubles at that coordinate when it is narrower:
/// a gap of 0 lands on the very same double (touching faces), a positive gap on a larger one.
struct Coord {
  double base = 0;
  std::vector<double> gaps;

  Coord() = default;
  Coord(double b) : base(b) {}  // NOLINT: implicit, so that plain numbers read as coordinates
  Coord plus(double gap) const {
    Coord c = *this;
    c.gaps.push_back(gap);
    return c;
  }
  /// The local value (for clearances and messages).
  double local() const {
    double x = base;
    for (double g : gaps) x += g;
    return x;
  }
  std::string describe() const {
    char s[64];
    std::snprintf(s, sizeof s, "%.17g", base);
    std::string out = s;
    for (double g : gaps) {
      std::snprintf(s, sizeof s, " %c %.3g", g < 0 ? '-' : '+', std::abs(g));
      out += s;
    }
    return out;
  }
};

inline double place(const Frame& frame, int axis, const Coord& c) {
  double x = frame.place(axis, c.base);
  for (double g : c.gaps) {
    if (g == 0) continue;
    const double y = x + frame.scale * g;
    const double least = 4 * (std::nextafter(std::abs(x), std::numeric_limits<double>::infinity()) - std::abs(x));
    x = std::abs(y - x) >= least ? y : x + std::copysign(least, g);
  }
  return x;
}

/// Whether two coordinates land on the same double in every frame: the same base and the same
/// nonzero gaps (a zero gap adds nothing).
inline bool same_place(const Coord& a, const Coord& b) {
  if (a.base != b.base) return false;
  std::vector<double> ga, gb;
  for (double g : a.gaps)
    if (g != 0) ga.push_back(g);
  for (double g : b.gaps)
    if (g != 0) gb.push_back(g);
  return ga == gb;
}

/// BoxFront's other side.
inline BoxFront flipped(BoxFront f) { return f == BoxFront::inside ? BoxFront::outside : BoxFront::inside; }
inline const char* to_string(BoxFront f) { return f == BoxFront::inside ? "wound inward" : "wound outward"; }

/// Appends the planar polygon `corners` as one facet (add_polygon), its order reversed when needed
/// so that it runs counter-clockwise seen from the side `front` points to (Newell normal, from the
/// corners relative to the first: absolute coordinates 1e8 away would cancel to noise).
inline Index add_polygon_facing(TriangleMesh& mesh, std::vector<Vec3> corners, const Vec3& front) {
  Vec3 normal = Vec3::Zero();
  for (std::size_t i = 0; i < corners.size(); ++i)
    normal += (corners[i] - corners[0]).cross(corners[(i + 1) % corners.size()] - corners[0]);
  if (normal.dot(front) < 0) std::reverse(corners.begin() + 1, corners.end());
  return add_polygon(mesh, corners);
}

// ------------------------------------------------------------------------------------------------
// Scenes of axis boxes

/// An axis box [lo, hi] (lo < hi) with the side its polygons run counter-clockwise from.
struct OracleBox {
  std::array<Coord, 3> lo, hi;
  BoxFront front = BoxFront::outside;
  std::string describe() const {
    std::string s = "[" + lo[0].describe() + ", " + hi[0].describe() + "] x [" + lo[1].describe() + ", " +
                    hi[1].describe() + "] x [" + lo[2].describe() + ", " + hi[2].describe() + "] ";
    return s + to_string(front);
  }
};

/// Whether the element at collocation point P with front (inner normal) n faces the unbounded air:
/// the outside of a solid, or a dent open to it. Empty: every element is in bounded air.
using OpenAir = std::function<bool(const Vec3& P, const Vec3& n)>;

/// Closed boxes (each a closed piece): typically a room first, then bodies and cavities.
struct BoxScene {
  std::string name;  ///< the scene and its parameters
  std::vector<OracleBox> boxes;

  TriangleMesh mesh(const Frame& frame) const {
    TriangleMesh m;
    m.source = name + ", " + frame.describe();
    for (const OracleBox& b : boxes) {
      Vec3 lo, hi;
      for (int k = 0; k < 3; ++k) {
        lo[k] = place(frame, k, b.lo[k]);
        hi[k] = place(frame, k, b.hi[k]);
      }
      add_axis_box(m, lo, hi, b.front);
    }
    return m;
  }
  std::string describe() const {
    std::string s = name + ":";
    for (std::size_t i = 0; i < boxes.size(); ++i) s += (i ? "; " : " ") + boxes[i].describe();
    return s;
  }

  /// The depth of box i in the nesting: how many other boxes contain it (local coordinates,
  /// touching allowed).
  int depth(std::size_t i) const {
    int d = 0;
    for (std::size_t j = 0; j < boxes.size(); ++j) {
      if (j == i) continue;
      bool in = true;
      for (int k = 0; k < 3; ++k)
        in = in && boxes[j].lo[k].local() <= boxes[i].lo[k].local() && boxes[i].hi[k].local() <= boxes[j].hi[k].local();
      d += in;
    }
    return d;
  }

  /// Whether the orientation rule (docs/scenes-and-visibility.md) reads this scene, whose first box
  /// holds all the others, as a solid: the nesting alternates, so of its two readings (the first box
  /// a room: front inward at even depth; or a solid: front outward at even depth) the one with
  /// fewer boxes against their winding is kept, a tie and a box alone going to the room.
  bool read_as_solid() const {
    std::size_t against_room = 0;
    for (std::size_t i = 0; i < boxes.size(); ++i)
      against_room += (boxes[i].front == BoxFront::outside) == (depth(i) % 2 == 0);
    return boxes.size() > 1 && boxes.size() - against_room < against_room;
  }

  /// Read as a solid, the boxes at depth 1 are its cavities. A cavity that touches the solid's
  /// outer surface (a face in the same plane: gap 0), directly or through other cavities it
  /// touches, is open to the outside there (the faces in contact are removed: the solid has no
  /// thickness there), a dent. Per box: whether it is such a cavity.
  std::vector<bool> dents() const {
    std::vector<bool> dent(boxes.size(), false);
    if (boxes.empty()) return dent;
    const auto overlap = [&](const OracleBox& a, const OracleBox& b, int skip) {
      for (int u = 0; u < 3; ++u)
        if (u != skip && !(a.lo[u].local() < b.hi[u].local() && b.lo[u].local() < a.hi[u].local())) return false;
      return true;
    };
    const OracleBox& room = boxes[0];
    std::vector<bool> cavity(boxes.size(), false);
    for (std::size_t i = 1; i < boxes.size(); ++i) {
      cavity[i] = depth(i) == 1;
      for (int k = 0; k < 3 && cavity[i]; ++k)
        if (same_place(boxes[i].lo[k], room.lo[k]) || same_place(boxes[i].hi[k], room.hi[k])) dent[i] = true;
    }
    for (bool grew = true; grew;) {
      grew = false;
      for (std::size_t i = 1; i < boxes.size(); ++i)
        for (std::size_t j = 1; j < boxes.size(); ++j) {
          if (!cavity[i] || !cavity[j] || !dent[i] || dent[j]) continue;
          for (int k = 0; k < 3; ++k)
            if ((same_place(boxes[i].hi[k], boxes[j].lo[k]) || same_place(boxes[i].lo[k], boxes[j].hi[k])) &&
                overlap(boxes[i], boxes[j], k)) {
              dent[j] = grew = true;
              break;
            }
        }
    }
    return dent;
  }

  /// Which elements face the unbounded air under the orientation rule: none when the first box is
  /// read as a room; read as a solid, those whose front looks out of the first box or into a dent.
  /// Decided a step of 1e-6 (local units) in front of the collocation point: far below every box
  /// size and far above the rounding of the point in every frame (1.5e-8 at 1e8).
  OpenAir open_air(const Frame& frame) const {
    if (!read_as_solid()) return {};
    return [scene = *this, frame, dent = dents()](const Vec3& P, const Vec3& n) {
      const Vec3 q = (P - frame.offset) / frame.scale + 1e-6 * n;
      const auto inside = [&](const OracleBox& b) {
        for (int k = 0; k < 3; ++k)
          if (!(b.lo[k].local() < q[k] && q[k] < b.hi[k].local())) return false;
        return true;
      };
      if (!inside(scene.boxes[0])) return true;
      for (std::size_t i = 1; i < scene.boxes.size(); ++i)
        if (dent[i] && inside(scene.boxes[i])) return true;
      return false;
    };
  }
};

/// How the closed pieces of a scene are wound in the input: as their front sides (rooms and
/// cavities counter-clockwise seen from inside, bodies from outside), all reversed, or every
/// second piece reversed. The orientation rule keeps the file's winding where the nesting allows
/// it: all reversed, a room with bodies is a solid with cavities (BoxScene::read_as_solid says
/// which reading each winding has); every second reversed, a room with one or two bodies is still
/// read as a room (a tie, or fewer pieces against the file).
enum class Winding { natural, reversed, alternate };
inline const char* to_string(Winding w) {
  return w == Winding::natural ? "natural winding" : w == Winding::reversed ? "reversed winding" : "alternate winding";
}
inline BoxScene wound(BoxScene scene, Winding w) {
  for (std::size_t i = 0; i < scene.boxes.size(); ++i)
    if (w == Winding::reversed || (w == Winding::alternate && i % 2 == 1))
      scene.boxes[i].front = flipped(scene.boxes[i].front);
  scene.name += ", " + std::string(to_string(w));
  return scene;
}

inline OracleBox axis_box_of(const std::array<Coord, 3>& lo, const std::array<Coord, 3>& hi, BoxFront front) {
  return {lo, hi, front};
}

/// The room [0, 1]^3, counter-clockwise seen from inside.
inline OracleBox unit_room() { return axis_box_of({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, BoxFront::inside); }

/// The room [0, 1]^3 alone, wound as `front` says.
inline BoxScene room_alone(BoxFront front) {
  OracleBox room = unit_room();
  room.front = front;
  return {std::string("room alone ") + to_string(front), {room}};
}

inline std::string gap_name(double gap) {
  char s[48];
  std::snprintf(s, sizeof s, "gap %.3g", gap);
  return s;
}

/// The room with the box [0.3, 0.6] x [0.35, 0.7] x [gap, 0.45] above its floor (gap 0: standing
/// on it, the box's bottom on the floor's plane).
inline BoxScene box_above_floor(double gap) {
  return {"room with a box above the floor, " + gap_name(gap),
          {unit_room(), axis_box_of({0.3, 0.35, Coord(0.0).plus(gap)}, {0.6, 0.7, 0.45}, BoxFront::outside)}};
}

/// The room with the box [0.35, 0.65] x [0.3, 0.6] x [0.6, 1 - gap] below its ceiling (gap 0:
/// hanging from it).
inline BoxScene box_below_ceiling(double gap) {
  return {"room with a box below the ceiling, " + gap_name(gap),
          {unit_room(), axis_box_of({0.35, 0.3, 0.6}, {0.65, 0.6, Coord(1.0).plus(-gap)}, BoxFront::outside)}};
}

/// The room with two boxes below its ceiling, [0.35, 0.65] x [0.3, 0.6] x [0.6, 1 - gap] and, near
/// its corner, [0.7, 0.8] x [0.65, 0.75] x [0.7, 1 - gap / 4]: the second reaches higher, so from a
/// point on the first's top its sides rise gap * 3/4 into the gap, and their vertical edges cast
/// shadow edges on the ceiling whose lines pass through the point's foot (the central projection
/// maps a line along the ceiling's normal to a line through the foot), within the ceiling's
/// elements that hold the foot at level 1.
inline BoxScene boxes_below_ceiling(double gap) {
  return {"room with two boxes below the ceiling, " + gap_name(gap) + " and a quarter of it",
          {unit_room(), axis_box_of({0.35, 0.3, 0.6}, {0.65, 0.6, Coord(1.0).plus(-gap)}, BoxFront::outside),
           axis_box_of({0.7, 0.65, 0.7}, {0.8, 0.75, Coord(1.0).plus(-gap / 4)}, BoxFront::outside)}};
}

/// The room with the box [gap, 0.3] x [0.3, 0.65] x [0.25, 0.6] beside its wall x = 0 (gap 0:
/// against it).
inline BoxScene box_beside_wall(double gap) {
  return {"room with a box beside the wall x = 0, " + gap_name(gap),
          {unit_room(), axis_box_of({Coord(0.0).plus(gap), 0.3, 0.25}, {0.3, 0.65, 0.6}, BoxFront::outside)}};
}

/// The room with two boxes whose faces x = 0.5 and x = 0.5 + gap face each other, the same
/// rectangle [0.3, 0.6] x [0.25, 0.55] (gap 0: face to face, the faces coincide).
inline BoxScene boxes_facing(double gap) {
  return {"room with two boxes facing across x = 0.5, " + gap_name(gap),
          {unit_room(), axis_box_of({0.2, 0.3, 0.25}, {0.5, 0.6, 0.55}, BoxFront::outside),
           axis_box_of({Coord(0.5).plus(gap), 0.3, 0.25}, {0.8, 0.6, 0.55}, BoxFront::outside)}};
}

/// The room with two boxes touching in the plane x = 0.5 on part of their faces only: the contact
/// is [0.35, 0.5] x [0.3, 0.5], and each face reaches beyond the other's on two sides.
inline BoxScene boxes_partly_touching() {
  return {"room with two boxes touching on part of their faces x = 0.5",
          {unit_room(), axis_box_of({0.15, 0.2, 0.2}, {0.5, 0.5, 0.5}, BoxFront::outside),
           axis_box_of({0.5, 0.35, 0.3}, {0.85, 0.7, 0.65}, BoxFront::outside)}};
}

/// The room with a pillar [0.4, 0.6] x [0.35, 0.65] x [0, 1] from floor to ceiling.
inline BoxScene pillar() {
  return {"room with a pillar from floor to ceiling",
          {unit_room(), axis_box_of({0.4, 0.35, 0.0}, {0.6, 0.65, 1.0}, BoxFront::outside)}};
}

/// The room with a thick hollow shell: outer surface [0.2, 0.8]^3 seen from outside, its closed
/// cavity [0.35, 0.65]^3 seen from inside (an enclosure of its own).
inline BoxScene hollow_shell() {
  return {"room with a hollow shell and its cavity",
          {unit_room(), axis_box_of({0.2, 0.2, 0.2}, {0.8, 0.8, 0.8}, BoxFront::outside),
           axis_box_of({0.35, 0.35, 0.35}, {0.65, 0.65, 0.65}, BoxFront::inside)}};
}

/// The flat room [0, 1] x [0, 1] x [0, 1e-5] alone.
inline BoxScene flat_room() {
  return {"flat room 1 x 1 x 1e-5", {axis_box_of({0.0, 0.0, 0.0}, {1.0, 1.0, 1e-5}, BoxFront::inside)}};
}

/// The room with a rug: the open square [0.3, 0.6] x [0.3, 0.6] on the floor, its front side up,
/// the same as the floor's: a coplanar overlap with the same front side, which is refused.
inline TriangleMesh room_with_rug(const Frame& frame, BoxFront room_front) {
  OracleBox room = unit_room();
  room.front = room_front;
  TriangleMesh m = BoxScene{"room with a rug on the floor facing up", {room}}.mesh(frame);
  const double a = 0.3, b = 0.6;
  add_polygon_facing(m, {frame.place(Vec3(a, a, 0)), frame.place(Vec3(b, a, 0)), frame.place(Vec3(b, b, 0)),
                         frame.place(Vec3(a, b, 0))},
                     Vec3(0, 0, 1));
  return m;
}

/// The floor, the ceiling and the walls y = 0 and y = 1 of the room [0, 1]^3 placed by `frame`,
/// fronts inward when s = 1 (outward when s = -1).
inline void add_room_floor_ceiling_and_side_walls(TriangleMesh& m, const Frame& frame, double s) {
  auto P = [&](double x, double y, double z) { return frame.place(Vec3(x, y, z)); };
  add_polygon_facing(m, {P(0, 0, 0), P(1, 0, 0), P(1, 1, 0), P(0, 1, 0)}, s * Vec3(0, 0, 1));   // floor
  add_polygon_facing(m, {P(0, 0, 1), P(1, 0, 1), P(1, 1, 1), P(0, 1, 1)}, s * Vec3(0, 0, -1));  // ceiling
  add_polygon_facing(m, {P(0, 0, 0), P(1, 0, 0), P(1, 0, 1), P(0, 0, 1)}, s * Vec3(0, 1, 0));   // y = 0
  add_polygon_facing(m, {P(0, 1, 0), P(1, 1, 0), P(1, 1, 1), P(0, 1, 1)}, s * Vec3(0, -1, 0));  // y = 1
}

/// The room [0, 1]^3 with its wall x = 0 given as two rectangles split at y = 0.5: the split
/// edge ends on the middle of the floor's edge and of the ceiling's (two T-junctions), with the
/// box [0.4, 0.7] x [0.3, 0.6] x [0.2, 0.5] inside. The room's polygons run counter-clockwise
/// seen from inside (natural) or outside (reversed); the box's the other way.
inline TriangleMesh t_junction_room_with_box(const Frame& frame, Winding winding) {
  TriangleMesh m;
  m.source = std::string("room with a T-junction on the wall x = 0 and a box, ") + to_string(winding) + ", " +
             frame.describe();
  const double s = winding == Winding::natural ? 1 : -1;  // +1: front sides inward
  auto P = [&](double x, double y, double z) { return frame.place(Vec3(x, y, z)); };
  add_room_floor_ceiling_and_side_walls(m, frame, s);
  add_polygon_facing(m, {P(1, 0, 0), P(1, 1, 0), P(1, 1, 1), P(1, 0, 1)}, s * Vec3(-1, 0, 0));  // x = 1
  add_polygon_facing(m, {P(0, 0, 0), P(0, 0.5, 0), P(0, 0.5, 1), P(0, 0, 1)}, s * Vec3(1, 0, 0));  // x = 0, y <= 0.5
  add_polygon_facing(m, {P(0, 0.5, 0), P(0, 1, 0), P(0, 1, 1), P(0, 0.5, 1)}, s * Vec3(1, 0, 0));  // x = 0, y >= 0.5
  add_axis_box(m, P(0.4, 0.3, 0.2), P(0.7, 0.6, 0.5), winding == Winding::natural ? BoxFront::outside : BoxFront::inside);
  return m;
}

/// A room [0, 1]^3 whose wall x = 1 has a square window [0.3, 0.7]^2 (in y, z), closed by a second
/// room [1, 1.5] x [0.3, 0.7]^2 open towards it: one closed enclosure, not convex. The wall around
/// the window is four rectangles whose corners lie inside each other's edges (T-junctions); the
/// second room's walls meet the first's wall along the window's outline. A box stands in the
/// first room. `winding`: natural (front sides inward) or reversed.
inline TriangleMesh room_with_window_closed_by_second_room(const Frame& frame, Winding winding) {
  TriangleMesh m;
  m.source = std::string("room with a window closed by a second room, and a box, ") + to_string(winding) + ", " +
             frame.describe();
  const double s = winding == Winding::natural ? 1 : -1;  // +1: front sides inward
  auto P = [&](double x, double y, double z) { return frame.place(Vec3(x, y, z)); };
  add_room_floor_ceiling_and_side_walls(m, frame, s);
  add_polygon_facing(m, {P(0, 0, 0), P(0, 1, 0), P(0, 1, 1), P(0, 0, 1)}, s * Vec3(1, 0, 0));   // x = 0
  const Vec3 in_x = s * Vec3(-1, 0, 0);  // the wall x = 1 around the window
  add_polygon_facing(m, {P(1, 0, 0), P(1, 1, 0), P(1, 1, 0.3), P(1, 0, 0.3)}, in_x);
  add_polygon_facing(m, {P(1, 0, 0.7), P(1, 1, 0.7), P(1, 1, 1), P(1, 0, 1)}, in_x);
  add_polygon_facing(m, {P(1, 0, 0.3), P(1, 0.3, 0.3), P(1, 0.3, 0.7), P(1, 0, 0.7)}, in_x);
  add_polygon_facing(m, {P(1, 0.7, 0.3), P(1, 1, 0.3), P(1, 1, 0.7), P(1, 0.7, 0.7)}, in_x);
  // The second room beyond the window, open at x = 1.
  add_polygon_facing(m, {P(1, 0.3, 0.3), P(1.5, 0.3, 0.3), P(1.5, 0.7, 0.3), P(1, 0.7, 0.3)}, s * Vec3(0, 0, 1));
  add_polygon_facing(m, {P(1, 0.3, 0.7), P(1.5, 0.3, 0.7), P(1.5, 0.7, 0.7), P(1, 0.7, 0.7)}, s * Vec3(0, 0, -1));
  add_polygon_facing(m, {P(1, 0.3, 0.3), P(1.5, 0.3, 0.3), P(1.5, 0.3, 0.7), P(1, 0.3, 0.7)}, s * Vec3(0, 1, 0));
  add_polygon_facing(m, {P(1, 0.7, 0.3), P(1.5, 0.7, 0.3), P(1.5, 0.7, 0.7), P(1, 0.7, 0.7)}, s * Vec3(0, -1, 0));
  add_polygon_facing(m, {P(1.5, 0.3, 0.3), P(1.5, 0.7, 0.3), P(1.5, 0.7, 0.7), P(1.5, 0.3, 0.7)}, s * Vec3(-1, 0, 0));
  add_axis_box(m, P(0.2, 0.3, 0.2), P(0.5, 0.6, 0.5), winding == Winding::natural ? BoxFront::outside : BoxFront::inside);
  return m;
}

// ------------------------------------------------------------------------------------------------
// Prism rooms as OBJ text: the floor and the ceiling one polygon each

/// A closed room: the prism over the simple polygon `outline` (counter-clockwise about +z, first
/// corner first) from z = 0 to z = 1, as OBJ text: the floor and the ceiling are one polygon each
/// (the outline, starting at its first corner), and each maximal straight run of the outline is
/// one wall polygon (a run through collinear outline corners keeps them on the wall's bottom and
/// top edges). Every polygon runs counter-clockwise seen from inside (or, reversed, from
/// outside), each listed from the same first corner. Every corner gets its own `v` line (the
/// reader merges equal coordinates).
inline std::string prism_room_obj(const std::vector<std::array<double, 2>>& outline, const Frame& frame,
                                  bool reversed) {
  std::ostringstream obj;
  auto face = [&](std::vector<Vec3> corners) {
    if (reversed) std::reverse(corners.begin() + 1, corners.end());
    char s[128];
    for (const Vec3& c : corners) {
      const Vec3 p = frame.place(c);
      std::snprintf(s, sizeof s, "v %.17g %.17g %.17g\n", p.x(), p.y(), p.z());
      obj << s;
    }
    obj << "f";
    for (std::size_t i = 0; i < corners.size(); ++i) obj << " " << -static_cast<long>(corners.size() - i);
    obj << "\n";
  };
  const std::size_t n = outline.size();
  auto at = [&](std::size_t i, double z) { return Vec3(outline[i % n][0], outline[i % n][1], z); };
  // The floor, counter-clockwise seen from above (inside); the ceiling from below.
  std::vector<Vec3> floor, ceiling;
  for (std::size_t i = 0; i < n; ++i) floor.push_back(at(i, 0));
  ceiling.push_back(at(0, 1));
  for (std::size_t i = n - 1; i >= 1; --i) ceiling.push_back(at(i, 1));
  face(floor);
  face(ceiling);
  // Corners where the outline turns (its direction changes).
  auto turns = [&](std::size_t i) {
    const auto& a = outline[(i + n - 1) % n];
    const auto& b = outline[i];
    const auto& c = outline[(i + 1) % n];
    return (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]) != 0;
  };
  std::size_t first = 0;
  while (!turns(first)) ++first;
  // Walls: for each run p = c_0, c_1, ..., c_k = q between turning corners (the room on its
  // left), the polygon p, p + z, c_1 + z, ..., q + z, q, c_k-1, ..., c_1 runs counter-clockwise
  // seen from the room.
  for (std::size_t i = first; i < first + n;) {
    std::size_t j = i + 1;
    while (!turns(j % n)) ++j;
    std::vector<Vec3> wall = {at(i, 0)};
    for (std::size_t k = i; k <= j; ++k) wall.push_back(at(k, 1));
    wall.push_back(at(j, 0));
    for (std::size_t k = j - 1; k > i; --k) wall.push_back(at(k, 0));
    face(wall);
    i = j;
  }
  return obj.str();
}

/// The L-shaped floor [0, 2] x [0, 1] U [0, 1] x [1, 2], counter-clockwise from (2, 0): a fan
/// from its first corner leaves the polygon (the diagonal to (1, 2) passes the reflex corner
/// (1, 1) outside).
inline std::vector<std::array<double, 2>> l_outline() { return {{2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}, {0, 0}}; }

/// The same L with the collinear corner (1, 0) on its edge y = 0, last: a fan from the first
/// corner ends in the zero-area triangle (2, 0), (0, 0), (1, 0); the wall y = 0 carries (1, 0) on
/// its bottom and top edges.
inline std::vector<std::array<double, 2>> l_outline_collinear() {
  return {{2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}, {0, 0}, {1, 0}};
}

/// The U-shaped floor [0, 3] x [0, 1] U [0, 1] x [1, 2] U [2, 3] x [1, 2], counter-clockwise from
/// (3, 0): no fan from the first corner stays inside (the diagonal to (1, 2) crosses the notch).
inline std::vector<std::array<double, 2>> u_outline() {
  return {{3, 0}, {3, 2}, {2, 2}, {2, 1}, {1, 1}, {1, 2}, {0, 2}, {0, 0}};
}

// ------------------------------------------------------------------------------------------------
// Open scenes with direct lighting

/// Facets all of whose triangles satisfy `in` (on its three corners), and that have one at least.
inline std::vector<bool> facets_where(const TriangleMesh& mesh,
                                      const std::function<bool(const Vec3&, const Vec3&, const Vec3&)>& in) {
  std::vector<int> state(static_cast<std::size_t>(mesh.num_facets), 0);  // 0 none yet, 1 all in, -1 not
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const auto& tri = mesh.triangles[t];
    const bool yes = in(mesh.vertices[static_cast<std::size_t>(tri[0])], mesh.vertices[static_cast<std::size_t>(tri[1])],
                        mesh.vertices[static_cast<std::size_t>(tri[2])]);
    int& s = state[static_cast<std::size_t>(mesh.facet_of_triangle[t])];
    s = (s >= 0 && yes) ? 1 : -1;
  }
  std::vector<bool> out(state.size());
  for (std::size_t f = 0; f < state.size(); ++f) out[f] = state[f] == 1;
  return out;
}

/// Facets lying in the plane x_axis = value (every corner exactly there).
inline std::vector<bool> facets_on_plane(const TriangleMesh& mesh, int axis, double value) {
  return facets_where(mesh, [&](const Vec3& a, const Vec3& b, const Vec3& c) {
    return a[axis] == value && b[axis] == value && c[axis] == value;
  });
}

/// A lamp over a cube: the closed cube [0, 1]^3 (wound as `cube_front` says) and, as an open
/// facet facing down, the square lamp [-0.5, 1.5]^2 at z = 2. No room: light that leaves the
/// scene is lost.
inline TriangleMesh cube_under_lamp(const Frame& frame, BoxFront cube_front) {
  TriangleMesh m = BoxScene{std::string("cube under a lamp, cube ") + to_string(cube_front),
                            {axis_box_of({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, cube_front)}}
                       .mesh(frame);
  auto P = [&](double x, double y, double z) { return frame.place(Vec3(x, y, z)); };
  add_polygon_facing(m, {P(-0.5, -0.5, 2), P(1.5, -0.5, 2), P(1.5, 1.5, 2), P(-0.5, 1.5, 2)}, Vec3(0, 0, -1));
  return m;
}
inline constexpr double kLampLo = -0.5, kLampHi = 1.5, kLampHeight = 2.0, kCubeTop = 1.0;

/// The measured Cornell box (examples/scenes/cornell_box.obj, millimetres, y up) read with the OBJ
/// reader, its two closed blocks (faces 12-23: tops, sides and bottoms) raised by `lift` (0:
/// standing on the floor, the bottoms on the floor's plane), placed in `frame`.
inline constexpr double kCornellLightX0 = 213, kCornellLightX1 = 343, kCornellLightZ0 = 227, kCornellLightZ1 = 332;
inline constexpr double kCornellCeiling = 548.8, kCornellTallTop = 330;
inline constexpr Index kCornellFirstBlockFacet = 12, kCornellLastBlockFacet = 23;

inline TriangleMesh cornell_box_with_closed_blocks(const Frame& frame, double lift) {
  TriangleMesh m = geometry::read_mesh(std::string(PANELRAD_SOURCE_DIR) + "/examples/scenes/cornell_box.obj");
  std::vector<bool> block_vertex(m.vertices.size(), false);
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    if (m.facet_of_triangle[t] >= kCornellFirstBlockFacet && m.facet_of_triangle[t] <= kCornellLastBlockFacet)
      for (Index v : m.triangles[t]) block_vertex[static_cast<std::size_t>(v)] = true;
  for (std::size_t v = 0; v < m.vertices.size(); ++v)
    if (block_vertex[v]) m.vertices[v].y() += lift;
  for (Vec3& v : m.vertices) v = frame.place(v);
  char s[64];
  std::snprintf(s, sizeof s, ", blocks closed and raised by %g mm, ", lift);
  m.source = "Cornell box" + std::string(s) + frame.describe();
  return m;
}

// ------------------------------------------------------------------------------------------------
// The runner of the closed-scene oracle

/// rho per facet in [0.2, 0.7), varying from facet to facet (the fractional parts of multiples of
/// the golden ratio spread evenly).
inline double oracle_rho(Index f) {
  const double t = 0.6180339887498949 * static_cast<double>(f + 1);
  return 0.2 + 0.5 * (t - std::floor(t));
}

/// How finely the coordinates of `mesh` resolve it: the spacing of doubles at its largest
/// coordinate relative to its size, delta = 2^-52 max |x_k| / diameter (about 1e-16 near the
/// origin whatever the scale; 1.3e-8 for the unit room 1e8 away).
inline double coordinate_resolution(const TriangleMesh& mesh) {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  double largest = 0;
  for (const Vec3& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
    largest = std::max(largest, v.cwiseAbs().maxCoeff());
  }
  return 0x1.0p-52 * largest / (hi - lo).norm();
}

/// The bound of the closed oracle, max_i |u_i - c| / c < 1e-9 + 10 delta / (1 - rho_max) with
/// rho_max = 0.7 and delta the coordinate resolution (test_occluded_oracle.cpp derives it): 1e-9
/// near the origin at any scale, 4.4e-7 for the unit room 1e8 away. Faces facing each other across
/// a narrow gap add nothing: the form factors are accurate to a few eps however close P is to a
/// plane (quadrature/exact_integrals.hpp, form_factor).
inline double oracle_tolerance(double resolution) { return 1e-9 + 10 * resolution / (1 - 0.7); }

/// What one closed-scene oracle run found.
struct OracleRun {
  bool valid = false;
  std::string rule, message;  ///< validation's refusal
  geometry::SceneShape shape = geometry::SceneShape::general;
  bool closed = false;        ///< Scene::closed() after validation
  Index n0 = 0, n = 0;        ///< triangles after validation; elements
  bool solved = false;
  std::string failure;        ///< the solver's message or exception
  double error = std::numeric_limits<double>::quiet_NaN();  ///< max_i |u_i - c| / c, elements in bounded air
  std::string worst;          ///< where that error is
  double resolution = 0;      ///< coordinate_resolution of the input
  double tolerance = 0;       ///< oracle_tolerance(resolution)
  std::vector<std::string> notes;  ///< validation's
  // Elements facing the unbounded air (OpenAir), when any:
  Index bounded = 0, blind = 0, seeing = 0;  ///< elements in bounded air; in the open air seeing nothing; seeing
  double blind_error = 0;     ///< max |u_i - E_i| / c over the blind ones (u = E exactly)
  std::string worst_blind;
  double outside_bounds = 0;  ///< max of (E_i - u_i) / c and (u_i - c) / c over the seeing ones (<= 0 inside)
  std::string worst_seeing;
  double lowest_seeing = std::numeric_limits<double>::infinity();  ///< min u_i / c over the seeing ones
  double seeing_gain = 0;     ///< max (u_i - E_i) / c over the seeing ones: light they receive

  std::string describe() const {
    if (!valid) return "refused (" + rule + "): " + message;
    std::ostringstream s;
    s << geometry::to_string(shape) << (closed ? ", closed" : ", not closed") << ", n0 " << n0 << ", n " << n;
    if (!solved) return s.str() + ", not solved: " + failure;
    s << ", max |u - c| / c = " << error << " (bound " << tolerance << ") over " << bounded
      << " elements in bounded air";
    if (bounded > 0) s << " at " << worst;
    if (blind + seeing > 0) {
      s << "; in the unbounded air, " << blind << " seeing nothing with max |u - E| / c = " << blind_error;
      if (blind > 0) s << " at " << worst_blind;
      s << ", " << seeing << " seeing something";
      if (seeing > 0)
        s << " with E <= u <= c exceeded by " << outside_bounds << " c at " << worst_seeing << ", lowest u / c "
          << lowest_seeing << ", largest (u - E) / c " << seeing_gain;
    }
    return s.str();
  }
  /// u = c in bounded air, u = E on blind elements and E <= u <= c on the others, each within the
  /// bound (false on NaN).
  bool within_bounds() const {
    return error < tolerance && blind_error < tolerance && !(outside_bounds >= tolerance) &&
           !std::isnan(outside_bounds);
  }
};

/// Dense collocation with exact clipping, the iteration's tolerance 1e-13.
inline SolveOptions oracle_solver_options(int level) {
  SolveOptions o;
  o.level = level;
  o.op.method = OperatorMethod::dense;
  o.solver.tolerance = 1e-13;
  return o;
}

/// Validates `mesh` and solves it with rho(f) per facet and E = c (1 - rho): the closed-scene
/// oracle, u = c on every element in bounded air; on those `open_air` says face the unbounded air,
/// u = E where the element sees nothing (no vertex of the validated scene in front of its plane,
/// beyond 1e-9 of the scene's size plus 16 spacings of the doubles at its largest coordinate) and
/// E <= u <= c elsewhere (see the top of this file). `level` < 0: level 1, or 0 when level 1 would
/// have more than max_elements.
inline OracleRun run_constant_oracle(TriangleMesh mesh, double c, int level,
                                     const std::function<double(Index)>& rho = oracle_rho,
                                     Index max_elements = 1024, const OpenAir& open_air = {}) {
  OracleRun run;
  run.resolution = coordinate_resolution(mesh);
  run.tolerance = oracle_tolerance(run.resolution);
  geometry::SceneValidationReport report;
  std::optional<geometry::ValidatedMesh> validated = geometry::try_validate(std::move(mesh), report);
  run.valid = report.valid;
  run.rule = report.rule;
  run.message = report.message;
  run.notes = report.notes;
  if (!report.valid) return run;
  run.shape = report.shape;
  run.n0 = static_cast<Index>(validated->mesh().triangles.size());
  if (level < 0) level = 4 * run.n0 <= max_elements ? 1 : 0;
  try {
    Scene scene(std::move(*validated));
    run.closed = scene.closed();
    std::vector<double> r(static_cast<std::size_t>(scene.num_facets())), e(r.size());
    for (Index f = 0; f < scene.num_facets(); ++f) {
      r[static_cast<std::size_t>(f)] = rho(f);
      e[static_cast<std::size_t>(f)] = c * (1 - rho(f));
    }
    scene.set_reflectivity(r);
    scene.set_emissivity(e);
    const RadiositySolver solver(scene, oracle_solver_options(level));
    run.n = solver.n();
    const ChannelSolve s = solver.solve(0);
    if (!s.converged()) {
      run.failure = s.message;
      return run;
    }
    run.solved = true;
    run.error = 0;
    run.outside_bounds = -std::numeric_limits<double>::infinity();
    const Collocation& col = solver.collocation();
    const std::vector<Vec3>& vertices = scene.mesh().vertices;
    double largest = 0;
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (const Vec3& v : vertices) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
      largest = std::max(largest, v.cwiseAbs().maxCoeff());
    }
    const double in_front = 1e-9 * (hi - lo).norm() + 16 * 0x1.0p-52 * largest;
    const auto where = [&](Index i) {
      const Vec3& P = col.collocation_point(i);
      const Vec3& nP = col.normal(i);
      std::ostringstream w;
      w.precision(17);
      w << "element " << i << " of facet " << col.facet(i) << ", P = (" << P.x() << ", " << P.y() << ", " << P.z()
        << "), n = (" << nP.x() << ", " << nP.y() << ", " << nP.z() << "), u = " << s.u[i];
      return w.str();
    };
    for (Index i = 0; i < col.size(); ++i) {
      if (open_air && open_air(col.collocation_point(i), col.normal(i))) {
        const Vec3& P = col.collocation_point(i);
        const Vec3& nP = col.normal(i);
        bool sees = false;
        for (const Vec3& v : vertices) sees = sees || (v - P).dot(nP) > in_front;
        const double E = c * (1 - rho(col.facet(i)));
        if (!sees) {
          ++run.blind;
          const double d = std::abs(s.u[i] - E) / c;
          if (!std::isnan(run.blind_error) && !(d <= run.blind_error)) {
            run.blind_error = d;
            run.worst_blind = where(i) + ", E = " + std::to_string(E);
          }
        } else {
          ++run.seeing;
          const double d = std::max(E - s.u[i], s.u[i] - c) / c;
          if (!std::isnan(run.outside_bounds) && !(d <= run.outside_bounds)) {
            run.outside_bounds = d;
            run.worst_seeing = where(i) + ", E = " + std::to_string(E);
          }
          if (!(s.u[i] / c >= run.lowest_seeing)) run.lowest_seeing = s.u[i] / c;
          if (!((s.u[i] - E) / c <= run.seeing_gain)) run.seeing_gain = (s.u[i] - E) / c;
        }
        continue;
      }
      ++run.bounded;
      const double d = std::abs(s.u[i] - c) / c;
      if (!(d <= run.error)) {  // NaN counts as the worst
        run.error = d;
        run.worst = where(i);
        if (std::isnan(d)) break;
      }
    }
  } catch (const std::exception& ex) {
    run.failure = ex.what();
  }
  return run;
}

// ------------------------------------------------------------------------------------------------
// Random closed scenes

/// A uniform double in [0, 1) from the engine's 53 high bits (the same on every standard library,
/// unlike std::uniform_real_distribution).
inline double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }
inline double uniform(std::mt19937_64& rng, double a, double b) { return a + (b - a) * uniform01(rng); }
/// An integer in [0, k): the engine's output mod k (bias below 2^-50 for small k).
inline int pick(std::mt19937_64& rng, int k) { return static_cast<int>(rng() % static_cast<std::uint64_t>(k)); }
/// Log-uniform in [a, b].
inline double log_uniform(std::mt19937_64& rng, double a, double b) {
  return a * std::pow(b / a, uniform01(rng));
}

/// One random closed scene: a room [0, L] with 1-3 axis boxes, placed in a frame.
struct RandomOracleScene {
  std::uint64_t seed = 0;
  int index = 0;
  BoxScene boxes;                ///< room first
  std::vector<std::string> how;  ///< per body: how it was placed
  std::vector<double> gaps;      ///< per body: its gap from what it is placed against (NaN: free)
  Frame frame;
  int level = 0;
  double c = 1;
  std::vector<double> rho;       ///< per facet id, cycled

  double rho_of(Index f) const { return rho[static_cast<std::size_t>(f) % rho.size()]; }
  std::string describe() const {
    std::ostringstream s;
    s.precision(17);
    s << "random scene " << index << " (seed " << seed << "): " << frame.describe() << ", level " << level
      << ", c " << c << ", " << boxes.describe() << " | placed: ";
    for (std::size_t i = 0; i < how.size(); ++i) s << (i ? "; " : "") << "body " << i + 1 << " " << how[i];
    return s.str();
  }
};

/// The random scene number `index` of the sweep with seed `seed`: its own engine, seeded from
/// both, so that any one scene can be made again alone.
///
/// The room [0, Lx] x [0, Ly] x [0, Lz], L uniform in [0.5, 2], then up to 3 axis boxes (sides
/// 0.15 .. 0.4 of the room's), each placed in one of these ways: on the floor, under the ceiling,
/// against one of the four walls, against a face of an earlier box (their faces overlapping on
/// at least a fifth of the new box's side), or free; a box that finds no place in 100 attempts
/// is left out. Except free, the box touches (gap 0, half the
/// time) or floats at a log-uniform gap in [1e-15, 1e-2] (local units) from what it is placed
/// against; from everything else it keeps a clearance of 0.04 min L, so that the scene is valid
/// by construction: closed pieces that only touch in planes with opposite front sides, or not at
/// all. Windings random per piece; rho per facet uniform in [0.2, 0.7]; c in [0.5, 4]; level 0 or
/// 1; the frame the origin (5/8 of the scenes), 1e8 away, or scaled by 1e-3 or 1e3.
inline RandomOracleScene random_oracle_scene(std::uint64_t seed, int index) {
  std::mt19937_64 rng(seed ^ (0x9E3779B97F4A7C15ull * static_cast<std::uint64_t>(index + 1)));
  RandomOracleScene s;
  s.seed = seed;
  s.index = index;
  const std::vector<Frame> frames = oracle_frames();
  const int fr = pick(rng, 8);
  s.frame = frames[static_cast<std::size_t>(fr < 5 ? 0 : fr - 4)];
  s.level = pick(rng, 2);
  s.c = uniform(rng, 0.5, 4);
  const std::array<double, 3> L = {uniform(rng, 0.5, 2), uniform(rng, 0.5, 2), uniform(rng, 0.5, 2)};
  const double margin = 0.04 * std::min({L[0], L[1], L[2]});
  OracleBox room = axis_box_of({0.0, 0.0, 0.0}, {L[0], L[1], L[2]}, pick(rng, 2) ? BoxFront::inside : BoxFront::outside);
  s.boxes.name = "random room";
  s.boxes.boxes.push_back(room);

  struct Local {
    std::array<double, 3> lo, hi;
  };
  std::vector<Local> placed;
  const int wanted = 1 + pick(rng, 3);
  for (int b = 0; b < wanted; ++b) {
    // 0 floor, 1 ceiling, 2 wall, 3 free, 4 against a body (twice as likely as the others, since
    // it fails the clearances more often); kept for every attempt at placing this box.
    const int weighted = pick(rng, placed.empty() ? 4 : 6);
    const int mode = std::min(weighted, 4);
    for (int attempt = 0; attempt < 100; ++attempt) {
      std::array<double, 3> size;
      for (int k = 0; k < 3; ++k) size[k] = L[k] * uniform(rng, 0.15, 0.4);
      OracleBox box;
      Local loc;
      for (int k = 0; k < 3; ++k) {
        loc.lo[k] = uniform(rng, margin, L[k] - margin - size[k]);
        loc.hi[k] = loc.lo[k] + size[k];
        box.lo[k] = loc.lo[k];
        box.hi[k] = loc.hi[k];
      }
      const double gap = pick(rng, 2) ? 0.0 : log_uniform(rng, 1e-15, 1e-2);
      int axis = 2, side = 0, target = -1;  // the contact: axis, side of the new box (0 lo, 1 hi)
      char how[160];
      if (mode == 0 || mode == 1 || mode == 2) {
        if (mode == 2) {
          axis = pick(rng, 2);
          side = pick(rng, 2);
        } else {
          side = mode;  // floor: the box's bottom (lo) at 0 + gap; ceiling: its top (hi) at Lz - gap
        }
        if (side == 0) {
          box.lo[axis] = Coord(0.0).plus(gap);
          loc.lo[axis] = gap;
          loc.hi[axis] = gap + size[axis];
          box.hi[axis] = loc.hi[axis];
        } else {
          box.hi[axis] = Coord(L[axis]).plus(-gap);
          loc.hi[axis] = L[axis] - gap;
          loc.lo[axis] = L[axis] - gap - size[axis];
          box.lo[axis] = loc.lo[axis];
        }
        std::snprintf(how, sizeof how, "%s, gap %.17g", mode == 0 ? "on the floor" : mode == 1 ? "under the ceiling"
                                                        : side == 0 ? (axis == 0 ? "against the wall x = 0" : "against the wall y = 0")
                                                                    : (axis == 0 ? "against the wall x = Lx" : "against the wall y = Ly"),
                      gap);
      } else if (mode == 3) {
        axis = -1;
        std::snprintf(how, sizeof how, "free");
      } else {
        target = pick(rng, static_cast<int>(placed.size()));
        axis = pick(rng, 3);
        side = pick(rng, 2);  // 0: the new box's lo face against the target's hi face; 1: the reverse
        const Local& t = placed[static_cast<std::size_t>(target)];
        const OracleBox& tb = s.boxes.boxes[static_cast<std::size_t>(target) + 1];
        if (side == 0) {
          box.lo[axis] = tb.hi[axis].plus(gap);
          loc.lo[axis] = t.hi[axis] + gap;
          loc.hi[axis] = loc.lo[axis] + size[axis];
          box.hi[axis] = loc.hi[axis];
        } else {
          box.hi[axis] = tb.lo[axis].plus(-gap);
          loc.hi[axis] = t.lo[axis] - gap;
          loc.lo[axis] = loc.hi[axis] - size[axis];
          box.lo[axis] = loc.lo[axis];
        }
        for (int u = 0; u < 3; ++u) {
          if (u == axis) continue;
          loc.lo[u] = uniform(rng, t.lo[u] - 0.8 * size[u], t.hi[u] - 0.2 * size[u]);
          loc.hi[u] = loc.lo[u] + size[u];
          box.lo[u] = loc.lo[u];
          box.hi[u] = loc.hi[u];
        }
        std::snprintf(how, sizeof how, "against the %s face %c of body %d, gap %.17g", side == 0 ? "upper" : "lower",
                      "xyz"[axis], target + 1, gap);
      }
      // Clearance from the room, except the contact side (floor, ceiling, wall).
      bool ok = true;
      for (int k = 0; k < 3 && ok; ++k) {
        const bool lo_contact = (mode <= 2) && k == axis && side == 0;
        const bool hi_contact = (mode <= 2) && k == axis && side == 1;
        if (!lo_contact && loc.lo[k] < margin) ok = false;
        if (!hi_contact && loc.hi[k] > L[k] - margin) ok = false;
      }
      // Clearance from every earlier box but the target.
      for (std::size_t j = 0; j < placed.size() && ok; ++j) {
        if (static_cast<int>(j) == target) continue;
        double sep = -std::numeric_limits<double>::infinity();
        for (int k = 0; k < 3; ++k)
          sep = std::max({sep, placed[j].lo[k] - loc.hi[k], loc.lo[k] - placed[j].hi[k]});
        if (sep < margin) ok = false;
      }
      if (!ok) continue;
      box.front = pick(rng, 2) ? BoxFront::outside : BoxFront::inside;
      placed.push_back(loc);
      s.boxes.boxes.push_back(box);
      s.how.emplace_back(how);
      s.gaps.push_back(mode == 3 ? std::numeric_limits<double>::quiet_NaN() : gap);
      break;
    }
  }
  s.rho.resize(64);
  for (double& r : s.rho) r = uniform(rng, 0.2, 0.7);
  return s;
}

}  // namespace panelrad::testing

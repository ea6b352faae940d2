// Exact oracles for the occluded radiosity equation (1) on general scenes (oracle_scenes.hpp),
// each scene at the origin, 1e8 away and scaled by 1e-3 and 1e3:
//  - closed scenes, with rho varying by facet in [0.2, 0.7) and E = c (1 - rho): the collocation
//    solution is u = c. Rooms wound inward and outward; boxes that stand on the floor, hang from
//    the ceiling, stand against a wall, touch each other on whole or partial faces, a pillar from
//    floor to ceiling (faces in one plane with opposite front sides: the covered parts leave the
//    scene); boxes facing the floor, the ceiling, a wall or each other across gaps from 1e-15 to
//    1e-3 (the faces see each other); a hollow shell with its cavity (nested pieces: room inward,
//    shell outward, cavity inward); a flat room; L- and U-shaped rooms whose floor and ceiling are
//    one non-convex polygon each, read from OBJ text, with and without collinear corners; a room
//    whose wall ends on the middle of the floor's edge (T-junctions, closed once the edge is
//    split); two separate rooms wound inward, an L-shaped room with a box in its notch wound
//    inward (each an enclosure); a room wound outward with one or three bodies wound outward (a
//    room with bodies: the tie rule, fewest flips);
//  - the orientation rule reads a scene as the file winds it where the nesting allows: every
//    piece reversed, a room with bodies is a solid with cavities, a shell outward around a cavity
//    inward a solid with a cavity. Then u = c still holds in each closed cavity, u = E on every
//    element of the solid's outside that sees nothing (its row of K is zero), and E <= u <= c on
//    the others (oracle_scenes.hpp): a cavity touching the outer surface is open there (the
//    faces in contact are removed: the solid has no thickness there), a dent that light leaves;
//  - open scenes under direct light: a point that sees, of everything lit, only the emitter
//    (rho = 0 elsewhere) has u = rho F(P -> emitter), the closed-form parallel-rectangle factor of
//    configuration_factors.hpp: a cube under a square lamp (both windings of the cube), and the
//    Cornell box with closed blocks, raised 1 mm and standing on the floor (the tall block's top
//    under the ceiling light);
//  - a coplanar overlap of faces with the same front side (a rug on the floor facing up) stays
//    refused as a crossing.
//
// The bound of the closed oracle. The error e = u_n - c 1 solves (I - K) e = c (K 1 - rho), so
// ||e||_inf <= c ||K 1 - rho||_inf / (1 - ||K||_inf). Each row sum of H is 1 up to the error of
// its entries: closed-form integrals over clipped polygons in double precision (relative error
// ~1e-14 per form factor, a few pieces per element) and the slivers of relative size 1e-12 that
// the shadow tests' margin drops (geometry/occluders.hpp); over n <= 1024 entries that is far below
// 1e-10, so ||K 1 - rho||_inf <= 0.7e-10 and ||K||_inf <= 0.7 (1 + 1e-10): ||e|| / c <= 2.4e-10.
// The iteration stops at the relative tolerance 1e-13, which adds at most 1e-13 / 0.3 of ||u||.
// So max |u_i - c| / c < 1e-9 near the origin, at any scale.
// Far from the origin the coordinates resolve the scene only to delta = 2^-52 max |x_k| / diameter
// (coordinate_resolution: 1.3e-8 for the unit room 1e8 away). The corners of the visible pieces
// (a face clipped by the shadow of an edge) are computed in those coordinates, each with an
// absolute error of about delta D (D the scene's size); seen from P at distances down to about
// D / 10 (the size of a level-1 element) that moves a factor by up to about 10 delta times the
// factor, so the row sums hold to about 10 delta instead of 1e-10 and the bound becomes
// 1e-9 + 10 delta / (1 - rho_max) (oracle_tolerance; 4.4e-7 there). The rounding of the
// collocation points themselves does not enter: the row sum is 1 at every point of the enclosure.
// Faces facing each other across a narrow gap h (P at height h below a plane, M the largest
// coordinate) add nothing to the bound. The two roundings that would weigh eps M / h there are
// avoided: the form factor's height of P and its foot's distances from edge lines near it are
// computed from exact coordinate differences (quadrature/exact_integrals.hpp), and where the
// visible pieces of an element (rounded corners, pieces meeting off each other's edges by eps M)
// have an edge passing near P's foot, as the extended shadow edges of a face rising into the gap
// do, the element's factor is taken as its own minus the covered pieces' (visible_covering.hpp).
// Measured (2026-12-06, Release): before, 7.1e-9 for h = 1e-9 under a ceiling at M = 1 and 4.0e-7
// for h = 8.4e-11 at M = 1.4 (about 110 eps M / h); now at most 3e-13 on every gap case near the
// origin (the margins' slivers, a slit 1e-11 wide seen from across the room), 5.3e-8 (bound
// 4.3e-7) 1e8 away. Gaps below four times the shadow tests' margin are taken as contact by
// validation. A collocation point that its rounding puts within the margin in front of the plane
// of a face across the gap (above a box's edge) sees that face by the exact orientation, its
// factor d / 2h (d its distance from the plane) included (TwoBoxesBelowTheCeilingAtLevelTwo).
// A face seen from its back, a hidden face counted, a face not seen across a gap or a covered part
// left in the scene changes a row sum by the factor of that face, far above these bounds at
// these sizes (level 1, elements of side >= 1/8 of the room's).
#include "configuration_factors.hpp"
#include "occluded_scenes.hpp"
#include "oracle_scenes.hpp"

#include <panelrad/geometry/mesh_io.hpp>
#include <panelrad/geometry/scene_validation.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/radiosity_solver.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace panelrad {
namespace {

using testing::BoxFront;
using testing::Frame;
using testing::TriangleMesh;
using testing::Winding;

constexpr double kC = 2.5;

/// The oracle on `mesh`: accepted, solved; max |u - c| / c below the bound above on the elements
/// in bounded air; on those `open_air` says face the unbounded air (a solid's outside), u = E
/// within the same bound where the element sees nothing and E <= u <= c within it elsewhere
/// (oracle_scenes.hpp). The run in `out` when given.
void expect_oracle(TriangleMesh mesh, const testing::OpenAir& open_air, bool expect_closed = false, int level = -1,
                   testing::OracleRun* out = nullptr) {
  const std::string what = mesh.source;
  const testing::OracleRun run =
      testing::run_constant_oracle(std::move(mesh), kC, level, testing::oracle_rho, 1024, open_air);
  if (out) *out = run;
  ASSERT_TRUE(run.valid) << what << ": " << run.describe();
  ASSERT_TRUE(run.solved) << what << ": " << run.describe();
  EXPECT_LT(run.error, run.tolerance) << what << ": " << run.describe();
  EXPECT_LT(run.blind_error, run.tolerance) << what << ": " << run.describe();
  if (run.seeing > 0) {
    EXPECT_LT(run.outside_bounds, run.tolerance) << what << ": " << run.describe();
  }
  if (expect_closed) {
    // Closed (every ray from a front side ends on a front side) exactly when no element faces the
    // unbounded air: a solid's outer faces emit to infinity.
    EXPECT_EQ(run.closed, run.blind + run.seeing == 0) << what << ": " << run.describe();
  }
}

/// The closed oracle on `mesh`: every element in bounded air, u = c.
void expect_constant_solution(TriangleMesh mesh, bool expect_closed = false, int level = -1) {
  expect_oracle(std::move(mesh), {}, expect_closed, level);
}

const std::vector<Winding> kWindings = {Winding::natural, Winding::reversed, Winding::alternate};

/// `scene` in each winding, as the orientation rule reads it (BoxScene::read_as_solid): a room,
/// u = c everywhere; a solid, u = c in its closed cavities, u = E on its outer faces (a box: they
/// see nothing), and in a cavity that touches the outer surface (a dent, open there) E <= u <= c
/// with some u below c by more than 1e-3 c (light leaves through the opening: its rows lose the
/// opening's factor times rho >= 0.2, far above the bound).
void expect_constant_solution(const testing::BoxScene& scene, const Frame& frame, int level = -1) {
  for (const Winding w : kWindings) {
    const testing::BoxScene wound = testing::wound(scene, w);
    testing::OracleRun run;
    expect_oracle(wound.mesh(frame), wound.open_air(frame), false, level, &run);
    if (!run.solved) continue;
    const std::vector<bool> dents = wound.dents();
    const bool dented = wound.read_as_solid() && std::count(dents.begin(), dents.end(), true) > 0;
    if (!wound.read_as_solid()) {
      EXPECT_EQ(run.blind + run.seeing, 0) << wound.describe() << ": read as a room, " << run.describe();
    } else if (!dented) {
      EXPECT_GT(run.blind, 0) << wound.describe() << ": read as a solid, " << run.describe();
      EXPECT_EQ(run.seeing, 0) << wound.describe() << ": the outer faces of a box see nothing, " << run.describe();
    } else {
      EXPECT_LT(run.lowest_seeing, 1 - 1e-3) << wound.describe() << ": a dent must let light out, " << run.describe();
    }
  }
}

class OccludedOracle : public ::testing::TestWithParam<Frame> {};

TEST_P(OccludedOracle, RoomAloneWoundInward) {
  expect_constant_solution(testing::room_alone(BoxFront::inside).mesh(GetParam()));
}

TEST_P(OccludedOracle, RoomAloneWoundOutward) {
  expect_constant_solution(testing::room_alone(BoxFront::outside).mesh(GetParam()));
}

TEST_P(OccludedOracle, BoxRestingOnTheFloor) { expect_constant_solution(testing::box_above_floor(0), GetParam()); }

TEST_P(OccludedOracle, BoxHangingFromTheCeiling) {
  expect_constant_solution(testing::box_below_ceiling(0), GetParam());
}

TEST_P(OccludedOracle, BoxAgainstAWall) { expect_constant_solution(testing::box_beside_wall(0), GetParam()); }

TEST_P(OccludedOracle, TwoBoxesFaceToFace) { expect_constant_solution(testing::boxes_facing(0), GetParam()); }

TEST_P(OccludedOracle, TwoBoxesWithPartlyOverlappingFaces) {
  expect_constant_solution(testing::boxes_partly_touching(), GetParam());
}

TEST_P(OccludedOracle, PillarFromFloorToCeiling) { expect_constant_solution(testing::pillar(), GetParam()); }

TEST_P(OccludedOracle, HollowShellWithItsCavity) { expect_constant_solution(testing::hollow_shell(), GetParam()); }

TEST_P(OccludedOracle, FlatRoom) {
  for (const Winding w : {Winding::natural, Winding::reversed})
    expect_constant_solution(testing::wound(testing::flat_room(), w).mesh(GetParam()));
}

/// The prism room over `outline` read from OBJ text (floor and ceiling one polygon each), both
/// windings.
void expect_prism_room_constant(const std::string& name, const std::vector<std::array<double, 2>>& outline,
                                const Frame& frame) {
  for (const bool reversed : {false, true}) {
    const std::string what = name + (reversed ? ", reversed winding, " : ", natural winding, ") + frame.describe();
    const std::string text = testing::prism_room_obj(outline, frame, reversed);
    std::istringstream in(text);
    TriangleMesh mesh;
    try {
      mesh = geometry::read_obj(in, what);
    } catch (const std::exception& e) {
      ADD_FAILURE() << what << ": the OBJ reader refused it: " << e.what() << "\n" << text;
      continue;
    }
    mesh.source = what;
    expect_constant_solution(std::move(mesh), true);
  }
}

TEST_P(OccludedOracle, LShapedRoomAsOnePolygon) {
  expect_prism_room_constant("L-shaped room, floor and ceiling one hexagon", testing::l_outline(), GetParam());
}

TEST_P(OccludedOracle, UShapedRoomAsOnePolygon) {
  expect_prism_room_constant("U-shaped room, floor and ceiling one octagon", testing::u_outline(), GetParam());
}

TEST_P(OccludedOracle, LShapedRoomWithCollinearCorners) {
  expect_prism_room_constant("L-shaped room with the collinear corner (1, 0)", testing::l_outline_collinear(),
                             GetParam());
}

/// Elements whose front looks out of the local box [lo, hi] (a step of 1e-6 local units in front
/// of the collocation point, as BoxScene::open_air): with a solid around the cavity [lo, hi], those
/// facing the unbounded air.
testing::OpenAir outside_of(const Frame& frame, const Vec3& lo, const Vec3& hi) {
  return [=](const Vec3& P, const Vec3& n) {
    const Vec3 q = (P - frame.offset) / frame.scale + 1e-6 * n;
    return !((q.array() > lo.array()).all() && (q.array() < hi.array()).all());
  };
}

// Reversed, the room is wound outward and the box inward: a solid with a cavity as the file
// winds it (no piece against the file, against two read as a room), so the box's faces have
// u = c and the outer faces u = E (the room is a box: they see nothing).
TEST_P(OccludedOracle, TJunctionRoomWithABox) {
  expect_constant_solution(testing::t_junction_room_with_box(GetParam(), Winding::natural), true);
  testing::OracleRun run;
  expect_oracle(testing::t_junction_room_with_box(GetParam(), Winding::reversed),
                outside_of(GetParam(), Vec3(0.4, 0.3, 0.2), Vec3(0.7, 0.6, 0.5)), true, -1, &run);
  EXPECT_GT(run.blind, 0) << run.describe();
  EXPECT_EQ(run.seeing, 0) << run.describe();
}

// Reversed: a solid (the two rooms' outer surface) with the box as its cavity, as for the
// T-junction room. Its outside is not convex (the second room stands out of the wall x = 1), so
// the faces around it see each other: E <= u <= c there, u = E where nothing is seen.
TEST_P(OccludedOracle, RoomWithAWindowClosedByASecondRoom) {
  expect_constant_solution(testing::room_with_window_closed_by_second_room(GetParam(), Winding::natural), true);
  testing::OracleRun run;
  expect_oracle(testing::room_with_window_closed_by_second_room(GetParam(), Winding::reversed),
                outside_of(GetParam(), Vec3(0.2, 0.3, 0.2), Vec3(0.5, 0.6, 0.5)), true, -1, &run);
  EXPECT_GT(run.blind, 0) << run.describe();
  EXPECT_GT(run.seeing, 0) << run.describe();
  EXPECT_LT(run.lowest_seeing, 1 - 1e-3) << run.describe();
}

// Two separate rooms side by side, [0, 1]^3 and [1.5, 2.5] x [0, 1]^2. Wound inward, each is an
// enclosure as the file winds it (closed pieces side by side do not constrain each other): u = c.
// Wound outward, two bodies: their facing walls see each other (E <= u <= c), the rest nothing
// (u = E). One of each: a room (u = c) and a body beside it that sees only the room's back faces,
// which give nothing (u = E: its row of K is zero, though the room's vertices lie in front of it).
TEST_P(OccludedOracle, TwoSeparateRooms) {
  const Frame& frame = GetParam();
  const auto second = [=](const Vec3& P, const Vec3&) { return (P.x() - frame.offset.x()) / frame.scale > 1.25; };
  for (const BoxFront first_front : {BoxFront::inside, BoxFront::outside})
    for (const BoxFront second_front : {BoxFront::inside, BoxFront::outside}) {
      const testing::BoxScene scene{std::string("two separate rooms, the first ") + testing::to_string(first_front) +
                                        ", the second " + testing::to_string(second_front),
                                    {testing::axis_box_of({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, first_front),
                                     testing::axis_box_of({1.5, 0.0, 0.0}, {2.5, 1.0, 1.0}, second_front)}};
      testing::OpenAir open_air;
      if (first_front == BoxFront::outside && second_front == BoxFront::outside)
        open_air = [](const Vec3&, const Vec3&) { return true; };
      else if (first_front == BoxFront::outside)
        open_air = [=](const Vec3& P, const Vec3& n) { return !second(P, n); };
      else if (second_front == BoxFront::outside)
        open_air = second;
      testing::OracleRun run;
      expect_oracle(scene.mesh(frame), open_air, true, -1, &run);
      if (first_front == BoxFront::inside && second_front == BoxFront::inside) {
        EXPECT_EQ(run.blind + run.seeing, 0) << scene.describe();
      }
      if (first_front != second_front) {  // the body's wall facing the room sees its back faces only
        EXPECT_LT(run.seeing_gain, run.tolerance) << scene.describe() << ": " << run.describe();
      }
      if (first_front == BoxFront::outside && second_front == BoxFront::outside) {
        EXPECT_GT(run.seeing_gain, 1e-3) << scene.describe() << ": the facing walls light each other, "
                                         << run.describe();
      }
    }
}

// The L-shaped room (OBJ text, floor and ceiling one hexagon each) and a closed box
// [1.2, 1.8]^2 x [0.2, 0.8] in its notch, outside it, touching nothing. Both wound inward: two
// enclosures as the file winds them, u = c. Both outward: two bodies, whose faces across the
// notch see each other (E <= u <= c), the rest nothing (u = E).
TEST_P(OccludedOracle, LShapedRoomWithABoxInItsNotch) {
  const Frame& frame = GetParam();
  for (const bool outward : {false, true}) {
    const std::string what = std::string("L-shaped room and a box in its notch, both wound ") +
                             (outward ? "outward, " : "inward, ") + frame.describe();
    std::istringstream in(testing::prism_room_obj(testing::l_outline(), frame, outward));
    TriangleMesh mesh = geometry::read_obj(in, what);
    mesh.source = what;
    testing::add_axis_box(mesh, frame.place(Vec3(1.2, 1.2, 0.2)), frame.place(Vec3(1.8, 1.8, 0.8)),
                          outward ? BoxFront::outside : BoxFront::inside);
    testing::OracleRun run;
    expect_oracle(std::move(mesh), outward ? testing::OpenAir([](const Vec3&, const Vec3&) { return true; })
                                           : testing::OpenAir(),
                  true, -1, &run);
    if (outward) {
      EXPECT_GT(run.seeing_gain, 1e-3) << what << ": the faces across the notch light each other, " << run.describe();
      EXPECT_GT(run.blind, 0) << what << ": " << run.describe();
    } else {
      EXPECT_EQ(run.blind + run.seeing, 0) << what << ": " << run.describe();
    }
  }
}

// A lone hollow solid: the outer surface [0, 1]^3 wound outward and the cavity [0.3, 0.7]^3
// wound inward, nothing else. As the file winds it, a solid with a cavity (reading it as a room
// with a body would put both pieces against the file). In the cavity u = c (a closed scene of its
// own). The outer faces see nothing: the solid is a convex box and the cavity lies behind their
// planes, so their rows of K are zero and u = E = c (1 - rho) exactly; asserted within the same
// bound, which any face seen that should not be (or a cavity face turned outward) would exceed
// by its factor. Reversed or with both wound outward, it is a room with a body: u = c.
TEST_P(OccludedOracle, LoneHollowSolid) {
  const testing::BoxScene solid{"lone hollow solid",
                                {testing::axis_box_of({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, BoxFront::outside),
                                 testing::axis_box_of({0.3, 0.3, 0.3}, {0.7, 0.7, 0.7}, BoxFront::inside)}};
  ASSERT_TRUE(solid.read_as_solid());
  ASSERT_FALSE(testing::wound(solid, Winding::reversed).read_as_solid());
  ASSERT_FALSE(testing::wound(solid, Winding::alternate).read_as_solid());
  testing::OracleRun run;
  expect_oracle(solid.mesh(GetParam()), solid.open_air(GetParam()), true, -1, &run);
  EXPECT_EQ(run.seeing, 0) << run.describe();
  EXPECT_GT(run.blind, 0) << run.describe();
  EXPECT_EQ(run.blind, run.bounded) << run.describe();  // the two boxes have as many elements
  expect_constant_solution(solid, GetParam());
}

// A room wound outward, as exporters write it, with one body or three (floating) or a box
// standing on its floor, all wound outward: a room with bodies. With one body the two readings
// tie (one piece against the file each) and the outermost is the room; with three, reading it as
// a solid would put three pieces against the file, as a room one.
TEST_P(OccludedOracle, RoomWoundOutwardWithFurniture) {
  const auto outward_room = [] {
    testing::OracleBox room = testing::unit_room();
    room.front = BoxFront::outside;
    return room;
  };
  const std::vector<testing::BoxScene> scenes = {
      {"room wound outward with one body wound outward",
       {outward_room(), testing::axis_box_of({0.3, 0.35, 0.2}, {0.6, 0.7, 0.55}, BoxFront::outside)}},
      {"room wound outward with three bodies wound outward",
       {outward_room(), testing::axis_box_of({0.1, 0.1, 0.1}, {0.3, 0.3, 0.4}, BoxFront::outside),
        testing::axis_box_of({0.5, 0.2, 0.3}, {0.8, 0.4, 0.6}, BoxFront::outside),
        testing::axis_box_of({0.3, 0.6, 0.55}, {0.6, 0.9, 0.85}, BoxFront::outside)}},
      {"room wound outward with a box wound outward standing on its floor",
       {outward_room(), testing::axis_box_of({0.3, 0.35, 0.0}, {0.6, 0.7, 0.45}, BoxFront::outside)}}};
  for (const testing::BoxScene& scene : scenes) {
    ASSERT_FALSE(scene.read_as_solid()) << scene.describe();
    expect_constant_solution(scene.mesh(GetParam()));
  }
}

// The floor and a rug on it both face up: a coplanar overlap with the same front side, refused
// as a crossing whichever way the room is wound (its floor faces up either way).
TEST_P(OccludedOracle, CoplanarOverlapWithTheSameFrontIsRefused) {
  for (const BoxFront room_front : {BoxFront::inside, BoxFront::outside}) {
    TriangleMesh mesh = testing::room_with_rug(GetParam(), room_front);
    const std::string what = mesh.source + ", room " + testing::to_string(room_front);
    const geometry::SceneValidationReport report = geometry::validate_scene(mesh);
    std::string notes;
    for (const std::string& n : report.notes) notes += "\n  " + n;
    EXPECT_FALSE(report.valid) << what << ": accepted, notes:" << notes;
    EXPECT_EQ(report.rule, "crossing") << what << ": " << report.message;
  }
}

/// Direct lighting: validates `mesh`, sets rho = rho_r on the facets in the plane x_axis =
/// receiver_plane, E = 1 on the emitter's facets (those `emitter` selects) and rho = E = 0
/// elsewhere, and checks every element of the receiver: u_i = rho_r F(P_i -> emitter), the
/// emitter the rectangle `rect` (coordinates along axes u, v) in the plane x_axis = emitter_plane,
/// parallel to the receiver and facing it, and wholly seen from it.
///
/// The collocation solution is exactly that: the receiver's elements are lit by the emitter only
/// (every other element has rho = E = 0, so u = 0 there, and the receiver does not see itself:
/// K^2 E = 0 on it), so u_i = rho_r (H E)_i and (H E)_i is the emitter's factor. Dense: each entry
/// a closed form in double precision (relative error ~1e-14), F <= 1: 1e-12 absolute.
void expect_direct_lighting(TriangleMesh mesh, int axis, double receiver_plane, double emitter_plane,
                            const testing::AxisRectangle& rect,
                            const std::function<bool(const Vec3&, const Vec3&, const Vec3&)>& emitter, int level) {
  const std::string what = mesh.source;
  const int u = axis == 0 ? 1 : 0, v = axis == 2 ? 1 : 2;  // the axes of the planes
  geometry::SceneValidationReport report;
  std::optional<geometry::ValidatedMesh> validated = geometry::try_validate(std::move(mesh), report);
  ASSERT_TRUE(validated) << what << ": " << report.message;
  const std::vector<bool> receiver = testing::facets_on_plane(validated->mesh(), axis, receiver_plane);
  const std::vector<bool> lamp = testing::facets_where(validated->mesh(), emitter);
  ASSERT_GT(std::count(lamp.begin(), lamp.end(), true), 0) << what << ": no emitter facet";
  const double rho_r = 0.55;
  std::vector<double> rho(receiver.size()), E(receiver.size());
  for (std::size_t f = 0; f < rho.size(); ++f) {
    rho[f] = receiver[f] ? rho_r : 0.0;
    E[f] = lamp[f] ? 1.0 : 0.0;
  }
  Scene scene(std::move(*validated));
  scene.set_reflectivity(rho);
  scene.set_emissivity(E);
  SolveOptions o = testing::oracle_solver_options(level);
  o.solver.tolerance = 1e-14;
  const RadiositySolver solver(scene, o);
  const ChannelSolve r = solver.solve(0);
  ASSERT_TRUE(r.converged()) << what << ": " << r.message;
  const Collocation& col = solver.collocation();
  int seen = 0;
  double worst = 0;
  std::string where;
  for (Index i = 0; i < col.size(); ++i) {
    if (!receiver[static_cast<std::size_t>(col.facet(i))]) continue;
    ++seen;
    const Vec3& P = col.collocation_point(i);
    const double truth = rho_r * testing::parallel_rectangle_factor(P[u], P[v], rect, emitter_plane - P[axis]);
    const double d = std::abs(r.u[i] - truth);
    if (!(d <= worst)) {
      worst = d;
      std::ostringstream s;
      s.precision(17);
      s << "element " << i << " of facet " << col.facet(i) << " at (" << P.x() << ", " << P.y() << ", " << P.z()
        << "): u = " << r.u[i] << ", rho F = " << truth;
      where = s.str();
    }
  }
  ASSERT_GT(seen, 0) << what << ": no receiving element";
  EXPECT_LT(worst, 1e-12) << what << ": " << where;
}

TEST_P(OccludedOracle, CubeUnderALamp) {
  const Frame& frame = GetParam();
  const testing::AxisRectangle lamp = {frame.place(0, testing::kLampLo), frame.place(0, testing::kLampHi),
                                       frame.place(1, testing::kLampLo), frame.place(1, testing::kLampHi)};
  const double lamp_z = frame.place(2, testing::kLampHeight);
  for (const BoxFront front : {BoxFront::outside, BoxFront::inside}) {
    expect_direct_lighting(
        testing::cube_under_lamp(frame, front), 2, frame.place(2, testing::kCubeTop), lamp_z, lamp,
        [&](const Vec3& a, const Vec3& b, const Vec3& c) { return a.z() == lamp_z && b.z() == lamp_z && c.z() == lamp_z; },
        2);
  }
}

void expect_cornell_tall_top(const Frame& frame, double lift) {
  using namespace testing;
  const AxisRectangle light = {frame.place(0, kCornellLightX0), frame.place(0, kCornellLightX1),
                               frame.place(2, kCornellLightZ0), frame.place(2, kCornellLightZ1)};
  const double ceiling = frame.place(1, kCornellCeiling);
  auto in_light = [&](const Vec3& p) {
    return p.y() == ceiling && p.x() >= light.x0 && p.x() <= light.x1 && p.z() >= light.y0 && p.z() <= light.y1;
  };
  expect_direct_lighting(
      cornell_box_with_closed_blocks(frame, lift), 1, frame.place(1, kCornellTallTop + lift), ceiling, light,
      [&](const Vec3& a, const Vec3& b, const Vec3& c) { return in_light(a) && in_light(b) && in_light(c); }, 1);
}

TEST_P(OccludedOracle, CornellBoxClosedBlocksRaisedOneMillimetre) { expect_cornell_tall_top(GetParam(), 1.0); }

TEST_P(OccludedOracle, CornellBoxClosedBlocksStandingOnTheFloor) { expect_cornell_tall_top(GetParam(), 0.0); }

// At level 2 a collocation point on the ceiling lies exactly above the lower box's edge y = 0.6,
// rounded 1.1e-16 in front of the plane of the box's side: within the visibility margin, it must
// still see that side (the factor 5.6e-6 that the box's top misses at the gap 1e-11).
TEST_P(OccludedOracle, TwoBoxesBelowTheCeilingAtLevelTwo) {
  expect_constant_solution(testing::boxes_below_ceiling(1e-11), GetParam(), 2);
}

std::string frame_name(const ::testing::TestParamInfo<Frame>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Frames, OccludedOracle, ::testing::ValuesIn(testing::oracle_frames()), frame_name);

// Faces facing each other across a gap see each other, from 1e-15 to 1e-3 of the room's size (at
// 1e8 a gap is at least four spacings of the doubles there, 6e-8: oracle_scenes.hpp; below the
// contact threshold there, 4 x 64 eps 1e8 = 5.7e-6, validation takes it as contact).
class OccludedOracleGap : public ::testing::TestWithParam<std::tuple<double, Frame>> {
 protected:
  double gap() const { return std::get<0>(GetParam()); }
  const Frame& frame() const { return std::get<1>(GetParam()); }
};

TEST_P(OccludedOracleGap, BoxAboveTheFloor) { expect_constant_solution(testing::box_above_floor(gap()), frame()); }

TEST_P(OccludedOracleGap, BoxBelowTheCeiling) {
  expect_constant_solution(testing::box_below_ceiling(gap()), frame());
}

TEST_P(OccludedOracleGap, TwoBoxesBelowTheCeilingAtDifferentGaps) {
  expect_constant_solution(testing::boxes_below_ceiling(gap()), frame());
}

TEST_P(OccludedOracleGap, BoxBesideAWall) { expect_constant_solution(testing::box_beside_wall(gap()), frame()); }

TEST_P(OccludedOracleGap, TwoBoxesAcrossAGap) { expect_constant_solution(testing::boxes_facing(gap()), frame()); }

std::string gap_frame_name(const ::testing::TestParamInfo<std::tuple<double, Frame>>& info) {
  char s[32];
  std::snprintf(s, sizeof s, "%.0e", std::get<0>(info.param));  // 1e-15
  std::string name = std::string("gap") + s + "_" + std::get<1>(info.param).name;
  for (char& ch : name)
    if (ch == '-') ch = 'm';
  return name;
}

INSTANTIATE_TEST_SUITE_P(Gaps, OccludedOracleGap,
                         ::testing::Combine(::testing::Values(1e-15, 1e-12, 1e-11, 1e-10, 1e-9, 1e-6, 1e-3),
                                            ::testing::ValuesIn(testing::oracle_frames())),
                         gap_frame_name);

}  // namespace
}  // namespace panelrad

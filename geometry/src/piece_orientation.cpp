// Rule "orientable" of validate_scene (scene_validation.hpp) and the front side of every face.
//
// Pieces: connected components of triangles joined across edges that exactly two triangles share
// (by vertex index; the readers merge coincident vertices) without being folded flat onto each
// other. An edge of one triangle (a boundary), of three or more (non-manifold), or of two that
// overlap (a polygon given twice, wound either way) joins nothing. A piece is closed when every edge of its
// triangles joins two of them.
//
// Within a piece the orientation propagates across joined edges (a neighbour runs the shared edge
// the other way); a piece where it cannot (a Moebius strip) is refused. Of its two consistent
// orientations the one that agrees with the input on most of its area is kept; the triangles that
// disagree are flipped.
//
// Front sides (the side that emits, reflects and sees: the paper's inner normal n):
// - open piece: the side from which its triangles run counter-clockwise (the OBJ/OFF convention);
// - closed piece: its winding in the file (the side most of its area runs counter-clockwise from)
//   is the user's statement, overridden only where physics forbids it. The closed pieces nest in a
//   forest (each inside its innermost container). A closed piece directly in the air of an
//   enclosure or a cavity is an object (front outward); one directly in an object's solid is a
//   cavity (front inward). So a tree has two readings, from its root: as a room (root an
//   enclosure, then objects and cavities alternating) or as a solid (root an object, then cavities
//   and objects alternating). Kept: the reading with fewer pieces against the file's winding; on a
//   tie, the room (the outermost piece is the room: a room with one body, both wound outward as
//   exporters write them, is a room with a body).
// - open pieces overrule the counts where they lie in air that only one reading has: a sheet
//   inside closed pieces lives in the air inside the innermost one (an enclosure or a cavity), a
//   sheet inside none in the air around every top-level closed piece it lies outside of (each an
//   object: a closed cube under a lamp, whatever its winding). When sheets ask for both readings of
//   one tree (air on both sides of a closed surface) the counts decide. Closed pieces side by side
//   do not constrain each other: two rooms wound inward are two enclosures.
// - a closed piece alone in the scene (every other piece, if any, lying on its surface) is an
//   enclosure, whatever its winding.
// Each closed piece's note says what it is, whether as the file winds it or against it, and the
// rule that decided (for a piece against the file, the physical rule that forced it).
// Nesting is decided with CGAL::Side_of_triangle_mesh (exact predicates, ray parity) by the
// majority of points of the inner piece off the outer piece's surface, taken just inside the inner
// piece's solid (faces may touch, and faces written within the rounding of a contact may lie an
// ulp on the wrong side of it: lies_inside); the same for an open piece inside a closed one. Which
// side of a closed piece is inside is the sign of its enclosed volume (volume_sign, exact).
// Storage: every triangle clockwise seen from its front, its geometric normal (b - a) x (c - a)
// pointing to the back (the convention of validate_closed_convex, counter-clockwise from outside).
#include "validation_internal.hpp"

#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <memory>
#include <utility>

namespace panelrad::geometry::validation_detail {

namespace {

using SurfaceMesh = CGAL::Surface_mesh<Point>;
using SideOfMesh = CGAL::Side_of_triangle_mesh<SurfaceMesh, Kernel>;

/// The pieces listed in the notes one by one; above this count, one summary note.
constexpr Sz kMaxPieceNotes = 8;

/// What a piece is, and so which of its sides is the front (the paper's inner normal n).
enum class Kind {
  open,       ///< not closed: the front is the side from which its faces run counter-clockwise
  enclosure,  ///< closed, seen from inside (a room): front side inward
  object,     ///< closed, seen from outside (a body): front side outward
  cavity,     ///< closed, inside an object (a hollow in a body): front side inward
};

struct Piece {
  std::vector<Index> triangles;
  bool closed = true;
  Sz flipped = 0;                 // triangles flipped to agree with most of the piece's area
  std::vector<Index> containers;  // closed pieces that contain this one (closed pieces only)
  Index parent = kNone;           // the innermost of them
  Kind kind = Kind::open;
  std::string why;                // the rule that gave the kind (closed pieces)
  bool file_front_outward = false;  // closed: the file's winding (most of the area) makes the outside the front
  bool against_file = false;      // the front side chosen is the back side of the file's winding
};

double area(const TriangleMesh& mesh, const Tri& t) {
  const Vec3& a = mesh.vertices[at(t[0])];
  return (mesh.vertices[at(t[1])] - a).cross(mesh.vertices[at(t[2])] - a).norm();
}

/// The slot of `tr` whose edge joins u and v (either direction).
int slot_of(const Tri& tr, Index u, Index v) {
  for (int s = 0; s < 3; ++s) {
    const Index a = tr[at(s)], b = tr[at((s + 1) % 3)];
    if ((a == u && b == v) || (a == v && b == u)) return s;
  }
  return -1;
}

/// The triangles of one piece as a mesh of its own (vertices renumbered).
TriangleMesh piece_mesh(const TriangleMesh& mesh, const Piece& piece) {
  TriangleMesh m;
  std::vector<Index> local(mesh.vertices.size(), kNone);
  for (Index t : piece.triangles) {
    Tri tr = mesh.triangles[at(t)];
    for (Index& v : tr) {
      if (local[at(v)] == kNone) {
        local[at(v)] = static_cast<Index>(m.vertices.size());
        m.vertices.push_back(mesh.vertices[at(v)]);
      }
      v = local[at(v)];
    }
    m.triangles.push_back(tr);
  }
  return m;
}

/// A closed piece as CGAL's surface mesh for Side_of_triangle_mesh (a vertex where the piece
/// touches itself is duplicated by orient_polygon_soup, so that the surface mesh can be built).
struct ClosedSurface {
  SurfaceMesh surface;
  std::unique_ptr<SideOfMesh> side;
  CGAL::Bbox_3 box;
};

std::unique_ptr<ClosedSurface> closed_surface(const TriangleMesh& m) {
  auto cs = std::make_unique<ClosedSurface>();
  std::vector<Point> points;
  points.reserve(m.vertices.size());
  for (const Vec3& v : m.vertices) {
    points.emplace_back(v.x(), v.y(), v.z());
    cs->box += points.back().bbox();
  }
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(m.triangles.size());
  for (const Tri& t : m.triangles) polygons.push_back({at(t[0]), at(t[1]), at(t[2])});
  CGAL::Polygon_mesh_processing::orient_polygon_soup(points, polygons);
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, cs->surface);
  cs->side = std::make_unique<SideOfMesh>(cs->surface);
  return cs;
}

CGAL::Bbox_3 mesh_box(const TriangleMesh& m) {
  CGAL::Bbox_3 box;
  for (const Vec3& v : m.vertices) box += CGAL::Bbox_3(v.x(), v.y(), v.z(), v.x(), v.y(), v.z());
  return box;
}

/// The inner box lies inside the outer one, up to 1e-5 of the outer one's diagonal (corners of a
/// contact written rounded may poke out of it by their rounding).
bool box_inside(const CGAL::Bbox_3& inner, const CGAL::Bbox_3& outer) {
  double diagonal = 0;
  for (int k = 0; k < 3; ++k) diagonal += (outer.max(k) - outer.min(k)) * (outer.max(k) - outer.min(k));
  const double slack = 1e-5 * std::sqrt(diagonal);
  for (int k = 0; k < 3; ++k)
    if (inner.min(k) < outer.min(k) - slack || inner.max(k) > outer.max(k) + slack) return false;
  return true;
}

/// Whether `inner` (a piece, touching allowed) lies inside the closed surface `outer`: decided by
/// the majority of sample points off that surface, one per triangle (up to kNestingSamples
/// triangles, evenly spread), then the vertices. A closed inner piece's points are its triangles'
/// centroids moved into its own solid by 1e-4 of the triangle's size: the pieces do not cross, so
/// those points lie on the inner piece's side of the outer surface, also where its faces lie on
/// that surface within the rounding of their corners as written (a box's bottom an ulp below the
/// floor it stands on, its sides on the walls of the room's corner it stands in). An open piece's
/// points are its centroids. Nothing when all lie on the surface (a sheet on a wall: neither
/// inside nor outside).
constexpr Sz kNestingSamples = 64;

/// Which side of a closed piece's geometric normals is its solid: against them when it runs
/// counter-clockwise from outside (volume_sign > 0); 0 for an open piece.
double into_solid(const TriangleMesh& piece, bool closed) {
  if (!closed) return 0.0;
  return volume_sign(piece, piece.vertices[0]) > 0 ? -1.0 : 1.0;
}

/// `into`: -1 or +1, the side of the geometric normals that is the inner piece's solid (into_solid),
/// 0 for an open piece.
std::optional<bool> lies_inside(const TriangleMesh& inner, double into, const ClosedSurface& outer) {
  const SideOfMesh& side = *outer.side;
  Sz in = 0, out = 0;
  const auto vote = [&](const Vec3& x) {
    const CGAL::Bounded_side s = side(Point(x.x(), x.y(), x.z()));
    in += s == CGAL::ON_BOUNDED_SIDE;
    out += s == CGAL::ON_UNBOUNDED_SIDE;
  };
  const Sz nt = inner.triangles.size();
  for (Sz k = 0; k < nt; k += std::max<Sz>(1, nt / kNestingSamples)) {
    const Tri& t = inner.triangles[k];
    const Vec3 &a = inner.vertices[at(t[0])], &b = inner.vertices[at(t[1])], &c = inner.vertices[at(t[2])];
    const Vec3 n = (b - a).cross(c - a);
    const double size = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const Vec3 offset = n.norm() > 0 ? Vec3(into * 1e-4 * size * n.normalized()) : Vec3::Zero();
    vote((a + b + c) / 3.0 + offset);
  }
  if (in != out) return in > out;
  const Sz nv = inner.vertices.size();
  for (Sz k = 0; k < nv; k += std::max<Sz>(1, nv / kNestingSamples)) vote(inner.vertices[k]);
  if (in != out) return in > out;
  return std::nullopt;
}

/// Two triangles folded flat onto each other across their common edge (a, b): their third
/// corners lie in one plane with it and on the same side of its line (exact). They overlap, so
/// they do not bound a region of space between them: the edge joins neither to the other (a
/// surface given twice with opposite windings, a two-sided sheet, is two open pieces, not a
/// closed piece of zero volume).
bool folded(const std::vector<Point>& p, Index a, Index b, Index c, Index d) {
  return CGAL::orientation(p[at(a)], p[at(b)], p[at(c)], p[at(d)]) == CGAL::COPLANAR &&
         CGAL::coplanar_orientation(p[at(a)], p[at(b)], p[at(c)], p[at(d)]) == CGAL::POSITIVE;
}

/// Removes the joins of build_adjacency across edges where two triangles are folded flat.
void unjoin_folded_edges(const TriangleMesh& mesh, Adjacency& adj) {
  const std::vector<Point> p = exact_points(mesh);
  for (Sz t = 0; t < mesh.triangles.size(); ++t)
    for (int s = 0; s < 3; ++s) {
      const Index n = adj.neighbour[3 * t + at(s)];
      if (n == kNone || at(n) < t) continue;
      const Tri& tr = mesh.triangles[t];
      const Index a = tr[at(s)], b = tr[at((s + 1) % 3)], c = tr[at((s + 2) % 3)];
      const int ns = slot_of(mesh.triangles[at(n)], a, b);
      const Index d = mesh.triangles[at(n)][at((ns + 2) % 3)];
      if (!folded(p, a, b, c, d)) continue;
      adj.neighbour[3 * t + at(s)] = kNone;
      adj.neighbour[3 * at(n) + at(ns)] = kNone;
    }
}

}  // namespace

std::string front_side_words(FrontSide side, bool against_file) {
  std::string s;
  switch (side) {
    case FrontSide::open: return "an open surface, front side where its faces run counter-clockwise, as the file winds it";
    case FrontSide::enclosure: s = "an enclosure, front side inward"; break;
    case FrontSide::object: s = "an object, front side outward"; break;
    case FrontSide::cavity: s = "a cavity, front side inward"; break;
  }
  if (!against_file) return s + ", as the file winds it";
  return s + ", against the file's winding (its faces run counter-clockwise seen from " +
         (side == FrontSide::object ? "inside" : "outside") + ")";
}

namespace {

std::string piece_name(Sz i, const Piece& p) {
  return "piece " + std::to_string(i) + " (" + std::to_string(p.triangles.size()) +
         (p.triangles.size() == 1 ? " triangle, " : " triangles, ") + (p.closed ? "closed)" : "open)");
}

std::string flipped_text(const Piece& p) {
  if (p.flipped == 0) return "";
  return "; " + std::to_string(p.flipped) + (p.flipped == 1 ? " triangle" : " triangles") +
         " flipped to agree with most of its area";
}

/// The individual piece notes at most; the rest are summarised (pieces against the file's
/// winding are listed first, as they are what a reader must check).
constexpr Sz kMaxListedPieces = 16;

std::string piece_text(Sz i, const Piece& p) {
  std::string what = front_side_words(p.kind == Kind::open       ? FrontSide::open
                                      : p.kind == Kind::object   ? FrontSide::object
                                      : p.kind == Kind::cavity   ? FrontSide::cavity
                                                                 : FrontSide::enclosure,
                                      p.against_file);
  if (!p.why.empty()) what += " (" + p.why + ")";
  return piece_name(i, p) + ": " + what + flipped_text(p);
}

void note_pieces(const std::vector<Piece>& pieces, std::vector<std::string>& notes) {
  if (pieces.size() <= kMaxPieceNotes) {
    for (Sz i = 0; i < pieces.size(); ++i) notes.push_back(piece_text(i, pieces[i]));
    return;
  }
  Sz counts[4] = {0, 0, 0, 0}, flipped = 0, flipped_pieces = 0, against = 0;
  for (const Piece& p : pieces) {
    ++counts[static_cast<int>(p.kind)];
    flipped += p.flipped;
    flipped_pieces += p.flipped > 0;
    against += p.against_file;
  }
  std::string s = std::to_string(pieces.size()) + " pieces: " + std::to_string(counts[1]) +
                  " enclosures (front side inward), " + std::to_string(counts[2]) + " objects (front side outward), " +
                  std::to_string(counts[3]) + " cavities (front side inward), " + std::to_string(counts[0]) +
                  " open (front side where the faces run counter-clockwise); " + std::to_string(against) +
                  " against the file's winding";
  if (flipped > 0)
    s += "; " + std::to_string(flipped) + " triangles in " + std::to_string(flipped_pieces) +
         " pieces flipped to agree with most of their piece's area";
  notes.push_back(s);
  // Each closed piece, those against the file's winding first, up to kMaxListedPieces.
  Sz listed = 0, left = 0;
  for (int pass = 0; pass < 2; ++pass)
    for (Sz i = 0; i < pieces.size(); ++i) {
      const Piece& p = pieces[i];
      if (!p.closed || p.against_file != (pass == 0)) continue;
      if (listed < kMaxListedPieces) {
        notes.push_back(piece_text(i, p));
        ++listed;
      } else {
        ++left;
      }
    }
  if (left > 0) notes.push_back("and " + std::to_string(left) + " more closed pieces, each as the file winds it or by the same rules");
}

}  // namespace

std::optional<Failure> orient_scene_pieces(TriangleMesh& mesh, ScenePieces& out) {
  const Describe d{mesh};
  const Sz nt = mesh.triangles.size();
  // The neighbours across edges in exactly two triangles; the failure (a boundary or a
  // non-manifold edge) is what makes a piece open here, not an error.
  Adjacency adj;
  (void)build_adjacency(mesh, adj);
  unjoin_folded_edges(mesh, adj);

  // 1. Pieces, each consistently oriented relative to its first triangle.
  std::vector<signed char> flip(nt, -1);
  std::vector<Piece> pieces;
  for (Sz seed = 0; seed < nt; ++seed) {
    if (flip[seed] >= 0) continue;
    Piece piece;
    flip[seed] = 0;
    std::deque<Index> queue{static_cast<Index>(seed)};
    while (!queue.empty()) {
      const Index t = queue.front();
      queue.pop_front();
      piece.triangles.push_back(t);
      const Tri& tr = mesh.triangles[at(t)];
      for (int s = 0; s < 3; ++s) {
        const Index n = adj.neighbour[3 * at(t) + at(s)];
        if (n == kNone) {
          piece.closed = false;
          continue;
        }
        const Index a = tr[at(s)], b = tr[at((s + 1) % 3)];
        const Tri& ntr = mesh.triangles[at(n)];
        const bool same_direction = ntr[at(slot_of(ntr, a, b))] == a;  // consistent neighbours run b -> a
        const signed char want = static_cast<signed char>(flip[at(t)] ^ (same_direction ? 1 : 0));
        if (flip[at(n)] < 0) {
          flip[at(n)] = want;
          queue.push_back(n);
        } else if (flip[at(n)] != want) {
          return Failure{"orientable",
                         "the piece of the surface containing triangle " + std::to_string(seed) +
                             " is one-sided (like a Moebius strip): " + d.triangle(n) +
                             " cannot be oriented consistently with its neighbours, so its faces have no front "
                             "side to emit and reflect on; remove that piece or replace it with a two-sided "
                             "(orientable) surface"};
        }
      }
    }
    // 2. The orientation of most of the piece's area.
    double kept = 0, reversed = 0;
    for (Index t : piece.triangles) (flip[at(t)] ? reversed : kept) += area(mesh, mesh.triangles[at(t)]);
    const bool invert = reversed > kept;
    for (Index t : piece.triangles) {
      if (invert) flip[at(t)] ^= 1;
      if (flip[at(t)]) {
        ++piece.flipped;
        std::swap(mesh.triangles[at(t)][1], mesh.triangles[at(t)][2]);
      }
    }
    pieces.push_back(std::move(piece));
  }

  // 3. Nesting of the closed pieces.
  std::vector<Index> closed;
  for (Sz i = 0; i < pieces.size(); ++i)
    if (pieces[i].closed) closed.push_back(static_cast<Index>(i));
  std::vector<TriangleMesh> piece_meshes(pieces.size());
  for (Sz i = 0; i < pieces.size(); ++i) piece_meshes[i] = piece_mesh(mesh, pieces[i]);
  std::vector<double> into(pieces.size());
  for (Sz i = 0; i < pieces.size(); ++i) into[i] = into_solid(piece_meshes[i], pieces[i].closed);
  std::vector<std::unique_ptr<ClosedSurface>> surfaces(pieces.size());
  if (pieces.size() > 1)
    for (Index i : closed) surfaces[at(i)] = closed_surface(piece_meshes[at(i)]);
  std::vector<CGAL::Bbox_3> boxes(pieces.size());
  for (Sz i = 0; i < pieces.size(); ++i) boxes[i] = mesh_box(piece_meshes[i]);
  // +1 inside, -1 outside, 0 on the surface (neither).
  const auto where = [&](Sz inner, Index outer) {
    if (!box_inside(boxes[inner], surfaces[at(outer)]->box)) return -1;
    const std::optional<bool> in = lies_inside(piece_meshes[inner], into[inner], *surfaces[at(outer)]);
    return !in ? 0 : *in ? 1 : -1;
  };
  for (Index a : closed)
    for (Index b : closed)
      if (a != b && surfaces[at(a)] && where(at(b), a) == 1) pieces[at(b)].containers.push_back(a);
  for (Index i : closed) {
    Piece& p = pieces[at(i)];
    for (Index c : p.containers)
      if (p.parent == kNone || pieces[at(c)].containers.size() > pieces[at(p.parent)].containers.size()) p.parent = c;
  }

  // 4. The kind of each closed piece. The file's winding first: the sign of the enclosed volume of
  // the piece as it runs now (most of its area as in the file), +1 when counter-clockwise seen from
  // outside, i.e. the file puts the front outside.
  for (Index i : closed) {
    Piece& p = pieces[at(i)];
    const TriangleMesh& m = piece_meshes[at(i)];
    const int sign = volume_sign(m, m.vertices[0]);
    if (sign == 0)
      return Failure{"non-degenerate", piece_name(at(i), p) + ", starting at " + d.triangle(p.triangles[0]) +
                                           ", encloses zero volume, so it has no inside and outside to choose a "
                                           "front side from; remove it or give it a volume"};
    p.file_front_outward = sign > 0;
  }
  // The nesting forest: the root of each closed piece's tree (its container inside no other) and
  // its depth there, the number of its containers (the nesting is laminar: pieces do not cross).
  std::vector<Index> root_of(pieces.size(), kNone);
  for (Index i : closed) {
    root_of[at(i)] = i;
    for (Index c : pieces[at(i)].containers)
      if (pieces[at(c)].containers.empty()) root_of[at(i)] = c;
  }
  const auto depth = [&](Index i) { return pieces[at(i)].containers.size(); };
  // Air that open pieces (one-sided sheets) live in. A sheet inside closed pieces lies in the air
  // inside the innermost one, which is then an enclosure or a cavity: the room reading of its tree
  // at even depth, the solid reading at odd depth. A sheet inside none lies in the air around every
  // top-level closed piece it lies outside of, which is then an object: the solid reading. A sheet
  // wholly on a surface is in neither. The first sheet that asks for each reading is kept.
  struct Demand {
    Index open = kNone;
    Index air_of = kNone;  // the closed piece whose inside is that air; kNone: the air outside the root
  };
  std::vector<Demand> wants_room(pieces.size()), wants_solid(pieces.size());
  for (Sz j = 0; j < pieces.size(); ++j) {
    if (pieces[j].closed) continue;
    Index inner = kNone;
    for (Index c : closed)
      if (where(j, c) == 1 && (inner == kNone || depth(c) > depth(inner))) inner = c;
    if (inner != kNone) {
      Demand& d = (depth(inner) % 2 == 0 ? wants_room : wants_solid)[at(root_of[at(inner)])];
      if (d.open == kNone) d = {static_cast<Index>(j), inner};
      continue;
    }
    for (Index r : closed)
      if (pieces[at(r)].containers.empty() && wants_solid[at(r)].open == kNone && where(j, r) == -1)
        wants_solid[at(r)] = {static_cast<Index>(j), kNone};
  }

  // Kinds, tree by tree. Physics fixes the alternation: a closed piece directly in the air of an
  // enclosure or a cavity is an object (a body in that air), one directly in an object's solid a
  // cavity. So a tree has two readings: from its root as a room (depth 0 an enclosure, odd depths
  // objects, even depths cavities) or as a solid (even depths objects, odd depths cavities). The
  // file's winding of each piece is the user's statement: the reading that puts the fewer pieces
  // against it is kept, a tie going to the room (the outermost piece as the room). Open pieces
  // overrule that when they lie in air that only one reading has, and a closed piece alone in the
  // scene (every other piece, if any, on its surface) is an enclosure whatever its winding.
  constexpr const char* kAlternate =
      "alternate, a closed piece in the air of an enclosure or a cavity being an object and one in an object's "
      "solid a cavity";
  const auto air_words = [&](const Demand& d, Index r) {
    return d.air_of == kNone ? std::string("outside it")
           : d.air_of == r   ? std::string("inside it")
                             : "inside piece " + std::to_string(d.air_of);
  };
  std::vector<std::vector<Index>> trees(pieces.size());
  for (Index i : closed) trees[at(root_of[at(i)])].push_back(i);
  for (Index r : closed) {
    Piece& root = pieces[at(r)];
    if (!root.containers.empty()) continue;
    const std::vector<Index>& tree = trees[at(r)];
    // Pieces against the file's winding when read as a room: those wound outward at even depth
    // and inward at odd depth. Read as a solid, the others.
    Sz against_room = 0;
    for (Index i : tree) against_room += pieces[at(i)].file_front_outward == (depth(i) % 2 == 0);
    const Sz against_solid = tree.size() - against_room;
    bool alone = tree.size() == 1;
    for (Sz j = 0; j < pieces.size() && alone; ++j)
      if (j != at(r) && where(j, r) != 0) alone = false;
    const Demand &room_d = wants_room[at(r)], &solid_d = wants_solid[at(r)];
    const bool need_room = room_d.open != kNone, need_solid = solid_d.open != kNone;
    // The counts of the two readings, the kept one first.
    const auto counts = [&](bool as_room) {
      if (tree.size() == 1)
        return std::string("inside no other closed piece and holding none, so the file's winding decides");
      const Sz kept = as_room ? against_room : against_solid, other = as_room ? against_solid : against_room;
      std::string s = "the outermost of " + std::to_string(tree.size()) + " nested closed pieces, which " + kAlternate +
                      ": " + std::to_string(kept) + " of them against the file's winding with it as " +
                      (as_room ? "a room, " : "a solid, ") + std::to_string(other) + " with it as " +
                      (as_room ? "a solid" : "a room");
      return s + (kept == other ? "; as many either way, so the outermost piece is the room" : "");
    };
    const auto forced = [&](const Demand& d, bool as_room) {
      std::string s = "open piece " + std::to_string(d.open) + " lies in the air " + air_words(d, r);
      if (d.air_of == kNone) s += ", so it is a body seen from outside";
      else if (d.air_of == r) s += ", so it is a room";
      else s += ", so piece " + std::to_string(d.air_of) + " holds air";
      if (tree.size() > 1) {
        const Sz against = as_room ? against_room : against_solid;
        s += ", and the " + std::to_string(tree.size()) + " nested closed pieces, which " + kAlternate +
             ", follow from it: " + std::to_string(against) + " of them against the file's winding";
      }
      return s;
    };
    bool as_room = true;
    if (alone) {
      root.why = pieces.size() == 1 ? "the only piece of the scene"
                                    : "every other piece of the scene lies on its surface, so it is alone: a room";
    } else if (need_room != need_solid) {
      as_room = need_room;
      root.why = forced(need_room ? room_d : solid_d, as_room);
    } else {
      as_room = against_room <= against_solid;
      root.why = counts(as_room);
      if (need_room)  // and need_solid: air on both sides, which no reading gives
        root.why = "open piece " + std::to_string(room_d.open) + " lies in the air " + air_words(room_d, r) +
                   " and open piece " + std::to_string(solid_d.open) + " in the air " + air_words(solid_d, r) +
                   ", which no reading allows (a closed surface has air on one side only); " + root.why;
    }
    for (Index i : tree)
      pieces[at(i)].kind = i == r ? (as_room ? Kind::enclosure : Kind::object)
                                  : ((depth(i) % 2 == 0) == as_room ? Kind::cavity : Kind::object);
    for (Index i : tree) {
      Piece& p = pieces[at(i)];
      if (i == r) continue;
      const Kind parent = pieces[at(p.parent)].kind;
      const std::string in = "inside the " + std::string(parent == Kind::object      ? "object"
                                                         : parent == Kind::cavity    ? "cavity"
                                                                                     : "enclosure") +
                             " piece " + std::to_string(p.parent);
      p.why = in + (parent == Kind::object ? ": a closed piece in an object's solid is a cavity"
                    : parent == Kind::cavity ? ": a closed piece in a cavity's air is an object"
                                             : ": a closed piece in an enclosure's air is an object");
    }
  }

  // 5. Stored clockwise from the front: an open piece reversed (its counter-clockwise side is the
  // front); a closed piece counter-clockwise from outside when its front is inward (enclosure,
  // cavity), from inside when outward (object).
  for (Index i : closed) {
    Piece& p = pieces[at(i)];
    const bool front_outward = p.kind == Kind::object;
    p.against_file = front_outward != p.file_front_outward;
    // The triangles run counter-clockwise seen from the file's front; stored clockwise from the
    // chosen front, they are reversed when the two agree.
    if (!p.against_file)
      for (Index t : p.triangles) std::swap(mesh.triangles[at(t)][1], mesh.triangles[at(t)][2]);
  }
  for (const Piece& p : pieces)
    if (!p.closed)
      for (Index t : p.triangles) std::swap(mesh.triangles[at(t)][1], mesh.triangles[at(t)][2]);

  out.in_closed_piece.assign(nt, 0);
  out.against_file = 0;
  for (const Piece& p : pieces) {
    out.against_file += p.against_file;
    if (p.closed)
      for (Index t : p.triangles) out.in_closed_piece[at(t)] = 1;
  }
  // 6. Whether light can leave the scene: not when every closed piece inside no other is an
  // enclosure and every open piece lies inside one of them (a sheet in a room). A ray from a front
  // side then ends on a face, front or back.
  out.enclosed = !closed.empty();
  for (Sz j = 0; j < pieces.size() && out.enclosed; ++j) {
    const Piece& p = pieces[j];
    if (p.closed) {
      out.enclosed = p.parent != kNone || p.kind == Kind::enclosure;
      continue;
    }
    out.enclosed = std::any_of(closed.begin(), closed.end(), [&](Index i) {
      return pieces[at(i)].parent == kNone && surfaces[at(i)] && where(j, i) == 1;
    });
  }
  out.pieces = pieces.size();
  out.closed_pieces = closed.size();
  out.flipped = 0;
  for (const Piece& p : pieces) out.flipped += p.flipped;
  note_pieces(pieces, out.notes);
  return std::nullopt;
}

}  // namespace panelrad::geometry::validation_detail

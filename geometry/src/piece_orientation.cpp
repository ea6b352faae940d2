// Rule "orientable" of validate_scene (scene_validation.hpp) and the front side of every face.
//
// Pieces: connected components of triangles joined across edges that exactly two triangles share
// (by vertex index; the readers merge coincident vertices). An edge of one triangle (a boundary)
// or of three or more (non-manifold) joins nothing. A piece is closed when every edge of its
// triangles joins two of them.
//
// Within a piece the orientation propagates across joined edges (a neighbour runs the shared edge
// the other way); a piece where it cannot (a Moebius strip) is refused. Of its two consistent
// orientations the one that agrees with the input on most of its area is kept; the triangles that
// disagree are flipped.
//
// Front sides (the side that emits, reflects and sees: the paper's inner normal n):
// - open piece: the side from which its triangles run counter-clockwise (the OBJ/OFF convention);
// - closed piece inside no other closed piece: an enclosure, front inward;
// - closed piece inside another: an object, front outward.
// Nesting is decided with CGAL::Side_of_triangle_mesh (exact predicates, ray parity) on the first
// vertex of the inner piece not on the outer piece's surface (faces may touch), else the centroid
// of one of its triangles. Which side of a closed piece is inside is the sign of its enclosed
// volume (volume_sign, exact).
// Storage: every triangle clockwise seen from its front, its geometric normal (b - a) x (c - a)
// pointing to the back (the convention of validate_closed_convex, counter-clockwise from outside).
#include "validation_internal.hpp"

#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <deque>
#include <memory>
#include <utility>

namespace panelrad::geometry::validation_detail {

namespace {

using SurfaceMesh = CGAL::Surface_mesh<Point>;
using SideOfMesh = CGAL::Side_of_triangle_mesh<SurfaceMesh, Kernel>;

/// The pieces listed in the notes one by one; above this count, one summary note.
constexpr Sz kMaxPieceNotes = 8;

struct Piece {
  std::vector<Index> triangles;
  bool closed = true;
  Sz flipped = 0;                 // triangles flipped to agree with most of the piece's area
  std::vector<Index> containers;  // closed pieces that contain this one (closed pieces only)
  Index parent = kNone;           // the innermost of them
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

bool box_inside(const CGAL::Bbox_3& inner, const CGAL::Bbox_3& outer) {
  for (int k = 0; k < 3; ++k)
    if (inner.min(k) < outer.min(k) || inner.max(k) > outer.max(k)) return false;
  return true;
}

/// Whether `inner` (a closed piece, touching allowed) lies inside the closed surface `outer`.
bool lies_inside(const TriangleMesh& inner, const ClosedSurface& outer) {
  const SideOfMesh& side = *outer.side;
  for (const Vec3& v : inner.vertices) {
    const CGAL::Bounded_side s = side(Point(v.x(), v.y(), v.z()));
    if (s != CGAL::ON_BOUNDARY) return s == CGAL::ON_BOUNDED_SIDE;
  }
  for (const Tri& t : inner.triangles) {
    const Vec3 c = (inner.vertices[at(t[0])] + inner.vertices[at(t[1])] + inner.vertices[at(t[2])]) / 3.0;
    const CGAL::Bounded_side s = side(Point(c.x(), c.y(), c.z()));
    if (s != CGAL::ON_BOUNDARY) return s == CGAL::ON_BOUNDED_SIDE;
  }
  return false;  // every vertex and centroid on the other surface: they would overlap, refused as crossing
}

std::string piece_name(Sz i, const Piece& p) {
  return "piece " + std::to_string(i) + " (" + std::to_string(p.triangles.size()) +
         (p.triangles.size() == 1 ? " triangle, " : " triangles, ") + (p.closed ? "closed)" : "open)");
}

std::string flipped_text(const Piece& p) {
  if (p.flipped == 0) return "";
  return "; " + std::to_string(p.flipped) + (p.flipped == 1 ? " triangle" : " triangles") +
         " flipped to agree with most of its area";
}

void note_pieces(const std::vector<Piece>& pieces, std::vector<std::string>& notes) {
  if (pieces.size() <= kMaxPieceNotes) {
    for (Sz i = 0; i < pieces.size(); ++i) {
      const Piece& p = pieces[i];
      std::string what;
      if (!p.closed)
        what = "an open surface, front side where its faces run counter-clockwise";
      else if (p.parent == kNone)
        what = "an enclosure inside no other closed piece, front side inward";
      else
        what = "an object inside piece " + std::to_string(p.parent) + ", front side outward";
      notes.push_back(piece_name(i, p) + ": " + what + flipped_text(p));
    }
    return;
  }
  Sz enclosures = 0, objects = 0, open = 0, flipped = 0, flipped_pieces = 0;
  Index first_flipped = kNone;
  for (Sz i = 0; i < pieces.size(); ++i) {
    const Piece& p = pieces[i];
    (!p.closed ? open : p.parent == kNone ? enclosures : objects) += 1;
    if (p.flipped > 0) {
      flipped += p.flipped;
      ++flipped_pieces;
      if (first_flipped == kNone) first_flipped = static_cast<Index>(i);
    }
  }
  std::string s = std::to_string(pieces.size()) + " pieces: " + std::to_string(enclosures) +
                  " enclosures (closed, inside no other; front side inward), " + std::to_string(objects) +
                  " objects (closed, inside another; front side outward), " + std::to_string(open) +
                  " open (front side where the faces run counter-clockwise)";
  if (flipped > 0)
    s += "; " + std::to_string(flipped) + " triangles in " + std::to_string(flipped_pieces) +
         " pieces flipped to agree with most of their piece's area (first: piece " + std::to_string(first_flipped) + ")";
  notes.push_back(s);
}

}  // namespace

std::optional<Failure> orient_scene_pieces(TriangleMesh& mesh, ScenePieces& out) {
  const Describe d{mesh};
  const Sz nt = mesh.triangles.size();
  // The neighbours across edges in exactly two triangles; the failure (a boundary or a
  // non-manifold edge) is what makes a piece open here, not an error.
  Adjacency adj;
  (void)build_adjacency(mesh, adj);

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
  std::vector<TriangleMesh> closed_meshes;
  std::vector<std::unique_ptr<ClosedSurface>> surfaces;
  for (Index i : closed) {
    closed_meshes.push_back(piece_mesh(mesh, pieces[at(i)]));
    surfaces.push_back(closed.size() > 1 ? closed_surface(closed_meshes.back()) : nullptr);
  }
  for (Sz a = 0; a < closed.size() && closed.size() > 1; ++a)
    for (Sz b = 0; b < closed.size(); ++b)
      if (a != b && box_inside(surfaces[b]->box, surfaces[a]->box) && lies_inside(closed_meshes[b], *surfaces[a]))
        pieces[at(closed[b])].containers.push_back(closed[a]);
  for (Index i : closed) {
    Piece& p = pieces[at(i)];
    for (Index c : p.containers)
      if (p.parent == kNone || pieces[at(c)].containers.size() > pieces[at(p.parent)].containers.size()) p.parent = c;
  }

  // 4. Stored clockwise from the front: an open piece reversed (its counter-clockwise side is the
  // front); a closed piece counter-clockwise from outside when an enclosure (front inward),
  // from inside when an object (front outward).
  for (Sz k = 0; k < closed.size(); ++k) {
    const Piece& p = pieces[at(closed[k])];
    const TriangleMesh& m = closed_meshes[k];
    const int sign = volume_sign(m, m.vertices[0]);
    if (sign == 0)
      return Failure{"non-degenerate", piece_name(at(closed[k]), p) + ", starting at " + d.triangle(p.triangles[0]) +
                                           ", encloses zero volume, so it has no inside and outside to choose a "
                                           "front side from; remove it or give it a volume"};
    const int want = p.parent == kNone ? 1 : -1;
    if (sign != want)
      for (Index t : p.triangles) std::swap(mesh.triangles[at(t)][1], mesh.triangles[at(t)][2]);
  }
  for (const Piece& p : pieces)
    if (!p.closed)
      for (Index t : p.triangles) std::swap(mesh.triangles[at(t)][1], mesh.triangles[at(t)][2]);

  out.pieces = pieces.size();
  out.closed_pieces = closed.size();
  out.flipped = 0;
  for (const Piece& p : pieces) out.flipped += p.flipped;
  note_pieces(pieces, out.notes);
  return std::nullopt;
}

}  // namespace panelrad::geometry::validation_detail

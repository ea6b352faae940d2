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

bool box_inside(const CGAL::Bbox_3& inner, const CGAL::Bbox_3& outer) {
  for (int k = 0; k < 3; ++k)
    if (inner.min(k) < outer.min(k) || inner.max(k) > outer.max(k)) return false;
  return true;
}

/// Whether `inner` (a piece, touching allowed) lies inside the closed surface `outer`: decided by
/// its first vertex, else triangle centroid, off that surface; nothing when it lies wholly on it
/// (a sheet on a wall: neither inside nor outside).
std::optional<bool> lies_inside(const TriangleMesh& inner, const ClosedSurface& outer) {
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
  return std::nullopt;
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

  // 3. Nesting of the closed pieces, and which pieces lie inside the closed pieces inside no other.
  std::vector<Index> closed;
  for (Sz i = 0; i < pieces.size(); ++i)
    if (pieces[i].closed) closed.push_back(static_cast<Index>(i));
  std::vector<TriangleMesh> piece_meshes(pieces.size());
  for (Sz i = 0; i < pieces.size(); ++i) piece_meshes[i] = piece_mesh(mesh, pieces[i]);
  std::vector<std::unique_ptr<ClosedSurface>> surfaces(pieces.size());
  if (pieces.size() > 1)
    for (Index i : closed) surfaces[at(i)] = closed_surface(piece_meshes[at(i)]);
  // +1 inside, -1 outside, 0 on the surface (neither).
  const auto where = [&](Sz inner, Index outer) {
    if (!box_inside(mesh_box(piece_meshes[inner]), surfaces[at(outer)]->box)) return -1;
    const std::optional<bool> in = lies_inside(piece_meshes[inner], *surfaces[at(outer)]);
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
  // Closed pieces inside no other: an enclosure when nothing of the scene lies outside it, an
  // object when something does and nothing lies inside it; when both, the file's winding decides.
  for (Index i : closed) {
    Piece& p = pieces[at(i)];
    if (p.parent != kNone) continue;
    bool contains = false, outside = false;
    for (Sz j = 0; j < pieces.size() && !(contains && outside); ++j) {
      if (j == at(i)) continue;
      const int w = pieces[j].closed ? (std::find(pieces[j].containers.begin(), pieces[j].containers.end(), i) !=
                                                pieces[j].containers.end()
                                            ? 1
                                            : where(j, i))
                                     : where(j, i);
      if (w == 1) contains = true;
      if (w == -1) outside = true;
    }
    if (!outside) {
      p.kind = Kind::enclosure;
      p.why = contains ? "every other piece lies inside it" : "the only piece of the scene";
    } else if (!contains) {
      p.kind = Kind::object;
      p.why = "other pieces lie outside it and none inside";
    } else {
      p.kind = p.file_front_outward ? Kind::object : Kind::enclosure;
      p.why = "pieces lie both inside and outside it, so the file's winding decides";
    }
  }
  // Nested pieces alternate, from the outermost in: inside an enclosure or a cavity an object,
  // inside an object a cavity. Containers have fewer containers, so the order of depth is safe.
  std::vector<Index> by_depth = closed;
  std::stable_sort(by_depth.begin(), by_depth.end(),
                   [&](Index a, Index b) { return pieces[at(a)].containers.size() < pieces[at(b)].containers.size(); });
  for (Index i : by_depth) {
    Piece& p = pieces[at(i)];
    if (p.parent == kNone) continue;
    const Piece& parent = pieces[at(p.parent)];
    p.kind = parent.kind == Kind::object ? Kind::cavity : Kind::object;
    p.why = (p.kind == Kind::cavity ? "inside the object piece " : "inside the ") +
            std::string(p.kind == Kind::cavity ? "" : parent.kind == Kind::cavity ? "cavity piece " : "enclosure piece ") +
            std::to_string(p.parent);
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

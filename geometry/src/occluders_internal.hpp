#pragma once
// The pieces of the line-of-sight function V(P, Q) of (1) (occluders.hpp): the shaft conv(P, tau)
// as five half-spaces, the cheap rejection of a face against it, the shadow a face casts on tau
// from P (the face clipped to the shaft, projected centrally from P onto tau's plane), and the
// subtraction of convex shadows from convex pieces of tau's plane. Plain double arithmetic with the
// margins of the rounding policy in occluders.hpp; no CGAL here.
#include <panelrad/geometry/occluders.hpp>

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <vector>

namespace panelrad::geometry::occluder_detail {

using Vec2 = Eigen::Vector2d;

/// An occluder, with what the shaft tests need precomputed.
struct FaceData {
  std::array<Vec3, 3> v;           ///< the corners
  Vec3 lo, hi;                     ///< bounding box
  Vec3 n;                          ///< unit normal of the plane (either orientation: faces occlude from both sides)
  std::array<Vec3, 3> edge_in;     ///< unit in-plane normals of the edges (v[i], v[i+1]), pointing into the face
};

FaceData make_face(const std::array<Vec3, 3>& v);

/// The shaft conv(P, tau) cut by the front half-space of P's plane. Every plane is given by a unit
/// normal pointing into the shaft, so that a signed distance > 0 means inside.
struct Shaft {
  Vec3 P;
  Vec3 nP;                         ///< unit normal of P's plane
  std::array<Vec3, 3> t;           ///< tau's corners, counter-clockwise about nQ
  Vec3 nQ;                         ///< unit geometric normal of tau, on the side of the given nQ
  std::array<Vec3, 3> side_n;      ///< unit inward normals of the planes through P and (t[i], t[i+1])
  double height = 0;               ///< distance of P from tau's plane (> margin unless grazing)
  /// P within the margin of tau's plane but strictly in front of it (exact orientation): the shaft
  /// is thinner than the margin, no face is tested against it (see make_shaft).
  bool grazing = false;
  std::array<double, 3> tP{};      ///< signed distances of tau's corners from P's plane
  bool straddles = false;          ///< tau crosses P's plane: its part behind is cut away
  Vec3 lo, hi;                     ///< bounding box of P and tau
  double margin = 0;               ///< kShadowMargin * scene diameter (distances)
  double area_margin = 0;          ///< kShadowMargin * area(tau)
  double area = 0;                 ///< area of tau
  Vec3 u, w;                       ///< orthonormal frame of tau's plane at t[0], (u, w, nQ) right-handed
};

/// P strictly in front of the plane of tau = (t0, t1, t2), counter-clockwise about its front
/// normal: the exact sign of the orientation determinant (occluders.cpp, CGAL's filtered predicate).
bool strictly_in_front(const Vec3& P, const std::array<Vec3, 3>& t);

/// Sets up tau's and P's planes of the shaft; false when nothing of tau is seen whatever the
/// occluders (P on or behind tau's plane, tau on or behind P's plane, both by the margin, except
/// that P within the margin but strictly in front of tau's plane sees it: s.grazing).
bool make_shaft(const Vec3& P, const Vec3& nP, const std::array<Vec3, 3>& tau, const Vec3& nQ, double margin,
                Shaft& s);

/// The rest of a shaft that make_shaft accepted: the side planes, the box and tau's frame (the
/// plane tests alone decide the class when there are no occluders to test).
void complete_shaft(Shaft& s);

/// False when the face cannot cast a shadow of positive area on tau: its box misses the shaft's
/// box, it lies on the outer side of one of the shaft's planes (tau's plane, P's plane, the three
/// planes through P and tau's edges) up to the margin, or its plane passes through P (edge-on).
bool may_meet(const FaceData& f, const Shaft& s);

/// True when the face alone hides all of tau from P: its plane separates P from every corner of
/// tau, and every corner lies inside the three planes through P and the face's edges, each by
/// kCoverMargins margins. Every segment from P to a point of tau (a convex combination of the
/// corners, inside the cone from P over the face and beyond its plane) then crosses the face's
/// interior. False for a shaft that straddles P's plane or grazes tau's.
bool covers_shaft(const FaceData& f, const Shaft& s);

/// The margins by which covers_shaft asks its separations to hold: a face that covers the shaft by
/// less is left to the shadow subtraction.
inline constexpr double kCoverMargins = 4;

/// The shaft between two triangles sigma and tau: conv(sigma, tau), which holds every segment PQ
/// with P in sigma and Q in tau, given by its box and its supporting planes among the planes of
/// sigma and tau and those through an edge of one and a corner of the other (every face of the
/// convex hull of two triangles is one of these).
struct ClusterShaft {
  std::array<Vec3, 6> x;             ///< sigma's corners, then tau's
  std::array<Vec3, 20> out_n;        ///< unit outward normals of the supporting planes
  std::array<double, 20> out_d{};    ///< their offsets: out_n . y <= out_d on the shaft (up to rounding)
  int planes = 0;
  Vec3 lo, hi;                       ///< bounding box of the six corners
};

/// False when the face lies farther than two margins from conv(sigma, tau) along its box's axes,
/// its own normal or a supporting plane of the shaft: it then meets no point shaft conv(P, tau)
/// of a P of sigma (each lies in the cluster shaft) and casts no shadow for any. Conservative: the
/// faces it accepts hold every face that meets some P's shaft; they need not hold every face
/// may_meet accepts (faces near a point's shaft that pass each of its plane tests but miss it).
bool may_enter(const FaceData& f, const ClusterShaft& s, double margin);

/// True when every segment from sigma to tau crosses the face's interior: its plane separates
/// sigma's corners from tau's, and the nine crossings of the segments between their corners (whose
/// convex hull holds every crossing) lie inside its edges, each by kCoverMargins margins.
bool covers_cluster_shaft(const FaceData& f, const ClusterShaft& s, double margin);

/// The class of tau seen from every point of sigma by the planes alone (nS, nT their front
/// normals): hidden when tau lies on or behind sigma's plane (its corners within the margin in
/// front at most) or sigma behind tau's plane by more than the margin, as the point shaft
/// (make_shaft) decides for every P of sigma; full when each lies farther than the margin in front
/// of the other's plane (the shaft s is then set up, and the class stays full only if no face may
/// block it); partial otherwise (undecided here: the points decide).
ShaftClass make_cluster_shaft(const std::array<Vec3, 3>& sigma, const Vec3& nS, const std::array<Vec3, 3>& tau,
                              const Vec3& nT, double margin, ClusterShaft& s);

/// False when face f cannot block a segment of the shaft by more than the margin: an axis
/// separates them up to the margin (its plane leaves all six corners on one side, it lies on the
/// outer side of a supporting plane of the shaft, or an edge of it crossed with a segment between
/// two corners of the shaft separates them). True means they meet, to within the margin.
bool may_block(const FaceData& f, const ClusterShaft& s, double margin);

/// A convex polygon of tau's plane in the frame (u, w) at t[0], counter-clockwise (cast_shadow
/// leaves its box unset).
using Shadow = PlaneShadow;

/// The shadow of the face on tau from P: the face clipped to the shaft, projected from P onto
/// tau's plane. False when its area is at most s.area_margin (no shadow).
bool cast_shadow(const FaceData& f, const Shaft& s, Shadow& out);

/// Convex pieces of a plane, flat: piece k is pts[end[k-1], end[k]) (end[-1] = 0), counter-clockwise.
struct Pieces {
  std::vector<Vec2> pts;
  std::vector<std::uint32_t> end;
  std::vector<double> area;  ///< polygon_area of each piece
  void clear() {
    pts.clear();
    end.clear();
    area.clear();
  }
  void swap(Pieces& o) noexcept {
    pts.swap(o.pts);
    end.swap(o.end);
    area.swap(o.area);
  }
};

/// tau in its frame, cut to the front of P's plane when it straddles it (at most 4 corners).
void front_part_of_tau(const Shaft& s, Pieces& out);

/// The triangle c (counter-clockwise) cut to the front of P's plane when it straddles it: tP are
/// the signed distances of its corners from P's plane, affine along the triangle.
void front_part(const std::array<Vec2, 3>& c, const std::array<double, 3>& tP, bool straddles, Pieces& out);

/// The part of the convex polygon in[0, n) on the inner side (x - o).m >= 0 of a line
/// (Sutherland-Hodgman) into out: at most n + 1 corners (n <= 11). Returns -1, out untouched, when
/// the whole polygon is on the inner side, and 0 when no corner is farther inside than enter_tol
/// (>= 0, in the units of (x - o).m).
int clip_to_half_plane(const Vec2* in, int n, const Vec2& o, const Vec2& m, double enter_tol, Vec2* out);

/// out = in minus the convex shadow poly[0, n) (counter-clockwise), by successive splits along the
/// shadow's edge lines: the part of a piece outside an edge's line is a piece of the difference,
/// the part inside goes on to the next edge, and what is inside every edge is covered. Corners
/// within `tol` of a line count as on it (no sliver pieces); pieces of area at most `min_area` are
/// dropped. `covered` given: the parts inside every edge line (of positive area) are appended to it.
void subtract_convex(const Pieces& in, const Vec2* poly, int n, double tol, double min_area, Pieces& out,
                     Pieces* covered = nullptr);

/// The same with the shadow given by its edge lines longer than tol (a point line_at[j] and the
/// unit normal line_in[j] towards the inside, in counter-clockwise order) and its box [slo, shi].
void subtract_convex(const Pieces& in, const Vec2* line_at, const Vec2* line_in, int n_lines, const Vec2& slo,
                     const Vec2& shi, double tol, double min_area, Pieces& out, Pieces* covered = nullptr);

/// One piece (corners piece[0, np), area piece_area) minus the shadow given by its edge lines, the
/// pieces of the difference appended to out (subtract_convex does this for each piece of `in`).
void subtract_convex_from_piece(const Vec2* piece, int np, double piece_area, const Vec2* line_at,
                                const Vec2* line_in, int n_lines, const Vec2& slo, const Vec2& shi, double tol,
                                double min_area, Pieces& out, Pieces* covered = nullptr);

double polygon_area(const Vec2* p, int n);

/// The counter-clockwise polygon p[0, n) with every corner that is not a strict left turn dropped,
/// repeatedly, in place: the convex hull of a polygon that is convex up to rounding. Returns the
/// number of corners left.
int convex_in_place(Vec2* p, int n);

}  // namespace panelrad::geometry::occluder_detail

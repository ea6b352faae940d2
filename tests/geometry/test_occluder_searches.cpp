// The occluders' searches against their definitions (geometry/src/occluders.cpp):
// - the AABB tree's shaft culling: the faces a shaft search returns are exactly those a scan of
//   every face returns, on a scene large enough for the tree (more than the linear scan's 512
//   faces), with shafts in every direction; the cluster shaft's class agrees with a scan of
//   may_block over every face;
// - the sight of a triangle from a whole cluster (cluster_candidates): hidden only when the
//   point-by-point classification hides it from each of the cluster's points; otherwise a list
//   holding every face that casts a shadow for any of its points, against which each point's
//   class, shadows and visible part are those of its own candidates, bit for bit;
// - a face that alone hides a triangle (hidden_by_a_face, hidden_by_one_of): the same answer from
//   the tree, from a cluster's list, with or without hints, and only where the shadows hide it.
#include <panelrad/geometry/occluders.hpp>

#include "../../geometry/src/occluders_internal.hpp"

#include "../common/occluded_scenes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <vector>

namespace {

using namespace panelrad::geometry;
using namespace panelrad::geometry::occluder_detail;
using Tri = std::array<Vec3, 3>;

TriangleMesh mesh_of(const std::vector<Tri>& tris) {
  return panelrad::testing::triangle_soup(tris, "culling test scene");
}

/// 900 small triangles of random orientation scattered in a box of side 10 (a clutter of faces
/// with shafts of every length and direction between them), placed `offset` from the origin.
std::vector<Tri> clutter(std::mt19937_64& rng, const Vec3& offset) {
  std::uniform_real_distribution<double> u01(0, 1);
  std::vector<Tri> tris;
  for (int i = 0; i < 900; ++i) {
    const Vec3 centre = offset + 10 * Vec3(u01(rng), u01(rng), u01(rng));
    Tri t;
    for (Vec3& v : t) v = centre + 0.4 * Vec3(2 * u01(rng) - 1, 2 * u01(rng) - 1, 2 * u01(rng) - 1);
    tris.push_back(t);
  }
  return tris;
}

Vec3 unit_normal(const Tri& t) { return (t[1] - t[0]).cross(t[2] - t[0]).normalized(); }

Vec3 centroid(const Tri& t) { return (t[0] + t[1] + t[2]) / 3; }

void expect_tree_equals_scan(const Vec3& offset, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const std::vector<Tri> tris = clutter(rng, offset);
  const Occluders occ(mesh_of(tris));
  const double margin = visibility_margin(mesh_of(tris));
  std::vector<FaceData> faces;
  for (const Tri& t : tris) faces.push_back(make_face(t));
  std::uniform_int_distribution<std::size_t> pick(0, tris.size() - 1);
  int compared = 0, nonempty = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Tri& from = tris[pick(rng)];
    const Tri& tau = tris[pick(rng)];
    // Either side of each face may be its front.
    const Vec3 nP = (trial & 1 ? 1.0 : -1.0) * unit_normal(from);
    const Vec3 nQ = (trial & 2 ? 1.0 : -1.0) * unit_normal(tau);
    const Vec3 P = centroid(from);
    std::vector<Index> tree;
    occ.candidates(P, nP, tau, nQ, tree);
    Shaft s;
    std::vector<Index> scan;
    if (make_shaft(P, nP, tau, nQ, margin, s) && !s.grazing) {
      complete_shaft(s);
      for (Index t = 0; t < static_cast<Index>(faces.size()); ++t)
        if (may_meet(faces[static_cast<std::size_t>(t)], s)) scan.push_back(t);
    }
    EXPECT_EQ(tree, scan) << "trial " << trial;
    ++compared;
    if (!scan.empty()) ++nonempty;
  }
  EXPECT_EQ(compared, 400);
  EXPECT_GT(nonempty, 50) << "shafts that meet faces";
}

TEST(OccluderSearches, TreeCandidatesAreTheScansFacesInEveryDirection) {
  expect_tree_equals_scan(Vec3(0, 0, 0), 17);
}

TEST(OccluderSearches, TreeCandidatesAreTheScansFacesFarFromTheOrigin) {
  // At 1e6 the margin is mostly the rounding of the coordinates (64 eps max|x|): the culling's
  // allowance for rounding is tested where it is tightest relative to the margin.
  expect_tree_equals_scan(Vec3(1e6, -2e6, 3e6), 18);
}

TEST(OccluderSearches, ClusterPairsAreFullExactlyWhenAScanFindsNoBlocker) {
  std::mt19937_64 rng(19);
  const std::vector<Tri> tris = clutter(rng, Vec3(0, 0, 0));
  const Occluders occ(mesh_of(tris));
  const double margin = visibility_margin(mesh_of(tris));
  std::vector<FaceData> faces;
  for (const Tri& t : tris) faces.push_back(make_face(t));
  std::uniform_int_distribution<std::size_t> pick(0, tris.size() - 1);
  std::uniform_real_distribution<double> u01(0, 1);
  int full = 0, blocked = 0;
  for (int trial = 0; trial < 6000; ++trial) {
    // Small sub-triangles of two faces near each other, so that both classes occur.
    const Tri& a = tris[pick(rng)];
    Tri b = tris[pick(rng)];
    if ((centroid(a) - centroid(b)).norm() > 4) continue;
    const double shrink = 0.3 + 0.7 * u01(rng);
    for (Vec3& v : b) v = centroid(b) + shrink * (v - centroid(b));
    const Vec3 nS = unit_normal(a), nT = (trial & 1 ? 1.0 : -1.0) * unit_normal(b);
    const ShaftClass cls = occ.classify_clusters(a, nS, b, nT);
    ClusterShaft s;
    if (make_cluster_shaft(a, nS, b, nT, margin, s) != ShaftClass::full) continue;
    const bool any = std::any_of(faces.begin(), faces.end(), [&](const FaceData& f) { return may_block(f, s, margin); });
    EXPECT_EQ(cls, any ? ShaftClass::partial : ShaftClass::full) << "trial " << trial;
    (any ? blocked : full)++;
  }
  EXPECT_GT(full, 20);
  EXPECT_GT(blocked, 20);
}

/// A city block: an 8 x 8 grid of boxes of unit footprint and heights 1..4 (walls and roof, two
/// triangles a face, fronts outside) on ground cells (fronts up) between them: 1,090 faces, most of
/// them hidden from most points by a nearer box.
struct City {
  std::vector<Tri> tris;
  std::vector<Vec3> front;  // the front normal of each face
};

City city() {
  City c;
  const auto quad = [&](const Vec3& a, const Vec3& b, const Vec3& d, const Vec3& n) {
    // The rectangle a, b, b + (d - a), d, its front n.
    const Vec3 e = b + (d - a);
    c.tris.push_back(Tri{a, b, e});
    c.tris.push_back(Tri{a, e, d});
    c.front.push_back(n);
    c.front.push_back(n);
  };
  const int K = 8;
  for (int i = 0; i <= 2 * K; ++i)
    for (int j = 0; j <= 2 * K; ++j) {
      const bool box = i % 2 == 1 && j % 2 == 1;
      const double x = i, y = j;
      if (!box) {
        quad(Vec3(x, y, 0), Vec3(x + 1, y, 0), Vec3(x, y + 1, 0), Vec3(0, 0, 1));
        continue;
      }
      const double h = 1 + ((3 * i + 5 * j) % 4);
      quad(Vec3(x, y, h), Vec3(x + 1, y, h), Vec3(x, y + 1, h), Vec3(0, 0, 1));
      quad(Vec3(x, y, 0), Vec3(x + 1, y, 0), Vec3(x, y, h), Vec3(0, -1, 0));
      quad(Vec3(x, y + 1, 0), Vec3(x + 1, y + 1, 0), Vec3(x, y + 1, h), Vec3(0, 1, 0));
      quad(Vec3(x, y, 0), Vec3(x, y + 1, 0), Vec3(x, y, h), Vec3(-1, 0, 0));
      quad(Vec3(x + 1, y, 0), Vec3(x + 1, y + 1, 0), Vec3(x + 1, y, h), Vec3(1, 0, 0));
    }
  return c;
}

/// The 16 sub-triangles of t two midpoint subdivisions down.
std::vector<Tri> grandchildren(const Tri& t) {
  const auto children = [](const Tri& p) {
    const Vec3 m01 = (p[0] + p[1]) / 2, m12 = (p[1] + p[2]) / 2, m20 = (p[2] + p[0]) / 2;
    return std::array<Tri, 4>{Tri{p[0], m01, m20}, Tri{m01, p[1], m12}, Tri{m20, m12, p[2]}, Tri{m01, m12, m20}};
  };
  std::vector<Tri> out;
  for (const Tri& c : children(t))
    for (const Tri& g : children(c)) out.push_back(g);
  return out;
}

TEST(OccluderSearches, ClusterSightsHoldEveryPointsCandidatesAndHideOnlyWhatEachPointFindsHidden) {
  const City c = city();
  const Occluders occ(mesh_of(c.tris));
  std::vector<Index> all(c.tris.size());
  for (std::size_t t = 0; t < all.size(); ++t) all[t] = static_cast<Index>(t);
  std::mt19937_64 rng(23);
  std::uniform_int_distribution<std::size_t> pick(0, c.tris.size() - 1);
  int hidden = 0, listed = 0, points_hidden_by_one = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const std::size_t si = pick(rng), ti = pick(rng);
    const Tri& sigma = c.tris[si];
    const Tri& tau = c.tris[ti];
    const Vec3 &nS = c.front[si], &nT = c.front[ti];
    std::vector<Index> list;
    const ClusterSight sight = occ.cluster_candidates(sigma, nS, tau, nT, list);
    EXPECT_FALSE(sight.hidden && sight.listed);
    EXPECT_TRUE(std::is_sorted(list.begin(), list.end()));
    hidden += sight.hidden;
    listed += sight.listed;
    BlockerHints hints;
    for (const Tri& g : grandchildren(sigma)) {
      const Vec3 P = centroid(g);
      std::vector<Index> own, meeting_own, meeting_all;
      const bool by_one = occ.hidden_by_a_face(P, nS, tau, nT, own);
      std::vector<Index> candidates;
      occ.candidates(P, nS, tau, nT, candidates);
      const ShaftClass cls_all = occ.classify(P, nS, tau, nT, all, meeting_all);
      if (by_one) {
        EXPECT_TRUE(own.empty());
        EXPECT_EQ(cls_all, ShaftClass::hidden) << "trial " << trial << ": one face hides tau, the shadows do not";
        ++points_hidden_by_one;
      } else {
        EXPECT_EQ(own, candidates);
      }
      if (sight.hidden) {
        EXPECT_EQ(cls_all, ShaftClass::hidden) << "trial " << trial << ": hidden from sigma, not from a point";
        continue;
      }
      if (!sight.listed) continue;
      EXPECT_EQ(occ.hidden_by_one_of(P, nS, tau, nT, list, &hints), by_one) << "trial " << trial;
      VisiblePart part_list, part_own;
      std::vector<Index> meeting_list;
      const ShaftClass cls_list = occ.classify(P, nS, tau, nT, list, meeting_list, &part_list);
      const ShaftClass cls_own = occ.classify(P, nS, tau, nT, candidates, meeting_own, &part_own);
      // Every face that casts a shadow for P is listed (candidates may hold more: faces near the
      // shaft that pass each of its plane tests but miss it).
      for (const Index t : meeting_own) EXPECT_TRUE(std::binary_search(list.begin(), list.end(), t)) << "face " << t;
      EXPECT_EQ(cls_list, cls_own);
      EXPECT_EQ(meeting_list, meeting_own);
      EXPECT_EQ(part_list.points, part_own.points);
      EXPECT_EQ(part_list.area, part_own.area);
    }
  }
  EXPECT_GT(hidden, 30);
  EXPECT_GT(listed, 30);
  EXPECT_GT(points_hidden_by_one, 100);
}

}  // namespace

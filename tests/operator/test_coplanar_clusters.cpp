// Clusters coplanar with the collocation point (section 4.2, case (a)): G(P, Q) = 0 on P's whole
// plane, so every cluster in it is skipped with its subtree and counted, whichever facet it is in.
#include <panelrad/geometry/scene_validation.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/operator/detail/fast_operator_testing.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/scene/scene.hpp>

#include "test_scenes.hpp"

#include "test_support.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <random>
#include <string>

namespace {

using namespace panelrad;

const std::string kScenes = std::string(PANELRAD_SOURCE_DIR) + "/examples/scenes/";

using panelrad::testing::random_vector;

// Whether element e lies in the plane of row i's element, in double precision, independently of
// the tree's plane ids: its corners within 1e-12 of the diameter of P's plane.
bool in_plane_of_row(const geometry::ClusterTree& tree, Index i, Index e) {
  const geometry::Cluster& p = tree.elements()[static_cast<std::size_t>(i)];
  const geometry::Cluster& q = tree.elements()[static_cast<std::size_t>(e)];
  for (const Vec3& v : q.vertex)
    if (std::abs(p.normal.dot(v - p.vertex[0])) > 1e-12 * tree.diameter()) return false;
  return true;
}

// The cube with each of its 12 triangles a facet of its own: the two triangles of a side are
// distinct facets in one plane. Its operators skip the same clusters as those of the cube with 6
// square facets, so they are the same bit for bit: the fast product, its coverings and counts,
// and the dense matrix.
TEST(CoplanarClusters, SplitFacetsSkipTheWholePlane) {
  geometry::TriangleMesh split = panelrad::testing::validated_builtin("cube");
  for (std::size_t t = 0; t < split.triangles.size(); ++t) split.facet_of_triangle[t] = static_cast<Index>(t);
  split.num_facets = static_cast<Index>(split.triangles.size());
  Scene squares = panelrad::testing::reflecting_builtin("cube", 0.5);
  Scene triangles(split);
  triangles.set_reflectivity(0.5);
  const Collocation a(squares, 3), b(triangles, 3);
  FastOptions o;
  o.eta = 0.5;
  o.degree = 5;
  const FastOperator fa(a, o), fb(b, o);
  EXPECT_EQ(fa.statistics().far_pairs, fb.statistics().far_pairs);
  EXPECT_EQ(fa.statistics().near_pairs, fb.statistics().near_pairs);
  EXPECT_EQ(fa.statistics().skipped_coplanar, fb.statistics().skipped_coplanar);
  for (Index i = 0; i < a.size(); ++i) {
    ASSERT_EQ(detail::far_clusters(fa, i), detail::far_clusters(fb, i)) << "row " << i;
    ASSERT_EQ(detail::near_elements(fa, i), detail::near_elements(fb, i)) << "row " << i;
    for (Index e : detail::near_elements(fb, i)) ASSERT_FALSE(in_plane_of_row(b.tree(), i, e));
    for (Index id : detail::far_clusters(fb, i)) {
      const auto [l, k] = detail::cluster_of_id(fb, id);
      ASSERT_FALSE(in_plane_of_row(b.tree(), i, b.tree().first_element(l, k))) << "row " << i;
    }
  }
  const Eigen::VectorXd v = random_vector(a.size(), 5);
  Eigen::VectorXd ya, yb;
  fa.apply(v, ya);
  fb.apply(v, yb);
  EXPECT_EQ(ya, yb);
  const DenseOperator da(a, NearFieldOptions{}), db(b, NearFieldOptions{});
  EXPECT_EQ(da.matrix(), db.matrix());
}

// The Cornell box with V: the light lies in the ceiling's plane. No row's covering holds a cluster
// of its own plane, and skipped_coplanar counts, per row, the roots in P's plane (counted here
// from the geometry in double precision).
TEST(CoplanarClusters, OccludedRootsInThePlaneOfPAreSkippedAndCounted) {
  const Scene scene = panelrad::testing::general_scene(geometry::load_scene_mesh(kScenes + "cornell_box.obj"));
  const Collocation col(scene, 1);
  const geometry::ClusterTree& tree = col.tree();
  FastOptions o;
  o.eta = 0.5;
  o.degree = 4;
  o.occluders = scene_occluders(tree);
  const FastOperator fast(col, o);
  std::size_t expected = 0, other_facet = 0;
  const int L = tree.finest_level();
  for (Index i = 0; i < col.size(); ++i) {
    for (Index r = 0; r < tree.num_roots(); ++r) {
      const bool coplanar = in_plane_of_row(tree, i, tree.first_element(0, r));
      expected += coplanar;
      other_facet += coplanar && tree.cluster(0, r).facet != tree.elements()[static_cast<std::size_t>(i)].facet;
    }
    for (Index e : detail::near_elements(fast, i)) ASSERT_NE(tree.plane(L, e), tree.plane(L, i));
    for (Index id : detail::far_clusters(fast, i)) {
      const auto [l, k] = detail::cluster_of_id(fast, id);
      ASSERT_NE(tree.plane(l, k), tree.plane(L, i)) << "row " << i;
    }
  }
  EXPECT_GT(other_facet, 0u);  // the light's rows skip the ceiling's roots, and the other way round
  EXPECT_EQ(fast.statistics().skipped_coplanar, expected);
}

}  // namespace

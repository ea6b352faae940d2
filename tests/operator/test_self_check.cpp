// The self-check (self_check.hpp) as a component of its own, on any RadiosityOperator: the dense
// matrix K_n of (33) agrees with the exact closed-form rows up to the rounding of its sums
// (~1e-15 relative, far below any fast operator's error), a perturbed product is measured at its
// perturbation, and the fast operator's check through its whole product apply() is, bit for bit,
// the check it makes on the sampled rows alone (FastOperator::self_check).
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/operator/self_check.hpp>
#include <panelrad/scene/scene.hpp>

#include "occluded_scenes.hpp"
#include "test_scenes.hpp"

#include "self_check_expectations.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>

namespace panelrad {
namespace {

// K_n v scaled by (1 + epsilon) row by row: a product off by epsilon relative, entry by entry.
class ScaledOperator final : public RadiosityOperator {
 public:
  ScaledOperator(const RadiosityOperator& op, double epsilon) : op_(op), epsilon_(epsilon) {}
  geometry::Index size() const override { return op_.size(); }
  void apply(const Eigen::VectorXd& v, Eigen::VectorXd& y) const override {
    op_.apply(v, y);
    y *= 1 + epsilon_;
  }
  std::string name() const override { return "scaled"; }
  std::size_t bytes() const override { return op_.bytes(); }

 private:
  const RadiosityOperator& op_;
  double epsilon_;
};

void expect_same_check(const SelfCheck& a, const SelfCheck& b) {
  EXPECT_EQ(a.rows, b.rows);
  testing::expect_same_check(a, b);
}

TEST(SelfCheck, DenseOperatorIsExactUpToRounding) {
  const Scene cube = make_paper_cube_scene();
  const Collocation col(cube, 3);  // n = 768
  const DenseOperator dense(col, NearFieldOptions{});
  const SelfCheck check = self_check(dense, col);
  EXPECT_GE(check.rows, 24);  // 16 evenly spaced + up to 16 corner rows, duplicates merged
  EXPECT_EQ(check.rows, static_cast<int>(check.sampled_rows.size()));
  ASSERT_EQ(check.vectors.size(), 6u);
  for (const SelfCheckVector& v : check.vectors) {
    EXPECT_LT(v.relative_error, 1e-13) << v.name;
    EXPECT_TRUE(std::binary_search(check.sampled_rows.begin(), check.sampled_rows.end(), v.row)) << v.name;
  }
  EXPECT_LT(check.relative_error, 1e-13);
  // The same reference, made once, for a product off by 1e-6: measured as 1e-6 (the constant
  // vector, K 1 >= 0, gives exactly the perturbation relative to K |1|).
  const SelfCheckReference reference = self_check_reference(col, nullptr, 32);
  expect_same_check(self_check(dense, reference), check);
  const SelfCheck off = self_check(ScaledOperator(dense, 1e-6), reference);
  EXPECT_NEAR(off.vectors.front().relative_error, 1e-6, 1e-9);
  EXPECT_NEAR(off.relative_error, 1e-6, 1e-9);
}

TEST(SelfCheck, DenseOperatorWithVisibility) {
  Scene scene = testing::general_scene(testing::room_with_box());
  const Collocation col(scene, 1);
  const auto occluders = scene_occluders(col.tree());
  const DenseOperator dense(col, NearFieldOptions{}, occluders);
  const SelfCheck check = self_check(dense, col, occluders.get(), 16);
  EXPECT_GT(check.rows, 0);
  EXPECT_LT(check.relative_error, 1e-13);
  // Without V the exact rows are those of the convex surface: the shadows are an O(1) error.
  EXPECT_GT(self_check(dense, col, nullptr, 16).relative_error, 1e-3);
}

TEST(SelfCheck, FastOperatorByItsProductMatchesItsSampledRows) {
  const Scene cube = make_paper_cube_scene();
  const Collocation col(cube, 4);  // n = 3072
  FastOptions fo;
  fo.eta = 0.4;
  fo.degree = 6;
  const FastOperator fast(col, fo);
  const SelfCheck by_rows = fast.self_check(32);
  const SelfCheck by_product = self_check(fast, col);
  expect_same_check(by_product, by_rows);
  EXPECT_GT(by_rows.relative_error, 1e-9);  // the Taylor remainder, not rounding
  EXPECT_LT(by_rows.relative_error, 1e-3);
  // The exact side is the operator's own: the same reference from the collocation.
  const SelfCheckReference mine = fast.self_check_reference(32), theirs = self_check_reference(col, nullptr, 32);
  EXPECT_EQ(mine.rows, theirs.rows);
  EXPECT_EQ(mine.exact, theirs.exact);
  EXPECT_EQ(mine.scale, theirs.scale);
  ASSERT_EQ(fast.self_check_vectors().size(), theirs.vectors.size());
  for (std::size_t k = 0; k < theirs.vectors.size(); ++k)
    EXPECT_EQ(fast.self_check_vectors()[k].second, theirs.vectors[k].second) << theirs.vectors[k].first;
}

TEST(SelfCheck, RejectsAReferenceOfOtherRows) {
  const Scene cube = make_paper_cube_scene();
  const Collocation col(cube, 2);
  const DenseOperator dense(col, NearFieldOptions{});
  SelfCheckReference reference = self_check_reference(col, nullptr, 8);
  SelfCheckReference bad = reference;
  bad.rows.push_back(col.size());
  EXPECT_THROW(self_check(dense, bad), std::invalid_argument);
  bad = reference;
  bad.exact.pop_back();
  EXPECT_THROW(self_check(dense, bad), std::invalid_argument);
  EXPECT_THROW(self_check_reference(col.tree(), {}, nullptr, 8), std::invalid_argument);  // weights of n rows
}

}  // namespace
}  // namespace panelrad

// Products of several vectors at once (RadiosityOperator::apply_block): every column of the block
// product is the single product of that column, bit for bit (the same sums in the same order), for
// the fast operator on a convex surface and with the line-of-sight function V, across the
// operator's column groups (FastOperator::kBlockColumns), and for the dense operator's default.
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/scene/scene.hpp>

#include "occluded_scenes.hpp"
#include "test_scenes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>

namespace panelrad {
namespace {

// Columns unlike each other: uniform, sign-changing, smooth in the index, and zero.
Eigen::MatrixXd test_block(Index n, Index columns) {
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> U(-1.0, 1.0);
  Eigen::MatrixXd V(n, columns);
  for (Index c = 0; c < columns; ++c)
    for (Index i = 0; i < n; ++i)
      V(i, c) = c % 4 == 0 ? U(gen) : c % 4 == 1 ? std::cos(0.37 * static_cast<double>(i) + c) : c % 4 == 2 ? 1.0 + 1e-3 * i : 0.0;
  return V;
}

void expect_columns_bit_identical(const RadiosityOperator& op, Index columns) {
  const Eigen::MatrixXd V = test_block(op.size(), columns);
  Eigen::MatrixXd Y;
  op.apply_block(V, Y);
  ASSERT_EQ(Y.rows(), op.size());
  ASSERT_EQ(Y.cols(), columns);
  for (Index c = 0; c < columns; ++c) {
    Eigen::VectorXd y;
    op.apply(V.col(c), y);
    for (Index i = 0; i < op.size(); ++i)
      ASSERT_EQ(Y(i, c), y[i]) << op.name() << ": column " << c << " of " << columns << ", row " << i;
  }
}

Scene room_scene() { return testing::general_scene(testing::room_with_box()); }

TEST(BlockProduct, FastConvexColumnsAreSingleProducts) {
  const Scene cube = testing::reflecting_builtin("cube");
  const Collocation col(cube, 3);
  const auto op = make_operator(col, testing::fast_options(0.4, 6));
  ASSERT_GT(dynamic_cast<const FastOperator&>(*op).statistics().far_pairs, 0u);
  for (const Index columns : {1, 2, 3, 4, 5, 9}) expect_columns_bit_identical(*op, columns);
}

TEST(BlockProduct, FastOccludedColumnsAreSingleProducts) {
  const Scene room = room_scene();
  const Collocation col(room, 2);
  const auto op = make_operator(col, testing::fast_options(0.4, 4), Visibility::occluded);
  for (const Index columns : {1, 3, 6}) expect_columns_bit_identical(*op, columns);
}

TEST(BlockProduct, FastWithCoefficientsRecomputed) {
  const Scene cube = testing::reflecting_builtin("cube");
  const Collocation col(cube, 3);
  FastOptions o;
  o.eta = 0.5;
  o.degree = 4;
  o.far_storage_limit = 1;  // nothing fits: the coefficients (44)-(45) are recomputed per row
  const FastOperator op(col, o);
  ASSERT_GT(op.statistics().far_pairs, 0u);
  ASSERT_FALSE(op.statistics().far_stored);
  expect_columns_bit_identical(op, 3);
}

TEST(BlockProduct, DenseDefaultColumnsAreSingleProducts) {
  const Scene room = room_scene();
  const Collocation col(room, 1);
  OperatorOptions o;
  o.method = OperatorMethod::dense;
  const auto op = make_operator(col, o, Visibility::occluded);
  expect_columns_bit_identical(*op, 3);
}

TEST(BlockProduct, RefusesWrongSizesAndPartialOperators) {
  const Scene cube = testing::reflecting_builtin("cube");
  const Collocation col(cube, 2);
  FastOptions o;
  o.eta = 0.5;
  o.degree = 3;
  const FastOperator whole(col, o);
  Eigen::MatrixXd Y;
  EXPECT_THROW(whole.apply_block(Eigen::MatrixXd::Ones(whole.size() + 1, 2), Y), std::invalid_argument);
  o.rows = {0, 10};
  const FastOperator part(col, o);
  EXPECT_THROW(part.apply_block(Eigen::MatrixXd::Ones(part.size(), 2), Y), std::logic_error);
}

}  // namespace
}  // namespace panelrad

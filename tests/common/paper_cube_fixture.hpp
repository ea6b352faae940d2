#pragma once
// A test fixture holding the paper's cube (31) at one level, its collocation and its dense
// operator (exact closed-form entries), built once per test suite: the reference of the fast
// operator's tests.
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/scene/scene.hpp>

#include <gtest/gtest.h>

#include <memory>

namespace panelrad::testing {

template <int Level>
struct PaperCubeFixture : ::testing::Test {
  static void SetUpTestSuite() {
    scene = std::make_unique<Scene>(make_paper_cube_scene());
    collocation = std::make_unique<Collocation>(*scene, Level);
    dense = std::make_unique<DenseOperator>(*collocation, NearFieldOptions{});
  }
  static void TearDownTestSuite() {
    dense.reset();
    collocation.reset();
    scene.reset();
  }
  static inline std::unique_ptr<Scene> scene;
  static inline std::unique_ptr<Collocation> collocation;
  static inline std::unique_ptr<DenseOperator> dense;
};

}  // namespace panelrad::testing

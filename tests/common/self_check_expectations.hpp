#pragma once
// Two self-checks (operator/self_check.hpp) that must agree bit for bit: the relative error, the
// sampled rows, and each test vector's error and worst row.
#include <panelrad/operator/self_check.hpp>

#include <gtest/gtest.h>

namespace panelrad::testing {

inline void expect_same_check(const SelfCheck& a, const SelfCheck& b) {
  EXPECT_EQ(a.relative_error, b.relative_error);
  EXPECT_EQ(a.sampled_rows, b.sampled_rows);
  ASSERT_EQ(a.vectors.size(), b.vectors.size());
  for (std::size_t k = 0; k < a.vectors.size(); ++k) {
    EXPECT_EQ(a.vectors[k].name, b.vectors[k].name);
    EXPECT_EQ(a.vectors[k].relative_error, b.vectors[k].relative_error) << a.vectors[k].name;
    EXPECT_EQ(a.vectors[k].row, b.vectors[k].row) << a.vectors[k].name;
  }
}

}  // namespace panelrad::testing

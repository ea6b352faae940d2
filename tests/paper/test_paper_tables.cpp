// The paper's own figures as the truth: Table 1 (centroid method, dense, exact entries) with
// Example 2's Neumann ratio (36), and Table 3 (fast method, (eta, mu, M) = (0.2, 2, 2), composite
// Stroud T2:5-1 near field, section 4.2). The figures are read from the project's copies in
// tests/data/paper/, each file naming its table.
//
// Tolerance: the paper prints 3 significant digits, so its figure is the true error to within half
// a unit of the last digit, up to 0.5 / 1.37 = 0.37% relative in these tables; 1% leaves room for
// the iteration's stopping error (tied to 1e-5 h/diam, 0.03% of the discretization error) and
// nothing else. A wrong kernel, normal, collocation point or far-field term moves the error by far
// more (e.g. M = 1 instead of 2 moves n = 3072 from 3.78e-3 to 7.49e-3, Table 2).
#include <panelrad/paper/cube_example.hpp>

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace {

using namespace panelrad;

// Rows of a CSV copy under tests/data/paper/: '#' lines are comments, the first other line names
// the columns. Every row is returned as column name -> text.
std::vector<std::map<std::string, std::string>> read_paper_csv(const std::string& name) {
  const std::string path = std::string(PANELRAD_SOURCE_DIR) + "/tests/data/paper/" + name;
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << "cannot read " << path;
  std::vector<std::string> columns;
  std::vector<std::map<std::string, std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::istringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
    if (columns.empty()) {
      columns = cells;
      continue;
    }
    std::map<std::string, std::string> row;
    for (std::size_t k = 0; k < columns.size() && k < cells.size(); ++k) row[columns[k]] = cells[k];
    rows.push_back(row);
  }
  return rows;
}

// Table 1: n -> max error.
std::map<Index, double> table1() {
  std::map<Index, double> t;
  for (const auto& row : read_paper_csv("table1_centroid_errors.csv")) t[std::stol(row.at("n"))] = std::stod(row.at("max_error"));
  return t;
}

// Table 3 (M = 2) of tables2to4: (n, eta, mu) -> max error.
std::map<std::tuple<Index, double, int>, double> table3() {
  std::map<std::tuple<Index, double, int>, double> t;
  for (const auto& row : read_paper_csv("tables2to4_fast_method.csv"))
    if (std::stoi(row.at("M")) == 2)
      t[{std::stol(row.at("n")), std::stod(row.at("eta")), std::stoi(row.at("mu"))}] = std::stod(row.at("max_error"));
  return t;
}

void expect_table1_rows(int min_level, int max_level) {
  const auto table = table1();
  ASSERT_EQ(table.size(), 6u) << "tests/data/paper/table1_centroid_errors.csv: expected n = 12 .. 12288";
  CubeRunOptions o;
  o.min_level = min_level;
  o.max_level = max_level;
  o.op.method = OperatorMethod::dense;  // exact closed-form entries (the paper's Table 1)
  o.solver.tolerance = 0;  // tied to the discretization error, as the CLI does
  o.solver.kind = SolverKind::neumann;  // the paper's iteration (34), whose ratio Example 2 gives
  const auto rows = run_paper_cube(o);
  ASSERT_EQ(rows.size(), static_cast<std::size_t>(max_level - min_level + 1));
  for (const auto& r : rows) {
    const double paper = table.at(r.n);
    std::printf("[paper] Table 1, n = %ld: %.4e (paper %.2e), Neumann ratio %.4f\n", static_cast<long>(r.n),
                r.max_error, paper, r.conv_ratio);
    EXPECT_NEAR(r.max_error, paper, 0.01 * paper) << "Table 1, n = " << r.n;
    // Example 2: the Neumann ratio (36) is about 0.40 for n >= 48 (measured 0.3974-0.3977).
    if (r.n >= 48) {
      EXPECT_GE(r.conv_ratio, 0.39) << "n = " << r.n;
      EXPECT_LE(r.conv_ratio, 0.41) << "n = " << r.n;
    }
  }
}

TEST(PaperTables, Table1AndExample2UpTo768) { expect_table1_rows(0, 3); }

// n = 3072 and 12288 with the dense matrix: about 10 s of setup at n = 12288 on 2 cores (Release),
// hence the label "slow" (ctest -L slow); the Release suite runs it.
TEST(PaperTablesSlow, Table1At3072And12288) { expect_table1_rows(4, 5); }

// Table 3's (eta, mu, M) = (0.2, 2, 2) column, the setting the paper recommends, with the composite
// Stroud T2:5-1 rule (section 4.2) in the near field: n = 768, 3072, 12288.
TEST(PaperTablesSlow, Table3CompositeRuleRows) {
  const auto table = table3();
  CubeRunOptions o;
  o.min_level = 3;
  o.max_level = 5;
  o.op.method = OperatorMethod::fast;
  o.op.local.enabled = false;  // the paper's per-point coverings (42)
  o.op.eta = 0.2;
  o.op.degree = 2;
  o.op.near.rule = NearRule::quadrature;
  o.op.near.mu = 2;
  o.op.near.basic_rule = "stroud7";
  o.solver.tolerance = 0;
  const auto rows = run_paper_cube(o);
  ASSERT_EQ(rows.size(), 3u);
  for (const auto& r : rows) {
    const auto it = table.find({r.n, 0.2, 2});
    ASSERT_NE(it, table.end()) << "Table 3 has no (0.2, 2) entry for n = " << r.n;
    std::printf("[paper] Table 3 (0.2, 2, 2), n = %ld: %.4e (paper %.2e)\n", static_cast<long>(r.n), r.max_error,
                it->second);
    EXPECT_NEAR(r.max_error, it->second, 0.01 * it->second) << "Table 3, n = " << r.n;
    EXPECT_GT(r.far_pairs, 0u) << "the fast path must use the far field, n = " << r.n;
  }
}

}  // namespace

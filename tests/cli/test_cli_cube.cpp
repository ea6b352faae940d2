// The `panelrad cube` command: table, CSV format, exit statuses, refusal of sizes that won't fit.
#include "cli_run.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace {

using panelrad::testing::CliRun;
CliRun run(const std::string& args, const std::string& redirect = "2>&1") {
  return panelrad::testing::run_cli(args, redirect);
}

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("panelrad_cli_cube_" + std::to_string(::getpid()) + "_" + name)).string();
}

TEST(CliCube, DenseCsvHasTheDocumentedHeaderAndOneRowPerN) {
  const std::string csv = temp_path("dense.csv");
  const CliRun r = run("cube --levels 1 --csv " + csv);
  ASSERT_EQ(r.status, 0) << r.output;
  const auto lines = lines_of(csv);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "method,near,eta,mu,degree,n,max_error,setup_s,solve_s,iterations,conv_ratio,peak_rss_mb");
  // eta and degree empty for dense, mu empty for the exact rule
  EXPECT_EQ(lines[1].rfind("dense,exact,,,,12,", 0), 0u) << lines[1];
  const double error = std::stod(lines[1].substr(std::string("dense,exact,,,,12,").size()));
  EXPECT_NEAR(error, 7.61e-2, 0.01 * 7.61e-2);  // Table 1, n = 12
  EXPECT_NE(lines[2].find(",48,"), std::string::npos) << lines[2];
  std::filesystem::remove(csv);
}

TEST(CliCube, FastCsvFillsEtaAndDegree) {
  const std::string csv = temp_path("fast.csv");
  const CliRun r = run("cube --method fast --eta 0.3 --degree 3 --levels 1 --csv " + csv);
  ASSERT_EQ(r.status, 0) << r.output;
  const auto lines = lines_of(csv);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[1].rfind("fast,exact,0.3,,3,12,", 0), 0u) << lines[1];
  EXPECT_NE(r.output.find("far pairs"), std::string::npos) << r.output;
  std::filesystem::remove(csv);
}

TEST(CliCube, UsageErrorsExitWithTwo) {
  EXPECT_EQ(run("cube --bogus 1").status, 2);
  EXPECT_EQ(run("cube --levels").status, 2);
  EXPECT_EQ(run("cube --levels x").status, 2);
  EXPECT_EQ(run("cube --method sparse").status, 2);
  EXPECT_EQ(run("cube --solver lu --method fast").status, 2);
  EXPECT_EQ(run("cube --eta 1.5").status, 2);
  EXPECT_EQ(run("cube --min-level 3 --levels 2").status, 2);
}

// n = 12 * 4^8 = 786432: the dense matrix needs ~4.9 TB; refused at once with the estimate.
TEST(CliCube, DenseLevelThatCannotFitIsRefusedBeforeWork) {
  const CliRun r = run("cube --method dense --min-level 8 --levels 8");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("786432"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("needs"), std::string::npos) << r.output;
}

// n = 12 * 4^14 = 3,221,225,472 elements: more than a 32-bit element index numbers. Refused by
// that reason at once (every level is checked before level 0 is solved), status 1, automatic and
// manual parameters alike; level 13 (805,306,368 elements) is numbered, and refused by memory.
TEST(CliCube, LevelBeyondTheElementIndexIsRefusedByItsCount) {
  for (const std::string& args : {std::string("cube --levels 14"), std::string("cube --min-level 15 --levels 15"),
                                  std::string("cube --method fast --eta 0.5 --degree 6 --levels 14"),
                                  std::string("cube --levels 1000000")}) {
    const CliRun r = run(args);
    EXPECT_EQ(r.status, 1) << args << "\n" << r.output;
    EXPECT_CONTAINS(r.output, "12 * 4^1");
    EXPECT_CONTAINS(r.output, "2147483647");
    EXPECT_EQ(r.output.find("must be positive"), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("Cube example"), std::string::npos) << "solved before the refusal:\n" << r.output;
  }
  const CliRun r13 = run("cube --min-level 13 --levels 13");
  EXPECT_EQ(r13.status, 1) << r13.output;
  EXPECT_CONTAINS(r13.output, "805306368");
  EXPECT_CONTAINS(r13.output, "needs");
}

TEST(CliCube, UnwritableCsvIsAnErrorAndLeavesNoFile) {
  const CliRun r = run("cube --levels 0 --csv /nonexistent-dir/x.csv");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_FALSE(std::filesystem::exists("/nonexistent-dir/x.csv"));
}

// The write check before the run uses a uniquely named temporary: an existing CSV.probe is not
// touched, and nothing but the CSV is left. A path that names a directory is a usage error.
TEST(CliCube, CsvWriteCheckKeepsAnExistingProbeFile) {
  namespace fs = std::filesystem;
  const fs::path dir = temp_path("probe");
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "x.csv.probe") << "the user's own file";
  const CliRun r = run("cube --levels 0 --csv " + (dir / "x.csv").string());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(lines_of((dir / "x.csv.probe").string()), std::vector<std::string>{"the user's own file"});
  EXPECT_TRUE(fs::exists(dir / "x.csv"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 2);
  EXPECT_EQ(run("cube --levels 0 --csv " + dir.string() + "/").status, 2);
  EXPECT_EQ(run("cube --levels 0 --csv " + dir.string() + "/.").status, 2);
  fs::remove_all(dir);
}

}  // namespace

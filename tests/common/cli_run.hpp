#pragma once
// Runs the panelrad program (PANELRAD_CLI, set by tests/CMakeLists.txt) for the CLI tests.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>
#include <sys/wait.h>

namespace panelrad::testing {

struct CliRun {
  int status = -1;     ///< exit status; -1 when the program did not exit normally
  std::string output;  ///< what the redirection kept
};

/// `redirect`: "2>&1" (stdout and stderr), "2>/dev/null" (stdout), "2>&1 >/dev/null" (stderr).
inline CliRun run_cli(const std::string& args, const std::string& redirect = "2>&1") {
  CliRun r;
  const std::string cmd = std::string("\"") + PANELRAD_CLI + "\" " + args + " " + redirect;
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf{};
  while (const std::size_t n = std::fread(buf.data(), 1, buf.size(), pipe)) r.output.append(buf.data(), n);
  const int st = ::pclose(pipe);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

/// A test with a directory of its own, made empty before and removed after it:
/// <tmp>/panelrad_<prefix>_<test name>.
class CliDirectoryTest : public ::testing::Test {
 protected:
  explicit CliDirectoryTest(std::string prefix) : prefix_(std::move(prefix)) {}
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("panelrad_" + prefix_ + "_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  void write(const std::string& name, const std::string& text) const { std::ofstream(dir_ / name) << text; }
  std::size_t files() const {
    return static_cast<std::size_t>(
        std::distance(std::filesystem::directory_iterator(dir_), std::filesystem::directory_iterator()));
  }
  std::string prefix_;
  std::filesystem::path dir_;
};

/// The rows of a CSV file, split at every comma (the tests' files quote no comma).
inline std::vector<std::vector<std::string>> read_csv(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> row;
    std::stringstream s(line);
    for (std::string field; std::getline(s, field, ',');) row.push_back(field);
    rows.push_back(row);
  }
  return rows;
}

}  // namespace panelrad::testing

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << "output:\n" << (haystack)

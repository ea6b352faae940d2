// The CLI refuses sizes that cannot fit before any work, by every command, with the estimate;
// the memory available honours the process's own limit (ulimit -v); option checks at parse
// time: --threads, cube --rule, the --tol range, --max-elements below n0.
#include "test_support.hpp"
#include "cli_run.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>


namespace {

using panelrad::testing::CliRun;
const std::string kCornell = std::string(PANELRAD_SOURCE_DIR) + "/examples/scenes/convex_box.obj";

CliRun run(const std::string& args) { return panelrad::testing::run_cli(args); }

// The suites' fixtures: a fresh directory per test for the outputs (probed before the solve; a
// refusal leaves it empty), removed afterwards (TempDirTest).
class CliMemoryRefusal : public panelrad::testing::TempDirTest {
 protected:
  CliMemoryRefusal() : TempDirTest("panelrad_cli_memory") {}
  std::string out_prefix() const { return (dir_ / "x").string(); }
};

class CliOptions : public panelrad::testing::TempDirTest {
 protected:
  CliOptions() : TempDirTest("panelrad_cli_options") {}
  std::string out_prefix() const { return (dir_ / "x").string(); }
};

// Runs the CLI under `ulimit -v kb` (RLIMIT_AS). The CLI binary is built with the same flags as
// this test, so under AddressSanitizer (terabytes of shadow mappings) this cannot work: skipped.
CliRun run_limited(long long kb, const std::string& args, double* seconds = nullptr) {
  const auto start = std::chrono::steady_clock::now();
  const std::string cmd = "ulimit -v " + std::to_string(kb) + "; exec \"" + PANELRAD_CLI + "\" " + args + " 2>&1";
  CliRun limited;
  FILE* pipe = ::popen(cmd.c_str(), "r");
  if (pipe) {
    char buf[4096];
    while (const std::size_t n = std::fread(buf, 1, sizeof buf, pipe)) limited.output.append(buf, n);
    const int st = ::pclose(pipe);
    limited.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  }
  if (seconds) *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return limited;
}

constexpr long long kSixGB = 6000000;  // kB, as `ulimit -v 6000000`

// A refusal under the address-space limit: exit 1, the estimate and the limit that binds, and
// nothing computed (no table row, no subdivision).
void expect_refused(const CliRun& r, const std::string& n) {
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_CONTAINS(r.output, "(n = " + n);
  EXPECT_CONTAINS(r.output, " GB");
  EXPECT_CONTAINS(r.output, "ulimit -v");
  EXPECT_CONTAINS(r.output, "refused before any work");
  EXPECT_EQ(r.output.find("bad_alloc"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("subdividing"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("max error"), std::string::npos) << r.output;
}

#ifdef PANELRAD_ASAN
#define SKIP_UNDER_ASAN() GTEST_SKIP() << "AddressSanitizer's shadow memory does not fit under ulimit -v"
#else
#define SKIP_UNDER_ASAN() (void)0
#endif

// Cornell box, n0 = 36: level 5 dense is n = 36864, a 10.9 GB matrix.
TEST_F(CliMemoryRefusal, DenseSolveUnderAnAddressSpaceLimit) {
  SKIP_UNDER_ASAN();
  double s = 0;
  const CliRun r = run_limited(kSixGB, "solve " + kCornell + " --levels 5 --method dense --formats csv --out " + out_prefix(), &s);
  std::cout << "[refusal " << s << " s] " << r.output;
  expect_refused(r, "36864");
  EXPECT_CONTAINS(r.output, "--method fast");
}

// Level 10: n = 37,748,736; the cluster tree alone needs 8 GB.
TEST_F(CliMemoryRefusal, AutomaticSolveUnderAnAddressSpaceLimit) {
  SKIP_UNDER_ASAN();
  double s = 0;
  const CliRun r = run_limited(kSixGB, "solve " + kCornell + " --levels 10 --formats csv --out " + out_prefix(), &s);
  std::cout << "[refusal " << s << " s] " << r.output;
  expect_refused(r, "37748736");
  EXPECT_CONTAINS(r.output, "cluster tree 8.15 GB");  // ClusterTree::estimate_bytes(36, 10)
}

TEST_F(CliMemoryRefusal, CubeLevelElevenUnderAnAddressSpaceLimit) {
  SKIP_UNDER_ASAN();
  double s = 0;
  const CliRun r = run_limited(kSixGB, "cube --levels 11 --min-level 11", &s);
  std::cout << "[refusal " << s << " s] " << r.output;
  expect_refused(r, "50331648");
}

// --levels 12 (levels 0..12): the first level that cannot fit is refused before level 0 runs.
TEST_F(CliMemoryRefusal, CubeLevelsAreAllCheckedBeforeLevelZero) {
  SKIP_UNDER_ASAN();
  const CliRun r = run_limited(kSixGB, "cube --levels 12");
  std::cout << "[refusal] " << r.output;
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_CONTAINS(r.output, "every level is checked before the first is solved");
  EXPECT_EQ(r.output.find("accuracy auto: levels 0"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("max error"), std::string::npos) << r.output;
}

// Without a limit of our own, level 12 (tree ~43 GB) is beyond this 24 GB machine: refused at
// once too, with the estimate (skipped on a machine that could hold it).
TEST_F(CliMemoryRefusal, CubeLevelTwelveIsRefusedAtOnce) {
  const CliRun r = run("cube --levels 12");
  if (r.status == 0) GTEST_SKIP() << "this machine holds level 12";
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_CONTAINS(r.output, "refused before any work");
  EXPECT_EQ(r.output.find("max error"), std::string::npos) << r.output;
}

TEST_F(CliOptions, ThreadsBeyondWhatCanHelpAreAUsageError) {
  for (const std::string& cmd : {std::string("cube --levels 0"), "solve " + kCornell + " --out /nonexistent-dir/x"}) {
    const CliRun r = run(cmd + " --threads 1024");
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_CONTAINS(r.output, "--threads: 1024 is more than the");
    EXPECT_EQ(r.output.find("libgomp"), std::string::npos) << r.output;
  }
  EXPECT_EQ(run("cube --levels 0 --threads 1").status, 0);
  EXPECT_EQ(run("cube --levels 0 --threads -1").status, 2);
}

TEST_F(CliOptions, CubeRuleIsCheckedAtParseTime) {
  const CliRun r = run("cube --near quadrature --rule stroud9 --levels 0");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_CONTAINS(r.output, "unknown quadrature rule 'stroud9'");
  EXPECT_CONTAINS(r.output, "three_point, stroud7 or degreeK");
  EXPECT_EQ(run("cube --near quadrature --rule degree21 --levels 0").status, 2);  // degrees 1..20
  EXPECT_EQ(run("cube --near quadrature --rule three_point --levels 0").status, 0);
  EXPECT_EQ(run("cube --near quadrature --rule degree4 --levels 0").status, 0);
}

TEST_F(CliOptions, TolRangeIsShownWithItsRealBounds) {
  for (const std::string& cmd : {std::string("cube"), "solve " + kCornell}) {
    const CliRun r = run(cmd + " --tol 1e-20");
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_CONTAINS(r.output, "--tol: needs a number in [1e-15, 0.5] or auto, got '1e-20'");
  }
}

// Every bad value is a usage error naming the option and the accepted range or names.
TEST_F(CliOptions, BadValuesNameTheOptionAndWhy) {
  const struct {
    const char* args;
    const char* message;
  } cases[] = {
      // A level too large for the scene is refused by its element count (CliCube tests it).
      {"cube --levels -1", "--levels: needs a level: an integer >= 0, got '-1'"},
      {"cube --levels 2.5", "--levels: needs a level: an integer >= 0, got '2.5'"},
      {"cube --min-level x", "--min-level: needs a level: an integer >= 0, got 'x'"},
      {"cube --levels 99999999999", "--levels: needs a level: an integer >= 0, got '99999999999'"},
      // Base 10 as before: CLI11's own integer conversion (base 0) would read 0x1 as 1.
      {"cube --levels 0x1", "--levels: needs a level: an integer >= 0, got '0x1'"},
      {"cube --eta 2", "--eta: needs a number in [0.001, 0.99], got '2'"},
      {"cube --eta nan", "--eta: needs a number in [0.001, 0.99], got 'nan'"},
      {"cube --tol abc", "--tol: needs a number in [1e-15, 0.5] or auto, got 'abc'"},
      {"cube --threads x", "--threads: needs an integer in [0, 1048576], got 'x'"},
      {"cube --method sparse", "--method: sparse not in {dense,fast}"},
      {"cube --levels", "--levels: 1 required L missing"},
      {"cube --bogus 1", "unknown option '--bogus'"},
      {"cube 3", "unexpected argument '3'"},
      {"solve " PANELRAD_SOURCE_DIR "/examples/scenes/convex_box.obj second.obj",
       "unexpected argument 'second.obj' after SCENE '" PANELRAD_SOURCE_DIR "/examples/scenes/convex_box.obj'"},
      {"solve", "no scene given"},
      {"solve --bogus", "unknown option '--bogus'"},
      {"check --builtin cube --builtin octahedron", "--builtin: At Most 1 required but received 2"},
      {"frobnicate", "panelrad: unknown command 'frobnicate'"},
  };
  for (const auto& c : cases) {
    const CliRun r = run(c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.output;
    EXPECT_CONTAINS(r.output, c.message);
    EXPECT_CONTAINS(r.output, "usage: panelrad");
  }
}

// --name=value is the same as --name value; of a repeated option the last one counts (as
// before the options were parsed with CLI11). prism_lamp has n0 = 20: level 1 is n = 80.
TEST_F(CliOptions, EqualsFormAndRepeatedOptions) {
  const std::string lamp = std::string(PANELRAD_SOURCE_DIR) + "/examples/scenes/prism_lamp.off";
  const std::string prefix = out_prefix();
  const CliRun equals = run("solve " + lamp + " --levels=1 --formats=csv --out=" + prefix + " --quiet");
  EXPECT_EQ(equals.status, 0) << equals.output;
  EXPECT_CONTAINS(equals.output, "n = 80 (level 1)");
  EXPECT_CONTAINS(equals.output, "wrote " + prefix + ".csv\n");
  const CliRun repeated = run("solve " + lamp + " --levels 3 --levels 1 --formats csv --out " + prefix + " --quiet");
  EXPECT_EQ(repeated.status, 0) << repeated.output;
  EXPECT_CONTAINS(repeated.output, "n = 80 (level 1)");
  // The first value of a repeated option is checked too.
  EXPECT_EQ(run("solve " + lamp + " --levels x --levels 1 --out " + prefix).status, 2);
}

// --help (and help COMMAND) print the command's usage on stdout with status 0; --version too.
TEST_F(CliOptions, HelpAndVersion) {
  for (const char* cmd : {"check", "cube", "solve"}) {
    const CliRun help = panelrad::testing::run_cli(std::string(cmd) + " --help", "2>/dev/null");
    EXPECT_EQ(help.status, 0) << help.output;
    EXPECT_EQ(help.output.rfind(std::string("usage: panelrad ") + cmd, 0), 0u) << help.output;
    EXPECT_EQ(panelrad::testing::run_cli(std::string("help ") + cmd, "2>/dev/null").output, help.output);
  }
  const CliRun top = panelrad::testing::run_cli("--help", "2>/dev/null");
  EXPECT_EQ(top.status, 0);
  EXPECT_EQ(top.output.rfind("usage: panelrad <command>", 0), 0u) << top.output;
  const CliRun none = panelrad::testing::run_cli("", "2>&1 >/dev/null");
  EXPECT_EQ(none.status, 2);
  EXPECT_EQ(none.output, top.output);  // no command: the usage on stderr
  const CliRun version = panelrad::testing::run_cli("--version");
  EXPECT_EQ(version.status, 0);
  EXPECT_EQ(version.output, panelrad::testing::run_cli("version").output);
  EXPECT_EQ(version.output.rfind("panelrad ", 0), 0u) << version.output;
}

TEST_F(CliOptions, MaxElementsBelowTheCoarseMeshSaysWhatItDid) {
  const CliRun r = run("solve " + kCornell + " --max-elements 5 --quiet --formats csv --out " + out_prefix());
  EXPECT_CONTAINS(r.output, "--max-elements 5 is below the scene's 36 triangles (n0): solving level 0, n = 36");
}

}  // namespace

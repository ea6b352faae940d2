#pragma once
// Runs the panelrad program (PANELRAD_CLI, set by tests/CMakeLists.txt) for the CLI tests.
#include <array>
#include <cstdio>
#include <string>
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

}  // namespace panelrad::testing

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << "output:\n" << (haystack)

#pragma once
// Sub-commands of the panelrad program. Each returns the process exit status:
// 0 success, 1 invalid input or failed run, 2 usage error.
namespace panelrad::cli {
int run_check(int argc, char** argv);   // argv[0] == "check"
int run_cube(int argc, char** argv);    // argv[0] == "cube"
int run_solve(int argc, char** argv);   // argv[0] == "solve"
}  // namespace panelrad::cli

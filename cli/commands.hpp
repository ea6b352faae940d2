#pragma once
// Sub-commands of the panelrad program. Each defines its options on a CLI11 sub-command of the
// program's App; they parse into the library's option structs. run() then checks what a single
// option cannot (options that exclude or need each other: a UsageError) and runs the command.
// Exit status: 0 success, 1 invalid input or failed run, 2 usage error.
#include <CLI/CLI.hpp>

#include <functional>

namespace panelrad::cli {

struct Command {
  CLI::App* app = nullptr;   ///< the sub-command; parsed() after App::parse when it was given
  std::function<int()> run;  ///< after parsing
};

Command add_check(CLI::App& panelrad);  ///< panelrad check
Command add_cube(CLI::App& panelrad);   ///< panelrad cube
Command add_solve(CLI::App& panelrad);  ///< panelrad solve

}  // namespace panelrad::cli

#pragma once
// Sub-commands of the panelrad program. Each defines its options on a CLI11 sub-command of the
// program's App; they parse into the library's option structs. run() then checks what a single
// option cannot (options that exclude or need each other: a UsageError) and runs the command.
// Exit status: 0 success, 1 invalid input or failed run, 2 usage error, 3 energy check failed
// (solve: the outputs are written, for inspection only), 128 + N ended by signal N.
#include <CLI/CLI.hpp>

#include <functional>

namespace panelrad::cli {

/// `panelrad solve`: the solution breaks the conservation of energy far beyond its discretization
/// error (SceneSolution::energy_balanced is false); its outputs are written, for inspection only.
inline constexpr int kExitEnergyCheckFailed = 3;

struct Command {
  CLI::App* app = nullptr;   ///< the sub-command; parsed() after App::parse when it was given
  std::function<int()> run;  ///< after parsing
};

Command add_check(CLI::App& panelrad);  ///< panelrad check
Command add_cube(CLI::App& panelrad);   ///< panelrad cube
Command add_solve(CLI::App& panelrad);  ///< panelrad solve
Command add_view_factors(CLI::App& panelrad);  ///< panelrad viewfactors
Command add_thermal(CLI::App& panelrad);       ///< panelrad thermal

}  // namespace panelrad::cli

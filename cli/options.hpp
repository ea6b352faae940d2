#pragma once
// Strict option checks for the sub-commands, as CLI11 validators. A bad value is a usage error
// (exit status 2); CLI11 puts the option's name in front of the validator's message, e.g.
// "--eta: needs a number in [0.001, 0.99], got '2'". Their descriptions are empty: the usage texts
// (set_usage) document the options, and CLI11 adds a description to the value's name in its
// messages ("--levels: 1 required L missing").
#include <panelrad/solve/radiosity_solver.hpp>

#include <CLI/CLI.hpp>

#include <stdexcept>
#include <string>
#include <vector>

namespace panelrad::cli {

/// A usage error found after parsing: options that exclude or need each other, a name the
/// library refuses (exit status 2, with the sub-command's usage).
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An integer in [lo, hi], read in base 10 (strtol). It is passed on in canonical decimal, so
/// CLI11's own conversion (strtoll with base 0, which would read "010" as octal) gets the same
/// integer.
CLI::Validator integer_in(int lo, int hi);
/// --levels, --min-level: a refinement level, an integer >= 0 read as integer_in reads it. How
/// large a level may be depends on the scene (n = 4^L n0 elements must have a 32-bit index, and
/// fit in memory): the library refuses a larger one by that reason (geometry::level_size_problem,
/// the memory plan), not a fixed bound here.
CLI::Validator level_number();
/// A finite number in [lo, hi], read with strtod. It is passed on as the exact hexadecimal form
/// of that double, so CLI11's own conversion (strtold, then a second rounding to double) gets
/// the same double bit for bit.
CLI::Validator number_in(double lo, double hi);
/// --tol: "auto" (passed on as 0: tied to the discretization error) or a number in [lo, hi].
CLI::Validator tolerance_in(double lo, double hi);
/// --threads T: 0 (the default) up to max_useful_threads(); more is a usage error saying the limit
/// (thousands of threads would only exhaust the address space and make the OpenMP runtime abort).
CLI::Validator thread_count();
/// A basic quadrature rule name as the near field accepts it (quadrature::rule_by_name); an
/// unknown one is a usage error listing the valid names.
CLI::Validator quadrature_rule();

/// One of the given names (CLI::IsMember: "--method: sparse not in {dense,fast}").
CLI::Validator one_of(std::vector<std::string> names);

/// The sub-command's usage text is its help (--help, and after a usage error).
void set_usage(CLI::App& app, const char* usage);

/// The options of the discretization and the operator that `solve` and `viewfactors` share, into
/// `o`: --levels L | --max-elements N, --method, --eta, --degree, --near, --mu, --visibility.
void add_operator_options(CLI::App& app, SolveOptions& o);
/// What those options cannot check one by one (a UsageError): --eta, --degree, --near and --mu
/// need --method dense or fast.
void check_operator_options(const CLI::App& app, const SolveOptions& o);

/// The outputs PREFIX.csv, ... beside PREFIX: its file name part must be a plain name, not empty
/// and not starting with '.' (hidden files); a UsageError otherwise.
void check_prefix(const std::string& prefix);

}  // namespace panelrad::cli

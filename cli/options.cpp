#include "options.hpp"

#include <panelrad/operator/near_field.hpp>
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/quadrature/triangle_rules.hpp>
#include <panelrad/support/resources.hpp>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <utility>

namespace panelrad::cli {

namespace {
// Shortest round-trip-free form of a bound: 1e-15, 0.5, 0.001 (not std::to_string's fixed
// "0.000000", which hides small bounds).
std::string show_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// The exact text of a double: hexadecimal, read back without rounding by strtod and strtold.
std::string exact_text(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%a", v);
  return buf;
}

// value as an integer in [lo, hi], or an error message (empty on success).
std::string read_integer(std::string& value, long lo, long hi) {
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(value.c_str(), &end, 10);
  if (value.empty() || *end != '\0' || errno != 0 || v < lo || v > hi)
    return "needs an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got '" + value + "'";
  value = std::to_string(v);
  return {};
}

std::string read_number(std::string& value, double lo, double hi) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || !std::isfinite(v) || v < lo || v > hi)
    return "needs a number in [" + show_number(lo) + ", " + show_number(hi) + "], got '" + value + "'";
  value = exact_text(v);
  return {};
}
}  // namespace

CLI::Validator integer_in(int lo, int hi) {
  return CLI::Validator([lo, hi](std::string& value) { return read_integer(value, lo, hi); },
                        "", "integer_in");
}

CLI::Validator level_number() {
  return CLI::Validator(
      [](std::string& value) {
        const std::string given = value;
        if (read_integer(value, 0, std::numeric_limits<int>::max()).empty()) return std::string();
        return "needs a level: an integer >= 0, got '" + given + "'";
      },
      "", "level_number");
}

CLI::Validator number_in(double lo, double hi) {
  return CLI::Validator([lo, hi](std::string& value) { return read_number(value, lo, hi); },
                        "", "number_in");
}

CLI::Validator tolerance_in(double lo, double hi) {
  return CLI::Validator(
      [lo, hi](std::string& value) {
        if (value == "auto") {
          value = "0";
          return std::string();
        }
        const std::string given = value;
        if (read_number(value, lo, hi).empty()) return std::string();
        return "needs a number in [" + show_number(lo) + ", " + show_number(hi) + "] or auto, got '" + given + "'";
      },
      "", "tolerance_in");
}

CLI::Validator thread_count() {
  return CLI::Validator(
      [](std::string& value) {
        const std::string given = value;
        if (std::string e = read_integer(value, 0, 1 << 20); !e.empty()) return e;
        const int limit = max_useful_threads();
        if (std::stoi(value) > limit)
          return given + " is more than the " + std::to_string(limit) +
                 " threads that can help here (4 per processor available to this process, and at most "
                 "the OpenMP thread limit); 0 uses the default, " + std::to_string(max_threads());
        return std::string();
      },
      "", "thread_count");
}

CLI::Validator quadrature_rule() {
  return CLI::Validator(
      [](std::string& value) {
        try {
          (void)quadrature::rule_by_name(value);  // the parser the near-field integrator uses
        } catch (const std::invalid_argument& e) {
          return std::string(e.what());
        }
        return std::string();
      },
      "", "quadrature_rule");
}

CLI::Validator one_of(std::vector<std::string> names) {
  CLI::Validator member = CLI::IsMember(std::move(names));
  member.description("");
  return member;
}

void set_usage(CLI::App& app, const char* usage) {
  app.formatter_fn([usage](const CLI::App*, std::string, CLI::AppFormatMode) { return std::string(usage); });
}

void add_operator_options(CLI::App& app, SolveOptions& o) {
  CLI::Option* levels = app.add_option("--levels", o.level)->type_name("L")->transform(level_number());
  CLI::Option* max_elements =
      app.add_option("--max-elements", o.max_elements)->type_name("N")->transform(integer_in(1, 1 << 30));
  levels->excludes(max_elements);
  app.add_option_function<std::string>("--method", [&o](const std::string& v) { o.op.method = parse_operator_method(v); })
      ->type_name("auto|dense|fast")
      ->check(one_of({"auto", "dense", "fast"}));
  app.add_option("--eta", o.op.eta)->type_name("E")->transform(number_in(1e-3, 0.99));
  app.add_option("--degree", o.op.degree)->type_name("M")->transform(integer_in(0, 12));
  app.add_option_function<std::string>("--near",
                                       [&o](const std::string& v) { o.op.near.rule = parse_near_rule(v); })
      ->type_name("exact|quadrature")
      ->check(one_of({"exact", "quadrature"}));
  app.add_option("--mu", o.op.near.mu)->type_name("K")->transform(integer_in(0, 6));
  app.add_option_function<std::string>("--visibility",
                                       [&o](const std::string& v) { o.visibility = parse_visibility(v); })
      ->type_name("auto|occluded")
      ->check(one_of({"auto", "occluded"}));
}

void check_operator_options(const CLI::App& app, const SolveOptions& o) {
  const bool manual = app.count("--eta") + app.count("--degree") + app.count("--near") + app.count("--mu") > 0;
  if (manual && o.op.method == OperatorMethod::automatic)
    throw UsageError("--eta, --degree, --near and --mu need --method dense or fast");
}

void check_prefix(const std::string& prefix) {
  // An empty name ("d/") or one starting with '.' (".", "..", "out/.") makes hidden files.
  const std::string name = std::filesystem::path(prefix).filename().string();
  if (name.empty() || name[0] == '.')
    throw UsageError("--out '" + prefix + "': the file name part " +
                     (name.empty() ? std::string("is empty") : "'" + name + "' starts with '.'") +
                     ", so the outputs would be hidden files such as '" + prefix +
                     ".csv'; give a prefix such as DIR/NAME");
}

}  // namespace panelrad::cli

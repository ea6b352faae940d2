#pragma once
// Minimal strict option parsing for the sub-commands: unknown options and bad values are usage
// errors (exit status 2) with a message saying which.
#include <stdexcept>
#include <string>

namespace panelrad::cli {

class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

int parse_int(const std::string& option, const std::string& value, int lo, int hi);
double parse_double(const std::string& option, const std::string& value, double lo, double hi);
/// --threads T: 0 (the default) up to max_useful_threads(); more is a usage error saying the limit
/// (thousands of threads would only exhaust the address space and make the OpenMP runtime abort).
int parse_threads(const std::string& option, const std::string& value);
/// A basic quadrature rule name as the near field accepts it (quadrature::rule_by_name); an
/// unknown one is a usage error listing the valid names.
void check_quadrature_rule(const std::string& option, const std::string& value);

}  // namespace panelrad::cli

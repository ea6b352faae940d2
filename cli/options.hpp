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

}  // namespace panelrad::cli

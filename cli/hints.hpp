#pragma once
// The command line's hints for the library's errors: the library's messages name the data and
// the rule ("or the fast method (section 4)"); the program adds which option does that.
#include <exception>
#include <string>

namespace panelrad::cli {

/// A line such as "hint: --method fast uses the fast operator (section 4); or fewer --levels",
/// or "" when the error has no option that addresses it.
std::string hint_for(const std::exception& error);

}  // namespace panelrad::cli

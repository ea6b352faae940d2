#pragma once
// The root of panelrad's exceptions (the whole hierarchy: panelrad/scene/errors.hpp), and the
// generic ResourceError. It lives in the lowest layer so that every layer's errors share it; a
// caller catches panelrad::Error for any failure that panelrad reports, and std::invalid_argument
// for a misuse of the API.
#include <stdexcept>

namespace panelrad {

/// Any failure panelrad reports: the message names the data (file and line, facet, element,
/// channel, stage) and the rule it breaks.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A size that cannot fit (refused before any work, with the estimate), or an allocation that
/// failed anyway (naming the stage, what was being allocated and how much).
class ResourceError : public Error {
 public:
  using Error::Error;
};

}  // namespace panelrad

#pragma once
// panelrad's exceptions, one hierarchy under panelrad::Error (std::runtime_error):
//   geometry::MeshError      a mesh that is malformed, degenerate, non-finite, not closed or not
//                            convex (names the file and line, vertex or facet, and the rule);
//   TextFileError            an input file that cannot be read as text (size limit, NUL byte);
//   SceneFileError           a scene file or its materials (file and line, facet or material);
//   SolverError              an iteration that did not reach its tolerance (how far it got);
//   EnergyBalanceError       a solution whose energy balance is far off its expected size (the
//                            channel, the mismatch and that size);
//   ResourceError            (support/error.hpp) a size that cannot fit in memory (the estimate and the limit), or
//                            an allocation that failed anyway (the stage and the size).
// A misuse of the API (an option out of range, vectors of the wrong size) is a
// std::invalid_argument. Messages name the data and the rule; programs add their own hints.
#include <panelrad/geometry/mesh.hpp>
#include <panelrad/support/error.hpp>
#include <panelrad/support/text_file.hpp>

namespace panelrad {

using geometry::MeshError;

/// A scene file or its materials: the message names the file, and the line or facet where it can.
class SceneFileError : public Error {
 public:
  using Error::Error;
};

/// An iteration that did not reach its tolerance: says how far it got.
class SolverError : public Error {
 public:
  using Error::Error;
};

/// A solution that breaks the conservation of energy far beyond its discretization error: names
/// the channel, the mismatch and its expected size.
class EnergyBalanceError : public Error {
 public:
  using Error::Error;
};

}  // namespace panelrad

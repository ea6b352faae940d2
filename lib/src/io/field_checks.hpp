#pragma once
// Checks of an ElementField before any output is made from it, and the small accessors the
// writers share (internal to panelrad_io).
#include <panelrad/solve/element_field.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <vector>

namespace panelrad::io_detail {

/// Throws std::invalid_argument ("<who>: ...") unless the names can be CSV columns and PLY/VTK
/// property names: at least one, each a non-empty token of letters, digits, '_', '-', '.', no
/// name twice.
void check_names(const char* who, const std::vector<std::string>& channels);

/// Throws std::invalid_argument naming the first problem: sizes, channel names, non-finite values.
void validate(const char* who, const ElementField& f);

/// The field's channels are R, G, B (colour), not a scalar set.
bool is_rgb(const ElementField& f);

inline double value(const Eigen::VectorXd& v, std::size_t i) { return v[static_cast<Eigen::Index>(i)]; }

}  // namespace panelrad::io_detail

#pragma once
// The colour of each element in the picture and the PLY (internal to panelrad_io): the rules are
// documented at element_colours() in panelrad/io/scene_output.hpp.
#include <panelrad/solve/element_field.hpp>

#include <array>
#include <vector>

namespace panelrad::io_detail {

using Rgb = std::array<unsigned char, 3>;

/// Viridis at t in [0, 1] (a non-finite t: the middle).
Rgb colour_map(double t);

/// element_colours() of a field that validate() accepted.
std::vector<Rgb> colours_of_valid(const ElementField& f);

}  // namespace panelrad::io_detail

#pragma once
// A scene's data per input facet in C channels: the reflectivity rho and the emission E of the
// radiosity equation (1) (paper (7): 0 <= rho < 1), and the checks every value passes.
#include <panelrad/geometry/mesh.hpp>

#include <string>
#include <vector>

namespace panelrad {

/// A validated closed convex scene with per-facet data in C channels.
struct ChannelScene {
  geometry::TriangleMesh mesh;                ///< validated (outward oriented), facet = input face
  std::vector<std::string> channels;          ///< {"R", "G", "B"} for OBJ+MTL; from the JSON otherwise
  std::vector<std::vector<double>> rho;       ///< rho[c][facet], 0 <= rho < 1
  std::vector<std::vector<double>> emission;  ///< emission[c][facet], finite, >= 0
  std::vector<std::string> facet_material;    ///< material name per facet (OBJ), else empty
  std::vector<std::string> notes;             ///< what loading did: merged vertices, re-orientation,
                                              ///< hull re-triangulation, files read
  std::size_t num_channels() const { return channels.size(); }
};

/// The largest emission E accepted. The solution of the radiosity equation (7) satisfies
/// |u| <= max E / (1 - max rho), and 1 / (1 - rho) reaches 2^53 ~ 9e15 for the largest double
/// below 1, so u <= 9e115; its squares (residual norms) summed over 1e9 elements stay below
/// 1e242, and its products with areas (at most 1e150: validation bounds lengths by 1e75) summed
/// over 1e9 elements below 1e275: finite.
inline constexpr double kMaxEmission = 1e100;
/// The smallest non-zero emission E accepted: with areas down to 1e-150, products area * E stay
/// above 1e-250 and squares of E above 1e-200, normal numbers (no underflow to subnormal or 0).
/// Subnormal E (below DBL_MIN) have lost precision already and are refused with that reason.
inline constexpr double kMinPositiveEmission = 1e-100;

/// What is wrong with a reflectivity rho ("is outside [0, 1) ..."), or "" when it is accepted:
/// finite, 0 <= rho < 1, not subnormal.
std::string reflectivity_problem(double rho);
/// What is wrong with an emission E, or "" when it is accepted: finite, E = 0 or
/// kMinPositiveEmission <= E <= kMaxEmission; a subnormal E is named as such.
std::string emission_problem(double e);

}  // namespace panelrad

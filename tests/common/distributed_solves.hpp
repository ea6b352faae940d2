#pragma once
// Solves run on one process and on several (a Communicator), for comparing their answers bit for
// bit: the paper's cube (31) with the fast operator (convex, V = 1), and a room with a box inside
// (occluded: V computed, each process classifying the pairs of its own rows), in three channels
// (the Neumann iterations of the channels together through block products, or GMRES one by one).
// Both at level 3: n = 768 and 1536, three and six blocks of kRowBlock rows, so that two and three
// processes each hold rows.
#include "occluded_scenes.hpp"

#include <panelrad/geometry/scene_validation.hpp>
#include <panelrad/solve/radiosity_solver.hpp>
#include <panelrad/solve/scene_solver.hpp>

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

namespace panelrad::testing {

/// What a solve gave: its vectors (u, and H u per channel), products and self-check.
struct SolveBits {
  std::vector<Eigen::VectorXd> vectors;
  std::vector<int> iterations;
  double self_check = -1;
};

/// The first index where a and b differ in their bits (-1: none; a.size() when the sizes differ).
inline Eigen::Index first_difference(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  if (a.size() != b.size()) return a.size();
  for (Eigen::Index i = 0; i < a.size(); ++i)
    if (std::memcmp(&a[i], &b[i], sizeof(double)) != 0) return i;
  return -1;
}

inline void expect_same_bits(const SolveBits& single, const SolveBits& shared, const std::string& what) {
  ASSERT_EQ(single.vectors.size(), shared.vectors.size()) << what;
  for (std::size_t k = 0; k < single.vectors.size(); ++k) {
    const Eigen::Index i = first_difference(single.vectors[k], shared.vectors[k]);
    EXPECT_EQ(i, -1) << what << ": vector " << k << " differs at entry " << i << " of "
                     << single.vectors[k].size();
  }
  EXPECT_EQ(single.iterations, shared.iterations) << what;
  EXPECT_EQ(0, std::memcmp(&single.self_check, &shared.self_check, sizeof(double))) << what;
}

/// Level 3, the fast operator from eta 0.4, M 4, tightened by its self-check, solver `kind`.
inline SolveOptions fast_level3(SolverKind kind, const Communicator* communicator) {
  SolveOptions o;
  o.level = 3;
  o.op.method = OperatorMethod::fast;
  o.op.eta = 0.4;
  o.op.degree = 4;
  o.tighten_on_failed_check = true;
  o.solver.kind = kind;
  o.communicator = communicator;
  return o;
}

/// The paper's cube (31) at level 3, rho folded into K_n; E manufactured from u = |x|^2.
inline SolveBits paper_cube_solve(SolverKind kind, const Communicator* communicator) {
  const Scene scene = make_paper_cube_scene();
  SolveOptions o = fast_level3(kind, communicator);
  o.fold_reflectivity = true;
  const RadiositySolver solver(scene, o);
  ChannelSolve r = solver.solve(0);
  EXPECT_TRUE(r.converged()) << r.message;
  SolveBits bits;
  bits.vectors.push_back(std::move(r.u));
  bits.iterations.push_back(r.iterations);
  bits.self_check = solver.self_check() ? solver.self_check()->relative_error : -1;
  return bits;
}

/// The room [0, 1]^3 with a box inside (room_with_box), three channels with their own rho and E
/// per facet, solved with V (occluded); the parameters chosen by probes.
inline SolveBits room_scene_solve(SolverKind kind, const Communicator* communicator) {
  geometry::TriangleMesh mesh = room_with_box();
  Scene scene(std::move(mesh), {"R", "G", "B"});
  for (std::size_t c = 0; c < 3; ++c) {
    std::vector<double> rho(static_cast<std::size_t>(scene.num_facets())), E(rho.size(), 0.0);
    for (std::size_t f = 0; f < rho.size(); ++f) rho[f] = 0.2 + 0.1 * static_cast<double>((f + c) % 6);
    E[5] = 1.0 + static_cast<double>(c);  // the ceiling emits
    E[8] = 0.5;                           // and one face of the box
    scene.set_reflectivity(rho, c);
    scene.set_emissivity(E, c);
  }
  const SceneSolution s = solve_scene(scene, fast_level3(kind, communicator));
  SolveBits bits;
  for (const ChannelSolution& ch : s.channels) {
    EXPECT_EQ(ch.status, SolveStatus::converged) << ch.message;
    bits.vectors.push_back(ch.radiosity);
    bits.vectors.push_back(ch.irradiance);
    bits.iterations.push_back(ch.iterations);
  }
  bits.self_check = s.self_check_error;
  return bits;
}

}  // namespace panelrad::testing

#pragma once
// A polyhedral scene: a validated closed convex surface with reflectivity rho and emissivity E
// (paper (1)), each given per facet, as a function of the point, or (E only) manufactured from a
// known solution u by E = u - K u (the paper's test method, section 3).
#include <panelrad/geometry/mesh.hpp>

#include <functional>
#include <string>
#include <vector>

namespace panelrad {

using geometry::Index;
using geometry::Vec3;

/// A function on the surface: value at `point`, which lies in input facet `facet`.
using SurfaceFunction = std::function<double(const Vec3& point, Index facet)>;

class Scene {
 public:
  /// Takes a mesh that passed geometry::validate_closed_convex (outward oriented).
  /// Reflectivity defaults to 0 and emissivity to 1 everywhere.
  explicit Scene(geometry::TriangleMesh validated_mesh);
  /// Reads and validates a mesh file, or "builtin:NAME" (cube, prism:K, tetrahedron, octahedron).
  static Scene load(const std::string& path_or_builtin, std::vector<std::string>* notes = nullptr);

  const geometry::TriangleMesh& mesh() const { return mesh_; }
  Index num_facets() const { return mesh_.num_facets; }
  /// Inner unit normal of input triangle t (points into the solid), (2).
  Vec3 triangle_inner_normal(Index t) const;

  /// rho: 0 <= rho < 1 (paper (7)); anything else, NaN included, is a std::invalid_argument
  /// naming the facet.
  void set_reflectivity(double rho);
  void set_reflectivity(std::vector<double> per_facet);
  /// Checked where evaluated (each collocation point): out of range -> std::invalid_argument.
  void set_reflectivity(SurfaceFunction rho);

  void set_emissivity(double e);
  void set_emissivity(std::vector<double> per_facet);
  void set_emissivity(SurfaceFunction e);
  /// E := u - K u, with K u integrated to relative accuracy `rel_tol` over the exact surface.
  void set_manufactured_solution(SurfaceFunction u, double rel_tol = 1e-11);

  /// rho(P) for P in facet; throws std::invalid_argument when outside [0,1) or not finite.
  double reflectivity(const Vec3& P, Index facet) const;
  /// Prescribed E(P); for a manufactured scene use manufactured_emissivity().
  double emissivity(const Vec3& P, Index facet) const;
  bool has_manufactured_solution() const { return static_cast<bool>(solution_); }
  const SurfaceFunction& manufactured_solution() const { return solution_; }
  /// E(P) = u(P) - rho(P)/pi Int_S u(Q) G(P,Q) dS_Q for the manufactured solution u, (1).
  /// std::runtime_error naming the point, its facet and the triangle when the integral cannot
  /// be computed (u not finite, or not smooth enough to converge within the evaluation cap).
  double manufactured_emissivity(const Vec3& P, Index facet, const Vec3& nP) const;
  /// Largest rho over the facets when given per facet (or constant), else NaN (unknown).
  double max_reflectivity() const;

 private:
  geometry::TriangleMesh mesh_;
  std::vector<double> rho_facet_;
  SurfaceFunction rho_fn_;
  std::vector<double> e_facet_;
  SurfaceFunction e_fn_;
  SurfaceFunction solution_;
  double solution_tol_ = 1e-11;
};

/// The paper's cube example (31): unit cube, rho = 0.5 on y = 0, 1; 0.4 on z = 0, 1; 0.3 on
/// x = 0, 1; true solution u = x^2 + y^2 + z^2 (E manufactured). With `scale` and `offset` the
/// cube becomes offset + scale [0,1]^3 and u(Q) = |(Q - offset) / scale|^2: the same problem, for
/// stress tests of where the scene sits and how large it is.
Scene make_paper_cube_scene(double scale = 1.0, const Vec3& offset = Vec3::Zero());

}  // namespace panelrad

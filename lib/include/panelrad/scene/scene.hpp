#pragma once
// A polyhedral scene: a validated set of planar polygons (geometry::validate_mesh: a closed convex
// surface, the paper's setting, or a general scene whose visibility V(P, Q) is computed) with, in
// each of C channels (C = 1 for a
// scalar problem; "R", "G", "B" for a colour one), the reflectivity rho and the emission E of the
// radiosity equation (1), each given per facet or as a function of the point; or (scalar scenes)
// E manufactured from a known solution u by E = u - K u (the paper's test method, section 3).
//
// Every value of rho and E passes one rule, reflectivity_problem / emission_problem: per-facet
// data when it is set, functions where they are evaluated (each collocation point).
#include <panelrad/geometry/mesh.hpp>
#include <panelrad/geometry/scene_validation.hpp>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace panelrad {

using geometry::Index;
using geometry::Vec3;

/// A function on the surface: value at `point`, which lies in input facet `facet`.
using SurfaceFunction = std::function<double(const Vec3& point, Index facet)>;

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
/// finite, 0 <= rho < 1 (paper (7)), not subnormal.
std::string reflectivity_problem(double rho);
/// What is wrong with an emission E, or "" when it is accepted: finite, E = 0 or
/// kMinPositiveEmission <= E <= kMaxEmission; a subnormal E is named as such.
std::string emission_problem(double e);

class Scene {
 public:
  /// Takes a validated mesh (geometry::validate_mesh, geometry::load_scene_mesh, load_scene) with the
  /// channels' names (at least one, distinct, non-empty); its shape is the visibility policy:
  /// convex (V = 1, the paper's setting) or general (the solver computes V(P, Q)). Reflectivity
  /// and emission default to 0 everywhere in every channel: no surface emits unless its E is
  /// given (set_emissivity).
  explicit Scene(geometry::ValidatedMesh mesh, std::vector<std::string> channels = {"value"});
  /// Validates `mesh` as read (geometry::validate_mesh: MeshError naming the rule and the faces when
  /// it is invalid), keeps the validation's notes, and takes it as above.
  explicit Scene(geometry::TriangleMesh mesh, std::vector<std::string> channels = {"value"});

  const geometry::TriangleMesh& mesh() const { return mesh_; }
  /// convex: proven by the exact check, V = 1 and no visibility work; general: V is computed.
  geometry::SceneShape shape() const { return shape_; }
  /// Every ray from a front side ends on a front side (geometry::SceneValidationReport::closed): a
  /// closed room alone or with bodies in it, standing on its floor or not, so the visible form
  /// factors at every point sum to 1 and the energy balance emitted = absorbed holds. False for an
  /// open room, bodies with nothing around them, or a one-sided surface (its back takes light).
  bool closed() const { return closed_; }
  /// No light leaves the scene (geometry::SceneValidationReport::enclosed): closed, or a room
  /// with one-sided surfaces in it, whose back sides take the light that reaches them.
  bool enclosed() const { return enclosed_; }
  Index num_facets() const { return mesh_.num_facets; }
  /// Inner unit normal of input triangle t (points into the solid), (2).
  Vec3 triangle_inner_normal(Index t) const;

  std::size_t num_channels() const { return channels_.size(); }
  const std::vector<std::string>& channels() const { return channels_; }

  /// rho in `channel`: every value must pass reflectivity_problem, else std::invalid_argument
  /// naming the facet, the channel and the rule. A function is checked where evaluated.
  void set_reflectivity(double rho, std::size_t channel = 0);
  void set_reflectivity(std::vector<double> per_facet, std::size_t channel = 0);
  void set_reflectivity(SurfaceFunction rho, std::size_t channel = 0);

  /// E in `channel`: every value must pass emission_problem (std::invalid_argument naming the
  /// facet, the channel and the rule); a function is checked where evaluated. Replaces a
  /// manufactured solution.
  void set_emissivity(double e, std::size_t channel = 0);
  void set_emissivity(std::vector<double> per_facet, std::size_t channel = 0);
  void set_emissivity(SurfaceFunction e, std::size_t channel = 0);
  /// The environment's radiosity in `channel` (the sky of an open scene): every point of a front
  /// side receives, besides the light of the surfaces it sees, this radiosity from the part s(P)
  /// of its hemisphere (cosine-weighted) that no front side covers, so that (1) becomes
  /// u - K u = E + rho u_env s. 0 (the default) is a black, empty environment. Checked by
  /// emission_problem (std::invalid_argument naming the channel). An enclosed scene has s = 0:
  /// its environment is never seen. What a front side sees of the back of a one-sided surface
  /// counts as environment; a sheet seen from both sides is given as a thin closed solid.
  void set_environment(double radiosity, std::size_t channel = 0);
  double environment(std::size_t channel = 0) const;
  /// The scene sees its environment in `channel`: one above 0, and the scene is not enclosed.
  bool sees_environment(std::size_t channel) const;

  /// E := u - K u, with K u integrated to relative accuracy `rel_tol` over the exact surface.
  /// Scalar convex scenes only (one channel, V = 1; std::logic_error otherwise). E may then be negative
  /// somewhere: it is derived, not data, and is not held to emission_problem.
  void set_manufactured_solution(SurfaceFunction u, double rel_tol = 1e-11);

  /// rho(P) in `channel` for P in facet; a function's value failing reflectivity_problem is a
  /// std::invalid_argument naming the point, its facet, the channel and the rule.
  double reflectivity(const Vec3& P, Index facet, std::size_t channel = 0) const;
  /// Prescribed E(P) (checked like reflectivity); for a manufactured scene use
  /// manufactured_emissivity().
  double emissivity(const Vec3& P, Index facet, std::size_t channel = 0) const;
  /// The per-facet values of `channel`, or an empty vector when given as a function.
  const std::vector<double>& facet_reflectivity(std::size_t channel = 0) const;
  const std::vector<double>& facet_emissivity(std::size_t channel = 0) const;

  bool has_manufactured_solution() const { return static_cast<bool>(solution_); }
  const SurfaceFunction& manufactured_solution() const { return solution_; }
  /// E(P) = u(P) - rho(P)/pi Int_S u(Q) G(P,Q) dS_Q for the manufactured solution u, (1).
  /// std::runtime_error naming the point, its facet and the triangle when the integral cannot
  /// be computed (u not finite, or not smooth enough to converge within the evaluation cap).
  double manufactured_emissivity(const Vec3& P, Index facet, const Vec3& nP) const;
  /// Largest rho over the facets of every channel when all are given per facet, else NaN
  /// (unknown until evaluated).
  double max_reflectivity() const;

  /// What loading did (merged vertices, re-orientation, hull re-triangulation, files read).
  const std::vector<std::string>& notes() const { return notes_; }
  void add_note(std::string note) { notes_.push_back(std::move(note)); }
  /// Material name per facet (OBJ scenes), else empty.
  const std::vector<std::string>& facet_material() const { return facet_material_; }
  void set_facet_material(std::vector<std::string> per_facet);

 private:
  struct Validated {
    geometry::ValidatedMesh mesh;
    std::vector<std::string> notes;
  };
  static Validated validate(geometry::TriangleMesh mesh);
  Scene(Validated validated, std::vector<std::string> channels);

  struct Channel {
    std::vector<double> rho_facet, e_facet;  // empty when the function is set
    SurfaceFunction rho_fn, e_fn;
    double environment = 0;
  };
  const Channel& channel(std::size_t c) const;
  Channel& channel(std::size_t c);

  geometry::SceneShape shape_ = geometry::SceneShape::convex;
  geometry::TriangleMesh mesh_;
  std::vector<std::string> channels_;
  bool closed_ = true, enclosed_ = true;
  std::vector<Channel> data_;
  SurfaceFunction solution_;
  double solution_tol_ = 1e-11;
  std::vector<std::string> notes_;
  std::vector<std::string> facet_material_;
};

/// The paper's cube example (31): unit cube, rho = 0.5 on y = 0, 1; 0.4 on z = 0, 1; 0.3 on
/// x = 0, 1; true solution u = x^2 + y^2 + z^2 (E manufactured). With `scale` and `offset` the
/// cube becomes offset + scale [0,1]^3 and u(Q) = |(Q - offset) / scale|^2: the same problem, for
/// stress tests of where the scene sits and how large it is.
Scene make_paper_cube_scene(double scale = 1.0, const Vec3& offset = Vec3::Zero());

}  // namespace panelrad

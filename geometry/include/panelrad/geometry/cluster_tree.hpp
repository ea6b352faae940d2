#pragma once
// Uniform 4-way midpoint subdivision kept as the paper's cluster tree U = T_{n_0} u ... u T_{n_c}
// (section 4, (39)-(40)). Implicit numbering: level l holds n0 * 4^l triangles; triangle k of
// level l has children 4k .. 4k+3 on level l+1. Hence the elements (leaves, finest level L)
// of cluster k of level l are the contiguous range [k * 4^(L-l), (k+1) * 4^(L-l)).
#include <panelrad/geometry/mesh.hpp>
#include <panelrad/geometry/planar_facets.hpp>
#include <panelrad/support/uninitialized_vector.hpp>

#include <array>
#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace panelrad::geometry {

/// Why n0 >= 1 triangles cannot be refined `level` >= 0 times, or "" when they can: the tree's
/// elements, n = n0 4^level, and its clusters on all levels (fewer than 4n/3) are numbered by
/// the 32-bit Index, so both must be at most 2^31 - 1. The reason names the level, n as
/// n0 * 4^level and its value, the limit and the largest level that has one, e.g. "level 14 gives
/// n = 12 * 4^14 = 3221225472 elements, more than the 2147483647 that the 32-bit indices of the
/// elements and clusters can number: level 13 is the largest for 12 triangles". Any level, without
/// overflow.
std::string level_size_problem(Index n0, int level);

/// One triangle of some level: a cluster tau of the paper.
/// Vertices are the exact midpoint-subdivision corners rounded to double (a midpoint is computed
/// once as (p + q) * 0.5, symmetric in p, q, so neighbouring triangles share their corners
/// bit for bit). normal and facet are those of the root triangle (level 0) and area is the root's
/// area / 4^level, so rounding of midpoints never perturbs them; centre and radius are exact for the stored (double) corners,
/// each rounded to nearest once.
struct Cluster {
  std::array<Vec3, 3> vertex;  ///< corners, counter-clockwise seen from outside
  Vec3 normal;                 ///< inner unit normal n of its plane (points into the solid), (2)
  Vec3 centre;                 ///< A(tau): circumcircle centre, exact construction rounded once, (41)
  double radius;               ///< R(tau): circumcircle radius, exact construction rounded once, (41)
  double area;                 ///< area of the exact midpoint subdivision: root area / 4^level
  Index facet;                 ///< input facet (maximal planar polygon) it lies in
};
// No member initializers: a level's clusters are allocated without being written and first
// written by the threads that compute them (UninitializedVector). Cluster{} is all zeros.

class ClusterTree {
 public:
  /// Subdivides a validated mesh (validate_closed_convex) `finest_level` times.
  /// Throws MeshError when the tree would not fit in memory (estimate given, checked before any
  /// allocation against default_memory_limit()), when level < 0, when n or the number of clusters
  /// would overflow Index (level_size_problem), or when the mesh is inconsistent (bad index,
  /// non-finite coordinate, zero-area triangle).
  ClusterTree(const TriangleMesh& validated_mesh, int finest_level);
  /// As above, refusing trees whose estimate_bytes() exceeds memory_limit_bytes; `planes` says
  /// which facets share a supporting plane (facet_planes): exact for a general scene.
  ClusterTree(const TriangleMesh& validated_mesh, int finest_level, std::size_t memory_limit_bytes,
              PlaneGrouping planes = PlaneGrouping::within_rounding);

  int finest_level() const { return finest_level_; }
  Index num_roots() const { return n0_; }                       ///< n0
  Index num_elements() const { return level_size(finest_level_); }  ///< n = n0 4^L
  Index level_size(int level) const { return n0_ << (2 * level); }
  Index num_facets() const { return num_facets_; }
  /// The supporting plane of cluster k of level l (of its root triangle): clusters of one plane
  /// id lie in one plane, exactly or (convex surfaces) within the rounding of the input (facet_planes in
  /// planar_facets.hpp), whichever facet they are in; a point of that plane sees none of them.
  Index plane(int l, Index k) const { return root_plane_[static_cast<std::size_t>(k >> (2 * l))]; }
  Index num_planes() const { return num_planes_; }

  std::span<const Cluster> level(int l) const { return levels_[static_cast<std::size_t>(l)]; }
  const Cluster& cluster(int l, Index k) const { return levels_[static_cast<std::size_t>(l)][static_cast<std::size_t>(k)]; }
  /// The elements Delta_k of the current triangulation T_{n_c} (the leaves).
  std::span<const Cluster> elements() const { return level(finest_level_); }

  /// Element range [first, end) of cluster k of level l (contiguous by construction).
  Index first_element(int l, Index k) const { return k << (2 * (finest_level_ - l)); }
  Index end_element(int l, Index k) const { return (k + 1) << (2 * (finest_level_ - l)); }

  /// Collocation point P_k: the centroid of element k, (22).
  const Vec3& collocation_point(Index k) const { return centroid_[static_cast<std::size_t>(k)]; }
  std::span<const Vec3> collocation_points() const { return centroid_; }

  /// Mesh size h: the largest element diameter (longest edge) at the finest level (section 3).
  double mesh_size() const { return mesh_size_; }
  /// Diameter of the surface (largest vertex distance bound: bounding-box diagonal).
  double diameter() const { return diameter_; }

  /// Bytes held by the tree (all levels) and per finest-level element.
  std::size_t bytes() const;
  double bytes_per_element() const { return static_cast<double>(bytes()) / num_elements(); }

  /// Estimated bytes for a given n0 and level, to refuse sizes that will not fit before allocating
  /// (saturates at SIZE_MAX).
  static std::size_t estimate_bytes(Index n0, int finest_level);
  /// The limit used by the two-argument constructor: the machine's physical memory.
  static std::size_t default_memory_limit();

 private:
  int finest_level_ = 0;
  Index n0_ = 0;
  Index num_facets_ = 0;
  Index num_planes_ = 0;
  std::vector<Index> root_plane_;  // per level-0 triangle: its facet's plane id
  double mesh_size_ = 0;
  double diameter_ = 0;
  std::vector<UninitializedVector<Cluster>> levels_;
  UninitializedVector<Vec3> centroid_;
};

}  // namespace panelrad::geometry

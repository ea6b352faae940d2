#pragma once
// The fast product K_n v of section 4 (panel clustering, Hackbusch & Nowak): for each collocation
// point P_i the minimal admissible covering (42) of the surface by clusters of the tree U (40):
// admissible clusters (41) are taken whole and integrated by the degree-M Taylor far field
// (44)-(48); non-admissible leaves form the near field (43), integrated once at setup and stored
// sparse. Clusters coplanar with P_i contribute exactly 0 and are skipped; rows with rho = 0 too.
// On convex scenes, target clusters (groups of collocation points, the triangles of the coarser
// levels) take the sources admissible for all of their points through one local expansion each
// (local_expansion.hpp, target_clusters.hpp): the per-point coverings then start where the
// targets stopped (LocalExpansionOptions; off, the paper's per-point coverings alone).
// An operator may own only the rows [begin, end) of K_n (FastOptions::rows): the coverings (42),
// near field (43) and far coefficients (44)-(45) of those rows; the cluster moments (48) of a
// product still need all of v.
// Beside it: the self-check of any operator (self_check.hpp), the cost model of storing the far
// coefficients (far_field_costs.hpp), and for the tests the coverings and moments as the operator
// holds them (detail/fast_operator_testing.hpp).
#include <panelrad/geometry/occluders.hpp>
#include <panelrad/support/uninitialized_vector.hpp>
#include <panelrad/operator/clustering_parameters.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/far_field.hpp>
#include <panelrad/operator/far_field_costs.hpp>
#include <panelrad/support/chunk_pool.hpp>
#include <panelrad/support/kept_vector.hpp>
#include <panelrad/support/large_buffer.hpp>
#include <panelrad/operator/linear_operator.hpp>
#include <panelrad/operator/near_field.hpp>
#include <panelrad/operator/self_check.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace panelrad {

namespace far_field_batch {
struct RowPoint;
struct ClusterFrames;
struct ClusterMoments;
}
struct TargetClusters;
namespace detail {
struct FastOperatorTesting;
}

/// Rows [begin, end) of K_n, the rows P_i whose coverings (42) an operator holds; end = -1 means
/// n. The default is every row.
struct RowRange {
  geometry::Index begin = 0;
  geometry::Index end = -1;
  bool operator==(const RowRange&) const = default;
};

/// The automatic interpolation degree for Taylor degree M: M up to 4, then max(4, M - 3).
int default_local_degree(int M);

/// eta of (41) and M of (44) (ClusteringParameters), the near rule, the storage limits and the
/// rows held.
struct FastOptions : ClusteringParameters {
  NearFieldOptions near;
  /// Far-field coefficients are stored when they take at most this many bytes (0: automatic,
  /// half of the available memory); otherwise they are recomputed in every product.
  std::size_t far_storage_limit = 0;
  /// The products the caller expects to make (0: unknown). When known, the coefficients are stored
  /// only if that many products repay writing them: expected x (recompute - read) > fill, per pair,
  /// by far_field_costs(); else they are recomputed in each product (bit-identical in double).
  int expected_products = 0;
  /// Setup is refused (std::runtime_error with the estimate) before any large allocation when
  /// its estimated peak memory exceeds this many bytes (0: the memory available).
  std::size_t memory_limit = 0;
  /// Called when a setup stage starts (cluster geometry, near field, far field), with a line
  /// saying what it does, e.g. for progress on stderr. May be empty.
  std::function<void(const std::string&)> progress;
  /// The rows set up and computed (default: all n). Must satisfy 0 <= begin <= end <= n
  /// (std::invalid_argument otherwise). With fewer than n rows, apply() throws and apply_rows()
  /// gives the rows held.
  RowRange rows;
  /// The scene's faces, when V(P, Q) is computed (Visibility::occluded in operator_factory.hpp):
  /// the coverings (42) classify each (P_i, cluster) pair as fully visible, hidden or partly
  /// visible (visible_covering.hpp). Empty: V = 1 (a convex scene), no visibility work at all.
  std::shared_ptr<const geometry::Occluders> occluders;
  /// Store the far coefficients (44)-(45) rounded to single precision (4 bytes a term instead of
  /// 8): half the memory, half the setup's writing and half a product's reading of them, at a
  /// rounding of 2^-24 ~ 6e-8 relative per coefficient (the sums stay double), which self_check
  /// measures with the Taylor remainder. Coefficients recomputed per product stay double.
  bool single_precision_coefficients = false;
  /// Store the near-field entries rho_i/pi Int G V (43) rounded to single precision (8 bytes an
  /// entry with its element id instead of 12): a covering with V holds several times the near
  /// entries of a convex surface (the elements along every shadow's edge are integrated one by
  /// one), which then dominate the memory and a product's reading. The rounding, 2^-24 ~ 6e-8
  /// relative per entry (the sums stay double), is included in what self_check measures.
  bool single_precision_near = false;
  /// A probe of these parameters: when > 0, only the rows that self_check(probe_samples) samples
  /// are covered and integrated (the others are held empty, their entries of a product 0), so
  /// that self_check(probe_samples) measures what it would measure on the whole operator, bit for
  /// bit (each row is computed independently of the others), at the cost of those rows alone.
  int probe_samples = 0;
};

/// What setup found and stored: the covering's counts (over the rows held).
struct FastStatistics {
  std::size_t near_pairs = 0;          ///< (P_i, element) pairs in the near field
  std::size_t far_pairs = 0;           ///< (P_i, cluster) pairs in the far field
  std::size_t skipped_coplanar = 0;    ///< clusters skipped as coplanar with P_i (whole subtrees)
  std::size_t skipped_rows = 0;        ///< rows with rho(P_i) = 0, not computed
  bool occluded = false;               ///< V(P, Q) computed (FastOptions::occluders)
  std::size_t visible_pairs = 0;       ///< occluded: (P_i, cluster) pairs classified fully visible
  std::size_t hidden_pairs = 0;        ///< occluded: pairs classified hidden (skipped with their subtrees)
  std::size_t partial_pairs = 0;       ///< occluded: pairs classified partly visible (refined or clipped)
  std::size_t clipped_elements = 0;    ///< occluded: near-field elements integrated over their visible part
  std::size_t rays_cast = 0;           ///< rays cast for V (0: every decision is a shaft classification)
  int target_level = -1;               ///< finest level of target clusters (-1: per-point coverings only)
  int local_degree = 0;                ///< d of the local expansions
  std::size_t target_clusters = 0;     ///< target clusters with a local expansion (with sources)
  std::size_t target_pairs = 0;        ///< (target, source) cluster pairs of the local expansions
  std::size_t target_point_pairs = 0;  ///< the (point, cluster) pairs they stand for: sum of |sigma| over the pairs
  std::size_t target_hidden_pairs = 0;     ///< occluded: (target, cluster) pairs hidden from the whole target
  std::size_t target_undecided_pairs = 0;  ///< occluded: admissible (target, cluster) pairs not proven fully visible
  bool far_stored = false;             ///< coefficients stored (true) or recomputed per product
  std::size_t bytes = 0;               ///< bytes held by the operator
  double geometry_s = 0;   ///< setup: cluster frames and element moments
  double covering_s = 0;   ///< setup: minimal admissible coverings (42) and near-field integrals (43)
  double far_s = 0;        ///< setup: far-field Taylor coefficients (44)-(45), when stored
  double targets_s = 0;    ///< setup: target clusters and their sources (local expansions)
};

/// The self-check's types for the fast operator (self_check.hpp: they serve any operator).
using FastSelfCheck = SelfCheck;
using FastSelfCheckReference = SelfCheckReference;

class FastOperator final : public RadiosityOperator {
 public:
  FastOperator(const Collocation& collocation, const FastOptions& options);

  /// n: the number of columns of K_n, and of rows of the whole operator.
  geometry::Index size() const override { return n_; }
  /// The rows held, [begin, end) with end resolved (every row: [0, n)).
  RowRange rows() const { return {row_begin_, row_end_}; }
  bool holds_all_rows() const { return row_begin_ == 0 && row_end_ == n_; }
  /// y = K_n v, all n rows. std::logic_error when the operator holds only some rows (it has no
  /// coverings for the others; apply_rows gives those it holds).
  void apply(const Eigen::VectorXd& v, Eigen::VectorXd& y) const override;
  /// The rows held of K_n v: y_block has length end - begin and y_block[i - begin] = (K_n v)_i,
  /// bit-identical to entry i of apply() on the whole operator. v has all n entries: the cluster
  /// moments (48) are integrals of v over the whole surface.
  void apply_rows(const Eigen::VectorXd& v, Eigen::VectorXd& y_block) const;
  /// Y = K_n V (all n rows held): column c bit-identical to apply(V.col(c)), every column's sums
  /// taken in the same order as apply's, while the stored far-field coefficients (44)-(45) and the
  /// near-field lists are read once per row for up to kBlockColumns columns at a time.
  void apply_block(const Eigen::MatrixXd& V, Eigen::MatrixXd& Y) const override;
  /// The rows held of K_n V: Y has end - begin rows, column c bit-identical to apply_rows(V.col(c))
  /// (apply_block's products on the rows held; V has all n rows).
  void apply_rows_block(const Eigen::MatrixXd& V, Eigen::MatrixXd& Y) const;
  /// Columns of V whose rows are computed together in apply_block.
  static constexpr int kBlockColumns = 4;
  std::string name() const override { return "fast"; }
  std::size_t bytes() const override { return stats_.bytes; }
  const FastStatistics& statistics() const { return stats_; }
  const FastOptions& options() const { return options_; }

  /// The self-check (self_check.hpp) of this operator: the product's real error on `samples`
  /// sampled rows against the exact closed-form rows (near field and far field together), for
  /// every self_check_vectors(). The rows are sampled among the rows held, and only they are
  /// computed (with the local expansions of their target clusters alone): the values of apply()
  /// on those rows, bit for bit.
  FastSelfCheck self_check(int samples = 32) const;
  /// The exact rows of self_check(samples) (self_check_reference of self_check.hpp on the rows
  /// held, with this operator's row weights and occluders), for comparing several operators of
  /// the same rows.
  FastSelfCheckReference self_check_reference(int samples = 32) const;
  /// self_check against a reference of an operator with the same collocation rows and occluders
  /// (std::invalid_argument when its rows are not held or its vectors are not of length n).
  FastSelfCheck self_check(const FastSelfCheckReference& reference) const;

  /// The test vectors of self_check, with their names: self_check_vectors of self_check.hpp on
  /// this operator's collocation points (and facets).
  SelfCheckVectors self_check_vectors() const;

  /// Bytes the operator will hold without far-field coefficients, and the far-field pairs, from
  /// the coverings of up to 256 evenly spaced rows of `rows` (cheap: no integrals). For refusing
  /// sizes that will not fit before allocating. The lists scale with the rows held; frames and
  /// moments are per cluster and element of the whole surface.
  struct MemoryEstimate {
    std::size_t bytes = 0;         ///< held after setup, coefficients not stored
    std::size_t list_bytes = 0;    ///< of which near/far lists (held twice during setup)
    std::size_t far_pairs = 0;     ///< estimated (point, cluster) pairs in the far field
    std::size_t near_pairs = 0;    ///< estimated (point, element) pairs in the near field
    std::size_t coefficient_bytes = 0;  ///< far_pairs x terms x 8, if stored
  };
  static MemoryEstimate estimate_memory(const Collocation& collocation, double eta, int degree,
                                        const RowRange& rows = {});
  /// The same for an operator of `options` (eta, M, rows held), with its target clusters
  /// (options.local on a convex scene): their per-point coverings start below the targets, and
  /// the targets' sources and values are counted.
  static MemoryEstimate estimate_memory(const Collocation& collocation, const FastOptions& options);
  /// Bytes of the arrays whose size depends only on n, the number of clusters and M (frames,
  /// moments, row data, row starts): MemoryEstimate::bytes without the near/far lists. With
  /// `rows` rows held (the row starts); without it, all n.
  static std::size_t fixed_bytes(std::size_t n, std::size_t clusters, int degree);
  static std::size_t fixed_bytes(std::size_t n, std::size_t clusters, int degree, std::size_t rows);

 private:
  // For the tests (detail/fast_operator_testing.hpp) and the setup's own use; not the operator's
  // interface.
  friend struct detail::FastOperatorTesting;

  /// Cluster ids of the far field and element ids of the near field of row i (for tests: the
  /// covering plus the skipped coplanar clusters must partition the surface). The far field is
  /// the sources of the local expansions of P_i's target ancestors (levels 0..target_level, coarse
  /// to fine), then P_i's per-point covering; empty for a row not computed (rho = 0, or a probe's
  /// row not sampled). Cluster id = level_offset(l) + k. Row i must be held (std::out_of_range
  /// otherwise).
  std::vector<geometry::Index> far_clusters(geometry::Index i) const;
  std::vector<geometry::Index> near_elements(geometry::Index i) const;
  /// The moments (48) Int_Delta x^p y^q dS of element e about A(Delta), in the axes of its
  /// plane's frame and the far field's length unit (far_field_unit()): num_taylor_terms(M) values in
  /// graded order. Every element of a root triangle is congruent to it (setup_element_data), so
  /// the operator holds two sets per root, not one per element.
  std::span<const double> element_moments(geometry::Index e) const;
  /// The moments of the four elements of cluster k of level L - 1 (L >= 1) about that cluster's
  /// A(tau), in its frame: 4 num_taylor_terms(M) values, child c's at c T. They are those
  /// of its placement class (the number of digits 3 in its path below the root, modulo 6: each
  /// negates the triangle and turns its corners' labels), shifted once at setup.
  std::span<const double> child_shape_moments(geometry::Index k) const;
  /// The centre A(tau) of the cluster of global id `id` as the far field expands about it, in the
  /// far field's unit: held above the finest level; an element's is formed from its centroid and
  /// its shape (far_field_batch::ClusterFrames), the circumcentre up to rounding.
  Vec3 expansion_centre(geometry::Index id) const;
  /// The placement classes of the clusters of level l of a root: min(l + 1, 6).
  static geometry::Index placement_classes(int l);
  /// The far field's length unit: the power of two 2^-ilogb(diameter) (lengths are multiplied by it).
  static double far_field_unit(const geometry::ClusterTree& tree);

  /// Global id of cluster k of level l and its inverse.
  geometry::Index cluster_id(int level, geometry::Index k) const { return level_offset_[static_cast<std::size_t>(level)] + k; }
  std::pair<int, geometry::Index> cluster_of_id(geometry::Index id) const;


  // The coverings (42) of a block of kRowBlock consecutive rows held, as they are stored: per row
  // the starts (within the block) of its near-field element ids with their integrals rho_i/pi Int G
  // (43) and of its far-field cluster ids, and the index among all far pairs of the block's first
  // one (where its stored coefficients start). Each block is built whole by one thread and kept:
  // the lists are never concatenated, so they are written once and held once, in one piece of
  // that thread's chunks (list_chunks_): near_val, near_col, far_cluster, near_start, far_start.
  // near_val holds doubles, or floats with single_precision_near (value_bytes 8 or 4).
  struct RowBlock {
    std::int64_t far_first = 0;
    std::uint32_t rows = 0, near = 0, far = 0, value_bytes = sizeof(double);
    std::byte* lists = nullptr;
    static std::size_t list_bytes(std::size_t rows, std::size_t near, std::size_t far, std::size_t value_bytes) {
      return near * (value_bytes + sizeof(geometry::Index)) + far * sizeof(geometry::Index) +
             2 * (rows + 1) * sizeof(std::uint32_t);
    }
    double* near_val() const { return reinterpret_cast<double*>(lists); }
    float* near_val_single() const { return reinterpret_cast<float*>(lists); }
    geometry::Index* near_col() const { return reinterpret_cast<geometry::Index*>(lists + near * value_bytes); }
    geometry::Index* far_cluster() const { return near_col() + near; }
    std::uint32_t* near_start() const { return reinterpret_cast<std::uint32_t*>(far_cluster() + far); }
    std::uint32_t* far_start() const { return near_start() + rows + 1; }
    std::size_t bytes() const { return sizeof(RowBlock) + list_bytes(rows, near, far, value_bytes); }
  };
  // Row r's lists (r counted from the first row held): near_val or near_val_single, by the block.
  struct RowLists {
    const geometry::Index* near_col;
    const double* near_val;
    const float* near_val_single;
    std::int64_t near_count;
    const geometry::Index* far_cluster;
    std::int64_t far_count;
    std::int64_t far_first;  // the index of its first far pair among all
  };

  // Setup (fast_operator.cpp), its stages in order.
  void check_options();
  void report_stage(const std::string& what) const;
  std::string rows_note() const;
  bool row_computed(geometry::Index i) const;
  std::size_t local_row(geometry::Index i, const char* who) const;
  static std::vector<geometry::Index> level_offsets(const geometry::ClusterTree& tree);

  // Cluster frames and element moments (fast_operator_geometry.cpp).
  void setup_cluster_frames();
  void setup_element_data(const Collocation& collocation);
  /// The element moments by shape, two sets per root (setup_element_data).
  void setup_shape_moments();
  /// The moments of level L - 1's four elements per placement class (setup_element_data).
  void setup_child_shape_moments();
  void compute_moments(const Eigen::VectorXd& v, UninitializedVector<double>& moments) const;
  /// Row i's side of its far pairs (P_i in the far field's unit, n_P, rho_i/pi).
  far_field_batch::RowPoint far_row_point(geometry::Index i) const;
  /// The frame of cluster `id` (global id): its origin A(tau), its root's axes.
  PlaneFrame frame(geometry::Index id) const;
  /// A(tau) (scaled: A) of cluster k of level l >= 1 in its parent's frame (the shift of centre of (48)).
  std::array<double, 2> offset_in_parent(int l, geometry::Index k, const Vec3& A) const;
  far_field_batch::ClusterFrames cluster_frames() const;
  /// The moments of every cluster for C columns: `moments` (compute_moments) above the finest
  /// level, v (C columns interleaved) times the element moments by shape on it.
  far_field_batch::ClusterMoments cluster_moments(const double* moments, const double* v) const;

  // The coverings (42) and their row lists (fast_operator_coverings.cpp).
  struct CoveringLists;  // one thread's lists of the block it builds
  struct CoveringTally;  // one thread's counts of skipped rows and clusters, and of visibility
  void cover_rows();
  /// Block b's coverings (42) and near-field integrals (43), gathered into `lists`.
  void cover_block(geometry::Index b, CoveringLists& lists, CoveringTally& tally) const;
  /// Row i's covering (42) and near field (43) appended to `lists` (a row computed, rho_i = rho).
  void cover_row(geometry::Index i, double rho, CoveringLists& lists, CoveringTally& tally) const;
  /// Block b's lists written once into one piece of the calling thread's chunks.
  void store_block(geometry::Index b, const CoveringLists& lists);
  void store_coverings();
  RowLists row_lists(std::size_t r) const;

  // The target clusters and their local expansions (fast_operator_targets.cpp).
  /// The target clusters' finest level lt (-1: none), degree d and eta_t (target_plan).
  struct TargetPlan {
    int level = -1;
    int degree = 0;
    double eta = 0;
  };
  static TargetPlan target_plan(const FastOptions& options, int finest_level);
  static std::shared_ptr<TargetClusters> make_target_clusters(const geometry::ClusterTree& tree, const FastOptions& options);
  void setup_target_clusters(std::shared_ptr<TargetClusters> targets);
  /// The target clusters of levels 0..target_level containing row i, coarse to fine, that have
  /// a local expansion (a slot), appended to `out`.
  void append_target_ancestors(geometry::Index i, std::vector<geometry::Index>& out) const;
  /// The values at their interpolation points of the local expansions of `targets` (ascending ids
  /// with a slot, each one's parent among them when it has a slot), C columns of moments
  /// interleaved, into values[slot (d+1)^2 C + k C + c]: each target's own sources, plus its
  /// parent's expansion evaluated at its points.
  void evaluate_local_expansions(const double* moments, const double* v, int C,
                                 const std::vector<geometry::Index>& targets, std::vector<double>& values) const;
  /// The first step of evaluate_local_expansions: each target's own sources at its points.
  void evaluate_target_sources(const double* moments, const double* v, int C,
                               const std::vector<geometry::Index>& targets, std::vector<double>& values) const;
  /// The second step: each target of levels 1..lt adds its parent's expansion at its points.
  void inherit_parent_expansions(int C, const std::vector<geometry::Index>& targets, std::vector<double>& values) const;
  /// Row i's local-expansion part for C columns: the interpolant of its target cluster of level
  /// target_level, whose values hold its ancestors' expansions too.
  template <int C>
  void add_local_expansions(geometry::Index i, const double* values, double* sum) const;

  // The far store (fast_operator_far_store.cpp).
  /// Whether the far coefficients are stored: only when they fit and storing pays for the
  /// products expected (far_field_costs).
  bool far_storage_chosen() const;
  void setup_far_coefficients();
  std::size_t coefficient_bytes() const { return options_.single_precision_coefficients ? sizeof(float) : sizeof(double); }

  // The memory estimate (fast_operator_memory.cpp).
  /// `alongside`, when given, is run by one thread of the sampling's team while the others sample.
  static MemoryEstimate estimate_memory(const Collocation& collocation, double eta, int degree, const RowRange& rows,
                                        const TargetClusters* targets, const std::function<void()>& alongside = {});
  void refuse_beyond_memory(const Collocation& collocation, const TargetClusters* targets) const;
  std::size_t held_bytes() const;

  // The arrays of a product (cluster moments (48), local expansions' values, a block's columns),
  // kept from one product to the next: allocating them anew costs a page fault per 4 KiB each
  // time (about 235 MB of moments at n = 3,145,728, M 6). They are sized uninitialized, so that
  // the parallel loops that fill them touch them first, not one thread zeroing them. The
  // self-check's products use them too. A product that finds them in use by another one running
  // at the same time uses arrays of its own.
  struct ProductWorkspace {
    UninitializedVector<double> moments, v_block, m_block;
    std::vector<double> local_values;
  };
  // The product (fast_operator_product.cpp).
  /// The shared workspace when it is free, else `own` (the lock, when taken, is held by `lock`).
  ProductWorkspace& acquire_workspace(std::unique_lock<std::mutex>& lock, ProductWorkspace& own) const;
  double apply_row(geometry::Index i, const Eigen::VectorXd& v, const UninitializedVector<double>& moments,
                   const std::vector<double>& local_values, double* scratch) const;
  /// Row i of the product for C vectors: out[c] = (K_n v_c)_i, each from its own moments, every
  /// sum in apply_row's order; v and moments hold the C columns interleaved (j C + c).
  template <int C>
  void apply_row_columns(geometry::Index i, const double* v, const double* moments, const double* local_values,
                         double* scratch, double* out) const;

  // The self-check's sampled rows (fast_operator_self_check.cpp).
  /// The self-check's rows among the rows held (self_check_rows of self_check.hpp).
  std::vector<geometry::Index> self_check_rows(int samples) const;
  /// Rows `rows` of K_n v, (K_n v)_{rows[r]} into out[r], each by apply_row: the moments (48) of
  /// v and the local expansions of those rows' targets only (`targets`: their ancestors, ascending).
  void apply_sampled_rows(const Eigen::VectorXd& v, std::span<const geometry::Index> rows,
                          const std::vector<geometry::Index>& targets, ProductWorkspace& workspace,
                          std::span<double> out) const;

  std::shared_ptr<const geometry::ClusterTree> tree_;
  FastOptions options_;
  geometry::Index n_ = 0;
  geometry::Index row_begin_ = 0, row_end_ = 0;   // the rows held, [begin, end)
  int terms_ = 0;                                 // (M+1)(M+2)/2
  std::vector<geometry::Index> level_offset_;     // first global id of each level
  // The per-cluster and per-row arrays are sized once and filled by parallel loops (first touch).
  KeptVector<double> rho_;                             // rho(P_i), all n rows (P_i and n_P are the tree's)
  double unit_scale_ = 1;                         // far field in units of 2^k ~ diameter (exact scaling)
  KeptVector<ClusterOrigin> cluster_origin_;  // per cluster of levels 0..L-1: A(tau) (scaled), its root's axes
  std::vector<double> leaf_shift_;                // per shape of level L: s (A(root) - C(root)) (scaled), 3 each
  std::vector<PlaneFrame> root_axes_;             // per root: its frame (the axes of all its clusters)
  KeptVector<std::array<double, 2>> to_parent_;  // per cluster of levels 0..L-1: its A in parent's frame (roots: 0)
  // Element moments Int_Delta x^p y^q dS about A(Delta) by shape: per root, the even and the odd
  // elements' (setup_element_data), 2 n0 T values.
  std::vector<double> shape_moments_;
  // The moments of a level-(L-1) cluster's four elements about its own A(tau), by the cluster's
  // placement class (placement_classes per root), four sets of T each: a product gets the
  // cluster's moments (48) as sum_c v_c times these, instead of four shifts of centre
  // (setup_element_data).
  std::vector<double> child_shape_moments_;
  // Near and far field lists by blocks of rows (RowBlock): CSR within each block, with 32-bit
  // starts (4 bytes a row each, the block's first pair held once); element index and rho_i/pi Int G,
  // cluster id (and, when stored, the rho-scaled Taylor coefficients in far_coef_). CSR rather than
  // Eigen::SparseMatrix<double, RowMajor, StorageIndex>, measured on the cube, eta 0.2 (near pairs
  // 5.6 a row at n = 49152): a 64-bit StorageIndex takes 16 bytes a pair against 12, at no gain in
  // speed. The near sum is fused with the far sum of the same row; it is < 1% of a product.
  std::vector<RowBlock> blocks_;
  // The blocks' lists, a slot per thread (chunk_pool.hpp). held_bytes counts the lists; each
  // slot's last chunk may hold up to 2 MiB more, unused.
  ChunkArena list_chunks_;
  LargeBuffer far_coef_;                         // uninitialized, huge pages, filled in parallel
  LargeArray<float> far_coef_single_;            // the same, single_precision_coefficients
  std::vector<char> probed_;                     // probe_samples > 0: per row held, covered or not
  // Local expansions of target clusters: the clusters and their sources, the slot of each target
  // id's values in a product (-1: none), and the targets with a slot in slot order.
  std::shared_ptr<const TargetClusters> targets_;
  std::vector<std::int64_t> local_slot_;
  std::vector<geometry::Index> active_targets_;
  mutable std::mutex workspace_mutex_;
  mutable ProductWorkspace workspace_;
  FastStatistics stats_;
};

}  // namespace panelrad

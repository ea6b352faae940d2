#pragma once
// The paper's cube example (section 3, (31); Table 1; Tables 2-4): solve on levels min..max and
// report, per n, the error (51), times, iterations, the Neumann ratio (36) and peak memory.
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/solve/memory_plan.hpp>
#include <panelrad/solve/radiosity_solver.hpp>
#include <panelrad/solve/solvers.hpp>

#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace panelrad {

/// Each level is one RadiositySolver on make_paper_cube_scene() with the rho of (31) folded into
/// the operator's rows (fold_reflectivity), E manufactured from u, and the error (51) against u.
struct CubeRunOptions {
  int min_level = 0;
  int max_level = 3;
  /// The operator of every level: method dense or fast, near rule, eta, M.
  OperatorOptions op;
  /// solver.tolerance 0: tied to the discretization error per level (discretization_tolerance).
  SolverOptions solver;
  /// Fast method: when the operator's self-check exceeds self_check_threshold(), tighten the
  /// parameters (tighten_parameters) and rebuild, until it passes or nothing is stricter
  /// (SolveOptions::tighten_on_failed_check).
  bool tighten_on_failed_check = false;
  /// The processes sharing each level's rows (SolveOptions::communicator; nullptr: one).
  const Communicator* communicator = nullptr;
};

/// One line of the table / CSV.
struct CubeRow {
  std::string method, near;
  std::string solver;         ///< the solver that ran, and why when chosen automatically
  double eta = 0;   ///< fast only
  int mu = 0;
  int degree = 0;   ///< fast only
  Index n = 0;
  double max_error = 0;       ///< max_k |u(P_k) - u_n(P_k)|, (51)
  double error_ratio = 0;     ///< previous level's error / this one (Table 1 "Ratio"), 0 for the first
  double setup_s = 0;         ///< refinement + cluster tree + operator (matrix or near/far field)
  double emissivity_s = 0;    ///< manufacturing E = u - K u (test data, not part of setup)
  double solve_s = 0;
  int iterations = 0;
  double conv_ratio = 0;      ///< (36), Neumann
  double peak_rss_mb = 0;
  double operator_mb = 0;     ///< bytes stored by the operator
  double per_product_s = 0;   ///< solve time / products
  // Fast method only (section 4): the covering's size (with several processes, summed over
  // them) and what was stored.
  std::size_t near_pairs = 0, far_pairs = 0, skipped_coplanar = 0;
  bool far_stored = false;
  double checked_product_error = 0;  ///< FastOperator::self_check on sampled rows
  int tightened = 0;                  ///< times the parameters were tightened after a failed check
};

/// Refuses (ResourceError) before any work a max_level whose n = 12 * 4^max_level elements exceed
/// the 32-bit index (level 13 is the largest: geometry::level_size_problem), and, with the
/// estimate (memory_plan.hpp), a level min_level..max_level that cannot fit: the cluster tree, the
/// collocation, the operator and the
/// solver of each level, with options.op, or with choose_parameters() per level when
/// `automatic_parameters`. run_paper_cube calls it with its own options.
/// Returns the estimates, one per level.
std::vector<LevelMemoryEstimate> check_paper_cube_fits(const CubeRunOptions& options, bool automatic_parameters = false);

/// Runs the levels in order; `on_row` (if set) sees each row as soon as it is done. Every level
/// is checked to fit (check_paper_cube_fits) before the first is solved; an allocation that
/// fails anyway is a ResourceError naming the level, the stage and the size. A level whose
/// iteration does not converge is a SolverError (require_converged).
std::vector<CubeRow> run_paper_cube(const CubeRunOptions& options,
                                    const std::function<void(const CubeRow&)>& on_row = {});

/// CSV header: method,near,eta,mu,degree,n,max_error,setup_s,solve_s,iterations,conv_ratio,peak_rss_mb
std::string cube_csv_header();
std::string cube_csv_line(const CubeRow& row);
/// Writes the CSV whole or not at all (temporary file, then rename). Throws std::runtime_error.
void write_cube_csv(const std::vector<CubeRow>& rows, const std::string& path);
/// Prints the table in the style of Table 1 (dense) or Tables 2-4 (fast).
void print_cube_header(std::ostream& os, const CubeRunOptions& options);
void print_cube_row(std::ostream& os, const CubeRow& row);
/// Growth of setup time and time per product per 4x in n (cost should grow like n log n, not n^2).
void print_cube_growth(std::ostream& os, const std::vector<CubeRow>& rows);

}  // namespace panelrad

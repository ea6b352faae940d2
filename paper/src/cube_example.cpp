#include <panelrad/geometry/cluster_tree.hpp>
#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/paper/cube_example.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/operator/fast_operator.hpp>
#include <panelrad/solve/memory_plan.hpp>
#include <panelrad/support/resources.hpp>
#include <panelrad/io/text_output.hpp>

#include <cstdio>
#include <ostream>
#include <sstream>

namespace panelrad {

std::vector<LevelMemoryEstimate> check_paper_cube_fits(const CubeRunOptions& options, bool automatic_parameters) {
  if (options.min_level < 0 || options.max_level < options.min_level)
    throw std::invalid_argument("levels: need 0 <= min_level <= max_level");
  const Scene scene = make_paper_cube_scene();
  // The finest level first: one beyond the 32-bit element index is refused by that count before
  // any level is planned (however many levels were asked for).
  const auto n0 = static_cast<Index>(scene.mesh().triangles.size());
  if (const std::string problem = geometry::level_size_problem(n0, options.max_level); !problem.empty())
    throw ResourceError("cube " + problem);
  std::vector<PlannedLevel> planned;
  for (int level = options.min_level; level <= options.max_level; ++level) {
    OperatorOptions op = automatic_parameters ? choose_parameters(problem_size(scene.mesh(), level)) : options.op;
    op.local = options.op.local;
    planned.push_back({level, op});
  }
  LevelMemoryOptions memory;
  memory.collocation_vectors = 3;  // rho, E and the manufactured u (31)
  memory.target_clusters = true;   // the cube is convex
  const std::vector<LevelMemoryEstimate> levels =
      estimate_levels_memory(scene.mesh(), planned, options.solver, scene.max_reflectivity(), memory);
  refuse_levels_that_cannot_fit(levels, "cube ");
  return levels;
}

namespace {

SolveOptions level_options(const CubeRunOptions& options, int level) {
  SolveOptions o;
  o.level = level;
  o.op = options.op;
  o.tighten_on_failed_check = options.tighten_on_failed_check;
  o.solver = options.solver;  // tolerance 0: discretization_tolerance, per level
  o.fold_reflectivity = true;  // K_n with rho (31) in its rows, as in the paper's tables
  o.communicator = options.communicator;
  return o;
}

// One line of the tables: the level's setup and solve, and the error (51) against u = |x|^2.
CubeRow cube_row(const RadiositySolver& solver, const ChannelSolve& result) {
  const RadiositySolverInfo& info = solver.info();
  const OperatorOptions& op = info.parameters;
  CubeRow row;
  row.method = to_string(op.method);
  row.near = to_string(op.near.rule);
  row.mu = op.near.mu;
  if (op.method == OperatorMethod::fast) {
    row.eta = op.eta;
    row.degree = op.degree;
  }
  row.tightened = info.tightened;
  row.n = info.n;
  row.emissivity_s = solver.collocation().emissivity_seconds();
  row.setup_s = solver.collocation().tree_seconds() + info.operator_s;
  row.operator_mb = static_cast<double>(info.operator_bytes) / (1024.0 * 1024.0);
  const auto* rows = dynamic_cast<const RowBlockOperator*>(&solver.op());
  if (const auto* fast = dynamic_cast<const FastOperator*>(rows ? &rows->local() : &solver.op())) {
    const FastStatistics& s = fast->statistics();
    row.near_pairs = s.near_pairs;
    row.far_pairs = s.far_pairs;
    row.skipped_coplanar = s.skipped_coplanar;
    row.far_stored = s.far_stored;
    row.checked_product_error = info.self_check->relative_error;
    if (rows) sum_counts(*solver.options().communicator, {&row.near_pairs, &row.far_pairs, &row.skipped_coplanar});
  }
  row.solver = result.solver;
  row.solve_s = result.seconds;
  row.iterations = result.iterations;
  row.per_product_s = result.iterations > 0 ? result.seconds / result.iterations : 0;
  row.conv_ratio = result.convergence_ratio;
  row.max_error = solver.collocation().max_error(result.u);
  return row;
}

}  // namespace

std::vector<CubeRow> run_paper_cube(const CubeRunOptions& options, const std::function<void(const CubeRow&)>& on_row) {
  // Every level is estimated before level min_level is computed: a size that cannot fit is
  // refused at once, not after the levels below it.
  check_paper_cube_fits(options);
  const Scene scene = make_paper_cube_scene();
  std::vector<CubeRow> rows;
  for (int level = options.min_level; level <= options.max_level; ++level) {
    CubeRow row;
    try {
      const RadiositySolver solver(scene, level_options(options, level));
      const ChannelSolve result = solver.solve(0);
      if (!result.converged()) throw SolverError(result.message);
      row = cube_row(solver, result);
    } catch (const ResourceError& e) {
      throw ResourceError("cube level " + std::to_string(level) + ": " + e.what());
    }
    if (!rows.empty() && row.max_error > 0) row.error_ratio = rows.back().max_error / row.max_error;
    row.peak_rss_mb = peak_rss_mb();
    rows.push_back(row);
    if (on_row) on_row(row);
  }
  return rows;
}

std::string cube_csv_header() {
  return "method,near,eta,mu,degree,n,max_error,setup_s,solve_s,iterations,conv_ratio,peak_rss_mb";
}

std::string cube_csv_line(const CubeRow& r) {
  const bool fast = r.method == "fast";
  char buf[512];
  // eta and degree only mean something for the fast method, mu only for the quadrature rule.
  const bool quadrature = r.near == "quadrature";
  char eta[32] = "", mu[16] = "", degree[16] = "";
  if (fast) std::snprintf(eta, sizeof eta, "%g", r.eta);
  if (fast) std::snprintf(degree, sizeof degree, "%d", r.degree);
  if (quadrature) std::snprintf(mu, sizeof mu, "%d", r.mu);
  std::snprintf(buf, sizeof buf, "%s,%s,%s,%s,%s,%d,%.6e,%.6g,%.6g,%d,%.6f,%.1f", r.method.c_str(), r.near.c_str(), eta,
                mu, degree,
                static_cast<int>(r.n), r.max_error, r.setup_s, r.solve_s, r.iterations, r.conv_ratio, r.peak_rss_mb);
  return buf;
}

void write_cube_csv(const std::vector<CubeRow>& rows, const std::string& path) {
  std::ostringstream os;
  os << cube_csv_header() << "\n";
  for (const auto& r : rows) os << cube_csv_line(r) << "\n";
  write_file_atomically(path, os.str());
}

void print_cube_header(std::ostream& os, const CubeRunOptions& o) {
  os << "Cube example (paper (31)): rho 0.5 on y=0,1; 0.4 on z=0,1; 0.3 on x=0,1; u = x^2+y^2+z^2\n"
     << "method " << to_string(o.op.method) << ", near field " << to_string(o.op.near.rule);
  if (o.op.near.rule == NearRule::quadrature) os << " (mu " << o.op.near.mu << ", " << o.op.near.basic_rule << ")";
  if (o.op.method == OperatorMethod::fast) os << ", eta " << o.op.eta << ", degree M " << o.op.degree;
  os << ", solver " << to_string(o.solver.kind) << ", threads " << max_threads() << "\n";
  char buf[256];
  std::snprintf(buf, sizeof buf, "%8s %11s %6s %9s %9s %9s %6s %8s %9s %9s %9s", "n", "max error", "ratio",
                "setup s", "E s", "solve s", "iters", "Neumann", "s/product", "op MB", "peak MB");
  os << buf;
  if (o.op.method == OperatorMethod::fast) {
    std::snprintf(buf, sizeof buf, " %12s %12s %11s %10s %s", "near pairs", "far pairs", "coplanar", "Kv error", "far field");
    os << buf;
  }
  os << "\n";
}

void print_cube_row(std::ostream& os, const CubeRow& r) {
  char buf[256];
  char ratio[16] = "";
  if (r.error_ratio > 0) std::snprintf(ratio, sizeof ratio, "%.2f", r.error_ratio);
  std::snprintf(buf, sizeof buf, "%8d %11.3e %6s %9.3f %9.3f %9.3f %6d %8.4f %9.3g %9.1f %9.0f",
                static_cast<int>(r.n), r.max_error, ratio, r.setup_s, r.emissivity_s, r.solve_s, r.iterations,
                r.conv_ratio, r.per_product_s, r.operator_mb, r.peak_rss_mb);
  os << buf;
  if (r.method == "fast") {
    std::snprintf(buf, sizeof buf, " %12zu %12zu %11zu %10.2e %s", r.near_pairs, r.far_pairs, r.skipped_coplanar,
                  r.checked_product_error, r.far_stored ? "stored" : "recomputed");
    os << buf;
    if (r.tightened > 0) {
      std::snprintf(buf, sizeof buf, " (self-check failed: tightened %d time%s to eta %g, M %d)", r.tightened,
                    r.tightened > 1 ? "s" : "", r.eta, r.degree);
      os << buf;
    }
  }
  os << "\n";
  os.flush();
}

}  // namespace panelrad

namespace panelrad {

void print_cube_growth(std::ostream& os, const std::vector<CubeRow>& rows) {
  if (rows.size() < 2) return;
  os << "growth per 4x in n (n log n would be ~4.3-4.6x, n^2 16x):\n";
  char buf[160];
  std::snprintf(buf, sizeof buf, "%8s -> %-8s %12s %14s %12s\n", "n", "4n", "setup", "per product", "error");
  os << buf;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const CubeRow& a = rows[k - 1];
    const CubeRow& b = rows[k];
    const auto ratio = [](double x, double y) { return x > 0 ? y / x : 0.0; };
    std::snprintf(buf, sizeof buf, "%8d -> %-8d %11.2fx %13.2fx %11.2fx\n", static_cast<int>(a.n), static_cast<int>(b.n),
                  ratio(a.setup_s, b.setup_s), ratio(a.per_product_s, b.per_product_s), ratio(a.max_error, b.max_error));
    os << buf;
  }
}

}  // namespace panelrad

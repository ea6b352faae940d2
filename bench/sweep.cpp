// Run time against error: sweeps method (dense, fast) x near rule (exact,
// quadrature with mu) x eta (41) x Taylor degree M (44) x n on the paper's cube (31) and on a
// hexagonal prism, both with the manufactured solution u = x^2 + y^2 + z^2, and writes one CSV row
// per run plus a log-log PNG of the error (51) against total time with the Pareto front marked.
//
//   usage: sweep [--quick | --full] [options]   (sweep --help lists them)
//
// Timing: total = setup (refinement + cluster tree + operator: matrix or near/far field) + solve.
// The manufactured E = u - K u (test data, identical for every method at a given n) is computed
// once per (scene, level) and not counted. Every run of a level uses the same Collocation.
// Reference: the dense operator with the exact near rule (the discretization error of the
// centroid method at that n); `deviation` = max_k |u_n(P_k) - u_ref(P_k)|, which bounds how far a
// run's error can be from the discretization error (triangle inequality).
#include <panelrad/operator/collocation.hpp>
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/validation.hpp>
#include <panelrad/operator/operator_factory.hpp>
#include <panelrad/support/resources.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/solvers.hpp>
#include <panelrad/io/text_output.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

using namespace panelrad;

namespace {

const char* kUsage =
    "usage: sweep [--quick | --full] [options]\n"
    "  --quick               small grid, runs in well under 2 minutes (default)\n"
    "  --full                cube levels 1..5, prism levels 1..4, eta {0.5,0.3,0.2,0.1},\n"
    "                        M {0..6}, near {exact, quadrature mu 1,2,3} (about half an hour\n"
    "                        on 2 cores with pruning)\n"
    "  --scenes LIST         cube,prism (default both)\n"
    "  --cube-levels A:B     levels of the cube (n = 12 * 4^l)\n"
    "  --prism-levels A:B    levels of the hexagonal prism (n = 20 * 4^l)\n"
    "  --etas LIST           admissibility parameters of (41), e.g. 0.5,0.3,0.2,0.1\n"
    "  --degrees LIST        Taylor degrees M of (44), e.g. 1,2,3\n"
    "  --nears LIST          near rules: exact, q1, q2, q3 (quadrature with mu = 1, 2, 3)\n"
    "  --dense-max-n N       largest n for the dense method (default 12288)\n"
    "  --fast-max-n N        largest n for the fast method (default: no limit)\n"
    "  --tol T               Neumann stopping tolerance (relative), default 1e-7\n"
    "  --threads T           OpenMP threads (default: all)\n"
    "  --out DIR             output folder (default bench/results)\n"
    "  --tag NAME            file name stem: DIR/NAME.csv, DIR/pareto_<scene>.png (default sweep)\n"
    "  --no-prune            run the whole grid (default: per (near rule, eta), stop one degree M\n"
    "                        after the first run within 5% of the discretization error; skip\n"
    "                        fast runs with a quadrature rule whose dense run is not within 5%)\n"
    "  --repeat R            runs shorter than 1 s are repeated, best time of R kept (default 2)\n"
    "  --no-plot             do not run gnuplot\n"
    "  --plot-script PATH    gnuplot script (default: plot_pareto.gp beside this source)\n";

struct NearChoice {
  NearFieldOptions options;
  std::string label() const {
    return options.rule == NearRule::exact ? "exact" : "quadrature mu=" + std::to_string(options.mu);
  }
};

struct Config {
  std::vector<std::string> scenes{"cube", "prism"};
  int cube_lo = 1, cube_hi = 3, prism_lo = 1, prism_hi = 3;
  std::vector<double> etas{0.5, 0.3, 0.2, 0.1};
  std::vector<int> degrees{1, 2, 3, 4};
  std::vector<NearChoice> nears;
  long dense_max_n = 12288;
  long fast_max_n = std::numeric_limits<long>::max();
  double tol = 1e-7;
  int threads = 0;
  std::string out = "bench/results";
  std::string tag = "sweep";
  bool plot = true;
  bool prune = true;
  int repeat = 2;
  std::string plot_script;
};

struct Run {
  std::string scene;
  Index n = 0;
  int level = 0;
  std::string method, near;
  double eta = 0;
  int mu = 0, degree = 0;
  double max_error = 0, setup_s = 0, solve_s = 0;
  int iterations = 0;
  double peak_rss_mb = 0;
  double deviation = std::numeric_limits<double>::quiet_NaN();  // vs dense exact, NaN: no reference
  double reference_error = std::numeric_limits<double>::quiet_NaN();
  bool series_front = false, pareto = false;
  double total() const { return setup_s + solve_s; }
  /// Within 5% of the discretization error: |u_n - u_ref|_inf <= 0.05 |u - u_ref|_inf, which
  /// implies max_error <= 1.05 * reference error without relying on lucky cancellation.
  bool faithful() const { return !std::isnan(deviation) && deviation <= 0.05 * reference_error; }
  std::string series() const {
    return method + " " + (near == "exact" ? std::string("exact") : "quadrature mu=" + std::to_string(mu));
  }
};

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  if (out.empty()) throw std::invalid_argument("empty list '" + s + "'");
  return out;
}

double to_double(const std::string& opt, const std::string& v) {
  std::size_t pos = 0;
  double x = 0;
  try {
    x = std::stod(v, &pos);
  } catch (const std::exception&) {
    pos = 0;
  }
  if (pos != v.size() || !std::isfinite(x)) throw std::invalid_argument(opt + ": '" + v + "' is not a number");
  return x;
}

long to_long(const std::string& opt, const std::string& v) {
  std::size_t pos = 0;
  long x = 0;
  try {
    x = std::stol(v, &pos);
  } catch (const std::exception&) {
    pos = 0;
  }
  if (pos != v.size()) throw std::invalid_argument(opt + ": '" + v + "' is not an integer");
  return x;
}

void parse_range(const std::string& opt, const std::string& v, int& lo, int& hi) {
  const auto colon = v.find(':');
  if (colon == std::string::npos) {
    lo = hi = static_cast<int>(to_long(opt, v));
  } else {
    lo = static_cast<int>(to_long(opt, v.substr(0, colon)));
    hi = static_cast<int>(to_long(opt, v.substr(colon + 1)));
  }
  if (lo < 0 || hi < lo || hi > 8) throw std::invalid_argument(opt + ": need 0 <= A <= B <= 8, got '" + v + "'");
}

NearChoice parse_near(const std::string& s) {
  NearChoice c;
  if (s == "exact") {
    c.options.rule = NearRule::exact;
    return c;
  }
  if (s.size() == 2 && s[0] == 'q' && s[1] >= '0' && s[1] <= '4') {
    c.options.rule = NearRule::quadrature;
    c.options.mu = s[1] - '0';
    return c;
  }
  throw std::invalid_argument("--nears: '" + s + "' is not exact or q0..q4");
}

/// Resets the kernel's peak-RSS counter (VmHWM) so that each run reports its own peak; false when
/// the kernel does not allow it (then peaks are cumulative).
bool reset_peak_rss() {
  std::ofstream f("/proc/self/clear_refs");
  if (!f) return false;
  f << "5";
  f.close();
  return static_cast<bool>(f);
}

/// The hexagonal prism (circumradius 1, height 1): rho 0.5 on the six sides, 0.3 on the bottom
/// cap, 0.4 on the top cap; u = x^2 + y^2 + z^2 manufactured (E = u - K u).
Scene make_prism_scene() {
  geometry::TriangleMesh mesh = geometry::make_builtin("prism:6");
  const geometry::ValidationReport report = geometry::validate_closed_convex(mesh);
  if (!report.valid) throw std::runtime_error("prism:6 failed validation: " + report.rule);
  Scene scene(std::move(mesh));
  std::vector<double> rho(static_cast<std::size_t>(scene.num_facets()), 0.5);  // facets: 6 sides,
  rho[6] = 0.3;                                                                 // bottom cap,
  rho[7] = 0.4;                                                                 // top cap
  scene.set_reflectivity(std::move(rho));
  scene.set_manufactured_solution([](const Vec3& Q, Index) { return Q.squaredNorm(); });
  return scene;
}

std::string csv_header() {
  return "scene,n,method,near,eta,mu,degree,max_error,setup_s,solve_s,iterations,peak_rss_mb,"
         "total_s,deviation,faithful,series_front,pareto";
}

std::string csv_line(const Run& r) {
  const bool fast = r.method == "fast";
  const bool quad = r.near == "quadrature";
  char buf[512];
  std::snprintf(buf, sizeof buf, "%s,%d,%s,%s,%s,%s,%s,%.6e,%.6g,%.6g,%d,%.1f,%.6g,%s,%d,%d,%d", r.scene.c_str(),
                static_cast<int>(r.n), r.method.c_str(), r.near.c_str(),
                fast ? (std::ostringstream() << r.eta).str().c_str() : "",
                quad ? std::to_string(r.mu).c_str() : "", fast ? std::to_string(r.degree).c_str() : "",
                r.max_error, r.setup_s, r.solve_s, r.iterations, r.peak_rss_mb, r.total(),
                std::isnan(r.deviation) ? "" : (std::ostringstream() << std::scientific << r.deviation).str().c_str(),
                r.faithful() ? 1 : 0, r.series_front ? 1 : 0, r.pareto ? 1 : 0);
  return buf;
}

/// Marks the Pareto front (no other run is both faster and more accurate) among `runs`; only
/// faithful runs (within 5% of the discretization error) take part, so that a run whose error is
/// low by a lucky cancellation of far-field and discretization errors does not define the front.
void mark_front(std::vector<Run*> runs, bool Run::*flag) {
  std::sort(runs.begin(), runs.end(), [](const Run* a, const Run* b) {
    return a->total() != b->total() ? a->total() < b->total() : a->max_error < b->max_error;
  });
  double best = std::numeric_limits<double>::infinity();
  for (Run* r : runs) {
    r->*flag = r->max_error < best;
    best = std::min(best, r->max_error);
  }
}

// The sweep times each operator's setup and solve on one shared collocation (the manufactured E
// of a level is computed once for all runs, so it builds the operators by hand; the solve
// pipeline itself is RadiositySolver's).
Run run_one(const Scene& scene, const std::string& scene_name, const Collocation& col, const OperatorOptions& op,
            const SolverOptions& solver, bool rss_reset, Eigen::VectorXd& u) {
  Run r;
  r.scene = scene_name;
  r.n = col.size();
  r.level = col.level();
  r.method = to_string(op.method);
  r.near = to_string(op.near.rule);
  r.mu = op.near.rule == NearRule::quadrature ? op.near.mu : 0;
  if (op.method == OperatorMethod::fast) {
    r.eta = op.eta;
    r.degree = op.degree;
  }
  if (rss_reset) reset_peak_rss();
  Stopwatch clock;
  const auto K = make_operator(col, op);
  r.setup_s = col.tree_seconds() + clock.seconds();  // refinement + tree + operator
  const SolveResult s = solve(*K, col.emissivity(), solver, scene.max_reflectivity());
  s.require_converged();  // a sweep row is only meaningful at the tolerance
  r.solve_s = s.seconds;
  r.iterations = s.iterations;
  r.max_error = col.max_error(s.u);  // (51)
  r.peak_rss_mb = peak_rss_mb();
  u = s.u;
  return r;
}

/// Series id of plot_pareto.gp: 1 dense exact, 2..4 dense quadrature mu = 1..3, 5 fast exact,
/// 6..8 fast quadrature mu = 1..3; 0 for a series the script does not draw.
int series_id(const Run& r) {
  const int base = r.method == "dense" ? 0 : 4;
  if (r.near == "exact") return base + 1;
  return r.mu >= 1 && r.mu <= 3 ? base + 1 + r.mu : 0;
}

std::string plot_command(const Config& cfg, const std::string& csv, const std::string& png, const std::string& scene,
                         const std::vector<Run>& runs) {
  std::string script = cfg.plot_script;
  if (script.empty()) script = (std::filesystem::path(__FILE__).parent_path() / "plot_pareto.gp").string();
  std::string series;  // the series present for this scene, so that the key lists only those
  for (int k = 1; k <= 8; ++k)
    for (const Run& r : runs)
      if (r.scene == scene && series_id(r) == k) {
        series += (series.empty() ? "" : " ") + std::to_string(k);
        break;
      }
  return "gnuplot -e \"csv='" + csv + "'; png='" + png + "'; scene='" + scene + "'; series='" + series + "'\" '" +
         script + "'";
}

/// For one (scene, n): the cheapest run whose solution stays within 5% of the discretization
/// error (deviation from the dense exact solution <= 0.05 * its error), the evidence for
/// auto_parameters.hpp.
void summarize_level(const std::vector<Run>& runs, const std::string& scene, Index n) {
  const Run* best = nullptr;
  const Run* best_fast = nullptr;
  for (const Run& r : runs) {
    if (r.scene != scene || r.n != n || std::isnan(r.deviation)) continue;
    if (!r.faithful()) continue;
    if (!best || r.total() < best->total()) best = &r;
    if (r.method == "fast" && (!best_fast || r.total() < best_fast->total())) best_fast = &r;
  }
  for (const Run* r : {best, best_fast}) {
    if (!r) continue;
    std::printf("  cheapest within 5%%%s: %s eta %g M %d, error %.4e (reference %.4e), total %.3f s\n",
                r == best ? "" : " (fast)", r->series().c_str(), r->eta, r->degree, r->max_error,
                r->reference_error, r->total());
  }
}

/// Reads the command line into cfg; returns 0 to go on, else the exit status (help: 0 printed).
int parse_config(int argc, char** argv, Config& cfg, bool& help) {
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "-h" || a == "--help") {
        std::cout << kUsage;
        help = true;
        return 0;
      }
      if (a == "--quick") continue;  // the defaults
      if (a == "--full") {
        cfg.cube_lo = 1, cfg.cube_hi = 5, cfg.prism_lo = 1, cfg.prism_hi = 4;
        cfg.degrees = {0, 1, 2, 3, 4, 5, 6};
        cfg.nears = {parse_near("exact"), parse_near("q1"), parse_near("q2"), parse_near("q3")};
        continue;
      }
      if (a == "--no-prune") {
        cfg.prune = false;
        continue;
      }
      if (a == "--no-plot") {
        cfg.plot = false;
        continue;
      }
      if (i + 1 >= argc) throw std::invalid_argument("option '" + a + "' needs a value (or is unknown)");
      const std::string v = argv[++i];
      if (a == "--scenes") {
        cfg.scenes = split(v);
        for (const auto& s : cfg.scenes)
          if (s != "cube" && s != "prism") throw std::invalid_argument("--scenes: unknown scene '" + s + "'");
      } else if (a == "--cube-levels") parse_range(a, v, cfg.cube_lo, cfg.cube_hi);
      else if (a == "--prism-levels") parse_range(a, v, cfg.prism_lo, cfg.prism_hi);
      else if (a == "--etas") {
        cfg.etas.clear();
        for (const auto& s : split(v)) {
          const double e = to_double(a, s);
          if (!(e > 0 && e < 1)) throw std::invalid_argument("--etas: eta must be in (0, 1), got " + s);
          cfg.etas.push_back(e);
        }
      } else if (a == "--degrees") {
        cfg.degrees.clear();
        for (const auto& s : split(v)) {
          const long m = to_long(a, s);
          if (m < 0 || m > 12) throw std::invalid_argument("--degrees: M must be in 0..12, got " + s);
          cfg.degrees.push_back(static_cast<int>(m));
        }
      } else if (a == "--nears") {
        cfg.nears.clear();
        for (const auto& s : split(v)) cfg.nears.push_back(parse_near(s));
      } else if (a == "--dense-max-n") cfg.dense_max_n = to_long(a, v);
      else if (a == "--fast-max-n") cfg.fast_max_n = to_long(a, v);
      else if (a == "--tol") {
        cfg.tol = to_double(a, v);
        if (!(cfg.tol > 0 && cfg.tol < 0.5)) throw std::invalid_argument("--tol must be in (0, 0.5)");
      } else if (a == "--threads") cfg.threads = static_cast<int>(to_long(a, v));
      else if (a == "--repeat") {
        cfg.repeat = static_cast<int>(to_long(a, v));
        if (cfg.repeat < 1 || cfg.repeat > 20) throw std::invalid_argument("--repeat must be in 1..20");
      } else if (a == "--out") cfg.out = v;
      else if (a == "--tag") cfg.tag = v;
      else if (a == "--plot-script") cfg.plot_script = v;
      else throw std::invalid_argument("unknown option '" + a + "'");
    }
  } catch (const std::exception& e) {
    std::cerr << "sweep: " << e.what() << "\n" << kUsage;
    return 2;
  }
  return 0;
}

/// The operators run at n elements: the dense exact reference first, then the other near rules,
/// then the fast grid.
std::vector<OperatorOptions> planned_operators(const Config& cfg, Index n) {
  std::vector<OperatorOptions> ops;
  if (n <= cfg.dense_max_n) {
    OperatorOptions reference;  // dense, exact near rule: first, it is the reference
    reference.method = OperatorMethod::dense;
    ops.push_back(reference);
    for (const auto& nc : cfg.nears) {
      if (nc.options.rule == NearRule::exact) continue;
      OperatorOptions o;
      o.method = OperatorMethod::dense;
      o.near = nc.options;
      ops.push_back(o);
    }
  }
  if (n <= cfg.fast_max_n)
    for (const auto& nc : cfg.nears)
      for (double eta : cfg.etas)
        for (int m : cfg.degrees) {
          OperatorOptions o;
          o.method = OperatorMethod::fast;
          o.near = nc.options;
          o.eta = eta;
          o.degree = m;
          ops.push_back(o);
        }
  return ops;
}

/// One (scene, level): every planned operator on one collocation (E manufactured once).
void sweep_level(const Config& cfg, const Scene& scene, const std::string& scene_name, int level,
                 const SolverOptions& solver, bool rss_reset, std::vector<Run>& runs) {
  const Collocation col(scene, level);  // E manufactured once per (scene, level), reused below
  std::printf("\n%s level %d: n = %d, h/diam = %.4g, E manufactured in %.2f s (not counted)\n",
              scene_name.c_str(), level, static_cast<int>(col.size()),
              col.tree().mesh_size() / col.tree().diameter(), col.emissivity_seconds());
  std::printf("  %-24s %5s %3s %11s %10s %9s %9s %5s %8s\n", "run", "eta", "M", "max error", "deviation",
              "setup s", "solve s", "iters", "peak MB");
  const std::vector<OperatorOptions> ops = planned_operators(cfg, col.size());
  std::optional<Eigen::VectorXd> u_ref;
  // Pruning (--prune): the degrees of one (near rule, eta) run in increasing order and stop
  // one degree after the first faithful run (a higher M only costs more); a quadrature
  // near rule whose dense run is not faithful is not tried with the fast method (its
  // near-field error alone exceeds the 5% margin).
  std::map<std::string, int> faithful_seen;  // (near, eta) -> faithful runs so far
  std::map<int, bool> dense_quad_faithful;   // mu -> dense quadrature run faithful
  for (const OperatorOptions& op : ops) {
    const int mu = op.near.rule == NearRule::quadrature ? op.near.mu : -1;
    const std::string key = std::to_string(mu) + "/" + std::to_string(op.eta);
    if (cfg.prune && op.method == OperatorMethod::fast && u_ref) {
      if (mu >= 0 && dense_quad_faithful.count(mu) && !dense_quad_faithful[mu]) continue;
      if (faithful_seen[key] >= 2) continue;
    }
    Eigen::VectorXd u;
    Run r = run_one(scene, scene_name, col, op, solver, rss_reset, u);
    for (int rep = 1; rep < cfg.repeat && r.total() < 1.0; ++rep) {  // timing noise: best of
      Eigen::VectorXd u2;
      const Run again = run_one(scene, scene_name, col, op, solver, rss_reset, u2);
      if (again.total() < r.total()) r = again;
    }
    if (!u_ref && op.method == OperatorMethod::dense && op.near.rule == NearRule::exact) u_ref = u;
    if (u_ref) {
      r.deviation = (u - *u_ref).lpNorm<Eigen::Infinity>();
      r.reference_error = col.max_error(*u_ref);
    }
    if (op.method == OperatorMethod::dense && mu >= 0) dense_quad_faithful[mu] = r.faithful();
    if (op.method == OperatorMethod::fast && (r.faithful() || faithful_seen[key] > 0)) ++faithful_seen[key];
    std::printf("  %-24s %5s %3s %11.4e %10.3e %9.3f %9.3f %5d %8.0f\n", r.series().c_str(),
                r.method == "fast" ? (std::ostringstream() << r.eta).str().c_str() : "",
                r.method == "fast" ? std::to_string(r.degree).c_str() : "", r.max_error, r.deviation,
                r.setup_s, r.solve_s, r.iterations, r.peak_rss_mb);
    std::fflush(stdout);
    runs.push_back(r);
  }
  summarize_level(runs, scene_name, col.size());
}

/// Marks the Pareto fronts of each scene and prints them.
void report_fronts(const Config& cfg, std::vector<Run>& runs) {
  // Pareto fronts per scene: of each series (method + near rule) and of all runs.
  for (const std::string& scene_name : cfg.scenes) {
    std::map<std::string, std::vector<Run*>> series;
    std::vector<Run*> all;
    for (Run& r : runs)
      if (r.scene == scene_name && r.faithful()) {
        series[r.series()].push_back(&r);
        all.push_back(&r);
      }
    for (auto& [name, list] : series) mark_front(list, &Run::series_front);
    mark_front(all, &Run::pareto);
  }
}

void print_fronts(const Config& cfg, const std::vector<Run>& runs) {
  for (const std::string& scene_name : cfg.scenes) {
    std::printf("\nPareto front, %s (error against setup + solve time; runs within 5%% of the discretization error):\n",
                scene_name.c_str());
    std::printf("  %7s %-24s %5s %3s %11s %9s %9s\n", "n", "run", "eta", "M", "max error", "total s", "peak MB");
    std::vector<const Run*> front;
    for (const Run& r : runs)
      if (r.scene == scene_name && r.pareto) front.push_back(&r);
    std::sort(front.begin(), front.end(), [](const Run* a, const Run* b) { return a->total() < b->total(); });
    for (const Run* r : front)
      std::printf("  %7d %-24s %5s %3s %11.4e %9.3f %9.0f\n", static_cast<int>(r->n), r->series().c_str(),
                  r->method == "fast" ? (std::ostringstream() << r->eta).str().c_str() : "",
                  r->method == "fast" ? std::to_string(r->degree).c_str() : "", r->max_error, r->total(),
                  r->peak_rss_mb);
  }
}

}  // namespace

int main(int argc, char** argv) {
  Config cfg;
  cfg.nears = {parse_near("exact"), parse_near("q2")};
  bool help = false;
  if (const int status = parse_config(argc, argv, cfg, help); status != 0 || help) return status;
  set_threads(cfg.threads);
  const bool rss_reset = reset_peak_rss();
  SolverOptions solver;  // Neumann (34) for every run, to the same tolerance
  solver.tolerance = cfg.tol;

  std::printf("sweep: threads %d, Neumann tol %.1e, peak RSS %s\n", max_threads(), cfg.tol,
              rss_reset ? "per run (VmHWM reset)" : "cumulative (cannot reset VmHWM)");
  std::vector<Run> runs;
  try {
    for (const std::string& scene_name : cfg.scenes) {
      const Scene scene = scene_name == "cube" ? make_paper_cube_scene() : make_prism_scene();
      const int lo = scene_name == "cube" ? cfg.cube_lo : cfg.prism_lo;
      const int hi = scene_name == "cube" ? cfg.cube_hi : cfg.prism_hi;
      for (int level = lo; level <= hi; ++level) {
        sweep_level(cfg, scene, scene_name, level, solver, rss_reset, runs);
      }
    }
  } catch (const std::exception& e) {
    std::cerr << "sweep: error: " << e.what() << "\n";
    return 1;
  }
  report_fronts(cfg, runs);
  std::ostringstream csv;
  csv << csv_header() << "\n";
  for (const Run& r : runs) csv << csv_line(r) << "\n";
  const std::filesystem::path dir(cfg.out);
  std::string csv_path = (dir / (cfg.tag + ".csv")).string();
  try {
    std::filesystem::create_directories(dir);
    write_file_atomically(csv_path, csv.str());
  } catch (const std::exception& e) {
    std::cerr << "sweep: error: " << e.what() << "\n";
    return 1;
  }
  std::printf("\nwrote %s (%zu runs)\n", csv_path.c_str(), runs.size());
  print_fronts(cfg, runs);
  if (cfg.plot) {
    int status = 0;
    for (const std::string& scene_name : cfg.scenes) {
      const std::string png = (dir / ("pareto_" + scene_name + ".png")).string();
      const std::string cmd = plot_command(cfg, csv_path, png, scene_name, runs);
      if (std::system(cmd.c_str()) != 0) {
        std::cerr << "sweep: gnuplot failed (is gnuplot-nox installed?): " << cmd << "\n";
        status = 1;
      } else {
        std::printf("wrote %s\n", png.c_str());
      }
    }
    return status;
  }
  return 0;
}

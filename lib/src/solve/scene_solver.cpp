#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/solve/memory_plan.hpp>
#include <panelrad/support/resources.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/scene_solver.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace panelrad {

ScaledOperator::ScaledOperator(const RadiosityOperator& H, Eigen::VectorXd row_scale)
    : H_(H), scale_(std::move(row_scale)) {
  if (scale_.size() != H_.size()) throw std::invalid_argument("ScaledOperator: scale size differs from n");
}

void ScaledOperator::apply(const Eigen::VectorXd& v, Eigen::VectorXd& y) const {
  H_.apply(v, y);
  y.array() *= scale_.array();  // (K v)_i = rho_i (H v)_i, (33)
}

int level_for_max_elements(geometry::Index n0, geometry::Index max_elements) {
  if (n0 <= 0) throw std::invalid_argument("level_for_max_elements: n0 must be positive");
  if (max_elements <= 0) throw std::invalid_argument("max elements must be positive");
  int level = 0;
  std::int64_t n = n0;
  while (n * 4 <= max_elements) {
    n *= 4;
    ++level;
  }
  return level;
}

namespace {

std::string fmt(const char* format, double a, double b = 0, double c = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, format, a, b, c);
  return buf;
}

// Channels with the same rho and E on every facet have the same solution: solved once.
int identical_earlier_channel(const ChannelScene& scene, std::size_t c) {
  for (std::size_t d = 0; d < c; ++d)
    if (scene.rho[d] == scene.rho[c] && scene.emission[d] == scene.emission[c]) return static_cast<int>(d);
  return -1;
}

// Where a solve is, so that an allocation failure can name the stage, n and the estimate.
struct SceneSolvePosition {
  std::string stage = "reading the options";
  double n = 0;
  std::size_t need = 0;  // bytes estimated for the stage, 0 when not known
};

SceneSolution solve_scene_stages(const ChannelScene& scene, const SceneSolveOptions& options, SceneSolvePosition& at);

}  // namespace

SceneSolution solve_channel_scene(const ChannelScene& scene, const SceneSolveOptions& options) {
  SceneSolvePosition at;
  try {
    return solve_scene_stages(scene, options, at);
  } catch (const std::bad_alloc&) {
    throw ResourceError(out_of_memory_message(at.stage, at.n, at.need));
  }
}

namespace {

SceneSolution solve_scene_stages(const ChannelScene& scene, const SceneSolveOptions& options, SceneSolvePosition& at) {
  const auto say = [&](const std::string& line) {
    if (options.progress) options.progress(line);
  };
  const std::size_t C = scene.num_channels();
  const Index F = scene.mesh.num_facets;
  if (C == 0) throw std::invalid_argument("scene has no channels");
  if (scene.rho.size() != C || scene.emission.size() != C)
    throw std::invalid_argument("scene: rho and emission need one array per channel");
  for (std::size_t c = 0; c < C; ++c) {
    if (scene.rho[c].size() != static_cast<std::size_t>(F) || scene.emission[c].size() != static_cast<std::size_t>(F))
      throw std::invalid_argument("scene: channel " + scene.channels[c] + " needs one rho and one E per facet");
    for (Index f = 0; f < F; ++f) {
      const double r = scene.rho[c][static_cast<std::size_t>(f)], e = scene.emission[c][static_cast<std::size_t>(f)];
      if (!(r >= 0 && r < 1))
        throw std::invalid_argument("scene: rho = " + std::to_string(r) + " of facet " + std::to_string(f) +
                                    ", channel " + scene.channels[c] + " is outside [0, 1)");
      if (!std::isfinite(e))
        throw std::invalid_argument("scene: E of facet " + std::to_string(f) + ", channel " + scene.channels[c] +
                                    " is not finite");
    }
  }
  Stopwatch total;
  SceneSolution out;
  const Index n0 = static_cast<Index>(scene.mesh.triangles.size());
  out.level = options.levels >= 0 ? options.levels : level_for_max_elements(n0, options.max_elements);
  if (out.level > 15) throw std::invalid_argument("levels: " + std::to_string(out.level) + " is more than 15");

  // The method first, so that a size that cannot fit is refused before any work.
  // The largest reflectivity over all channels: the conditioning 1 / (1 - rho_max) of every
  // channel's equation (11), which the automatic product accuracy must honour.
  double conditioning_rho = 0;
  for (const std::vector<double>& rho : scene.rho)
    for (double r : rho) conditioning_rho = std::max(conditioning_rho, r);
  OperatorOptions op;
  if (options.method == "auto") {
    op = choose_parameters(problem_size(scene.mesh, out.level), 0.05, conditioning_rho);
  } else if (options.method == "dense" || options.method == "fast") {
    op = options.manual;
    op.method = options.method;
  } else {
    throw std::invalid_argument("method '" + options.method + "' is not auto, dense or fast");
  }
  // Everything this level will hold, estimated from the input mesh (memory_plan.hpp), and
  // refused with the estimate when it cannot fit: before the subdivision starts.
  SolverOptions planned_solver;
  planned_solver.kind = options.solver;
  double max_rho = 0;
  for (const std::vector<double>& rho : scene.rho)
    for (double r : rho) max_rho = std::max(max_rho, r);
  LevelMemoryOptions memory;
  memory.collocation_vectors = 4;  // the geometric collocation's rho, E and the unit-weight copy's
  // Per element: the triangle, inner normal, centroid, area and facet of the output field, and
  // per channel rho, E, radiosity (twice: solution and field) and irradiance.
  memory.field_bytes_per_element = sizeof(std::array<Vec3, 3>) + 2 * sizeof(Vec3) + sizeof(double) + sizeof(Index) +
                                   C * 5 * sizeof(double);
  const LevelMemoryEstimate estimate =
      estimate_level_memory(scene.mesh, out.level, op, planned_solver, max_rho, memory);
  refuse_levels_that_cannot_fit({estimate}, (scene.mesh.source.empty() ? std::string("scene") : scene.mesh.source) + ": ");
  at.n = static_cast<double>(estimate.n);

  // 1. Geometry: subdivision and collocation points (22); rho and E per channel by facet.
  Stopwatch clock;
  say("subdividing " + std::to_string(n0) + " triangles " + std::to_string(out.level) + " times: n = " +
      std::to_string(static_cast<long long>(n0) << (2 * out.level)));
  at.stage = "subdividing: the cluster tree (40) and the collocation points (22)";
  at.need = estimate.tree + estimate.collocation / 2;
  const Scene geometric(scene.mesh);  // rho, E of the channels are applied per row below
  const Collocation base(geometric, out.level);
  const Index n = out.n = base.size();
  out.mesh_size = base.tree().mesh_size();
  out.diameter = base.tree().diameter();
  out.subdivision_s = clock.seconds();
  say(fmt("subdivision done in %.2f s", out.subdivision_s));

  // 2. One operator for every channel: H (rho replaced by 1), so K_c = diag(rho_c) H.
  clock.restart();
  // The operator's own stages (near field, far field) are named by its progress lines.
  at.stage = "building the operator (" + describe_parameters(op) + ")";
  at.need = estimate.op;
  op.progress = [&at, &options](const std::string& line) {
    at.stage = "building the operator: " + line;
    if (options.progress) options.progress(line);
  };
  const Collocation unit = base.with_row_weights(Eigen::VectorXd::Ones(n));
  std::unique_ptr<RadiosityOperator> H = make_operator(unit, op);
  if (const auto* fast = dynamic_cast<const FastOperator*>(H.get())) {
    say("fast operator: checking the product on sampled exact rows");
    out.self_check_threshold = self_check_threshold(problem_size(scene.mesh, out.level), conditioning_rho);
    out.self_check = fast->self_check();
    out.self_check_error = out.self_check.relative_error;
    while (options.method == "auto" && !(out.self_check_error <= out.self_check_threshold)) {
      const OperatorOptions stricter = tighten_parameters(op);
      if (describe_parameters(stricter) == describe_parameters(op)) break;  // nothing stricter
      say(fmt("self-check %.2e above %.2e: tightening", out.self_check_error, out.self_check_threshold));
      op = stricter;
      ++out.tightened;
      H.reset();  // free the looser operator before building the stricter one
      H = make_operator(unit, op);
      out.self_check = dynamic_cast<const FastOperator&>(*H).self_check();
      out.self_check_error = out.self_check.relative_error;
    }
    if (!(out.self_check_error <= out.self_check_threshold))
      out.warnings.push_back(fmt("the fast product's measured relative error %.2e is above the accepted %.2e "
                                 "(nothing stricter to try); the answer may be less accurate than the discretization",
                                 out.self_check_error, out.self_check_threshold));
  }
  out.method = describe_parameters(op);
  out.operator_bytes = H->bytes();
  out.operator_s = clock.seconds();
  say(fmt("operator ready in %.2f s: ", out.operator_s) + out.method + ", " +
      format_bytes(static_cast<double>(out.operator_bytes)));

  // 3. Every channel: (I - diag(rho_c) H) u_c = E_c, (32); then the energy balance.
  clock.restart();
  SolverOptions solver;
  solver.kind = options.solver;
  solver.tolerance = options.tolerance > 0 ? options.tolerance : discretization_tolerance(out.mesh_size, out.diameter);
  // The elements and rho, E per channel at every element (by facet): what the solves and the
  // output writers need.
  at.stage = "storing the per-element results (element geometry, rho and E of each channel)";
  at.need = estimate.fields;
  ElementField& field = out.field;
  field.channels = scene.channels;
  field.triangle.resize(static_cast<std::size_t>(n));
  field.inner_normal.resize(static_cast<std::size_t>(n));
  field.centroid.resize(static_cast<std::size_t>(n));
  field.area.resize(static_cast<std::size_t>(n));
  field.facet.resize(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) {
    const geometry::Cluster& e = base.tree().elements()[static_cast<std::size_t>(i)];
    field.triangle[static_cast<std::size_t>(i)] = e.vertex;
    field.inner_normal[static_cast<std::size_t>(i)] = e.normal;
    field.centroid[static_cast<std::size_t>(i)] = base.collocation_point(i);
    field.area[static_cast<std::size_t>(i)] = e.area;
    field.facet[static_cast<std::size_t>(i)] = e.facet;
  }
  for (std::size_t c = 0; c < C; ++c) {
    Eigen::VectorXd rho(n), E(n);
    for (Index i = 0; i < n; ++i) {
      const std::size_t f = static_cast<std::size_t>(field.facet[static_cast<std::size_t>(i)]);
      rho[i] = scene.rho[c][f];
      E[i] = scene.emission[c][f];
    }
    field.rho.push_back(std::move(rho));
    field.emission.push_back(std::move(E));
  }
  // Expected size of the energy mismatch: a discretization effect (point-to-element form factors
  // are not reciprocal), measured at most 0.35 h/diam on the cube, prisms and the tetrahedron at
  // levels 1-5 (tests/solve/test_scene_solver.cpp): 0.5 h/diam; a warning above 4 times that.
  out.expected_energy_mismatch = 0.5 * out.mesh_size / out.diameter;
  for (std::size_t c = 0; c < C; ++c) {
    ChannelSolution ch;
    ch.name = scene.channels[c];
    const Eigen::VectorXd& rho = field.rho[c];
    const Eigen::VectorXd& E = field.emission[c];
    const int same = identical_earlier_channel(scene, c);
    if (same >= 0) {
      const ChannelSolution& d = out.channels[static_cast<std::size_t>(same)];
      ch = d;
      ch.name = scene.channels[c];
      ch.shared_with = d.name;
      say("channel " + ch.name + ": same rho and E as channel " + d.name + ", solution shared");
      out.channels.push_back(std::move(ch));
      continue;
    }
    if (E.lpNorm<Eigen::Infinity>() == 0) {
      ch.radiosity = Eigen::VectorXd::Zero(n);  // nothing emitted: u = 0 exactly
      ch.irradiance = Eigen::VectorXd::Zero(n);
      ch.solver = "none (E = 0 in this channel: u = 0)";
      out.channels.push_back(std::move(ch));
      continue;
    }
    const SolverKind kind = solver.kind == SolverKind::automatic ? choose_solver(rho.maxCoeff()) : solver.kind;
    at.stage = "solving channel " + ch.name + " (32) with " + to_string(kind);
    at.need = estimate.solver;
    const double max_rho = rho.maxCoeff();
    const ScaledOperator K(*H, rho);
    SolverOptions channel_solver = solver;
    if (options.progress)
      channel_solver.progress = [&](int products, double estimate) {
        say(std::string("channel ") + ch.name + fmt(": product %.0f, error estimate %.2e", products, estimate));
      };
    const SolveResult r = solve(K, E, channel_solver, max_rho);
    ch.radiosity = r.u;
    ch.solver = r.choice.empty() ? r.solver : r.choice;
    ch.iterations = r.iterations;
    ch.residual = r.residual;
    ch.error_estimate = r.error_estimate;
    H->apply(ch.radiosity, ch.irradiance);  // the light arriving: the product without rho
    for (Index i = 0; i < n; ++i) {
      const double a = field.area[static_cast<std::size_t>(i)];
      ch.emitted += a * E[i];
      ch.absorbed += a * (1 - rho[i]) * ch.irradiance[i];
    }
    ch.energy_mismatch = ch.emitted != 0 ? std::abs(ch.emitted - ch.absorbed) / std::abs(ch.emitted) : 0;
    if (ch.energy_mismatch > 4 * out.expected_energy_mismatch)
      out.warnings.push_back(std::string("channel ") + ch.name +
                             fmt(": energy mismatch %.2e is far above its expected size %.2e (0.5 h/diam): is the "
                                 "scene really closed and convex, or the operator inaccurate?",
                                 ch.energy_mismatch, out.expected_energy_mismatch));
    say(std::string("channel ") + ch.name + ": " + ch.solver + fmt(", %.0f products, energy mismatch %.2e", ch.iterations, ch.energy_mismatch));
    out.channels.push_back(std::move(ch));
  }
  out.solve_s = clock.seconds();

  for (const ChannelSolution& ch : out.channels) field.radiosity.push_back(ch.radiosity);
  out.peak_rss_mb = peak_rss_mb();
  out.total_s = total.seconds();
  return out;
}

}  // namespace

}  // namespace panelrad

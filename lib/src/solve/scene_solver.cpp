#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/solve/scene_solver.hpp>
#include <panelrad/scene/errors.hpp>
#include <panelrad/support/resources.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace panelrad {

namespace {

std::string fmt(const char* format, double a, double b = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, format, a, b);
  return buf;
}

// The visibility work of the operator: with several processes, the sums of their rows' work.
VisibilityWork operator_visibility_work(const RadiositySolver& solver) {
  const auto* rows = dynamic_cast<const RowBlockOperator*>(&solver.op());
  if (!rows) return visibility_work(solver.op());
  VisibilityWork w = visibility_work(rows->local());
  sum_counts(*solver.options().communicator,
             {&w.visible_pairs, &w.hidden_pairs, &w.partial_pairs, &w.clipped_elements, &w.rays_cast});
  return w;
}

// What the setup did, for the summary.
void copy_setup(const RadiositySolver& solver, SceneSolution& out) {
  const RadiositySolverInfo& info = solver.info();
  out.level = info.level;
  out.n = info.n;
  out.mesh_size = info.mesh_size;
  out.diameter = info.diameter;
  out.parameters = info.parameters;
  out.method = describe_parameters(info.parameters);
  if (info.self_check) {
    out.self_check = *info.self_check;
    out.self_check_error = info.self_check->relative_error;
    out.self_check_threshold = info.self_check_threshold;
  }
  out.tightened = info.tightened;
  out.visibility = info.visibility;
  out.visibility_work = operator_visibility_work(solver);
  out.subdivision_s = info.subdivision_s;
  out.operator_s = info.operator_s;
  out.operator_bytes = info.operator_bytes;
  out.warnings = info.warnings;
}

// The elements, and rho and E of every channel at every element: what the solves and the output
// writers need.
void fill_field(const Scene& scene, const RadiositySolver& solver, ElementField& field) {
  const Collocation& base = solver.collocation();
  const Index n = base.size();
  field.channels = scene.channels();
  field.triangle.resize(static_cast<std::size_t>(n));
  field.inner_normal.resize(static_cast<std::size_t>(n));
  field.centroid.resize(static_cast<std::size_t>(n));
  field.area.resize(static_cast<std::size_t>(n));
  field.facet.resize(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) {
    const geometry::Cluster& e = base.tree().elements()[static_cast<std::size_t>(i)];
    const auto k = static_cast<std::size_t>(i);
    field.triangle[k] = e.vertex;
    field.inner_normal[k] = e.normal;
    field.centroid[k] = base.collocation_point(i);
    field.area[k] = e.area;
    field.facet[k] = e.facet;
  }
  for (std::size_t c = 0; c < scene.num_channels(); ++c) {
    Collocation::ChannelValues v = solver.channel_values(c);
    field.rho.push_back(std::move(v.rho));
    field.emission.push_back(std::move(v.E));
  }
}

// Channels with the same rho, E and environment at every element have the same solution: solved
// once.
int identical_earlier_channel(const Scene& scene, const ElementField& field, std::size_t c) {
  for (std::size_t d = 0; d < c; ++d)
    if (field.rho[d] == field.rho[c] && field.emission[d] == field.emission[c] &&
        scene.environment(d) == scene.environment(c))
      return static_cast<int>(d);
  return -1;
}

// The energy balance of channel c: emitted power sum A_i E_i, the environment's power arriving
// sum A_i u_env s_i, absorbed power sum A_i (1 - rho_i) H_i, and, in a scene that is not closed,
// the power that reaches no front side. Of the light leaving dA_i a fraction H_ij (the
// point-to-element form factor) lands on element j, so 1 - (H 1)_i of it (`uncovered`, taken >= 0;
// null in a closed scene, where it is 0) leaves the scene or falls on a back side.
void energy_balance(const Scene& scene, const ElementField& field, std::size_t c, const Eigen::VectorXd* uncovered,
                    ChannelSolution& ch) {
  const Eigen::VectorXd& rho = field.rho[c];
  const Eigen::VectorXd& E = field.emission[c];
  const double environment = scene.sees_environment(c) ? scene.environment(c) : 0;
  double escaped = 0;
  for (Index i = 0; i < rho.size(); ++i) {
    const double a = field.area[static_cast<std::size_t>(i)];
    ch.emitted += a * E[i];
    ch.absorbed += a * (1 - rho[i]) * ch.irradiance[i];
    if (uncovered) {
      escaped += a * ch.radiosity[i] * (*uncovered)[i];
      ch.environment_in += a * environment * (*uncovered)[i];
    }
  }
  const double in = ch.emitted + ch.environment_in;
  ch.energy_mismatch = in != 0 ? std::abs(in - ch.absorbed - escaped) / std::abs(in) : 0;
  ch.escaped = in != 0 ? escaped / in : 0;
}

// What channel c needs before any solve: the solution of an identical earlier channel, or u = 0
// when it emits nothing; false when it is to be solved.
bool channel_without_solve(const Scene& scene, const SceneSolution& out, std::size_t c, ChannelSolution& ch,
                           const std::function<void(const std::string&)>& say) {
  const ElementField& field = out.field;
  ch.name = field.channels[c];
  if (const int same = identical_earlier_channel(scene, field, c); same >= 0) {
    ch.shared_with = out.channels[static_cast<std::size_t>(same)].name;  // its solution is copied once solved
    say("channel " + ch.name + ": same rho and E as channel " + ch.shared_with + ", solution shared");
    return true;
  }
  if (field.emission[c].lpNorm<Eigen::Infinity>() == 0 && !scene.sees_environment(c)) {
    ch.radiosity = Eigen::VectorXd::Zero(out.n);  // nothing emitted: u = 0 exactly
    ch.irradiance = Eigen::VectorXd::Zero(out.n);
    ch.solver = "none (E = 0 in this channel: u = 0)";
    return true;
  }
  return false;
}

// (I - diag(rho_c) H) u_c = E_c, (32), solved, and the energy balance.
void take_solve(ChannelSolve&& r, const Scene& scene, const ElementField& field, std::size_t c,
                const Eigen::VectorXd* uncovered, ChannelSolution& ch,
                const std::function<void(const std::string&)>& say) {
  ch.status = r.status;
  ch.message = std::move(r.message);
  ch.radiosity = std::move(r.u);
  ch.solver = std::move(r.solver);
  ch.iterations = r.iterations;
  ch.residual = r.residual;
  ch.error_estimate = r.error_estimate;
  ch.irradiance = std::move(r.irradiance);  // the light arriving: the product without rho
  energy_balance(scene, field, c, uncovered, ch);
  say("channel " + ch.name + ": " + ch.solver + fmt(", %.0f products, energy mismatch %.2e", ch.iterations, ch.energy_mismatch));
}

// The energy check's failure, for the warning and EnergyBalanceError.
std::string energy_check_message(const ChannelSolution& ch, double expected) {
  return "channel " + ch.name +
         fmt(": energy mismatch %.2e is far above its expected size %.2e (0.5 h/diam", ch.energy_mismatch, expected) +
         fmt("; at most %g times it is accepted): the solution breaks the conservation of energy and is not to be "
             "trusted; is the operator inaccurate?",
             kEnergyMismatchAllowance);
}

// What a channel's answer says beside its numbers.
void channel_warnings(const ChannelSolution& ch, SceneSolution& out) {
  if (!ch.shared_with.empty()) return;
  if (ch.status != SolveStatus::converged) out.warnings.push_back("channel " + ch.name + ": " + ch.message);
  if (!ch.energy_balanced) out.warnings.push_back(energy_check_message(ch, out.expected_energy_mismatch));
}

}  // namespace

SceneSolution solve_scene(const Scene& scene, const SolveOptions& options) {
  if (options.fold_reflectivity)
    throw std::invalid_argument("solve_scene: one operator H for every channel (fold_reflectivity must be false)");
  Stopwatch total;
  SolveOptions o = options;
  // Per element: the triangle, inner normal, centroid, area and facet of the output field, F = H 1
  // (a scene that is not closed), and per channel rho, E, radiosity (twice: solution and field) and
  // irradiance.
  o.result_bytes_per_element = sizeof(std::array<Vec3, 3>) + 2 * sizeof(Vec3) + sizeof(double) + sizeof(Index) +
                               (scene.closed() ? 0 : sizeof(double)) + scene.num_channels() * 5 * sizeof(double);
  const RadiositySolver solver(scene, o);
  SceneSolution out;
  copy_setup(solver, out);
  out.shape = scene.shape();
  out.closed = scene.closed();
  out.enclosed = scene.enclosed();
  const auto say = [&](const std::string& line) {
    if (options.progress) options.progress(line);
  };
  Stopwatch clock;
  try {
    fill_field(scene, solver, out.field);
  } catch (const std::bad_alloc&) {
    throw ResourceError(out_of_memory_message("storing the per-element results (element geometry, rho and E of each "
                                              "channel)", static_cast<double>(out.n), solver.info().memory.fields));
  }
  // Expected size of the energy mismatch: a discretization effect (point-to-element form factors
  // are not reciprocal), measured at most 0.35 h/diam on the cube, prisms and the tetrahedron at
  // levels 1-5 (tests/solve/test_scene_solver.cpp): 0.5 h/diam; the energy check fails above
  // kEnergyMismatchAllowance = 4 times that.
  out.expected_energy_mismatch = 0.5 * out.mesh_size / out.diameter;
  // Channels that share their solution with an earlier one, or emit nothing, need no solve; the
  // others are solved together (RadiositySolver::solve_channels: one pass over the operator per
  // Neumann step for all of them).
  std::vector<std::size_t> to_solve;
  for (std::size_t c = 0; c < scene.num_channels(); ++c) {
    ChannelSolution ch;
    if (!channel_without_solve(scene, out, c, ch, say)) to_solve.push_back(c);
    out.channels.push_back(std::move(ch));
  }
  std::vector<ChannelSolve> solves = solver.solve_channels(to_solve);
  // Outside a closed scene, 1 - H 1: the fraction of each point's light that reaches no front side.
  const Eigen::VectorXd* uncovered = !out.closed && !to_solve.empty() ? &solver.uncovered() : nullptr;
  for (std::size_t s = 0; s < to_solve.size(); ++s)
    take_solve(std::move(solves[s]), scene, out.field, to_solve[s], uncovered, out.channels[to_solve[s]], say);
  for (std::size_t c = 0; c < scene.num_channels(); ++c) {
    ChannelSolution& ch = out.channels[c];
    if (!ch.shared_with.empty()) {  // copy the solution of the channel it shares (solved above)
      const std::string name = ch.name, shared = ch.shared_with;
      const int same = identical_earlier_channel(scene, out.field, c);
      ch = out.channels[static_cast<std::size_t>(same)];
      ch.name = name;
      ch.shared_with = shared;
    }
    ch.energy_balanced = energy_balance_holds(ch.energy_mismatch, out.expected_energy_mismatch);
    out.energy_balanced = out.energy_balanced && ch.energy_balanced;
    channel_warnings(ch, out);
  }
  out.solve_s = clock.seconds();
  for (const ChannelSolution& ch : out.channels) out.field.radiosity.push_back(ch.radiosity);
  out.peak_rss_mb = peak_rss_mb();
  out.total_s = total.seconds();
  return out;
}

bool SceneSolution::converged() const {
  return std::all_of(channels.begin(), channels.end(), [](const ChannelSolution& ch) { return ch.converged(); });
}

void SceneSolution::require_converged() const {
  for (const ChannelSolution& ch : channels) ch.require_converged();
}

void SceneSolution::require_energy_balance() const {
  for (const ChannelSolution& ch : channels)
    if (!ch.energy_balanced) throw EnergyBalanceError(energy_check_message(ch, expected_energy_mismatch));
}

bool energy_balance_holds(double mismatch, double expected) { return mismatch <= kEnergyMismatchAllowance * expected; }

}  // namespace panelrad

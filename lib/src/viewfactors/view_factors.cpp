// View factors between groups of surfaces by block products of H (view_factors.hpp).
#include <panelrad/viewfactors/view_factors.hpp>

#include <panelrad/operator/auto_parameters.hpp>
#include <panelrad/support/resources.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <stdexcept>

namespace panelrad {

using geometry::Index;

namespace {

/// The factors of one level: F(I, J) and A_I, from the solver's H.
struct LevelFactors {
  Eigen::MatrixXd F;
  Eigen::VectorXd area;
  int level = 0;
  Index n = 0;
  std::string method;
  double self_check_error = -1;
  ElementSky elements;  // with `keep_elements`
};

/// What the finest level keeps per element: nothing (`keep` false), or the sky and the factors to
/// `targets` (group indices, in the order of their names).
struct ElementRequest {
  bool keep = false;
  std::vector<Index> targets;
  std::vector<std::string> names;
};

/// The group index of every name of `options.element_targets` (std::invalid_argument naming one
/// that is no group, or one given twice).
ElementRequest element_request(const SurfaceGroups& groups, const ViewFactorOptions& options) {
  ElementRequest r;
  r.keep = options.elements || !options.element_targets.empty();
  for (const std::string& name : options.element_targets) {
    const auto it = std::find(groups.names.begin(), groups.names.end(), name);
    if (it == groups.names.end())
      throw std::invalid_argument("view factors: element target '" + name + "' is not a group (the groups are " +
                                  std::to_string(groups.names.size()) + ": '" + groups.names.front() + "'" +
                                  (groups.names.size() > 1 ? ", ..." : "") + ")");
    if (std::find(r.names.begin(), r.names.end(), name) != r.names.end())
      throw std::invalid_argument("view factors: element target '" + name + "' is given twice");
    r.targets.push_back(static_cast<Index>(it - groups.names.begin()));
    r.names.push_back(name);
  }
  return r;
}

/// The elements' record: geometry, group, sky = 1 - covered.
ElementSky element_record(const Collocation& col, const std::vector<Index>& group, const Eigen::VectorXd& area,
                          const Eigen::VectorXd& covered) {
  ElementSky e;
  e.group = group;
  e.area = area;
  e.sky = Eigen::VectorXd::Ones(area.size()) - covered;
  for (Index i = 0; i < area.size(); ++i) {
    e.facet.push_back(col.facet(i));
    e.triangle.push_back(col.tree().elements()[static_cast<std::size_t>(i)].vertex);
    e.centroid.push_back(col.collocation_point(i));
  }
  return e;
}

LevelFactors factors_at(const Scene& scene, const SurfaceGroups& groups, const SolveOptions& solve, int block_columns,
                        const ElementRequest& keep) {
  const bool keep_elements = keep.keep;
  const RadiositySolver solver(scene, solve);
  const Collocation& col = solver.collocation();
  const Index n = col.size();
  const Index G = static_cast<Index>(groups.names.size());
  LevelFactors out;
  out.level = solver.level();
  out.n = n;
  out.method = describe_parameters(solver.parameters());
  if (solver.self_check()) out.self_check_error = solver.self_check()->relative_error;
  std::vector<Index> group(static_cast<std::size_t>(n));
  Eigen::VectorXd a(n);
  out.area = Eigen::VectorXd::Zero(G);
  for (Index i = 0; i < n; ++i) {
    group[static_cast<std::size_t>(i)] = groups.of_facet[static_cast<std::size_t>(col.facet(i))];
    a[i] = col.tree().elements()[static_cast<std::size_t>(i)].area;
    out.area[group[static_cast<std::size_t>(i)]] += a[i];
  }
  out.F = Eigen::MatrixXd::Zero(G, G);
  Eigen::VectorXd covered;  // (H 1)_i, summed over the groups' columns in group order
  if (keep_elements) covered = Eigen::VectorXd::Zero(n);
  Eigen::MatrixXd to = Eigen::MatrixXd::Zero(keep_elements ? n : 0, static_cast<Index>(keep.targets.size()));
  Eigen::MatrixXd X, Y;
  for (Index first = 0; first < G; first += block_columns) {
    const Index m = std::min<Index>(block_columns, G - first);
    X = Eigen::MatrixXd::Zero(n, m);
    for (Index i = 0; i < n; ++i) {
      const Index J = group[static_cast<std::size_t>(i)];
      if (J >= first && J < first + m) X(i, J - first) = 1;
    }
    solver.op().apply_block(X, Y);
    // Sums in element order, one column at a time: the same for any thread count.
    for (Index c = 0; c < m; ++c)
      for (Index i = 0; i < n; ++i) out.F(group[static_cast<std::size_t>(i)], first + c) += a[i] * Y(i, c);
    if (keep_elements)
      for (Index c = 0; c < m; ++c) covered += Y.col(c);
    for (std::size_t k = 0; k < keep.targets.size(); ++k)
      if (keep.targets[k] >= first && keep.targets[k] < first + m)
        to.col(static_cast<Index>(k)) = Y.col(keep.targets[k] - first);
  }
  if (keep_elements) {
    out.elements = element_record(col, group, a, covered);
    out.elements.target_names = keep.names;
    out.elements.to = std::move(to);
  }
  for (Index I = 0; I < G; ++I) out.F.row(I) /= out.area[I];
  return out;
}

}  // namespace

SurfaceGroups groups_by_facet(const Scene& scene) {
  SurfaceGroups g;
  for (Index f = 0; f < scene.num_facets(); ++f) {
    g.names.push_back("facet " + std::to_string(f));
    g.of_facet.push_back(f);
  }
  return g;
}

SurfaceGroups groups_by_name(const std::vector<std::string>& per_facet) {
  SurfaceGroups g;
  std::map<std::string, Index> index;
  for (const std::string& m : per_facet) {
    const std::string name = m.empty() ? "default" : m;
    const auto [it, added] = index.try_emplace(name, static_cast<Index>(g.names.size()));
    if (added) g.names.push_back(name);
    g.of_facet.push_back(it->second);
  }
  return g;
}

SurfaceGroups groups_by_material(const Scene& scene) {
  if (scene.facet_material().empty())
    throw std::invalid_argument("groups by material: the scene has no materials (an OBJ's usemtl); group by facet instead");
  return groups_by_name(scene.facet_material());
}

SurfaceGroups groups_by_object(const Scene& scene) {
  if (scene.mesh().facet_group.empty())
    throw std::invalid_argument("groups by object: the file names no object (an OBJ's o or g, an ASCII STL's solid); "
                                "group by facet instead");
  return groups_by_name(scene.mesh().facet_group);
}

std::string groups_problem(const Scene& scene, const SurfaceGroups& groups) {
  if (static_cast<Index>(groups.of_facet.size()) != scene.num_facets())
    return "groups: " + std::to_string(groups.of_facet.size()) + " facets given a group, the scene has " +
           std::to_string(scene.num_facets());
  if (groups.names.empty()) return "groups: none given";
  const Index G = static_cast<Index>(groups.names.size());
  std::set<std::string> seen;
  for (const std::string& name : groups.names) {
    if (name.empty()) return "groups: a group has an empty name";
    if (!seen.insert(name).second) return "groups: the name '" + name + "' is given twice";
  }
  std::vector<char> used(static_cast<std::size_t>(G), 0);
  for (std::size_t f = 0; f < groups.of_facet.size(); ++f) {
    const Index g = groups.of_facet[f];
    if (g < 0 || g >= G)
      return "groups: facet " + std::to_string(f) + " is in group " + std::to_string(g) + ", not in [0, " +
             std::to_string(G) + ")";
    used[static_cast<std::size_t>(g)] = 1;
  }
  for (Index g = 0; g < G; ++g)
    if (!used[static_cast<std::size_t>(g)]) return "groups: '" + groups.names[static_cast<std::size_t>(g)] + "' has no facet";
  return "";
}

Eigen::MatrixXd reciprocal_and_closed(const Eigen::MatrixXd& F, const Eigen::VectorXd& area, bool enclosed) {
  const Index G = F.rows();
  if (F.cols() != G || area.size() != G)
    throw std::invalid_argument("reciprocal_and_closed: F (" + std::to_string(F.rows()) + " x " +
                                std::to_string(F.cols()) + ") and the areas (" + std::to_string(area.size()) +
                                ") differ in size");
  if (!(F.array() >= 0).all() || !(area.array() >= 0).all())
    throw std::invalid_argument("reciprocal_and_closed: F and the areas must be finite and >= 0");
  const Eigen::MatrixXd AF = area.asDiagonal() * F;
  const Eigen::MatrixXd S = 0.5 * (AF + AF.transpose());
  const Eigen::VectorXd& target = area;
  Eigen::VectorXd d = Eigen::VectorXd::Ones(G);
  for (int sweep = 0; enclosed; ++sweep) {
    const Eigen::VectorXd Sd = S * d;
    double residual = 0;
    for (Index I = 0; I < G; ++I) {
      if (!(Sd[I] > 0) || !(target[I] > 0)) continue;  // exchanges nothing: the row stays 0
      residual = std::max(residual, std::abs(d[I] * Sd[I] - target[I]) / target[I]);
    }
    if (residual <= 1e-13) break;
    if (sweep == 10000)
      throw std::runtime_error("reciprocal_and_closed: the balance did not converge (residual " +
                               std::to_string(residual) + " after 10,000 sweeps)");
    for (Index I = 0; I < G; ++I)
      if (Sd[I] > 0 && target[I] > 0) d[I] = std::sqrt(d[I] * target[I] / Sd[I]);
  }
  Eigen::MatrixXd out = d.asDiagonal() * S * d.asDiagonal();
  for (Index I = 0; I < G; ++I) out.row(I) /= area[I];
  return out;
}

ViewFactors compute_view_factors(const Scene& scene, const SurfaceGroups& groups, const ViewFactorOptions& options) {
  if (const std::string why = groups_problem(scene, groups); !why.empty()) throw std::invalid_argument(why);
  if (options.block_columns < 1)
    throw std::invalid_argument("view factors: block_columns " + std::to_string(options.block_columns) + " is not >= 1");
  if (options.solve.communicator)
    throw std::invalid_argument("view factors: one process only (the solver's communicator is set)");
  const ElementRequest keep = element_request(groups, options);
  Stopwatch clock;
  LevelFactors fine = factors_at(scene, groups, options.solve, options.block_columns, keep);
  ViewFactors v;
  v.names = groups.names;
  v.area = fine.area;
  v.F = fine.F;
  v.enclosed = scene.enclosed();
  v.uncovered = Eigen::VectorXd::Ones(fine.F.rows()) - fine.F.rowwise().sum();
  v.level = fine.level;
  v.n = fine.n;
  v.method = fine.method;
  v.self_check_error = fine.self_check_error;
  v.elements = std::move(fine.elements);
  if (options.estimate_error && fine.level >= 1) {
    SolveOptions coarser = options.solve;
    coarser.level = fine.level - 1;
    const LevelFactors c = factors_at(scene, groups, coarser, options.block_columns, ElementRequest{});
    v.error = (fine.F - c.F).cwiseAbs();
    v.uncovered_error = (v.uncovered - (Eigen::VectorXd::Ones(c.F.rows()) - c.F.rowwise().sum())).cwiseAbs();
  }
  if (options.reciprocal) {
    const Eigen::MatrixXd balanced = reciprocal_and_closed(v.F.cwiseMax(0.0), v.area, v.enclosed);
    v.correction = (balanced - v.F).cwiseAbs().maxCoeff();
    v.F = balanced;
    v.uncovered = Eigen::VectorXd::Ones(v.F.rows()) - v.F.rowwise().sum();
  }
  const Index G = static_cast<Index>(v.names.size());
  for (Index I = 0; I < G; ++I)
    for (Index J = I + 1; J < G; ++J) {
      const double a = v.area[I] * v.F(I, J), b = v.area[J] * v.F(J, I);
      const double larger = std::max(std::abs(a), std::abs(b));
      if (!(larger > 0)) continue;
      const double defect = std::abs(a - b) / larger;
      if (defect > v.reciprocity_defect || v.reciprocity_I < 0) {
        v.reciprocity_defect = defect;
        v.reciprocity_I = I;
        v.reciprocity_J = J;
      }
    }
  v.seconds = clock.seconds();
  return v;
}

}  // namespace panelrad

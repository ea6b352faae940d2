#include <panelrad/operator/auto_parameters.hpp>

#include <panelrad/geometry/bounding_box.hpp>
#include <panelrad/geometry/cluster_tree.hpp>
#include <panelrad/operator/far_field.hpp>
#include <panelrad/support/error.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace panelrad {

namespace {
// h / diam of the paper cube at level 0: longest edge sqrt(2) (a face diagonal) over the
// bounding-box diagonal sqrt(3).
const double kCubeRelativeH0 = std::sqrt(2.0 / 3.0);
// Largest n solved densely by the automatic rule whatever the work ratio (see the header).
constexpr geometry::Index kDenseMaxN = 768;
// Far pairs per row that the refinement below the roots adds, times eta^2: 19.5 (cube, 12 roots,
// eta 0.4: 134 per row at n = 3072), 19.3 (cube, eta 0.5: 89 per row at n = 12288).
constexpr double kRefinedFarPairsTimesEta2 = 20;
// The dense matrix from this estimated fast-to-dense work ratio W on (header: between 9.7, where
// the fast method was faster, and 12.2 and 12.35, where the dense matrix took the same time in a
// fifth of the memory).
constexpr double kDenseFromWorkRatio = 11;
// Rows of roots sampled for the facing fraction.
constexpr std::size_t kFacingSampleRows = 256;

/// ProblemSize::facing of `mesh`: over min(n0, 256) evenly spaced roots i and every other root j,
/// the fraction of pairs whose centroids lie strictly on each other's front side (the side of the
/// inner normal -(b - a) x (c - a) of a validated mesh).
double facing_fraction(const geometry::TriangleMesh& mesh) {
  const std::size_t n0 = mesh.triangles.size();
  if (n0 < 2) return 1;  // no pair to count: nothing known
  std::vector<geometry::Vec3> centre(n0), front(n0);
  for (std::size_t t = 0; t < n0; ++t) {
    const auto& tr = mesh.triangles[t];
    const geometry::Vec3& a = mesh.vertices[static_cast<std::size_t>(tr[0])];
    const geometry::Vec3& b = mesh.vertices[static_cast<std::size_t>(tr[1])];
    const geometry::Vec3& c = mesh.vertices[static_cast<std::size_t>(tr[2])];
    centre[t] = (a + b + c) / 3;
    front[t] = -(b - a).cross(c - a);
  }
  const std::size_t rows = std::min(n0, kFacingSampleRows);
  std::size_t facing = 0;
  for (std::size_t k = 0; k < rows; ++k) {
    const std::size_t i = k * n0 / rows;
    for (std::size_t j = 0; j < n0; ++j) {
      const geometry::Vec3 d = centre[j] - centre[i];
      facing += j != i && d.dot(front[i]) > 0 && d.dot(front[j]) < 0;
    }
  }
  return static_cast<double>(facing) / (static_cast<double>(rows) * static_cast<double>(n0 - 1));
}
// The cube's discretization error relative to ||u||_inf per unit h/diam (Table 1: 3.77e-3 / 3
// at h/diam 0.0510, 1.92e-3 / 3 at 0.0255).
constexpr double kDiscretizationErrorPerRelativeH = 0.025;
// The eta ladder of the sweep, loosest first.
constexpr double kEtaLadder[] = {0.5, 0.3, 0.2, 0.1};
}  // namespace

double ProblemSize::equivalent_level() const { return std::log2(kCubeRelativeH0 * diameter / mesh_size); }

ProblemSize problem_size(const geometry::TriangleMesh& mesh, int level) {
  if (level < 0) throw std::invalid_argument("problem_size: level must be >= 0, got " + std::to_string(level));
  if (mesh.triangles.empty()) throw std::invalid_argument("problem_size: empty mesh '" + mesh.source + "'");
  if (mesh.triangles.size() > static_cast<std::size_t>(std::numeric_limits<geometry::Index>::max()))
    throw ResourceError(mesh.source + ": " + std::to_string(mesh.triangles.size()) +
                        " triangles, more than 32-bit indices can number");
  ProblemSize s;
  s.roots = static_cast<geometry::Index>(mesh.triangles.size());
  if (const std::string problem = geometry::level_size_problem(s.roots, level); !problem.empty())
    throw ResourceError(mesh.source + ": " + problem);
  s.n = s.roots << (2 * level);
  double longest = 0;
  for (const auto& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) {
      const auto a = static_cast<std::size_t>(t[static_cast<std::size_t>(k)]);
      const auto b = static_cast<std::size_t>(t[static_cast<std::size_t>((k + 1) % 3)]);
      if (a >= mesh.vertices.size() || b >= mesh.vertices.size())
        throw std::invalid_argument("problem_size: vertex index out of range in '" + mesh.source + "'");
      longest = std::max(longest, (mesh.vertices[a] - mesh.vertices[b]).norm());
    }
  s.mesh_size = std::ldexp(longest, -level);  // midpoint subdivision halves every edge
  s.diameter = geometry::bounding_box_diameter(mesh.vertices);
  s.facing = facing_fraction(mesh);
  return s;
}

double conditioning_factor(double rho_max) {
  if (!(rho_max >= 0 && rho_max < 1))
    throw std::invalid_argument("conditioning_factor: rho_max = " + std::to_string(rho_max) +
                                " is outside [0, 1) (the radiosity equation needs rho < 1)");
  return std::max(1.0, rho_max / (1 - rho_max));  // ||(I-K)^-1|| ||K|| <= rho_max/(1-rho_max), (11)
}

OperatorOptions choose_parameters(const ProblemSize& size, double margin, double rho_max, Visibility visibility) {
  if (!(margin >= 0.05) || !std::isfinite(margin))
    throw std::invalid_argument("choose_parameters: margin " + std::to_string(margin) +
                                " is below the measured 5% (use explicit parameters for a tighter target)");
  if (size.n <= 0) throw std::invalid_argument("choose_parameters: n must be positive");
  if (!(size.mesh_size > 0) || !(size.diameter > 0) || !std::isfinite(size.mesh_size) ||
      !std::isfinite(size.diameter) || size.mesh_size > size.diameter)
    throw std::invalid_argument("choose_parameters: need 0 < h <= diameter, both finite");
  if (size.roots < 1 || size.roots > size.n)
    throw std::invalid_argument("choose_parameters: need 1 <= roots <= n, got " + std::to_string(size.roots) +
                                " roots for n = " + std::to_string(size.n));
  if (!(size.facing >= 0 && size.facing <= 1))
    throw std::invalid_argument("choose_parameters: the facing fraction must be in [0, 1]");
  if (visibility != Visibility::unoccluded && visibility != Visibility::occluded)
    throw std::invalid_argument("choose_parameters: visibility must be resolved (unoccluded or occluded)");
  const double amplification = conditioning_factor(rho_max);  // validates rho_max for every n
  OperatorOptions dense;
  dense.near.rule = NearRule::exact;  // no mu to tune; never the limiting error (header)
  if (size.n <= kDenseMaxN) return dense;
  OperatorOptions o = dense;
  o.method = OperatorMethod::fast;
  // delta* halves per level and shrinks by the amplification: a target log2 A levels finer.
  const double lambda = size.equivalent_level() + std::log2(amplification) - std::log2(margin / 0.05);
  // Each setting while its self-check on the cube (header) stays below delta* = 1.02e-3 2^-lambda.
  if (lambda < 2.5) {  // check 1.5e-4 (worst: cos 7x + sin(5y) z)
    o.eta = 0.5;
    o.degree = 6;
  } else if (lambda < 5.5) {  // check 2.2e-5; deviation 1.3e-5 (cube n = 3072), 3.0e-5 (prism 5120)
    o.eta = 0.4;
    o.degree = 6;
  } else if (lambda < 7.5) {  // check 4.1e-6; deviation 1.8e-6 (cube), 4.0e-6 (prism)
    o.eta = 0.4;
    o.degree = 8;
  } else if (lambda < 10.5) {  // check 3.2e-7; deviation 2.0e-7 (cube n = 3072)
    o.eta = 0.4;
    o.degree = 10;
  } else {  // check 3.8e-8; deviation 3.1e-8 (cube n = 3072); the self-check tightens eta beyond
    o.eta = 0.4;
    o.degree = 12;
  }
  // The far field no cheaper than the matrix: few elements per root cluster (header, W >= 11).
  if (fast_to_dense_work(size, o.eta, o.degree, visibility) >= kDenseFromWorkRatio) return dense;
  return o;
}

double fast_to_dense_work(const ProblemSize& size, double eta, int degree, Visibility visibility) {
  if (size.n <= 0 || size.roots < 1 || size.roots > size.n)
    throw std::invalid_argument("fast_to_dense_work: need 1 <= roots <= n");
  if (!(eta > 0 && eta < 1) || degree < 0)
    throw std::invalid_argument("fast_to_dense_work: need 0 < eta < 1 and M >= 0");
  if (!(size.facing >= 0 && size.facing <= 1))
    throw std::invalid_argument("fast_to_dense_work: the facing fraction must be in [0, 1]");
  if (visibility != Visibility::unoccluded && visibility != Visibility::occluded)
    throw std::invalid_argument("fast_to_dense_work: visibility must be resolved (unoccluded or occluded)");
  const double n = static_cast<double>(size.n);
  const double far_pairs = std::min(n, static_cast<double>(size.roots) + kRefinedFarPairsTimesEta2 / (eta * eta));
  // V = 1 on a convex surface: every pair interacts. With V, a pair of roots that do not face
  // each other is hidden, and so is every pair of their elements.
  const double seen = visibility == Visibility::occluded ? size.facing : 1.0;
  return seen * far_pairs * num_taylor_terms(degree) / n;
}

double self_check_threshold(const ProblemSize& size, double rho_max, double margin) {
  if (!(size.mesh_size > 0) || !(size.diameter > 0))
    throw std::invalid_argument("self_check_threshold: mesh size and diameter must be positive");
  if (!(margin >= 0.05) || !std::isfinite(margin))
    throw std::invalid_argument("self_check_threshold: margin " + std::to_string(margin) + " is below the measured 5%");
  // margin (5%) of the discretization error scale 0.025 h/diam (Table 1), over the amplification.
  return margin * kDiscretizationErrorPerRelativeH * size.mesh_size / size.diameter / conditioning_factor(rho_max);
}

OperatorOptions tighten_parameters(const OperatorOptions& options) {
  OperatorOptions o = options;
  if (o.method != OperatorMethod::fast) return o;
  if (o.degree < 6) {
    ++o.degree;
    return o;
  }
  for (double eta : kEtaLadder)
    if (eta < o.eta - 1e-12) {
      o.eta = eta;
      return o;
    }
  return o;
}

std::vector<OperatorOptions> stricter_settings(const OperatorOptions& options) {
  std::vector<OperatorOptions> out;
  if (options.method != OperatorMethod::fast) return out;
  std::vector<double> etas = {options.eta};
  for (double eta : kEtaLadder)
    if (eta < options.eta - 1e-12 && etas.size() < 3) etas.push_back(eta);
  for (const double eta : etas)
    for (int degree = std::max(1, options.degree - 2); degree <= std::min(12, options.degree + 2); ++degree) {
      if (eta == options.eta && degree <= options.degree) continue;
      OperatorOptions o = options;
      o.eta = eta;
      o.degree = degree;
      out.push_back(o);
    }
  return out;
}

std::string describe_parameters(const OperatorOptions& o) {
  std::ostringstream os;
  os << to_string(o.method) << ", " << to_string(o.near.rule) << " near field";
  if (o.near.rule == NearRule::quadrature) os << " (mu " << o.near.mu << ")";
  if (o.method == OperatorMethod::fast) os << ", eta " << o.eta << ", M " << o.degree;
  return os.str();
}

}  // namespace panelrad

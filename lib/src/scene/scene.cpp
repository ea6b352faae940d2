#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/validation.hpp>
#include <panelrad/quadrature/singular_integration.hpp>
#include <panelrad/scene/scene.hpp>

#include <algorithm>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace panelrad {

namespace {

/// Shortest round-trip text of a number (inf, nan as such).
std::string number(double v) {
  char buf[40];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return ec == std::errc() ? std::string(buf, ptr) : std::to_string(v);
}

std::string point_name(const Vec3& P, Index f) {
  std::ostringstream os;
  os << "point (" << P.x() << ", " << P.y() << ", " << P.z() << ") of facet " << f;
  return os.str();
}

void check_size(std::size_t got, Index facets, const char* what, const std::string& channel) {
  if (got != static_cast<std::size_t>(facets)) {
    std::ostringstream os;
    os << what << " of channel " << channel << ": " << got << " values given for " << facets << " facets";
    throw std::invalid_argument(os.str());
  }
}

}  // namespace

std::string reflectivity_problem(double rho) {
  if (!std::isfinite(rho)) return "is not a finite number";
  if (!(rho >= 0.0 && rho < 1.0)) return "is outside [0, 1) (paper (7): 0 <= rho < 1)";
  if (rho > 0.0 && rho < DBL_MIN)
    return "is subnormal (below DBL_MIN = " + number(DBL_MIN) +
           "): it has lost precision and makes the solve compute with subnormal numbers; write 0";
  return "";
}

std::string emission_problem(double e) {
  if (!std::isfinite(e)) return "is not a finite number";
  if (e < 0.0) return "is negative (emission E must be >= 0)";
  if (e > 0.0 && e < DBL_MIN)
    return "is subnormal (below DBL_MIN = " + number(DBL_MIN) +
           "): it has lost precision already and the solve would lose the rest; scale all E up (the radiosity "
           "equation is linear in E) or write 0";
  if (e > 0.0 && e < kMinPositiveEmission)
    return "is below " + number(kMinPositiveEmission) +
           ", the smallest non-zero E accepted (products with areas and squared norms in the solve would "
           "underflow); scale all E up (the radiosity equation is linear in E) or write 0";
  if (e > kMaxEmission)
    return "is above " + number(kMaxEmission) +
           ", the largest E accepted (the radiosity u <= E / (1 - rho) and its squares and products with areas "
           "in the solve would overflow); scale all E down (the radiosity equation is linear in E)";
  return "";
}

namespace {

// The one place a value is refused: "reflectivity rho = 1 of facet 3, channel R, is outside
// [0, 1) (paper (7): 0 <= rho < 1)".
void check_value(bool is_rho, double v, const std::string& where, const std::string& channel) {
  const std::string problem = is_rho ? reflectivity_problem(v) : emission_problem(v);
  if (problem.empty()) return;
  throw std::invalid_argument(std::string(is_rho ? "reflectivity rho = " : "emission E = ") + number(v) + " of " +
                              where + ", channel " + channel + ", " + problem);
}

}  // namespace

Scene::Validated Scene::validate(geometry::TriangleMesh mesh) {
  std::vector<std::string> notes;
  geometry::ValidatedMesh v = geometry::validate_mesh(std::move(mesh), &notes);
  return {std::move(v), std::move(notes)};
}

Scene::Scene(geometry::TriangleMesh mesh, std::vector<std::string> channels)
    : Scene(validate(std::move(mesh)), std::move(channels)) {}

Scene::Scene(Validated validated, std::vector<std::string> channels)
    : Scene(std::move(validated.mesh), std::move(channels)) {
  notes_ = std::move(validated.notes);
}

Scene::Scene(geometry::ValidatedMesh mesh, std::vector<std::string> channels)
    : shape_(mesh.shape()),
      mesh_(std::move(mesh).take_mesh()),
      channels_(std::move(channels)),
      closed_(mesh.closed()),
      enclosed_(mesh.enclosed()) {
  if (mesh_.triangles.empty()) throw std::invalid_argument("scene: empty mesh");
  if (channels_.empty()) throw std::invalid_argument("scene: no channels");
  for (std::size_t c = 0; c < channels_.size(); ++c) {
    if (channels_[c].empty()) throw std::invalid_argument("scene: channel " + std::to_string(c) + " has no name");
    for (std::size_t d = 0; d < c; ++d)
      if (channels_[d] == channels_[c]) throw std::invalid_argument("scene: channel '" + channels_[c] + "' is named twice");
  }
  data_.resize(channels_.size());
  for (Channel& ch : data_) {  // nothing reflects and nothing emits until given
    ch.rho_facet.assign(static_cast<std::size_t>(mesh_.num_facets), 0.0);
    ch.e_facet.assign(static_cast<std::size_t>(mesh_.num_facets), 0.0);
  }
}

const Scene::Channel& Scene::channel(std::size_t c) const {
  if (c >= data_.size())
    throw std::out_of_range("scene: there is no channel " + std::to_string(c) + "; the scene has " +
                            std::to_string(data_.size()) + " (0 to " + std::to_string(data_.size() - 1) + ")");
  return data_[c];
}

Scene::Channel& Scene::channel(std::size_t c) { return const_cast<Channel&>(std::as_const(*this).channel(c)); }

Vec3 Scene::triangle_inner_normal(Index t) const {
  const auto& tri = mesh_.triangles[static_cast<std::size_t>(t)];
  const Vec3& a = mesh_.vertices[static_cast<std::size_t>(tri[0])];
  const Vec3& b = mesh_.vertices[static_cast<std::size_t>(tri[1])];
  const Vec3& c = mesh_.vertices[static_cast<std::size_t>(tri[2])];
  return -(b - a).cross(c - a).normalized();  // outward CCW orientation -> inner normal
}

void Scene::set_reflectivity(double rho, std::size_t c) {
  set_reflectivity(std::vector<double>(static_cast<std::size_t>(mesh_.num_facets), rho), c);
}

void Scene::set_reflectivity(std::vector<double> per_facet, std::size_t c) {
  Channel& ch = channel(c);
  check_size(per_facet.size(), mesh_.num_facets, "reflectivity", channels_[c]);
  for (std::size_t f = 0; f < per_facet.size(); ++f) check_value(true, per_facet[f], "facet " + std::to_string(f), channels_[c]);
  ch.rho_fn = nullptr;
  ch.rho_facet = std::move(per_facet);
}

void Scene::set_reflectivity(SurfaceFunction rho, std::size_t c) {
  Channel& ch = channel(c);
  if (!rho) throw std::invalid_argument("reflectivity of channel " + channels_[c] + ": empty function");
  ch.rho_fn = std::move(rho);
  ch.rho_facet.clear();
}

void Scene::set_emissivity(double e, std::size_t c) {
  set_emissivity(std::vector<double>(static_cast<std::size_t>(mesh_.num_facets), e), c);
}

void Scene::set_emissivity(std::vector<double> per_facet, std::size_t c) {
  Channel& ch = channel(c);
  check_size(per_facet.size(), mesh_.num_facets, "emission", channels_[c]);
  for (std::size_t f = 0; f < per_facet.size(); ++f) check_value(false, per_facet[f], "facet " + std::to_string(f), channels_[c]);
  ch.e_fn = nullptr;
  solution_ = nullptr;
  ch.e_facet = std::move(per_facet);
}

void Scene::set_emissivity(SurfaceFunction e, std::size_t c) {
  Channel& ch = channel(c);
  if (!e) throw std::invalid_argument("emission of channel " + channels_[c] + ": empty function");
  solution_ = nullptr;
  ch.e_fn = std::move(e);
  ch.e_facet.clear();
}

void Scene::set_environment(double radiosity, std::size_t c) {
  Channel& ch = channel(c);
  check_value(false, radiosity, "the environment", channels_[c]);
  ch.environment = radiosity;
}

double Scene::environment(std::size_t c) const { return channel(c).environment; }

bool Scene::sees_environment(std::size_t c) const { return channel(c).environment > 0 && !enclosed_; }

void Scene::set_manufactured_solution(SurfaceFunction u, double rel_tol) {
  if (channels_.size() != 1)
    throw std::logic_error("manufactured solution: a scalar scene (one channel) only, this one has " +
                           std::to_string(channels_.size()));
  if (shape_ != geometry::SceneShape::convex)
    throw std::logic_error("manufactured solution: E = u - K u is integrated with V = 1, exact on a convex scene "
                           "only; this scene is general (its visibility is computed)");
  if (!u) throw std::invalid_argument("manufactured solution: empty function");
  if (!(rel_tol > 0 && rel_tol < 1)) throw std::invalid_argument("manufactured solution: rel_tol must be in (0,1)");
  solution_ = std::move(u);
  solution_tol_ = rel_tol;
}

double Scene::reflectivity(const Vec3& P, Index facet, std::size_t c) const {
  const Channel& ch = channel(c);
  if (!ch.rho_fn) return ch.rho_facet[static_cast<std::size_t>(facet)];
  const double rho = ch.rho_fn(P, facet);
  check_value(true, rho, point_name(P, facet), channels_[c]);
  return rho;
}

double Scene::emissivity(const Vec3& P, Index facet, std::size_t c) const {
  const Channel& ch = channel(c);
  if (!ch.e_fn) return ch.e_facet[static_cast<std::size_t>(facet)];
  const double e = ch.e_fn(P, facet);
  check_value(false, e, point_name(P, facet), channels_[c]);
  return e;
}

const std::vector<double>& Scene::facet_reflectivity(std::size_t c) const { return channel(c).rho_facet; }
const std::vector<double>& Scene::facet_emissivity(std::size_t c) const { return channel(c).e_facet; }

void Scene::set_facet_material(std::vector<std::string> per_facet) {
  if (!per_facet.empty() && per_facet.size() != static_cast<std::size_t>(mesh_.num_facets))
    throw std::invalid_argument("facet materials: " + std::to_string(per_facet.size()) + " names for " +
                                std::to_string(mesh_.num_facets) + " facets");
  facet_material_ = std::move(per_facet);
}

double Scene::manufactured_emissivity(const Vec3& P, Index facet, const Vec3& nP) const {
  if (!solution_) throw std::logic_error("manufactured_emissivity: no manufactured solution set");
  const double u = solution_(P, facet);
  if (!std::isfinite(u))
    throw std::invalid_argument("manufactured solution = " + number(u) + " at " + point_name(P, facet) + " is not finite");
  const double rho = reflectivity(P, facet);
  if (rho == 0) return u;
  // (1/pi) Int_S u G dS over the exact surface. The triangles of P's own facet are coplanar with
  // P and contribute 0 (section 4.2, case (a)); a triangle of another facet that is coplanar
  // with P only up to the rounding of the coordinates (a slanted rectangle given as two
  // triangles) is integrated and gives a value at the rounding level (integrate_kernel_times).
  // Where u is quadratic on a facet, the facet is integrated at once over its boundary with the
  // radial integral in closed form (integrate_kernel_times_quadratic_facet); other facets
  // triangle by triangle, in the triangles' order.
  const SurfaceFunction& sol = solution_;
  std::vector<Index> facets;              // the other facets, by their first triangle
  std::vector<std::size_t> first_triangle;  // whose inner normal is the facet's
  std::vector<std::vector<std::array<Index, 3>>> facet_triangles;
  std::vector<std::size_t> slot(mesh_.triangles.size());
  {
    std::vector<std::size_t> facet_slot(static_cast<std::size_t>(num_facets()), mesh_.triangles.size());
    for (std::size_t t = 0; t < mesh_.triangles.size(); ++t) {
      const Index ft = mesh_.facet_of_triangle[t];
      if (ft == facet) continue;
      std::size_t& k = facet_slot[static_cast<std::size_t>(ft)];
      if (k == mesh_.triangles.size()) {
        k = facets.size();
        facets.push_back(ft);
        first_triangle.push_back(t);
        facet_triangles.emplace_back();
      }
      facet_triangles[k].push_back(mesh_.triangles[t]);
      slot[t] = k;
    }
  }
  std::vector<std::optional<double>> facet_Ku(facets.size());
  for (std::size_t k = 0; k < facets.size(); ++k) {
    const Index ft = facets[k];
    const auto f = [&sol, ft](const Vec3& Q) { return sol(Q, ft); };
    try {
      const auto r = quadrature::integrate_kernel_times_quadratic_facet(
          f, P, nP, mesh_.vertices, facet_triangles[k],
          triangle_inner_normal(static_cast<Index>(first_triangle[k])), solution_tol_);
      if (r) facet_Ku[k] = r->value;
    } catch (const std::exception&) {
      // u failed on this facet: the triangle-by-triangle integration below reports it
    }
  }
  double Ku = 0;
  std::vector<char> added(facets.size(), 0);
  for (std::size_t t = 0; t < mesh_.triangles.size(); ++t) {
    const Index ft = mesh_.facet_of_triangle[t];
    if (ft == facet) continue;
    if (const auto& fk = facet_Ku[slot[t]]) {
      if (!added[slot[t]]) Ku += *fk;
      added[slot[t]] = 1;
      continue;
    }
    const auto& tri = mesh_.triangles[t];
    const auto f = [&sol, ft](const Vec3& Q) { return sol(Q, ft); };
    try {
      Ku += quadrature::integrate_kernel_times(
                f, P, nP, mesh_.vertices[static_cast<std::size_t>(tri[0])],
                mesh_.vertices[static_cast<std::size_t>(tri[1])],
                mesh_.vertices[static_cast<std::size_t>(tri[2])],
                triangle_inner_normal(static_cast<Index>(t)), solution_tol_)
                .value;
    } catch (const std::runtime_error& e) {
      throw std::runtime_error("manufactured solution: K u at " + point_name(P, facet) +
                               ", over triangle " + std::to_string(t) + " (facet " +
                               std::to_string(ft) + ") of " + mesh_.source + ": " + e.what());
    }
  }
  return u - rho * Ku;
}

double Scene::max_reflectivity() const {
  double m = 0;
  for (const Channel& ch : data_) {
    if (ch.rho_fn) return std::numeric_limits<double>::quiet_NaN();
    for (double r : ch.rho_facet) m = std::max(m, r);
  }
  return m;
}

Scene make_paper_cube_scene(double scale, const Vec3& offset) {
  if (!(scale > 0) || !std::isfinite(scale) || !offset.allFinite())
    throw std::invalid_argument("paper cube: scale must be positive and finite, offset finite");
  geometry::TriangleMesh cube = geometry::make_cube();
  for (Vec3& v : cube.vertices) v = offset + scale * v;  // orientation and facets unchanged
  Scene scene(std::move(cube));
  // rho by the facet's orientation: 0.5 on y = const, 0.4 on z = const, 0.3 on x = const (31).
  std::vector<double> rho(static_cast<std::size_t>(scene.num_facets()), 0.0);
  const auto& mesh = scene.mesh();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Vec3 n = scene.triangle_inner_normal(static_cast<Index>(t));
    int axis = 0;
    n.cwiseAbs().maxCoeff(&axis);
    rho[static_cast<std::size_t>(mesh.facet_of_triangle[t])] = axis == 0 ? 0.3 : axis == 1 ? 0.5 : 0.4;
  }
  scene.set_reflectivity(std::move(rho));
  scene.set_manufactured_solution(
      [scale, offset](const Vec3& Q, Index) { return ((Q - offset) / scale).squaredNorm(); });
  return scene;
}

}  // namespace panelrad

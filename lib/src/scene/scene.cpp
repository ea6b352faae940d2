#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/validation.hpp>
#include <panelrad/quadrature/singular_integration.hpp>
#include <panelrad/scene/scene.hpp>

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace panelrad {

namespace {
void check_reflectivity(double rho, const std::string& where) {
  if (!(rho >= 0.0 && rho < 1.0)) {  // also catches NaN
    std::ostringstream os;
    os << "reflectivity rho = " << rho << " at " << where << " is outside [0, 1) (paper (7))";
    throw std::invalid_argument(os.str());
  }
}
void check_finite(double v, const char* what, const std::string& where) {
  if (!std::isfinite(v)) {
    std::ostringstream os;
    os << what << " = " << v << " at " << where << " is not finite";
    throw std::invalid_argument(os.str());
  }
}
std::string facet_name(Index f) { return "facet " + std::to_string(f); }
std::string point_name(const Vec3& P, Index f) {
  std::ostringstream os;
  os << "point (" << P.x() << ", " << P.y() << ", " << P.z() << ") of facet " << f;
  return os.str();
}
void check_size(std::size_t got, Index facets, const char* what) {
  if (got != static_cast<std::size_t>(facets)) {
    std::ostringstream os;
    os << what << ": " << got << " values given for " << facets << " facets";
    throw std::invalid_argument(os.str());
  }
}
}  // namespace

Scene::Scene(geometry::TriangleMesh validated_mesh) : mesh_(std::move(validated_mesh)) {
  if (mesh_.triangles.empty()) throw std::invalid_argument("scene: empty mesh");
  rho_facet_.assign(static_cast<std::size_t>(mesh_.num_facets), 0.0);
  e_facet_.assign(static_cast<std::size_t>(mesh_.num_facets), 1.0);
}

Scene Scene::load(const std::string& path_or_builtin, std::vector<std::string>* notes) {
  return Scene(geometry::load_closed_convex(path_or_builtin, notes));
}

Vec3 Scene::triangle_inner_normal(Index t) const {
  const auto& tri = mesh_.triangles[static_cast<std::size_t>(t)];
  const Vec3& a = mesh_.vertices[static_cast<std::size_t>(tri[0])];
  const Vec3& b = mesh_.vertices[static_cast<std::size_t>(tri[1])];
  const Vec3& c = mesh_.vertices[static_cast<std::size_t>(tri[2])];
  return -(b - a).cross(c - a).normalized();  // outward CCW orientation -> inner normal
}

void Scene::set_reflectivity(double rho) {
  check_reflectivity(rho, "every facet");
  rho_fn_ = nullptr;
  rho_facet_.assign(static_cast<std::size_t>(mesh_.num_facets), rho);
}

void Scene::set_reflectivity(std::vector<double> per_facet) {
  check_size(per_facet.size(), mesh_.num_facets, "reflectivity");
  for (std::size_t f = 0; f < per_facet.size(); ++f)
    check_reflectivity(per_facet[f], facet_name(static_cast<Index>(f)));
  rho_fn_ = nullptr;
  rho_facet_ = std::move(per_facet);
}

void Scene::set_reflectivity(SurfaceFunction rho) {
  if (!rho) throw std::invalid_argument("reflectivity: empty function");
  rho_fn_ = std::move(rho);
}

void Scene::set_emissivity(double e) {
  check_finite(e, "emissivity", "every facet");
  e_fn_ = nullptr;
  solution_ = nullptr;
  e_facet_.assign(static_cast<std::size_t>(mesh_.num_facets), e);
}

void Scene::set_emissivity(std::vector<double> per_facet) {
  check_size(per_facet.size(), mesh_.num_facets, "emissivity");
  for (std::size_t f = 0; f < per_facet.size(); ++f)
    check_finite(per_facet[f], "emissivity", facet_name(static_cast<Index>(f)));
  e_fn_ = nullptr;
  solution_ = nullptr;
  e_facet_ = std::move(per_facet);
}

void Scene::set_emissivity(SurfaceFunction e) {
  if (!e) throw std::invalid_argument("emissivity: empty function");
  solution_ = nullptr;
  e_fn_ = std::move(e);
}

void Scene::set_manufactured_solution(SurfaceFunction u, double rel_tol) {
  if (!u) throw std::invalid_argument("manufactured solution: empty function");
  if (!(rel_tol > 0 && rel_tol < 1)) throw std::invalid_argument("manufactured solution: rel_tol must be in (0,1)");
  solution_ = std::move(u);
  solution_tol_ = rel_tol;
}

double Scene::reflectivity(const Vec3& P, Index facet) const {
  if (!rho_fn_) return rho_facet_[static_cast<std::size_t>(facet)];
  const double rho = rho_fn_(P, facet);
  check_reflectivity(rho, point_name(P, facet));
  return rho;
}

double Scene::emissivity(const Vec3& P, Index facet) const {
  if (!e_fn_) return e_facet_[static_cast<std::size_t>(facet)];
  const double e = e_fn_(P, facet);
  check_finite(e, "emissivity", point_name(P, facet));
  return e;
}

double Scene::manufactured_emissivity(const Vec3& P, Index facet, const Vec3& nP) const {
  if (!solution_) throw std::logic_error("manufactured_emissivity: no manufactured solution set");
  const double u = solution_(P, facet);
  check_finite(u, "manufactured solution", point_name(P, facet));
  const double rho = reflectivity(P, facet);
  if (rho == 0) return u;
  // (1/pi) Int_S u G dS over the exact surface. The triangles of P's own facet are coplanar with
  // P and contribute 0 (section 4.2, case (a)); a triangle of another facet that is coplanar
  // with P only up to the rounding of the coordinates (a slanted rectangle given as two
  // triangles) is integrated and gives a value at the rounding level (integrate_kernel_times).
  double Ku = 0;
  for (std::size_t t = 0; t < mesh_.triangles.size(); ++t) {
    const Index ft = mesh_.facet_of_triangle[t];
    if (ft == facet) continue;
    const auto& tri = mesh_.triangles[t];
    const SurfaceFunction& sol = solution_;
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
  if (rho_fn_) return std::numeric_limits<double>::quiet_NaN();
  double m = 0;
  for (double r : rho_facet_) m = std::max(m, r);
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

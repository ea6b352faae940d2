#include <panelrad/operator/kernel.hpp>
#include <panelrad/operator/near_field.hpp>
#include <panelrad/quadrature/exact_integrals.hpp>

#include <stdexcept>

namespace panelrad {

NearRule parse_near_rule(const std::string& name) {
  if (name == "exact") return NearRule::exact;
  if (name == "quadrature") return NearRule::quadrature;
  throw std::invalid_argument("near-field rule '" + name + "' is not 'exact' or 'quadrature'");
}

const char* to_string(NearRule rule) { return rule == NearRule::exact ? "exact" : "quadrature"; }

NearFieldIntegrator::NearFieldIntegrator(const NearFieldOptions& options, double h)
    : options_(options), h_(h) {
  if (options_.rule == NearRule::quadrature) {
    if (options_.mu < 0 || options_.mu > 8)
      throw std::invalid_argument("near field: mu = " + std::to_string(options_.mu) + " is outside [0, 8]");
    basic_ = &quadrature::rule_by_name(options_.basic_rule);
  }
}

double NearFieldIntegrator::operator()(const Vec3& P, const Vec3& nP,
                                       const geometry::Cluster& element) const {
  const auto& v = element.vertex;
  if (options_.rule == NearRule::exact)
    return quadrature::form_factor(P, nP, v[0], v[1], v[2], element.normal);
  // Section 4.2, case (b): composite rule with levels chosen from dist(P, element) / h.
  const int levels =
      quadrature::composite_levels(quadrature::distance_point_triangle(P, v[0], v[1], v[2]), h_, options_.mu);
  const Vec3& nQ = element.normal;
  return quadrature::integrate_composite(*basic_, v[0], v[1], v[2], levels,
                                         [&](const Vec3& Q) { return radiosity_G(P, nP, Q, nQ); }) /
         pi;
}

}  // namespace panelrad

#pragma once
// Near-field integrals (1/pi) Int_Delta G(P_i,Q) dS_Q of (43), by the exact closed form or by the
// composite quadrature of section 4.2 (mu levels of subdivision when dist <= h, mu-1 when <= 2h...).
#include <panelrad/geometry/cluster_tree.hpp>
#include <panelrad/quadrature/triangle_rules.hpp>

#include <string>

namespace panelrad {

using geometry::Vec3;

enum class NearRule { exact, quadrature };

struct NearFieldOptions {
  NearRule rule = NearRule::exact;
  int mu = 2;                        ///< section 4.2 subdivision levels (quadrature rule only)
  std::string basic_rule = "stroud7";  ///< basic rule of the composite scheme: stroud7, three_point...
  bool operator==(const NearFieldOptions&) const = default;
};

/// "exact" / "quadrature"; throws std::invalid_argument otherwise.
NearRule parse_near_rule(const std::string& name);
const char* to_string(NearRule rule);

/// Evaluates near-field integrals for one set of options.
class NearFieldIntegrator {
 public:
  /// h: mesh size of the triangulation (section 4.2).
  NearFieldIntegrator(const NearFieldOptions& options, double h);
  /// (1/pi) Int_element G(P,Q) dS_Q, paper (50); the caller skips coplanar elements (case (a)).
  double operator()(const Vec3& P, const Vec3& nP, const geometry::Cluster& element) const;
  const NearFieldOptions& options() const { return options_; }

 private:
  NearFieldOptions options_;
  const quadrature::TriangleRule* basic_ = nullptr;
  double h_ = 0;
};

}  // namespace panelrad

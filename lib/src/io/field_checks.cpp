#include "field_checks.hpp"

#include <panelrad/geometry/mesh.hpp>

#include <cctype>
#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>

namespace panelrad::io_detail {

using geometry::Vec3;

namespace {

[[noreturn]] void invalid(const char* who, const std::string& what) {
  throw std::invalid_argument(std::string(who) + ": " + what);
}

void check_vec3(const char* who, const Vec3& v, const char* what, std::size_t i) {
  if (!v.allFinite()) {
    std::ostringstream os;
    os << what << " of element " << i << " is not finite (" << v.x() << ", " << v.y() << ", "
       << v.z() << ")";
    invalid(who, os.str());
  }
}

}  // namespace

void check_names(const char* who, const std::vector<std::string>& channels) {
  if (channels.empty()) invalid(who, "the field has no channels");
  std::set<std::string> names;
  for (const std::string& c : channels) {
    // Channel names become CSV columns and PLY/VTK property names: one plain token each.
    if (c.empty()) invalid(who, "empty channel name");
    for (const char ch : c)
      if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-' || ch == '.'))
        invalid(who, "channel name '" + c + "' has a character other than letters, digits, _ - .");
    if (!names.insert(c).second) invalid(who, "channel name '" + c + "' appears twice");
  }
}

void validate(const char* who, const ElementField& f) {
  const std::size_t n = f.triangle.size();
  if (n == 0) invalid(who, "the field has no elements");
  const auto same = [&](std::size_t got, const char* what) {
    if (got != n)
      invalid(who, std::string(what) + " has " + std::to_string(got) + " entries for " +
                       std::to_string(n) + " elements");
  };
  same(f.inner_normal.size(), "inner_normal");
  same(f.centroid.size(), "centroid");
  same(f.area.size(), "area");
  same(f.facet.size(), "facet");
  const std::size_t C = f.channels.size();
  check_names(who, f.channels);
  const auto per_channel = [&](const std::vector<Eigen::VectorXd>& v, const char* what) {
    if (v.size() != C)
      invalid(who, std::string(what) + " has " + std::to_string(v.size()) + " channels for " +
                       std::to_string(C) + " channel names");
    for (std::size_t c = 0; c < C; ++c) {
      if (static_cast<std::size_t>(v[c].size()) != n)
        invalid(who, std::string(what) + "[" + f.channels[c] + "] has " +
                         std::to_string(v[c].size()) + " values for " + std::to_string(n) +
                         " elements");
      for (std::size_t i = 0; i < n; ++i)
        if (!std::isfinite(v[c][static_cast<Eigen::Index>(i)])) {
          std::ostringstream os;
          os << what << "[" << f.channels[c] << "] of element " << i << " is not finite ("
             << v[c][static_cast<Eigen::Index>(i)] << ")";
          invalid(who, os.str());
        }
    }
  };
  per_channel(f.rho, "rho");
  per_channel(f.emission, "emission");
  per_channel(f.radiosity, "radiosity");
  for (std::size_t i = 0; i < n; ++i) {
    for (const Vec3& p : f.triangle[i]) check_vec3(who, p, "a corner", i);
    check_vec3(who, f.inner_normal[i], "the inner normal", i);
    check_vec3(who, f.centroid[i], "the centroid", i);
    if (!std::isfinite(f.area[i])) {
      std::ostringstream os;
      os << "area of element " << i << " is not finite (" << f.area[i] << ")";
      invalid(who, os.str());
    }
  }
}

bool is_rgb(const ElementField& f) {
  return f.channels.size() == 3 && f.channels[0] == "R" && f.channels[1] == "G" &&
         f.channels[2] == "B";
}

}  // namespace panelrad::io_detail

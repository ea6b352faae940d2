// The rounding of coordinates as written, and the distance within which two faces are the contact
// they stand for (validation_internal.hpp: ContactTolerance).
//
// A coordinate read from a file is the decimal that was printed, read to the nearest double. When
// it was printed with many digits (6 or more significant digits: a value computed by the writer,
// such as a transformed corner, printed to a fixed number of decimals or of significant digits),
// the value meant may lie anywhere within half a unit in its last printed place: 5e-7 for six
// decimals, about an ulp for 17 significant digits (at least one ulp: the writer computed it in
// double). A short decimal (at most 5 significant digits: 0.3, 548.8, 1) is taken as meant
// exactly; the digits that a value needs are those of its shortest round-trip decimal, so that
// trailing zeros ("0.500000") do not count. A mesh built in code is exact.
//
// Two faces are the contact they stand for when they lie within 8 times the larger rounding of
// their own corners (a corner's distance from the plane through three others moves by up to about
// sqrt(3) times the rounding at each of the four, 4 sqrt(3) < 8), never more than 1e-4 of the pair's
// size (the bound of a polygon's planarity, polygon_triangulation.cpp), and never less than the
// visibility's resolution (scene_validation.cpp).
#include "contact_removal.hpp"
#include "validation_internal.hpp"

#include <algorithm>
#include <string>
#include <vector>
#include <charconv>
#include <cmath>
#include <limits>

namespace panelrad::geometry::validation_detail {

namespace {

/// Significant digits and decimal exponent of the shortest decimal that reads back as x (x != 0).
void shortest_decimal(double x, int& digits, int& exponent) {
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::scientific);
  digits = 0;
  const char* c = buf;
  for (; c != res.ptr && *c != 'e'; ++c)
    if (*c >= '0' && *c <= '9') ++digits;
  exponent = 0;
  if (c != res.ptr) std::from_chars(c + 1 + (c[1] == '+' ? 1 : 0), res.ptr, exponent);
}

}  // namespace

double printed_place_rounding(double x) {
  if (x == 0 || !std::isfinite(x)) return 0;
  int digits = 0, exponent = 0;
  shortest_decimal(x, digits, exponent);
  return 0.5 * std::pow(10.0, exponent - digits + 1);
}

double written_rounding(double x) {
  if (x == 0 || !std::isfinite(x)) return 0;
  int digits = 0, exponent = 0;
  shortest_decimal(x, digits, exponent);
  if (digits <= 5) return 0;
  const double half_unit = 0.5 * std::pow(10.0, exponent - digits + 1);
  const double ulp = std::nextafter(std::abs(x), std::numeric_limits<double>::infinity()) - std::abs(x);
  return std::max(half_unit, ulp);
}

std::vector<double> facet_rounding(const TriangleMesh& mesh) {
  std::vector<double> r(at(mesh.num_facets), 0.0);
  if (mesh.facet_line.empty()) return r;  // built in code: exact
  for (Sz t = 0; t < mesh.triangles.size(); ++t) {
    double& rf = r[at(mesh.facet_of_triangle[t])];
    for (Index v : mesh.triangles[t])
      for (int k = 0; k < 3; ++k) rf = std::max(rf, written_rounding(mesh.vertices[at(v)][k]));
  }
  return r;
}

ContactTolerance::ContactTolerance(const TriangleMesh& mesh, double resolution_)
    : resolution(resolution_), rounding(facet_rounding(mesh)) {}

double rounding_tolerance(const ContactTolerance& tolerance, Index f, Index g, double pair_size) {
  double r = 0;
  for (Index x : {f, g})
    if (x >= 0 && at(x) < tolerance.rounding.size()) r = std::max(r, tolerance.rounding[at(x)]);
  return std::min(8 * r, 1e-4 * pair_size);
}

double ContactTolerance::of(Index f, Index g, double pair_size) const {
  return std::max(resolution, rounding_tolerance(*this, f, g, pair_size));
}

double printed_rounding(const std::vector<Vec3>& corners, double size) {
  double r = std::numeric_limits<double>::infinity();
  for (const Vec3& x : corners)
    for (int k = 0; k < 3; ++k)
      if (x[k] != 0) r = std::min(r, printed_place_rounding(x[k]));
  // A place coarser than a hundredth of the size is a short number meant as written (0.3, 12.5).
  return std::isfinite(r) && r <= 1e-2 * size ? r : 0.0;
}

std::string more_digits_hint(double rounding, double distance, double roundings, double size) {
  if (!(rounding > 0) || !(distance <= roundings * rounding)) return "";
  return ". The coordinates are printed to " + num(2 * rounding) + " (a rounding of " + sci(rounding) + ", " +
         sci(rounding / size) + " of the size " + sci(size) + "), which can account for " + sci(distance) +
         ", but a rounding of more than 1e-4 of the size is not taken for one (the faces could be meant apart "
         "or crossing): if they were meant flat or touching, write the coordinates with more digits (17 "
         "significant digits keep each double exactly)";
}

namespace {

/// The largest rounding of any face's numbers as written.
double largest_rounding(const ContactTolerance& tolerance) {
  double r = 0;
  for (double x : tolerance.rounding) r = std::max(r, x);
  return r;
}

}  // namespace

double largest_tolerance(const ContactTolerance& tolerance, double size) {
  return std::max(tolerance.resolution, std::min(8 * largest_rounding(tolerance), 1e-4 * size));
}

double t_junction_tolerance(const ContactTolerance& tolerance, double size) {
  return std::max(largest_tolerance(tolerance, size), 4 * largest_rounding(tolerance));
}

}  // namespace panelrad::geometry::validation_detail

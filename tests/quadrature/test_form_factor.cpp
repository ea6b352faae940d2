// The closed-form point-to-triangle form factor (1/pi) Int G dS (paper (2), section 4.2).
#include <panelrad/quadrature/exact_integrals.hpp>
#include <panelrad/quadrature/singular_integration.hpp>
#include <panelrad/quadrature/triangle_rules.hpp>

#include "configuration_factors.hpp"

#include <gtest/gtest.h>

#include <array>
#include <utility>
#include <cmath>
#include <limits>
#include <vector>

using namespace panelrad::quadrature;

namespace {

constexpr double kPi = 3.14159265358979323846;

double G(const Vec3& P, const Vec3& nP, const Vec3& Q, const Vec3& nQ) {
  const Vec3 d = Q - P;
  const double r2 = d.squaredNorm();
  return d.dot(nP) * (-d.dot(nQ)) / (r2 * r2);  // paper (2)
}

double composite_reference(const Vec3& P, const Vec3& nP, const Vec3& a, const Vec3& b,
                           const Vec3& c, const Vec3& nQ, int levels) {
  return integrate_composite(rule_of_degree(20), a, b, c, levels,
                             [&](const Vec3& Q) { return G(P, nP, Q, nQ); }) /
         kPi;
}

struct Tri {
  Vec3 a, b, c, n;  // n: inner unit normal
};

// A closed convex polyhedron as triangles with inner normals (from the interior point `inside`).
std::vector<Tri> with_inner_normals(const std::vector<Vec3>& v,
                                    const std::vector<std::array<int, 3>>& faces,
                                    const Vec3& inside) {
  std::vector<Tri> tris;
  for (const auto& f : faces) {
    Tri t{v[f[0]], v[f[1]], v[f[2]], (v[f[1]] - v[f[0]]).cross(v[f[2]] - v[f[0]]).normalized()};
    if ((inside - t.a).dot(t.n) < 0) t.n = -t.n;
    tris.push_back(t);
  }
  return tris;
}

std::vector<Tri> unit_cube() {
  std::vector<Vec3> v;
  for (int i = 0; i < 8; ++i) v.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  const std::vector<std::array<int, 3>> faces = {
      {0, 1, 3}, {0, 3, 2}, {4, 5, 7}, {4, 7, 6},  // z = 0, z = 1
      {0, 1, 5}, {0, 5, 4}, {2, 3, 7}, {2, 7, 6},  // y = 0, y = 1
      {0, 2, 6}, {0, 6, 4}, {1, 3, 7}, {1, 7, 5}}; // x = 0, x = 1
  return with_inner_normals(v, faces, Vec3(0.5, 0.5, 0.5));
}

std::vector<Tri> tetrahedron() {
  const std::vector<Vec3> v = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  return with_inner_normals(v, {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}}, Vec3(0, 0, 0));
}

}  // namespace

// Well-separated pairs: closed form against the degree-20 composite rule (exact to rounding for
// such smooth integrands): 1e-13 relative.
TEST(FormFactor, AgainstHighOrderQuadratureSeparated) {
  const Vec3 a(0.1, 0.2, 0.0), b(1.3, -0.1, 0.2), c(0.4, 0.9, -0.1);
  const Vec3 nQ = (b - a).cross(c - a).normalized();
  const Vec3 Ps[] = {{0.5, 0.3, 2.0}, {-1.5, 0.4, 1.0}, {0.2, -2.0, -1.5}, {3.0, 3.0, 0.5}};
  const Vec3 ns[] = {{0.1, -0.2, -1}, {1, 0.1, -0.3}, {-0.2, 1, 0.8}, {-1, -1, 0.2}};
  for (int i = 0; i < 4; ++i) {
    const Vec3 nP = ns[i].normalized();
    const double ff = form_factor(Ps[i], nP, a, b, c, nQ);
    const double ref = composite_reference(Ps[i], nP, a, b, c, nQ, 3);
    EXPECT_NEAR(ff, ref, 1e-13 * std::abs(ref)) << i;
    // Vertex order does not matter; reversing nQ (or nP) reverses the sign (G is linear in each).
    EXPECT_NEAR(form_factor(Ps[i], nP, a, c, b, nQ), ff, 1e-15 * std::abs(ff));
    EXPECT_NEAR(form_factor(Ps[i], nP, a, b, c, -nQ), -ff, 1e-15 * std::abs(ff));
    EXPECT_NEAR(form_factor(Ps[i], -nP, a, b, c, nQ), -ff, 1e-15 * std::abs(ff));
  }
}

// Nearly singular pairs: P on a perpendicular neighbour close to the shared edge, and P above
// the triangle close to its plane. References: fine composite quadrature (6 levels of the
// degree-20 rule, 495616 points, accurate to ~1e-13 at dist 1e-1 and ~5e-11 at 1e-2) and, for
// all distances down to 1e-8, the independent adaptive polar integration (integrate_kernel_times
// at 1e-12).
TEST(FormFactor, AgainstQuadratureNearlySingular) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), nQ(0, 0, 1);
  const auto one = [](const Vec3&) { return 1.0; };
  for (const auto& [dist, tol] : {std::pair{1e-1, 1e-12}, std::pair{1e-2, 1e-10}}) {
    const Vec3 P(0.3, 0, dist), nP(0, 1, 0);
    const double ff = form_factor(P, nP, a, b, c, nQ);
    EXPECT_NEAR(ff, composite_reference(P, nP, a, b, c, nQ, 6), tol * ff) << dist;
  }
  for (double dist : {1e-2, 1e-4, 1e-6, 1e-8}) {
    for (const Vec3& nP0 : {Vec3(0, 1, 0), Vec3(0, 0.5, -0.5), Vec3(0.3, 0.2, -1)}) {
      const Vec3 nP = nP0.normalized();
      for (const Vec3& P : {Vec3(0.3, 0, dist), Vec3(0.3, -dist, dist), Vec3(0.25, 0.25, dist),
                            Vec3(1.2, 0.1, dist)}) {
        const double ff = form_factor(P, nP, a, b, c, nQ);
        const double ref = integrate_kernel_times(one, P, nP, a, b, c, nQ, 1e-12).value;
        // 5e-12 relative: the reference's tolerance with margin. Absolute floor 1e-15: with nP
        // tangential and the foot inside, the value is O(h) made of O(1) polar pieces that
        // cancel, so the reference is only good to ~1e-16 absolute there (the closed form is
        // better: its sum carries the factor h explicitly).
        EXPECT_NEAR(ff, ref, 5e-12 * std::abs(ref) + 1e-15)
            << "dist " << dist << " P " << P.transpose();
      }
    }
  }
}

// P very close to the plane but far outside the triangle, nP along the normal: the value is
// O(h^2) while the contour terms are O(1) (cancellation-free branch). Reference: for h -> 0,
// (1/pi) Int G dS = (h^2/pi) Int dS / r^4 (1 + O(h^2)), the integral by high-order quadrature.
TEST(FormFactor, TinyHeightFarFromTriangleKeepsRelativeAccuracy) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), nQ(0, 0, 1), nP(0, 0, -1);
  for (double h : {1e-4, 1e-7, 1e-10}) {
    const Vec3 P(3, 2, h);
    const double ff = form_factor(P, nP, a, b, c, nQ);
    const double inv_r4 = integrate_composite(rule_of_degree(20), a, b, c, 2, [&](const Vec3& Q) {
      const double r2 = (Q - P).squaredNorm();
      return 1.0 / (r2 * r2);
    });
    const double leading = h * h * inv_r4 / kPi;
    EXPECT_NEAR(ff, leading, 1e-13 * leading + 10 * h * h * leading) << h;  // O(h^2) correction
    EXPECT_GT(ff, 0);
  }
}

// A point a narrow gap h below a plane, its foot within a rounding (1e-16) of the edges of the
// elements there: the square [0, 1]^2 at z = 1 split into the 8 triangles of the midpoint
// subdivision of its two halves (edges on the diagonal x = y and the lines x = 1/2, y = 1/2). The
// contour terms of an edge under the foot are e gamma / D with D ~ h, so an error of a few eps in
// the foot's distance e from the edge (rounded dot products with vectors of length ~1) would be a
// relative error eps / h in the factor (1e-7 at h = 1e-9), and the two triangles sharing the edge
// would not cancel it. The sum must equal the closed-form factor of the square
// (configuration_factors.hpp): 8 factors and 4 corner terms, each accurate to a few eps: 64 eps.
TEST(FormFactor, NarrowGapBelowEdgesSumsToTheSquare) {
  const double mid = 0.5;
  std::vector<std::array<Vec3, 3>> tris;
  for (const std::array<Vec3, 3>& half : {std::array<Vec3, 3>{Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(1, 1, 1)},
                                          std::array<Vec3, 3>{Vec3(0, 0, 1), Vec3(1, 1, 1), Vec3(0, 1, 1)}}) {
    const Vec3 m01 = mid * (half[0] + half[1]), m12 = mid * (half[1] + half[2]), m20 = mid * (half[2] + half[0]);
    tris.push_back({half[0], m01, m20});
    tris.push_back({m01, half[1], m12});
    tris.push_back({m20, m12, half[2]});
    tris.push_back({m01, m12, m20});
  }
  const Vec3 nP(0, 0, 1), nQ(0, 0, -1);
  const panelrad::testing::AxisRectangle square{0, 1, 0, 1};
  const std::vector<std::array<double, 2>> feet = {{0.55000000000000004, 0.54999999999999993},
                                                   {0.3, std::nextafter(0.3, 1.0)},
                                                   {0.5, 0.3},
                                                   {std::nextafter(0.5, 0.0), 0.8},
                                                   {0.7, std::nextafter(0.5, 1.0)},
                                                   {0.8, 0.8}};
  for (const double h : {1e-3, 1e-6, 1e-9, 1e-11}) {
    for (const auto& foot : feet) {
      const Vec3 P(foot[0], foot[1], 1 - h);
      double sum = 0;
      for (const auto& t : tris) sum += form_factor(P, nP, t[0], t[1], t[2], nQ);
      const double truth = panelrad::testing::parallel_rectangle_factor(foot[0], foot[1], square, 1 - P.z());
      EXPECT_NEAR(sum, truth, 64 * std::numeric_limits<double>::epsilon())
          << "h " << h << ", foot (" << foot[0] << ", " << foot[1] << ")";
    }
  }
}

TEST(FormFactor, CoplanarIsExactlyZero) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0), nQ(0, 0, 1);
  for (const Vec3& P : {Vec3(0.2, 0.2, 0), Vec3(2, 3, 0), Vec3(0.5, 0, 0), Vec3(-1e-300, 5, 0)})
    EXPECT_EQ(form_factor(P, Vec3(0, 1, 0), a, b, c, nQ), 0.0);
  EXPECT_EQ(form_factor(Vec3(0, 0, 0), Vec3(0, 0, 1), a, b, c, nQ), 0.0);  // P at a vertex
}

// Lemma 1 / section 4.3: for P on a face of a closed convex polyhedron, (1/pi) Int_S G dS = 1.
TEST(FormFactor, ClosedPolyhedraSumToOne) {
  struct Case {
    std::vector<Tri> tris;
    const char* name;
  };
  for (const Case& cs : {Case{unit_cube(), "cube"}, Case{tetrahedron(), "tetrahedron"}}) {
    for (const Tri& face : cs.tris) {
      for (const std::array<double, 2>& st :
           {std::array<double, 2>{0.3, 0.3}, {0.1, 0.8}, {0.5, 1e-6}, {0.98, 0.01}}) {
        const Vec3 P = face.a + st[0] * (face.b - face.a) + st[1] * (face.c - face.a);
        double sum = 0;
        // P's own triangle is skipped as a caller does (same facet): P computed from its
        // vertices need not lie exactly (to the last bit) in its plane, and then the closed form
        // gives the one-sided limit, not the coplanar 0.
        for (const Tri& t : cs.tris)
          if (&t != &face) sum += form_factor(P, face.n, t.a, t.b, t.c, t.n);
        // 1e-13: rounding of a dozen O(1) terms (near an edge the neighbour gives ~1/2).
        EXPECT_NEAR(sum, 1.0, 1e-13) << cs.name << " P " << P.transpose();
      }
    }
  }
}

TEST(FormFactor, TranslationInvariance) {
  const Vec3 a(0.1, 0.2, 0.0), b(1.3, -0.1, 0.2), c(0.4, 0.9, -0.1);
  const Vec3 nQ = (b - a).cross(c - a).normalized();
  const Vec3 shift(1e6, -1e6, 1e6);
  for (const Vec3& P : {Vec3(0.5, 0.3, 2.0), Vec3(0.6, 0.2, 0.05), Vec3(1.0, -0.5, 0.3)}) {
    const Vec3 nP = Vec3(0.2, 0.3, -1).normalized();
    const double f0 = form_factor(P, nP, a, b, c, nQ);
    const double f1 = form_factor(P + shift, nP, a + shift, b + shift, c + shift, nQ);
    // Coordinates of size 1e6 carry absolute rounding ~1e-10; relative to the distance d of P
    // from the plane that is 1e-10/d: tolerance 1e-10 (1 + 1/d).
    const double d = std::abs((P - a).dot(nQ));
    EXPECT_NEAR(f1, f0, 1e-10 * (1 + 1 / d) * std::abs(f0)) << P.transpose();
  }
}

// Slivers of the visible parts (a shadow's edge passing an ulp-level distance from a corner):
// triangles with an edge 1e-11 to 1e-10 long, P at distance about 1. Their factor is the
// integrand's value times an area of 1e-12, which the degree-20 rule gets to rounding; the
// contour formula's O(1) terms must cancel to that. Two failure modes, both once off by 1e-6
// and 1e-8 of the element: the short edge's direction tilted out of the plane by the corners'
// rounding (h times it entered the edge's parameters), and the foot of P a few 1e-9 from the
// sliver's tip (the in-plane angles no longer sum to 0 there, which the cancellation-free form
// assumed). The absolute bound 1e-15 is 1e-3 of the factor's size.
TEST(FormFactor, SliversAgainstQuadrature) {
  struct Case {
    Vec3 P, nP, nQ, a, b, c;
  };
  const Case cases[] = {
      // The short edge tilted (P's foot 1e-6 from the tip).
      {{0.063456749999922415, 0.2150070833333067, 0.68375133333326699},
       {0.45888650730554592, 0.79242954155474099, -0.40184399346544941},
       {-0.45888650730554603, -0.79242954155474099, 0.40184399346544952},
       {1.3507432500000998, 0.56254925000007716, 0.35059000000004181},
       {0.5223423173222782, 1.0074370842224081, 0.28190725600508415},
       {0.52234231733740721, 1.0074370842090907, 0.281907255996099}},
      // The foot 2e-9 from the tip.
      {{0.1422520102945927, 0.18384096642027134, 0.015686215686729853},
       {0.51945234351163172, 0.84928297039146483, 0.094274593731949574},
       {-0.51945234300339571, -0.8492829704572824, -0.09427459593940099},
       {0.60388642497957634, 1.0778766154879138, 0.02537780509450081},
       {0.66170435559816887, 1.0331239363123172, 0.10996081178129109},
       {0.66170435537868899, 1.0331239364728961, 0.10996081154402979}},
  };
  for (const Case& k : cases) {
    const double ff = form_factor(k.P, k.nP, k.a, k.b, k.c, k.nQ);
    const double ref = composite_reference(k.P, k.nP, k.a, k.b, k.c, k.nQ, 2);
    EXPECT_GT(std::abs(ref), 1e-13);
    EXPECT_NEAR(ff, ref, 1e-15) << "area " << (k.b - k.a).cross(k.c - k.a).norm() / 2;
    // Each corner first: the same factor.
    EXPECT_NEAR(form_factor(k.P, k.nP, k.b, k.c, k.a, k.nQ), ref, 1e-15);
    EXPECT_NEAR(form_factor(k.P, k.nP, k.c, k.a, k.b, k.nQ), ref, 1e-15);
  }
}

// Far field (paper section 4.1, (44)-(48)): Taylor coefficients of the kernel in local coordinates
// of a cluster's plane, exact triangle moments and the shift of moments, each against truth that
// is computed independently here (exact kernel, a second-order jet type, Gauss-Legendre on the
// collapsed square, fine composite quadrature).
#include <panelrad/operator/far_field.hpp>
#include <panelrad/geometry/subdivision.hpp>

#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

namespace {

using panelrad::num_taylor_terms;
using panelrad::PlaneFrame;
using panelrad::taylor_index;
using panelrad::Vec3;

constexpr double kEps = std::numeric_limits<double>::epsilon();

// The kernel G(P,Q) of paper (2), written out here independently of the library.
double exact_G(const Vec3& P, const Vec3& nP, const Vec3& Q, const Vec3& nQ) {
  const Vec3 d = Q - P;
  const double r2 = d.squaredNorm();
  return d.dot(nP) * (-d.dot(nQ)) / (r2 * r2);
}

double eval_poly(const std::vector<double>& c, int M, double x, double y) {
  double s = 0.0;
  for (int p = 0; p <= M; ++p)
    for (int q = 0; p + q <= M; ++q) s += c[static_cast<std::size_t>(taylor_index(p, q))] * std::pow(x, p) * std::pow(y, q);
  return s;
}

double binom(int n, int k) {
  double r = 1.0;
  for (int i = 1; i <= k; ++i) r = r * (n - k + i) / i;
  return r;
}

// T_M(eta) = sum_{n > M} C(n+3,3) eta^n: the Gegenbauer terms of (1 - 2 t r + r^2)^-2 obey
// |C_n^2(t)| <= C_n^2(1) = C(n+3,3) for |t| <= 1, so this bounds the tail of 1/|P-Q|^4 * |P-A|^4.
double tail(int M, double eta) {
  double s = 0.0;
  for (int n = M + 1; n < 4000; ++n) s += binom(n + 3, 3) * std::pow(eta, n);
  return s;
}

struct Config {
  Vec3 P, nP;
  PlaneFrame frame;
  double rho;  // |P - A|
};

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  for (;;) {
    Vec3 v(g(rng), g(rng), g(rng));
    if (v.norm() > 1e-3) return v.normalized();
  }
}

Config random_config(std::mt19937_64& rng, const Vec3& offset = Vec3::Zero()) {
  std::uniform_real_distribution<double> u(-3.0, 3.0), r(0.5, 4.0);
  Config c;
  const Vec3 A = offset + Vec3(u(rng), u(rng), u(rng));
  c.frame = panelrad::make_plane_frame(A, random_unit(rng));
  c.rho = r(rng);
  c.P = A + c.rho * random_unit(rng);
  c.nP = random_unit(rng);
  return c;
}

// Pointwise bound of |G - Taylor_M| on the disc |Q - A| <= R (see tail()): G = h L / |P-Q|^4 with
// h = (P-A).nQ and L = L0 + grad L.(x,y); truncating the product at degree M leaves
// h/rho^4 [L0 (F - F_{<=M}) + (grad L.(x,y)) (F - F_{<=M-1})], F = rho^4/|P-Q|^4.
// Rounding: every series term is bounded by the same majorant S; allow 64 eps (M+1)^2 S.
double taylor_error_bound(const Config& c, int M, double R) {
  const Vec3 d = c.P - c.frame.origin;
  const double eta = R / c.rho;
  const double h = std::abs(d.dot(c.frame.normal));
  const double L0 = std::abs(d.dot(c.nP));
  const double gradL = std::hypot(c.frame.e1.dot(c.nP), c.frame.e2.dot(c.nP));
  const double pre = h / std::pow(c.rho, 4);
  const double tailM1 = M == 0 ? std::pow(1.0 - eta, -4) : tail(M - 1, eta);
  const double S = pre * (L0 + gradL * R) * std::pow(1.0 - eta, -4);
  return pre * (L0 * tail(M, eta) + gradL * R * tailM1) + 64.0 * kEps * (M + 1) * (M + 1) * S;
}

// Natural size of the kernel on the disc: |h|/rho^4 (|L0| + |grad L| R) >= |G| (1-eta)^4.
double kernel_scale(const Config& c, double R) {
  const Vec3 d = c.P - c.frame.origin;
  return std::abs(d.dot(c.frame.normal)) *
         (std::abs(d.dot(c.nP)) + R * std::hypot(c.frame.e1.dot(c.nP), c.frame.e2.dot(c.nP))) / std::pow(c.rho, 4);
}

// (a) Pointwise Taylor error on the disc: below the rigorous bound, shrinking like eta^(M+1).
TEST(FarField, TaylorSeriesConvergesGeometricallyOnTheDisc) {
  constexpr int kTrials = 40, kMmax = panelrad::kMaxTaylorDegree;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (const double eta : {0.5, 0.2, 0.1}) {
    // Geometric mean over configurations of the max error on the disc, relative to the kernel's
    // scale: one configuration may have a nearly vanishing homogeneous term at some degree.
    std::vector<double> mean_log(kMmax + 1, 0.0);
    for (int trial = 0; trial < kTrials; ++trial) {
      const Config c = random_config(rng);
      const double R = eta * c.rho;
      for (int M = 0; M <= kMmax; ++M) {
        std::vector<double> coef(static_cast<std::size_t>(num_taylor_terms(M)));
        panelrad::kernel_taylor_coefficients(c.P, c.nP, c.frame, M, coef.data());
        std::mt19937_64 pts(99);  // the same sample points for every M
        double err = 0.0;
        for (int k = 0; k < 200; ++k) {
          const double r = R * std::sqrt(unit(pts)), phi = 2 * M_PI * unit(pts);
          const double x = r * std::cos(phi), y = r * std::sin(phi);
          const Vec3 Q = c.frame.origin + x * c.frame.e1 + y * c.frame.e2;
          const double approx = eval_poly(coef, M, x, y);
          ASSERT_TRUE(std::isfinite(approx));
          err = std::max(err, std::abs(approx - exact_G(c.P, c.nP, Q, c.frame.normal)));
        }
        EXPECT_LE(err, taylor_error_bound(c, M, R)) << "eta " << eta << " M " << M << " trial " << trial;
        mean_log[static_cast<std::size_t>(M)] += std::log(err / kernel_scale(c, R) + 1e-300) / kTrials;
      }
    }
    // Monotone geometric decrease: from M to M+1 the majorant's leading term shrinks by
    // eta (M+5)/(M+2) (ratio of C(n+3,3) eta^n at n = M+2, M+1); allow 1.5 times that.
    for (int M = 0; M < kMmax; ++M) {
      const double ratio = std::exp(mean_log[static_cast<std::size_t>(M) + 1] - mean_log[static_cast<std::size_t>(M)]);
      EXPECT_LT(ratio, 1.0) << "eta " << eta << " M " << M;
      EXPECT_LE(ratio, 1.5 * eta * (M + 5) / (M + 2)) << "eta " << eta << " M " << M;
    }
  }
}

// A second-order jet in (x, y): value, gradient and Hessian, for independent derivatives.
struct Jet {
  double v = 0, x = 0, y = 0, xx = 0, xy = 0, yy = 0;
};
Jet operator+(const Jet& a, const Jet& b) { return {a.v + b.v, a.x + b.x, a.y + b.y, a.xx + b.xx, a.xy + b.xy, a.yy + b.yy}; }
Jet operator*(const Jet& a, const Jet& b) {
  return {a.v * b.v,
          a.x * b.v + a.v * b.x,
          a.y * b.v + a.v * b.y,
          a.xx * b.v + 2 * a.x * b.x + a.v * b.xx,
          a.xy * b.v + a.x * b.y + a.y * b.x + a.v * b.xy,
          a.yy * b.v + 2 * a.y * b.y + a.v * b.yy};
}
Jet reciprocal(const Jet& g) {
  const double r = 1 / g.v, r2 = r * r, r3 = r2 * r;
  return {r, -g.x * r2, -g.y * r2, 2 * g.x * g.x * r3 - g.xx * r2, 2 * g.x * g.y * r3 - g.xy * r2,
          2 * g.y * g.y * r3 - g.yy * r2};
}
Jet constant(double c) { return {c}; }

// (b) Degree-2 coefficients against derivatives from automatic differentiation:
// c_00 = G, c_10 = G_x, c_01 = G_y, c_20 = G_xx/2, c_11 = G_xy, c_02 = G_yy/2 at (x,y) = (0,0).
TEST(FarField, DegreeTwoCoefficientsMatchAutomaticDerivatives) {
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 50; ++trial) {
    const Config c = random_config(rng);
    const Jet X{0, 1, 0}, Y{0, 0, 1};
    Jet D[3];  // Q - P, componentwise
    for (int k = 0; k < 3; ++k)
      D[k] = constant(c.frame.origin[k] - c.P[k]) + X * constant(c.frame.e1[k]) + Y * constant(c.frame.e2[k]);
    Jet r2, dnP, dnQ;
    for (int k = 0; k < 3; ++k) {
      r2 = r2 + D[k] * D[k];
      dnP = dnP + D[k] * constant(c.nP[k]);
      dnQ = dnQ + D[k] * constant(-c.frame.normal[k]);
    }
    const Jet G = dnP * dnQ * reciprocal(r2 * r2);
    double coef[6];
    panelrad::kernel_taylor_coefficients(c.P, c.nP, c.frame, 2, coef);
    const double truth[6] = {G.v, G.x, G.y, G.xx / 2, G.xy, G.yy / 2};
    // Scale of the p+q = n coefficient: |G|-like magnitude / rho^n; both sides are computed in a
    // handful of O(1)-conditioned operations, so 1e-13 relative to that scale is generous.
    const Vec3 d = c.P - c.frame.origin;
    const double base = std::abs(d.dot(c.frame.normal)) * c.rho / std::pow(c.rho, 4);
    for (int t = 0; t < 6; ++t) {
      const int n = t == 0 ? 0 : (t < 3 ? 1 : 2);
      EXPECT_NEAR(coef[t], truth[t], 1e-13 * base / std::pow(c.rho, n)) << "trial " << trial << " term " << t;
    }
  }
}

// Triangle (a,b,c) with a plane frame centred at its circumcentre.
struct Tri {
  Vec3 a, b, c;
};
Vec3 circumcentre(const Tri& t) {
  const Vec3 ab = t.b - t.a, ac = t.c - t.a, n = ab.cross(ac);
  return t.a + (ac.squaredNorm() * n.cross(ab) + ab.squaredNorm() * ac.cross(n)) / (2 * n.squaredNorm());
}
Vec3 inner_normal(const Tri& t) { return (t.b - t.a).cross(t.c - t.a).normalized(); }

// The four children of the 4-way midpoint subdivision (the cluster tree's split).
std::array<Tri, 4> children(const Tri& t) {
  const auto c = panelrad::geometry::midpoint_subdivision(t.a, t.b, t.c);
  return {{{c[0][0], c[0][1], c[0][2]}, {c[1][0], c[1][1], c[1][2]}, {c[2][0], c[2][1], c[2][2]},
           {c[3][0], c[3][1], c[3][2]}}};
}

// Gauss-Legendre nodes and weights on [0,1] by Newton's method on P_n (independent of the library).
void gauss_legendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(static_cast<std::size_t>(n), 0);
  w.assign(static_cast<std::size_t>(n), 0);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(M_PI * (i + 0.75) / (n + 0.5)), dp = 0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    x[static_cast<std::size_t>(i)] = 0.5 * (1 - z);
    w[static_cast<std::size_t>(i)] = 1.0 / ((1 - z * z) * dp * dp);  // = 2/((1-z^2)P'^2) / 2
  }
}

// Int_T f dS on the collapsed square: Q = a + s (b-a) + s v (c-b), dS = 2|T| s ds dv.
template <class F>
double collapsed_square_rule(const Tri& t, int n, F&& f) {
  std::vector<double> x, w;
  gauss_legendre(n, x, w);
  const double twice_area = (t.b - t.a).cross(t.c - t.a).norm();
  double s = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double si = x[static_cast<std::size_t>(i)], vj = x[static_cast<std::size_t>(j)];
      s += w[static_cast<std::size_t>(i)] * w[static_cast<std::size_t>(j)] * si * f(t.a + si * (t.b - t.a) + si * vj * (t.c - t.b));
    }
  return s * twice_area;
}

Tri random_triangle(std::mt19937_64& rng, const Vec3& offset = Vec3::Zero()) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (;;) {
    Tri t{offset + Vec3(u(rng), u(rng), u(rng)), offset + Vec3(u(rng), u(rng), u(rng)), offset + Vec3(u(rng), u(rng), u(rng))};
    const double area2 = (t.b - t.a).cross(t.c - t.a).norm();
    if (area2 > 0.2) return t;  // not a sliver: keeps the circumradius moderate
  }
}

// (d) Exact moments against Gauss-Legendre on the collapsed square (degree p+q+1 in s, p+q in v:
// 8 points integrate up to degree 15 exactly, so only rounding separates the two).
TEST(FarField, TriangleMomentsMatchGaussLegendre) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 20; ++trial) {
    const Tri t = random_triangle(rng);
    const PlaneFrame f = panelrad::make_plane_frame(circumcentre(t), inner_normal(t));
    const int M = 8;
    std::vector<double> m(static_cast<std::size_t>(num_taylor_terms(M)));
    panelrad::triangle_moments(f, t.a, t.b, t.c, M, m.data());
    const double Rmax = std::max({(t.a - f.origin).norm(), (t.b - f.origin).norm(), (t.c - f.origin).norm()});
    const double area = 0.5 * (t.b - t.a).cross(t.c - t.a).norm();
    EXPECT_NEAR(m[0], area, 1e-14 * area);
    for (int p = 0; p <= M; ++p)
      for (int q = 0; p + q <= M; ++q) {
        const double ref = collapsed_square_rule(t, 8, [&](const Vec3& Q) {
          const auto xy = f.local(Q);
          return std::pow(xy[0], p) * std::pow(xy[1], q);
        });
        // Both are sums of O(number of terms) products bounded by area * Rmax^(p+q).
        EXPECT_NEAR(m[static_cast<std::size_t>(taylor_index(p, q))], ref, 1e-13 * area * std::pow(Rmax, p + q))
            << "p " << p << " q " << q;
      }
  }
}

// (e) Shifting moments: about O1 then shifted to O2 equals computed about O2 directly; and the
// four midpoint children, each about its own circumcentre, shifted up sum to the parent's moments.
TEST(FarField, ShiftOfMomentsIsExact) {
  std::mt19937_64 rng(5);
  const int M = panelrad::kMaxTaylorDegree;
  const int T = num_taylor_terms(M);
  for (int trial = 0; trial < 20; ++trial) {
    const Tri t = random_triangle(rng);
    const PlaneFrame f2 = panelrad::make_plane_frame(circumcentre(t), inner_normal(t));
    PlaneFrame f1 = f2;
    f1.origin = t.a + 0.3 * (t.b - t.a) + 0.2 * (t.c - t.a);
    std::vector<double> m1(static_cast<std::size_t>(T)), m2(static_cast<std::size_t>(T)), shifted(static_cast<std::size_t>(T), 0.0);
    panelrad::triangle_moments(f1, t.a, t.b, t.c, M, m1.data());
    panelrad::triangle_moments(f2, t.a, t.b, t.c, M, m2.data());
    const auto d = f2.local(f1.origin);
    panelrad::shift_moments_add(m1.data(), d[0], d[1], M, shifted.data());
    const double area = m2[0];
    const double Rmax = std::max({(t.a - f2.origin).norm(), (t.b - f2.origin).norm(), (t.c - f2.origin).norm()});
    for (int p = 0; p <= M; ++p)
      for (int q = 0; p + q <= M; ++q) {
        const std::size_t k = static_cast<std::size_t>(taylor_index(p, q));
        // Terms of the binomial sum are bounded by area (|d| + Rmax)^(p+q) <= area (2 Rmax)^(p+q).
        EXPECT_NEAR(shifted[k], m2[k], 1e-13 * area * std::pow(2 * Rmax, p + q)) << "p " << p << " q " << q;
      }

    // Children of the midpoint subdivision (the cluster tree's 4-way split).
    const std::array<Tri, 4> kids = children(t);
    std::vector<double> sum(static_cast<std::size_t>(T), 0.0), mk(static_cast<std::size_t>(T));
    for (const Tri& kid : kids) {
      PlaneFrame fk = f2;  // same axes: same facet
      fk.origin = circumcentre(kid);
      panelrad::triangle_moments(fk, kid.a, kid.b, kid.c, M, mk.data());
      const auto dk = f2.local(fk.origin);
      panelrad::shift_moments_add(mk.data(), dk[0], dk[1], M, sum.data());
    }
    for (int p = 0; p <= M; ++p)
      for (int q = 0; p + q <= M; ++q) {
        const std::size_t k = static_cast<std::size_t>(taylor_index(p, q));
        EXPECT_NEAR(sum[k], m2[k], 1e-13 * area * std::pow(2 * Rmax, p + q)) << "p " << p << " q " << q;
      }
  }
}

// Fine composite reference for Int_T g: 4^levels midpoint subtriangles, 10x10 collapsed-square
// Gauss-Legendre on each.
template <class F>
double composite_reference(const Tri& t, int levels, F&& f) {
  if (levels == 0) return collapsed_square_rule(t, 10, f);
  double s = 0;
  for (const Tri& k : children(t)) s += composite_reference(k, levels - 1, f);
  return s;
}

// An admissible pair (41): P at distance R(tau)/eta from A(tau), in a random direction off the
// triangle's plane, with a random normal nP.
Config admissible_config(std::mt19937_64& rng, const Tri& t, double eta) {
  Config c;
  c.frame = panelrad::make_plane_frame(circumcentre(t), inner_normal(t));
  const double R = (t.a - c.frame.origin).norm();
  c.rho = R / eta;
  Vec3 dir = random_unit(rng);
  if (std::abs(dir.dot(c.frame.normal)) < 0.05) dir = (dir + 0.1 * c.frame.normal).normalized();
  c.P = c.frame.origin + c.rho * dir;
  c.nP = random_unit(rng);
  return c;
}

double far_field_integral(const Config& c, const Tri& t, int M) {
  std::vector<double> coef(static_cast<std::size_t>(num_taylor_terms(M))), m(coef.size());
  panelrad::kernel_taylor_coefficients(c.P, c.nP, c.frame, M, coef.data());
  panelrad::triangle_moments(c.frame, t.a, t.b, t.c, M, m.data());
  double s = 0;
  for (std::size_t k = 0; k < coef.size(); ++k) s += coef[k] * m[k];  // (47)
  return s;
}

// (f) sum c_pq m_pq against a fine composite quadrature of Int_T G dS: error below area times the
// pointwise bound (the triangle lies in its circumcircle, radius R(tau)), shrinking with M.
TEST(FarField, FarFieldIntegralConvergesToQuadrature) {
  constexpr int kTrials = 12, kMmax = 8;
  std::mt19937_64 rng(17);
  for (const double eta : {0.5, 0.2, 0.1}) {
    std::vector<double> mean_log(kMmax + 1, 0.0);
    for (int trial = 0; trial < kTrials; ++trial) {
      const Tri t = random_triangle(rng);
      const Config c = admissible_config(rng, t, eta);
      auto G = [&](const Vec3& Q) { return exact_G(c.P, c.nP, Q, c.frame.normal); };
      const double ref = composite_reference(t, 3, G);
      const double ref_coarse = composite_reference(t, 2, G);
      const double area = 0.5 * (t.b - t.a).cross(t.c - t.a).norm();
      const double R = (t.a - c.frame.origin).norm();
      const double size = area * kernel_scale(c, R);
      // The reference is converged: two refinements agree to rounding level.
      ASSERT_NEAR(ref, ref_coarse, 1e-13 * size);
      for (int M = 0; M <= kMmax; ++M) {
        const double approx = far_field_integral(c, t, M);
        ASSERT_TRUE(std::isfinite(approx));
        const double err = std::abs(approx - ref);
        EXPECT_LE(err, area * taylor_error_bound(c, M, R)) << "eta " << eta << " M " << M;
        mean_log[static_cast<std::size_t>(M)] += std::log(err / size + 1e-300) / kTrials;
      }
    }
    // Shrinking with M: geometric mean over the triangles (one triangle's error may stall at a
    // degree whose homogeneous term integrates to nearly zero). Odd terms partly cancel over a
    // triangle centred at its circumcentre, so the rate is checked over two degrees: at most
    // (1.5 eta)^2 (M+5)(M+6)/((M+2)(M+3)), the pointwise rate squared, while above rounding.
    for (int M = 0; M + 2 <= kMmax; ++M) {
      const double e0 = mean_log[static_cast<std::size_t>(M)], e1 = mean_log[static_cast<std::size_t>(M) + 1],
                   e2 = mean_log[static_cast<std::size_t>(M) + 2];
      if (e2 < std::log(1e-13)) break;
      EXPECT_LT(e1, e0) << "eta " << eta << " M " << M;
      EXPECT_LE(std::exp(e2 - e0), 2.25 * eta * eta * (M + 5) * (M + 6) / ((M + 2) * (M + 3)))
          << "eta " << eta << " M " << M;
    }
  }
}

// No NaN/Inf and the bound holds for every M up to 12 at eta up to 0.5, including P close to the
// cluster's plane and nP nearly parallel to it.
TEST(FarField, StableUpToDegreeTwelve) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Tri t = random_triangle(rng);
    Config c = admissible_config(rng, t, 0.5 * (0.2 + 0.8 * unit(rng)));
    if (trial % 3 == 1) {  // P nearly in the plane of the cluster
      const Vec3 d = c.P - c.frame.origin;
      c.P = c.frame.origin + (d - d.dot(c.frame.normal) * c.frame.normal * (1 - 1e-6)).normalized() * c.rho;
    }
    if (trial % 3 == 2) c.nP = (c.nP - c.nP.dot(c.frame.normal) * c.frame.normal * (1 - 1e-9)).normalized();
    const double R = (t.a - c.frame.origin).norm();
    const double area = 0.5 * (t.b - t.a).cross(t.c - t.a).norm();
    const double ref = composite_reference(t, 2, [&](const Vec3& Q) { return exact_G(c.P, c.nP, Q, c.frame.normal); });
    for (int M = 0; M <= panelrad::kMaxTaylorDegree; ++M) {
      const double approx = far_field_integral(c, t, M);
      ASSERT_TRUE(std::isfinite(approx)) << "trial " << trial << " M " << M;
      // Reference error (2 levels, 10x10 points) is far below the bound's rounding allowance.
      EXPECT_LE(std::abs(approx - ref), area * taylor_error_bound(c, M, R)) << "trial " << trial << " M " << M;
    }
  }
}

// (c) Translating P, A and the triangle by (1e6, -1e6, 1e6) leaves sum c_pq m_pq unchanged to the
// rounding of the input coordinates (~1e6 * eps / |P-A| ~ 1e-10 relative).
TEST(FarField, TranslationInvariant) {
  std::mt19937_64 rng(29);
  const Vec3 shift(1e6, -1e6, 1e6);
  for (int trial = 0; trial < 20; ++trial) {
    const Tri t = random_triangle(rng);
    const Config c = admissible_config(rng, t, 0.3);
    const Tri ts{t.a + shift, t.b + shift, t.c + shift};
    Config cs = c;
    cs.P = c.P + shift;
    cs.frame = panelrad::make_plane_frame(circumcentre(ts), inner_normal(ts));
    for (const int M : {2, 8, 12}) {
      const double v0 = far_field_integral(c, t, M), v1 = far_field_integral(cs, ts, M);
      const double R = (t.a - c.frame.origin).norm();
      const double area = 0.5 * (t.b - t.a).cross(t.c - t.a).norm();
      // Relative to the integral's natural size (area times the kernel scale), as G may change sign.
      const double size = area * kernel_scale(c, R) + std::abs(v0);
      EXPECT_NEAR(v1, v0, 1e-9 * size) << "trial " << trial << " M " << M;
    }
  }
}

// Int_T G dS is invariant under scaling (G ~ length^-2, dS ~ length^2): the scene scaled by 1e-6
// and by 1e6 gives the same sum c_pq m_pq up to rounding, also at M = 12 (the unscaled
// coefficients then reach |P-A|^-14 ~ 1e84 without overflow).
TEST(FarField, ScaleInvariant) {
  std::mt19937_64 rng(37);
  for (int trial = 0; trial < 20; ++trial) {
    const Tri t = random_triangle(rng);
    const Config c = admissible_config(rng, t, 0.4);
    for (const double s : {1e-6, 1e6}) {
      const Tri ts{s * t.a, s * t.b, s * t.c};
      Config cs = c;
      cs.P = s * c.P;
      cs.frame = panelrad::make_plane_frame(circumcentre(ts), inner_normal(ts));
      const double R = (t.a - c.frame.origin).norm();
      const double size = 0.5 * (t.b - t.a).cross(t.c - t.a).norm() * kernel_scale(c, R);
      for (const int M : {2, 8, 12}) {
        const double v0 = far_field_integral(c, t, M), v1 = far_field_integral(cs, ts, M);
        ASSERT_TRUE(std::isfinite(v1));
        // Only rounding differs (scaling by s is inexact in the last bit of each input).
        EXPECT_NEAR(v1, v0, 1e-12 * size) << "trial " << trial << " scale " << s << " M " << M;
      }
    }
  }
}

TEST(FarField, FrameIsOrthonormalAndDependsOnTheNormalOnly) {
  std::mt19937_64 rng(31);
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 n = random_unit(rng);
    const PlaneFrame f = panelrad::make_plane_frame(Vec3(1, 2, 3), n);
    const PlaneFrame g = panelrad::make_plane_frame(Vec3(-7, 1e6, 0.5), n);
    EXPECT_NEAR(f.e1.norm(), 1, 4 * kEps);
    EXPECT_NEAR(f.e2.norm(), 1, 4 * kEps);
    EXPECT_NEAR(f.e1.dot(f.e2), 0, 4 * kEps);
    EXPECT_NEAR(f.e1.dot(n), 0, 4 * kEps);
    EXPECT_NEAR(f.e2.dot(n), 0, 4 * kEps);
    EXPECT_GT(f.e1.cross(f.e2).dot(n), 0);  // right-handed (e1, e2, normal)
    EXPECT_EQ(f.e1, g.e1);
    EXPECT_EQ(f.e2, g.e2);
  }
}

TEST(FarField, BadInputIsRefused) {
  const PlaneFrame f = panelrad::make_plane_frame(Vec3::Zero(), Vec3(0, 0, 1));
  std::vector<double> c(200);
  EXPECT_THROW(panelrad::kernel_taylor_coefficients(Vec3(0, 0, 1), Vec3(0, 0, -1), f, 13, c.data()), std::invalid_argument);
  EXPECT_THROW(panelrad::kernel_taylor_coefficients(Vec3(0, 0, 1), Vec3(0, 0, -1), f, -1, c.data()), std::invalid_argument);
  EXPECT_THROW(panelrad::kernel_taylor_coefficients(Vec3::Zero(), Vec3(0, 0, -1), f, 2, c.data()), std::invalid_argument);
  EXPECT_THROW(panelrad::kernel_taylor_coefficients(Vec3(NAN, 0, 1), Vec3(0, 0, -1), f, 2, c.data()), std::invalid_argument);
  EXPECT_THROW(panelrad::make_plane_frame(Vec3::Zero(), Vec3::Zero()), std::invalid_argument);
  EXPECT_THROW(panelrad::make_plane_frame(Vec3::Zero(), Vec3(INFINITY, 0, 0)), std::invalid_argument);
  EXPECT_THROW(panelrad::triangle_moments(f, Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 13, c.data()), std::invalid_argument);
  EXPECT_THROW(panelrad::shift_moments_add(c.data(), 0.1, 0.2, 13, c.data() + 100), std::invalid_argument);
}

// A point in the cluster's own plane gets all-zero coefficients ((P-Q).nQ = 0: paper case (a)).
TEST(FarField, CoplanarPointGivesZeroCoefficients) {
  const PlaneFrame f = panelrad::make_plane_frame(Vec3(0.5, 0.5, 0), Vec3(0, 0, 1));
  std::vector<double> c(static_cast<std::size_t>(num_taylor_terms(6)));
  panelrad::kernel_taylor_coefficients(Vec3(5, -3, 0), Vec3(0, 0, 1), f, 6, c.data());
  for (const double v : c) EXPECT_EQ(v, 0.0);
}

}  // namespace

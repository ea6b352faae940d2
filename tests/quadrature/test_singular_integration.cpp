// High-accuracy integration of f(Q) G(P,Q) (manufactured E = u - K u needs 1e-9 relative
// accuracy also when P is close to an edge shared with a neighbouring facet).
#include <panelrad/operator/collocation.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/quadrature/exact_integrals.hpp>
#include <panelrad/quadrature/singular_integration.hpp>
#include <panelrad/quadrature/triangle_rules.hpp>

#include "edge_configurations.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <bit>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

using namespace panelrad::quadrature;

namespace {

using namespace panelrad::testing::edge_triangle;  // the triangle (a, b, c), inner normal nQ = +z

double u_poly(const Vec3& q) { return q.x() * q.x() + q.y() * q.y() + q.z() * q.z(); }  // (31)
double smooth(const Vec3& q) { return std::exp(q.x() - 0.5 * q.y()) + q.x() * q.y(); }

}  // namespace

// f = 1 equals the closed form to 1e-10 relative (requested 1e-11), from 1e-2 to 1e-7 away from
// the shared edge, for dihedral angles 90, 60 and 150 degrees, and near a corner.
TEST(SingularIntegration, ConstantMatchesClosedFormNearSharedEdge) {
  const auto one = [](const Vec3&) { return 1.0; };
  for (double alpha : {90.0, 60.0, 150.0})
    for (double x : {0.3, 0.999, -0.01})
      for (double dist = 1e-2; dist >= 0.99e-7; dist /= 10) {
        const Neighbour nb = neighbour_point(alpha, x, dist);
        const double ff = form_factor(nb.P, nb.nP, a, b, c, nQ);
        const SingularIntegralResult r =
            integrate_kernel_times(one, nb.P, nb.nP, a, b, c, nQ, 1e-11);
        EXPECT_GT(ff, 0);
        EXPECT_NEAR(r.value, ff, 1e-10 * ff)
            << "alpha " << alpha << " x " << x << " dist " << dist << " evals " << r.evaluations;
        EXPECT_LT(r.error_estimate, 1e-10 * ff);
        EXPECT_GT(r.evaluations, 0);
      }
}

// Far P (both branches: well separated and moderately close): polynomial and smooth f against a
// very fine composite Stroud rule (6 levels, 28672 points; its error ~ (size/dist)^6 tiny here).
TEST(SingularIntegration, PolynomialAgainstFineCompositeRuleFarAway) {
  for (const Vec3& P : {Vec3(0.4, 0.3, 3.0), Vec3(0.2, 0.2, 0.8), Vec3(-0.5, 0.4, 0.6)}) {
    const Vec3 nP = Vec3(0.1, 0.05, -1).normalized();
    for (auto f : {&u_poly, &smooth}) {
      const double ref =
          integrate_composite(stroud_t2_5_1(), a, b, c, 6, [&](const Vec3& Q) {
            const Vec3 d = Q - P;
            const double r2 = d.squaredNorm();
            return f(Q) * d.dot(nP) * (-d.dot(nQ)) / (r2 * r2);
          }) / kPi;
      const SingularIntegralResult r = integrate_kernel_times(f, P, nP, a, b, c, nQ, 1e-11);
      EXPECT_NEAR(r.value, ref, 1e-10 * std::abs(ref)) << "P " << P.transpose();
    }
  }
}

// Near P: self-convergence. Tightening rel_tol changes the value by less than the looser
// tolerance, and the reported error estimate covers the change.
TEST(SingularIntegration, SelfConvergenceNearEdge) {
  for (double alpha : {90.0, 60.0, 150.0})
    for (double dist : {1e-3, 1e-6}) {
      const Neighbour nb = neighbour_point(alpha, 0.4, dist);
      for (auto f : {&u_poly, &smooth}) {
        const double fine = integrate_kernel_times(f, nb.P, nb.nP, a, b, c, nQ, 1e-12).value;
        for (double tol : {1e-6, 1e-8, 1e-10}) {
          const SingularIntegralResult r = integrate_kernel_times(f, nb.P, nb.nP, a, b, c, nQ, tol);
          EXPECT_NEAR(r.value, fine, tol * std::abs(fine))
              << "alpha " << alpha << " dist " << dist << " tol " << tol;
          EXPECT_LE(std::abs(r.value - fine), std::max(r.error_estimate, 1e-14 * std::abs(fine)));
        }
      }
    }
}

// The polynomial integral near the edge also agrees with its exact decomposition for f linear
// in the coordinate along the edge: by symmetry about x = x0, Int (x - x0) G is small, and
// Int (2 + (x - x0)) G = 2 F + Int (x - x0) G: linearity check at full accuracy.
TEST(SingularIntegration, LinearityAgainstClosedForm) {
  const Neighbour nb = neighbour_point(60.0, 0.4, 1e-5);
  const double ff = form_factor(nb.P, nb.nP, a, b, c, nQ);
  const auto lin = [](const Vec3& q) { return q.x() - 0.4; };
  const auto aff = [](const Vec3& q) { return 2 + (q.x() - 0.4); };
  const double vl = integrate_kernel_times(lin, nb.P, nb.nP, a, b, c, nQ, 1e-12).value;
  const double va = integrate_kernel_times(aff, nb.P, nb.nP, a, b, c, nQ, 1e-12).value;
  EXPECT_NEAR(va, 2 * ff + vl, 1e-11 * va);
}

TEST(SingularIntegration, CoplanarIsZero) {
  const auto one = [](const Vec3&) { return 1.0; };
  const SingularIntegralResult r =
      integrate_kernel_times(one, Vec3(2, 3, 0), Vec3(0, 1, 0), a, b, c, nQ);
  EXPECT_EQ(r.value, 0.0);
  EXPECT_EQ(r.evaluations, 0);
}

TEST(SingularIntegration, BadInputIsAClearError) {
  const auto one = [](const Vec3&) { return 1.0; };
  const Vec3 P(0.3, 0.3, 1), nP(0, 0, -1);
  EXPECT_THROW(integrate_kernel_times({}, P, nP, a, b, c, nQ), std::invalid_argument);
  EXPECT_THROW(integrate_kernel_times(one, P, nP, a, b, c, nQ, 0.0), std::invalid_argument);
  EXPECT_THROW(integrate_kernel_times(one, P, nP, a, b, c, nQ, -1.0), std::invalid_argument);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(integrate_kernel_times(one, Vec3(nan, 0, 1), nP, a, b, c, nQ),
               std::invalid_argument);
  EXPECT_THROW(integrate_kernel_times(one, P, nP, a, b, Vec3(2, 0, 0), nQ),
               std::invalid_argument);  // collinear vertices: zero area
  const auto bad = [nan](const Vec3&) { return nan; };
  EXPECT_THROW(integrate_kernel_times(bad, P, nP, a, b, c, nQ), std::runtime_error);
}

// P hanging very close over the interior of the triangle (a thin slab): the polar pieces around
// the foot of P. f = 1 against the closed form, requested 1e-11, checked to 1e-10.
TEST(SingularIntegration, ConstantMatchesClosedFormOverInterior) {
  const auto one = [](const Vec3&) { return 1.0; };
  for (double hgt : {1e-2, 1e-4, 1e-7}) {
    const Vec3 P(0.3, 0.25, hgt), nP(0.2, 0.1, -1.0);
    const Vec3 nPn = nP.normalized();
    const double ff = form_factor(P, nPn, a, b, c, nQ);
    const SingularIntegralResult r = integrate_kernel_times(one, P, nPn, a, b, c, nQ, 1e-11);
    EXPECT_NEAR(r.value, ff, 1e-10 * std::abs(ff)) << "height " << hgt;
    EXPECT_LT(r.error_estimate, 1e-10 * std::abs(ff)) << "height " << hgt;
  }
}

// Manufactured E on the paper's cube at level 2 (192 collocation points). For u = 1, K u = 1 on a
// closed convex surface (the form factors of all facets sum to 1), so E = 1 - rho exactly: the
// integration (1e-11 requested, summed over 10 triangles) must match to 1e-11 of E >= 0.5.
TEST(SingularIntegration, CubeEmissivityForConstantSolutionIsOneMinusRho) {
  panelrad::Scene scene = panelrad::make_paper_cube_scene();
  scene.set_manufactured_solution([](const Vec3&, panelrad::Index) { return 1.0; }, 1e-11);
  const panelrad::Collocation col(scene, 2);
  ASSERT_EQ(col.size(), 192);
  for (panelrad::Index i = 0; i < col.size(); ++i)
    EXPECT_NEAR(col.emissivity()[i], 1.0 - col.reflectivity()[i], 1e-11) << "point " << i;
}

// For u = x^2 + y^2 + z^2 (31): self-convergence. E with rel_tol 1e-9 (the accuracy required
// of E) differs from E with 1e-12 by less than 1e-9 relative at every point.
TEST(SingularIntegration, CubeEmissivitySelfConvergence) {
  const auto u = [](const Vec3& q, panelrad::Index) { return q.squaredNorm(); };
  panelrad::Scene coarse = panelrad::make_paper_cube_scene();
  panelrad::Scene fine = panelrad::make_paper_cube_scene();
  coarse.set_manufactured_solution(u, 1e-9);
  fine.set_manufactured_solution(u, 1e-12);
  const panelrad::Collocation cc(coarse, 2), cf(fine, 2);
  ASSERT_EQ(cc.size(), cf.size());
  for (panelrad::Index i = 0; i < cc.size(); ++i)
    EXPECT_NEAR(cc.emissivity()[i], cf.emissivity()[i], 1e-9 * std::abs(cf.emissivity()[i]))
        << "point " << i;
}

// P on a neighbouring facet folded by a tiny angle t against the triangle's plane (t = 0:
// coplanar): the facet spans direction (0, -cos t, sin t) from the edge y = z = 0, P at
// distance d from it. With axis-aligned data h = d sin t is exact to rounding, so the value must
// equal the closed-form form factor (~ t^2/4, down to 1e-31) to 1e-10 relative, in a bounded
// number of evaluations (a few pieces per halving of d; measured 44258 at d = 1e-6).
TEST(SingularIntegration, NearlyCoplanarNeighbourMatchesClosedForm) {
  const auto one = [](const Vec3&) { return 1.0; };
  const Vec3 c2(0.3, 1, 0);
  for (double t : {1e-15, -1e-15, 1e-13, -1e-13, 1e-11, 1e-8, 1e-4})
    for (double d : {1e-1, 1e-3, 1e-6}) {
      const Vec3 P = Vec3(0.4, 0, 0) + d * Vec3(0, -std::cos(t), std::sin(t));
      const Vec3 nP(0, std::sin(t), std::cos(t));
      const double ff = form_factor(P, nP, a, b, c2, nQ);
      const SingularIntegralResult r = integrate_kernel_times(one, P, nP, a, b, c2, nQ, 1e-11);
      EXPECT_GT(ff, 0) << "t " << t << " d " << d;
      EXPECT_NEAR(r.value, ff, 1e-10 * ff) << "t " << t << " d " << d;
      EXPECT_LT(r.evaluations, 200000) << "t " << t << " d " << d;
    }
}

// The same configurations rotated about (1, 2, 3) by 0.7 rad: every coordinate and normal is
// rounded, so for t = 0 (exactly coplanar data before rounding) h is 1e-17 rounding noise, not 0,
// and so is the integrand's factor (Q - P).nP. The integration must end at the rounding level
// (not at the 5e7 evaluation cap) with a value negligible against the row sum 1 of a closed
// surface: the exact values are below t^2/4 + 1e-31 < 1e-26, so 1e-20 leaves room only for
// rounding. For u = x^2 + y^2 + z^2 + 1 likewise (|u| <= 4 here).
TEST(SingularIntegration, CoplanarWithinRoundingEndsAtTheRoundingLevel) {
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Vec3 ra = R * a, rb = R * b, rc = R * Vec3(0.3, 1, 0), rnQ = (R * nQ).normalized();
  const auto one = [](const Vec3&) { return 1.0; };
  const auto u1 = [](const Vec3& q) { return q.squaredNorm() + 1; };
  for (double t : {0.0, 1e-15, -1e-15, 1e-13, -1e-13})
    for (double d : {1e-1, 1e-3, 1e-6}) {
      const Vec3 P = R * (Vec3(0.4, 0, 0) + d * Vec3(0, -std::cos(t), std::sin(t)));
      const Vec3 nP = (R * Vec3(0, std::sin(t), std::cos(t))).normalized();
      for (const auto& f : {std::function<double(const Vec3&)>(one), std::function<double(const Vec3&)>(u1)}) {
        SingularIntegralResult r;
        ASSERT_NO_THROW(r = integrate_kernel_times(f, P, nP, ra, rb, rc, rnQ, 1e-11))
            << "t " << t << " d " << d;
        EXPECT_LT(std::abs(r.value), 1e-20) << "t " << t << " d " << d;
        EXPECT_LT(r.evaluations, 200000) << "t " << t << " d " << d;
      }
    }
}

// A genuinely impossible request (f = 1 or 1.5 by a hash of the bits of Q: discontinuous
// everywhere, no rule resolves it) still stops at the evaluation cap with an error naming the
// cap, the tolerance, P and the triangle.
TEST(SingularIntegration, UnresolvableIntegrandIsAClearError) {
  const auto wild = [](const Vec3& q) {
    const std::uint64_t bits = std::bit_cast<std::uint64_t>(q.x()) ^
                               (std::bit_cast<std::uint64_t>(q.y()) * 0x9E3779B97F4A7C15ull);
    return 1.0 + 0.5 * static_cast<double>((bits * 0xBF58476D1CE4E5B9ull) >> 63);
  };
  const Neighbour nb = neighbour_point(90.0, 0.4, 1e-3);
  try {
    integrate_kernel_times(wild, nb.P, nb.nP, a, b, c, nQ, 1e-11);
    FAIL() << "no error for an unresolvable integrand";
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("more than 50000000 evaluations"), std::string::npos) << msg;
    EXPECT_NE(msg.find("rel_tol 1e-11"), std::string::npos) << msg;
    EXPECT_NE(msg.find("P = (0.4"), std::string::npos) << msg;
    EXPECT_NE(msg.find("triangle (0, 0, 0)"), std::string::npos) << msg;
  }
}

#include <panelrad/quadrature/singular_integration.hpp>
#include <panelrad/quadrature/exact_integrals.hpp>
#include <panelrad/quadrature/triangle_rules.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace panelrad::quadrature {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInvPi = 0.31830988618379067154;
constexpr long kMaxEvaluations = 50'000'000;

std::string vec_str(const Vec3& v) {
  std::ostringstream s;
  s.precision(17);
  s << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return s.str();
}

// ------------------------------------------------------------------------------------------------
// Adaptive Gauss-Kronrod (7-point Gauss, 15-point Kronrod), globally adaptive on the interval
// with the largest error estimate (the QUADPACK QAG scheme and its error scaling).
constexpr std::array<double, 8> kXgk = {
    0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
    0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
    0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
    0.207784955007898467600689403773245, 0.000000000000000000000000000000000};
constexpr std::array<double, 8> kWgk = {
    0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
    0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
    0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
    0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr std::array<double, 4> kWg = {  // Gauss weights at kXgk[1], [3], [5], [7]
    0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
    0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

struct Panel {
  double a, b, value, error, l1;
  bool operator<(const Panel& o) const { return error < o.error; }
};

template <class F>
Panel gk15(F& f, double a, double b) {
  const double c = 0.5 * (a + b), hl = 0.5 * (b - a);
  const double fc = f(c);
  double k = fc * kWgk[7], g = fc * kWg[3], l1 = std::abs(fc) * kWgk[7];
  std::array<double, 15> fv{};
  fv[14] = fc;
  for (int j = 0; j < 7; ++j) {
    const double dx = hl * kXgk[static_cast<std::size_t>(j)];
    const double f1 = f(c - dx), f2 = f(c + dx);
    fv[static_cast<std::size_t>(2 * j)] = f1;
    fv[static_cast<std::size_t>(2 * j + 1)] = f2;
    k += kWgk[static_cast<std::size_t>(j)] * (f1 + f2);
    l1 += kWgk[static_cast<std::size_t>(j)] * (std::abs(f1) + std::abs(f2));
    if (j % 2 == 1) g += kWg[static_cast<std::size_t>(j / 2)] * (f1 + f2);
  }
  // QUADPACK's estimate: |K - G| scaled by the variation about the mean (resasc).
  const double mean = 0.5 * k;
  double resasc = kWgk[7] * std::abs(fc - mean);
  for (int j = 0; j < 7; ++j)
    resasc += kWgk[static_cast<std::size_t>(j)] *
              (std::abs(fv[static_cast<std::size_t>(2 * j)] - mean) +
               std::abs(fv[static_cast<std::size_t>(2 * j + 1)] - mean));
  resasc *= std::abs(hl);
  double err = std::abs((k - g) * hl);
  if (resasc != 0 && err != 0) err = resasc * std::min(1.0, std::pow(200.0 * err / resasc, 1.5));
  const double round = 50.0 * std::numeric_limits<double>::epsilon() * l1 * std::abs(hl);
  if (round > err) err = round;
  return {a, b, k * hl, err, l1 * std::abs(hl)};
}

struct Integral1D {
  double value = 0, error = 0, l1 = 0;
};

/// Int_a^b f to max(abs_tol, rel_tol * |value|); at most max_panels panels.
template <class F>
Integral1D adaptive_gk15(F&& f, double a, double b, double rel_tol, double abs_tol,
                         int max_panels = 400) {
  Integral1D r;
  if (!(b > a)) return r;
  std::priority_queue<Panel> heap;
  heap.push(gk15(f, a, b));
  r.value = heap.top().value;
  r.error = heap.top().error;
  r.l1 = heap.top().l1;
  int panels = 1;
  while (r.error > std::max(abs_tol, rel_tol * std::abs(r.value)) && panels < max_panels) {
    const Panel p = heap.top();
    heap.pop();
    const double m = 0.5 * (p.a + p.b);
    if (!(m > p.a && m < p.b)) {  // interval exhausted at double resolution
      heap.push(p);
      break;
    }
    const Panel left = gk15(f, p.a, m), right = gk15(f, m, p.b);
    heap.push(left);
    heap.push(right);
    ++panels;
    r.value = 0;
    r.error = 0;
    r.l1 = 0;
    std::priority_queue<Panel> copy = heap;
    for (; !copy.empty(); copy.pop()) {
      r.value += copy.top().value;
      r.error += copy.top().error;
      r.l1 += copy.top().l1;
    }
  }
  return r;
}

// ------------------------------------------------------------------------------------------------
// Well-separated pairs (dist(P, triangle) >= 2 diam): global adaptive midpoint subdivision of the
// triangle with the embedded pair collapsed Gauss degree 10 / degree 8, in coordinates relative
// to P (so that node positions are accurate relative to their distance from P).
struct Element {
  Vec3 a, b, c;  // relative to P
  double value = 0;
  double error = 0;
  bool operator<(const Element& o) const { return error < o.error; }
};

class SeparatedIntegrator {
 public:
  SeparatedIntegrator(const std::function<double(const Vec3&)>& f, const Vec3& P, const Vec3& nP,
                      double h)
      : f_(f), P_(P), nP_(nP), h_(h), high_(collapsed_gauss_rule(6)),
        low_(collapsed_gauss_rule(5)) {}

  Element evaluate(const Vec3& a, const Vec3& b, const Vec3& c) {
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const double qh = apply(high_, a, b, c) * area;
    const double ql = apply(low_, a, b, c) * area;
    return {a, b, c, qh, std::abs(qh - ql)};
  }
  long evaluations = 0;

 private:
  double apply(const TriangleRule& rule, const Vec3& a, const Vec3& b, const Vec3& c) {
    double s = 0;
    for (std::size_t i = 0; i < rule.size(); ++i) {
      const auto& l = rule.barycentric[i];
      const Vec3 R(l[0] * a + l[1] * b + l[2] * c);  // Q - P
      const double r2 = R.squaredNorm();
      // f(Q) G(P,Q), paper (2), with (P - Q).nQ = h exactly constant
      s += rule.weight[i] * f_(Vec3(P_ + R)) * R.dot(nP_) * h_ / (r2 * r2);
    }
    evaluations += static_cast<long>(rule.size());
    return s;
  }
  const std::function<double(const Vec3&)>& f_;
  Vec3 P_, nP_;
  double h_;
  const TriangleRule& high_;
  const TriangleRule& low_;
};

SingularIntegralResult integrate_separated(const std::function<double(const Vec3&)>& f,
                                           const Vec3& P, const Vec3& nP, const Vec3& a,
                                           const Vec3& b, const Vec3& c, double h, double tol) {
  SeparatedIntegrator integ(f, P, nP, h);
  std::priority_queue<Element> heap;
  heap.push(integ.evaluate(a - P, b - P, c - P));
  double value = heap.top().value, error = heap.top().error, l1 = std::abs(value);
  while (error > tol * std::max(std::abs(value), 0.01 * l1) && integ.evaluations < kMaxEvaluations) {
    const Element e = heap.top();
    heap.pop();
    const Vec3 ab = 0.5 * (e.a + e.b), bc = 0.5 * (e.b + e.c), ca = 0.5 * (e.c + e.a);
    heap.push(integ.evaluate(e.a, ab, ca));
    heap.push(integ.evaluate(ab, e.b, bc));
    heap.push(integ.evaluate(ca, bc, e.c));
    heap.push(integ.evaluate(ab, bc, ca));
    value = error = l1 = 0;
    std::priority_queue<Element> copy = heap;
    for (; !copy.empty(); copy.pop()) {
      value += copy.top().value;
      error += copy.top().error;
      l1 += std::abs(copy.top().value);
    }
  }
  SingularIntegralResult r;
  r.value = value;
  r.error_estimate = error;
  r.evaluations = static_cast<int>(integ.evaluations);
  return r;
}

// ------------------------------------------------------------------------------------------------
// Near pairs: polar coordinates (r, theta) about the foot F = P - h nQ of P on the plane.
// With Q = F + r u(theta), R = Q - P, (P-Q).nQ = h and R.nP = r (u.t) - h nu (t, nu: tangential
// and normal parts of nP), the integrand of (1/pi) Int f G dS is
//   f(Q) [r (u.t) - h nu] h r / (r^2 + h^2)^2  dr dtheta.
// Radially, r <= |h| is integrated in phi = atan(r/|h|) (r dr/(r^2+h^2)^2 = sin phi cos phi/h^2
// dphi, a bounded smooth integrand), r >= |h| in s = ln r (the 1/r^2 tail becomes smooth and
// decaying). In angle, the range is split at the vertex directions; each sector is split in
// half and each half integrated in tau = ln(psi + eps), psi the angle from the sector's end and
// eps the smallest angle there between the ray and an edge line (where the entry/exit distance
// r = e_k/(n_k.u) has its pole): this absorbs the nearly singular behaviour when F is close to
// an edge line or a vertex.
class PolarIntegrator {
 public:
  PolarIntegrator(const std::function<double(const Vec3&)>& f, const Vec3& P, const Vec3& nP,
                  const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& nQ, double h,
                  double tol, double scale)
      : f_(f), h_(h), ah_(std::abs(h)), tol_(tol), scale_(scale) {
    foot_ = P - h * nQ;
    e1_ = (b - a) - (b - a).dot(nQ) * nQ;
    e1_.normalize();
    e2_ = nQ.cross(e1_);
    t1_ = nP.dot(e1_);
    t2_ = nP.dot(e2_);
    nu_ = nP.dot(nQ);
    const Vec3* V[3] = {&a, &b, &c};
    for (int k = 0; k < 3; ++k) {
      const Vec3 w = *V[k] - P;  // in-plane coordinates relative to the foot
      vx_[k] = w.dot(e1_);
      vy_[k] = w.dot(e2_);
    }
    if ((vx_[1] - vx_[0]) * (vy_[2] - vy_[0]) - (vy_[1] - vy_[0]) * (vx_[2] - vx_[0]) < 0) {
      std::swap(vx_[1], vx_[2]);
      std::swap(vy_[1], vy_[2]);
    }
    for (int k = 0; k < 3; ++k) {  // outward edge normals and signed distances of the foot
      const int k1 = (k + 1) % 3;
      const double dx = vx_[k1] - vx_[k], dy = vy_[k1] - vy_[k];
      const double L = std::hypot(dx, dy);
      nx_[k] = dy / L;
      ny_[k] = -dx / L;
      e_[k] = nx_[k] * vx_[k] + ny_[k] * vy_[k];
    }
  }

  SingularIntegralResult run() {
    std::vector<double> angles;
    for (int k = 0; k < 3; ++k)
      if (vx_[k] != 0 || vy_[k] != 0) angles.push_back(std::atan2(vy_[k], vx_[k]));
    std::sort(angles.begin(), angles.end());
    SingularIntegralResult res;
    const std::size_t m = angles.size();
    for (std::size_t i = 0; i < m; ++i) {
      const double alpha = angles[i];
      const double beta = (i + 1 < m) ? angles[i + 1] : angles[0] + 2 * kPi;
      if (!(beta > alpha)) continue;
      const double mid = 0.5 * (alpha + beta);
      double rin, rout;
      ray_interval(std::cos(mid), std::sin(mid), rin, rout);
      if (!(rout > rin)) continue;  // the triangle is not seen in this sector
      const double half = 0.5 * (beta - alpha);
      for (int side = 0; side < 2; ++side) {
        const double end = side == 0 ? alpha : beta;
        const double dir = side == 0 ? 1.0 : -1.0;
        double eps = 1.0;
        for (int k = 0; k < 3; ++k)
          if (e_[k] != 0) eps = std::min(eps, std::abs(nx_[k] * std::cos(end) + ny_[k] * std::sin(end)));
        eps = std::max(eps, 1e-15 * half);
        auto outer = [&](double tau) {
          const double et = std::exp(tau);
          const double psi = std::min(std::max(et - eps, 0.0), half);
          return et * inner(end + dir * psi);
        };
        const Integral1D part = adaptive_gk15(outer, std::log(eps), std::log(half + eps), tol_,
                                              0.125 * tol_ * scale_);
        res.value += part.value;
        // outer estimate, plus the inner integrals' relative tolerance over the L1 norm
        res.error_estimate += part.error + 0.1 * tol_ * part.l1;
      }
    }
    res.evaluations = static_cast<int>(std::min<long>(evaluations_, std::numeric_limits<int>::max()));
    return res;
  }

  long evaluations() const { return evaluations_; }

 private:
  void ray_interval(double ux, double uy, double& rin, double& rout) const {
    rin = 0;
    rout = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k) {
      const double d = nx_[k] * ux + ny_[k] * uy;
      if (d > 0)
        rout = std::min(rout, e_[k] / d);
      else if (d < 0)
        rin = std::max(rin, e_[k] / d);
      else if (e_[k] < 0)
        rout = -1;  // parallel to an edge, outside its half-plane
    }
  }

  // Int over the ray segment inside the triangle of f(Q) G r dr (times 1/h-free factors).
  double inner(double theta) {
    if (evaluations_ > kMaxEvaluations) return 0;
    const double ux = std::cos(theta), uy = std::sin(theta);
    double rin, rout;
    ray_interval(ux, uy, rin, rout);
    if (!(rout > rin)) return 0;
    const Vec3 u = ux * e1_ + uy * e2_;
    const double ut = ux * t1_ + uy * t2_;
    const double sgn = h_ > 0 ? 1.0 : -1.0;
    double total = 0;
    if (rin < ah_) {  // phi = atan(r/|h|): f [sgn(h) (u.t) sin^2 phi - nu sin phi cos phi] dphi
      auto g = [&](double phi) {
        ++evaluations_;
        const double s = std::sin(phi), c = std::cos(phi);
        return f_(Vec3(foot_ + (ah_ * std::tan(phi)) * u)) * (sgn * ut * s * s - nu_ * s * c);
      };
      const Integral1D r = adaptive_gk15(g, std::atan(rin / ah_),
                                         std::atan(std::min(rout, ah_) / ah_), 0.1 * tol_,
                                         inner_abs_tol());
      total += r.value;
    }
    if (rout > ah_) {  // s = ln r: f [r (u.t) - h nu] h r^2 / (r^2 + h^2)^2 ds
      auto g = [&](double s) {
        ++evaluations_;
        const double r = std::exp(s);
        const double q = r * r + h_ * h_;
        return f_(Vec3(foot_ + r * u)) * (r * ut - h_ * nu_) * h_ * r * r / (q * q);
      };
      const Integral1D r =
          adaptive_gk15(g, std::log(std::max(rin, ah_)), std::log(rout), 0.1 * tol_,
                        inner_abs_tol());
      total += r.value;
    }
    return total;
  }

  // Inner integrals are integrated over at most 2 pi of angle: this keeps their summed
  // absolute error below 0.1 tol scale.
  double inner_abs_tol() const { return 0.1 * tol_ * scale_ / (2 * kPi); }

  const std::function<double(const Vec3&)>& f_;
  double h_, ah_, tol_, scale_;
  Vec3 foot_, e1_, e2_;
  double t1_, t2_, nu_;
  double vx_[3], vy_[3], nx_[3], ny_[3], e_[3];
  long evaluations_ = 0;
};

}  // namespace

SingularIntegralResult integrate_kernel_times(const std::function<double(const Vec3&)>& f,
                                              const Vec3& P, const Vec3& nP, const Vec3& a,
                                              const Vec3& b, const Vec3& c, const Vec3& nQ,
                                              double rel_tol) {
  if (!f) throw std::invalid_argument("integrate_kernel_times: the function f is empty");
  if (!(rel_tol > 0) || !std::isfinite(rel_tol))
    throw std::invalid_argument("integrate_kernel_times: rel_tol must be positive and finite, got " +
                                std::to_string(rel_tol));
  if (!P.allFinite() || !nP.allFinite() || !a.allFinite() || !b.allFinite() || !c.allFinite() ||
      !nQ.allFinite())
    throw std::invalid_argument("integrate_kernel_times: non-finite point or normal (P = " +
                                vec_str(P) + ", triangle " + vec_str(a) + " " + vec_str(b) + " " +
                                vec_str(c) + ")");
  if ((b - a).cross(c - a).squaredNorm() == 0)
    throw std::invalid_argument("integrate_kernel_times: degenerate (zero-area) triangle " +
                                vec_str(a) + " " + vec_str(b) + " " + vec_str(c));
  // Below 1e-12 the nested Gauss-Kronrod estimates reach their rounding floor (50 eps of the
  // L1 norm per panel) and cannot certify more: the effective tolerance is max(rel_tol, 1e-12).
  const double tol = std::max(rel_tol, 1e-12);

  SingularIntegralResult result;
  const double h = (P - a).dot(nQ);  // (P - Q).nQ, constant over the plane
  if (h == 0) return result;         // paper 4.2, case (a): the integrand vanishes identically

  const double diam = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  long evaluations = 0;
  if (distance_point_triangle(P, a, b, c) >= 2.0 * diam) {
    result = integrate_separated(f, P, nP, a, b, c, h, tol);
    evaluations = result.evaluations;
  } else {
    // Absolute scale for the tolerances: pi |form factor| (the integral for f = 1) times the
    // largest |f| at the vertices and the centroid; the relative criterion acts as well.
    double fmag = 0;
    for (const Vec3& q : {a, b, c, Vec3((a + b + c) / 3.0)}) fmag = std::max(fmag, std::abs(f(q)));
    if (!(fmag > 0) || !std::isfinite(fmag)) fmag = 1;
    const double scale = kPi * std::abs(form_factor(P, nP, a, b, c, nQ)) * fmag;
    PolarIntegrator polar(f, P, nP, a, b, c, nQ, h, tol, scale);
    result = polar.run();
    evaluations = polar.evaluations();
  }
  result.value *= kInvPi;
  result.error_estimate *= kInvPi;
  if (!std::isfinite(result.value))
    throw std::runtime_error("integrate_kernel_times: non-finite result (f returned NaN/Inf?) for P = " +
                             vec_str(P));
  if (evaluations > kMaxEvaluations)
    throw std::runtime_error("integrate_kernel_times: more than " + std::to_string(kMaxEvaluations) +
                             " evaluations without reaching rel_tol " + std::to_string(rel_tol) +
                             " for P = " + vec_str(P));
  return result;
}

}  // namespace panelrad::quadrature

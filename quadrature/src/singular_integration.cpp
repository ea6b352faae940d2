#include <panelrad/quadrature/singular_integration.hpp>
#include <panelrad/quadrature/exact_integrals.hpp>
#include <panelrad/quadrature/gauss_legendre.hpp>
#include <panelrad/quadrature/triangle_rules.hpp>
#include <panelrad/geometry/subdivision.hpp>

#include <algorithm>
#include <utility>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <queue>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace panelrad::quadrature {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInvPi = 0.31830988618379067154;
constexpr long kMaxEvaluations = 50'000'000;
// 2 log10(rho) n_low = 11: the (n - 2)-point rule of a separated piece is designed for about 11
// digits by the one-dimensional model of separated_order (measured errors are far smaller).
constexpr double kOrderDigits = 5.5;

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
// The largest Gauss-Legendre rule of a separated piece (gauss_legendre.hpp).
constexpr int kMaxGauss = kMaxGaussLegendrePoints;

// ------------------------------------------------------------------------------------------------
// Separated pieces (dist(P, piece) >= kSeparation * diam(piece)): a collapsed (Duffy)
// Gauss-Legendre product rule of n x n points, n chosen from the ratio q = dist / diam, with the
// (n - 2) x (n - 2) rule as its error estimate (an estimate of the lower rule's error, so
// conservative for the n x n value that is kept). For a segment of length D at distance q D from
// the pole of 1/|Q - P|^2, Gauss-Legendre converges like rho^(-2n) with rho = 2q + sqrt(4q^2+1)
// (Bernstein ellipse through the pole). kSeparation = 0.4 was chosen by measuring the evaluation
// count for the paper's cube (0.3 .. 1.0 tried): lower ratios trade subdivisions for orders.
constexpr double kSeparation = 0.4;

int separated_order(double q) {
  const double rho = 2 * q + std::sqrt(4 * q * q + 1);
  const int n = static_cast<int>(std::ceil(kOrderDigits / std::log10(rho))) + 2;
  return std::clamp(n, 4, kMaxGauss);
}

class KernelEvaluator {
 public:
  KernelEvaluator(const std::function<double(const Vec3&)>& f, const Vec3& P, const Vec3& nP,
                  double h)
      : f_(f), P_(P), nP_(nP), h_(h) {}

  /// Int_S f G dS (without 1/pi) over S = P + (a, b, c) with the n x n collapsed rule; the
  /// collapsed vertex is the one farthest from P, so that the rule's rows of n points lie
  /// across the side nearest to P.
  /// `rounding` (optional) receives the scale of the rounding errors of the computed sum:
  /// sum_k |w_k f(Q_k) h| (|R_k.nP| + |R_k|) / r_k^4 times the area factor. The factor
  /// (Q - P).nP is a dot product of a rounded R = Q - P with a rounded unit normal, so each
  /// term carries an absolute error of a few eps |R| |f h| / r^4 whatever |R.nP| is: when the
  /// piece lies (within rounding) in the plane of P, R.nP is rounding noise of that size, and
  /// so is every difference of two rules.
  double collapsed(Vec3 a, Vec3 b, Vec3 c, int n, double* rounding = nullptr) {
    const double da = a.squaredNorm(), db = b.squaredNorm(), dc = c.squaredNorm();
    if (db >= da && db >= dc)
      std::swap(a, b);
    else if (dc >= da && dc >= db)
      std::swap(a, c);
    // Q = a + x (b - a) + x t (c - b), dS = x |(b-a) x (c-b)| dx dt, (x, t) in [0,1]^2.
    const GaussLegendreRule& g = gauss_legendre_01(n);
    const std::vector<double>& x = g.node;
    const std::vector<double>& w = g.weight;
    const Vec3 ba = b - a, cb = c - b;
    double sum = 0, abs_sum = 0;
    for (int i = 0; i < n; ++i) {
      const double xi = x[static_cast<std::size_t>(i)];
      const Vec3 row = a + xi * ba, step = xi * cb;
      double s = 0, sa = 0;
      for (int j = 0; j < n; ++j) {
        const Vec3 R(row + x[static_cast<std::size_t>(j)] * step);  // Q - P
        const double r2 = R.squaredNorm();
        // f(Q) G(P,Q), paper (2), with (P - Q).nQ = h exactly constant
        const double wf = w[static_cast<std::size_t>(j)] * f_(Vec3(P_ + R)) / (r2 * r2);
        const double RnP = R.dot(nP_);
        s += wf * RnP;
        sa += std::abs(wf) * (std::abs(RnP) + std::sqrt(r2));
      }
      sum += w[static_cast<std::size_t>(i)] * xi * s;
      abs_sum += w[static_cast<std::size_t>(i)] * xi * sa;
    }
    evaluations += static_cast<long>(n) * n;
    const double factor = h_ * ba.cross(cb).norm();
    if (rounding) *rounding = std::abs(abs_sum * factor);
    return sum * factor;
  }
  long evaluations = 0;

 private:
  const std::function<double(const Vec3&)>& f_;
  Vec3 P_, nP_;
  double h_;
};

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

// ------------------------------------------------------------------------------------------------
// Hierarchical splitting of the triangle (4-way midpoint subdivision, as the cluster tree) before
// choosing the method: a piece S with dist(P, S) >= kSeparation diam(S) takes the collapsed Gauss
// pair; a piece over which P hangs closely (the foot of P inside S and dist(P, S) <
// kPolarRatio diam(S)) takes the polar method, which costs a few thousand evaluations whatever
// the ratio; other pieces are split, so that P close to an edge of the triangle costs a few
// pieces per halving of the distance. Then, while the summed error estimates exceed
// tol max(|value|, 0.01 sum |piece|), the separated piece with the largest estimate is refined:
// order n + 2 (the n-point value becoming the lower rule), or 4-way split at the largest order.
constexpr double kPolarRatio = 0.05;

struct Piece {
  Vec3 a, b, c;  // relative to P
  double value = 0, error = 0;
  int order = 0;  // n of the n x n collapsed rule used
  double rounding = 0;  // rounding scale of the n x n value (KernelEvaluator::collapsed)
  bool operator<(const Piece& o) const { return error < o.error; }
};

class HierarchicalIntegrator {
 public:
  HierarchicalIntegrator(const std::function<double(const Vec3&)>& f, const Vec3& P,
                         const Vec3& nP, const Vec3& nQ, double h, double tol,
                         double abs_floor)
      : f_(f), P_(P), nP_(nP), nQ_(nQ), h_(h), tol_(tol), abs_floor_(abs_floor),
        kernel_(f, P, nP, h) {}

  SingularIntegralResult run(const Vec3& a, const Vec3& b, const Vec3& c) {
    classify(a - P_, b - P_, c - P_);
    for (;;) {
      // running sums for the stopping test; the result is summed afresh below
      // Stop at the tolerance; also when what remains is the polar pieces' error (controlled
      // inside PolarIntegrator), on a non-finite value (reported by the caller) or at the cap.
      const double target = std::max(tol_ * std::max(std::abs(value_), 0.01 * l1_), abs_floor_);
      if (error_ <= target || error_ - polar_error_ <= 0.1 * target || heap_.empty() ||
          !std::isfinite(error_) || evaluations() > kMaxEvaluations) {
        double value = polar_value_ + frozen_value_, error = polar_error_;
        for (const Piece& p : heap_) {
          value += p.value;
          error += p.error;
        }
        SingularIntegralResult r;
        r.value = value;
        r.error_estimate = error;
        r.evaluations = static_cast<int>(std::min<long>(evaluations(), std::numeric_limits<int>::max()));
        return r;
      }
      std::pop_heap(heap_.begin(), heap_.end());
      const Piece e = heap_.back();
      heap_.pop_back();
      value_ -= e.value;
      error_ -= e.error;
      l1_ -= std::abs(e.value);
      if (e.order + 2 <= kMaxGauss) {  // p-refinement: the previous rule becomes the low one
        double rounding = 0;
        const double high = kernel_.collapsed(e.a, e.b, e.c, e.order + 2, &rounding);
        push(e.a, e.b, e.c, high, std::abs(high - e.value), e.order + 2, rounding,
             std::max(rounding, e.rounding));
      } else {
        refine(e);
      }
    }
  }

  long evaluations() const { return kernel_.evaluations + polar_evaluations_; }

 private:
  // Children of a separated piece are separated too (their ratio dist/diam is at least twice
  // the parent's) and keep at least the parent's order, so that refinement always gains.
  void refine(const Piece& e) {
    for (const auto& t : geometry::midpoint_subdivision(e.a, e.b, e.c)) separated(t[0], t[1], t[2], e.order);
  }

  void split(const Vec3& a, const Vec3& b, const Vec3& c) {
    for (const auto& t : geometry::midpoint_subdivision(a, b, c)) classify(t[0], t[1], t[2]);
  }

  void classify(const Vec3& a, const Vec3& b, const Vec3& c) {
    const double diam = std::sqrt(std::max({(b - a).squaredNorm(), (c - b).squaredNorm(),
                                            (a - c).squaredNorm()}));
    const double dist = distance_point_triangle(Vec3::Zero(), a, b, c);
    if (dist >= kSeparation * diam)
      separated(a, b, c, 0);
    else if (std::abs(h_) < kPolarRatio * diam && foot_depth(a, b, c) >= std::abs(h_))
      polar(a, b, c);
    else
      split(a, b, c);
  }

  // Signed in-plane distance from the foot of P to the boundary of S (positive inside).
  double foot_depth(const Vec3& a, const Vec3& b, const Vec3& c) const {
    const Vec3 foot = -h_ * nQ_;  // relative to P
    const double orient = (b - a).cross(c - a).dot(nQ_) > 0 ? 1.0 : -1.0;
    double depth = std::numeric_limits<double>::infinity();
    for (const auto& [u, v] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}})
      depth = std::min(depth, orient * (v - u).cross(foot - u).dot(nQ_) / (v - u).norm());
    return depth;
  }

  void separated(const Vec3& a, const Vec3& b, const Vec3& c, int min_order) {
    const double diam = std::sqrt(std::max({(b - a).squaredNorm(), (c - b).squaredNorm(),
                                            (a - c).squaredNorm()}));
    const double q = distance_point_triangle(Vec3::Zero(), a, b, c) / diam;
    const int order = std::max(separated_order(q), min_order);
    double rounding = 0, rounding_low = 0;
    const double high = kernel_.collapsed(a, b, c, order, &rounding);
    const double low = kernel_.collapsed(a, b, c, order - 2, &rounding_low);
    push(a, b, c, high, std::abs(high - low), order, rounding, std::max(rounding, rounding_low));
  }

  // A piece whose estimate |high - low| is at the rounding level of the two sums (100 eps of
  // their rounding scales, KernelEvaluator::collapsed) cannot be improved by refinement: it is
  // kept aside (frozen), its estimate still counted. This is what ends the refinement of a
  // piece lying in the plane of P within rounding (a triangle coplanar with P's triangle whose
  // rounded coordinates give h ~ 1e-17 instead of 0): there R.nP, hence every term and every
  // difference of rules, is rounding noise, and no relative criterion could be met.
  void push(const Vec3& a, const Vec3& b, const Vec3& c, double value, double error, int order,
            double rounding, double pair_rounding) {
    if (error <= 100 * std::numeric_limits<double>::epsilon() * pair_rounding) {
      frozen_value_ += value;
      polar_error_ += error;  // not refinable, like the polar pieces
    } else {
      heap_.push_back({a, b, c, value, error, order, rounding});
      std::push_heap(heap_.begin(), heap_.end());
    }
    value_ += value;
    error_ += error;
    l1_ += std::abs(value);
  }

  void polar(const Vec3& a, const Vec3& b, const Vec3& c) {
    const Vec3 A = P_ + a, B = P_ + b, C = P_ + c;
    // Absolute scale for the tolerances: pi |form factor| (the integral for f = 1) times the
    // largest |f| at the vertices and the centroid; the relative criterion acts as well.
    double fmag = 0;
    for (const Vec3& q : {A, B, C, Vec3((A + B + C) / 3.0)}) fmag = std::max(fmag, std::abs(f_(q)));
    polar_evaluations_ += 4;
    if (!(fmag > 0) || !std::isfinite(fmag)) fmag = 1;
    const double scale = kPi * std::abs(form_factor(P_, nP_, A, B, C, nQ_)) * fmag;
    PolarIntegrator integ(f_, P_, nP_, A, B, C, nQ_, h_, 0.5 * tol_, scale);
    const SingularIntegralResult r = integ.run();
    polar_value_ += r.value;
    polar_error_ += r.error_estimate;
    value_ += r.value;
    error_ += r.error_estimate;
    l1_ += std::abs(r.value);
    polar_evaluations_ += integ.evaluations();
  }

  const std::function<double(const Vec3&)>& f_;
  Vec3 P_, nP_, nQ_;
  double h_, tol_, abs_floor_;
  KernelEvaluator kernel_;
  std::vector<Piece> heap_;  // separated pieces, max-heap on the error estimate
  double polar_value_ = 0, polar_error_ = 0;  // pieces not refinable here (polar and frozen)
  double frozen_value_ = 0;
  double value_ = 0, error_ = 0, l1_ = 0;  // running sums over all pieces
  long polar_evaluations_ = 0;
};

// ------------------------------------------------------------------------------------------------
// Quadratic f: the radial integral in closed form (polar coordinates about the foot F of P).
//
// With Q = F + rho u (u a unit vector of the plane), R = Q - P = rho u - h nQ, (P - Q).nQ = h,
// R.nP = rho (u.t) - h nu (t the tangential part of nP, nu = nP.nQ), and f(F + rho u) =
// p0 + rho p1(u) + rho^2 p2(u) for a quadratic f, the integrand of Int f G dS is
//   [p0 + rho p1 + rho^2 p2] (rho (u.t) - h nu) h rho / (rho^2 + h^2)^2  drho dtheta,
// whose radial integral from 0 to L is a combination of J_k(L) = Int_0^L rho^k / (rho^2 + h^2)^2
// drho (k = 1..4), in closed form (with a = |h|, x = L / a):
//   a^2 J_1 = x^2 / (2 (1 + x^2))
//   a   J_2 = (atan x - x / (1 + x^2)) / 2
//       J_3 = (ln(1 + x^2) - x^2 / (1 + x^2)) / 2
//   a^-1 J_4 = x - 3/2 atan x + x / (2 (1 + x^2)).
// The triangle is the signed sum of the triangles (F, v_k, v_k+1) over its edges; on each,
// with d the distance from F to the edge's line and tau = d sinh(w) the position along the line
// from the foot of F, the angle is theta = gd(w) (dtheta = sech w dw) and L = d cosh w. In w the
// angular integrand is analytic in the strip |Im w| < pi/2 whatever d / a and d / |edge| (the
// singularities of L^2 + h^2 = 0, of sech w, of atan(L/a) and of ln(L^2 + h^2) all lie on
// Im w = +-pi/2), so that Gauss-Legendre panels (gauss_panels) converge fast also when F is
// close to an edge line or a vertex (P close to the triangle's edge).

// The radial integrals above, by their power series for x < 0.2 (the closed forms cancel there:
// a J_2 ~ x^3/3, J_3 ~ x^4/4, J_4 / a ~ x^5/5).
struct RadialIntegrals {
  double a2J1, aJ2, J3, J4_a;
};

// Coefficients of the series in y = x^2 (k = 1..12; 0.2^2 = 0.04 and 0.04^12 < 1e-16):
// a J_2 = x sum_k (-1)^(k+1) k/(2k+1) y^k, J_3 = 1/2 sum_(k>=2) (-1)^k (k-1)/k y^k,
// J_4 / a = x sum_(k>=2) (-1)^k (k-1)/(2k+1) y^k.
constexpr int kSeriesTerms = 12;
constexpr std::array<double, kSeriesTerms + 1> series_coefficients(int which) {
  std::array<double, kSeriesTerms + 1> c{};
  for (int k = 1; k <= kSeriesTerms; ++k) {
    const double sg = (k % 2 == 0) ? 1.0 : -1.0;
    if (which == 2) c[static_cast<std::size_t>(k)] = -sg * k / (2.0 * k + 1);
    if (which == 3) c[static_cast<std::size_t>(k)] = 0.5 * sg * (k - 1) / k;
    if (which == 4) c[static_cast<std::size_t>(k)] = sg * (k - 1) / (2.0 * k + 1);
  }
  return c;
}
constexpr auto kSeries2 = series_coefficients(2), kSeries3 = series_coefficients(3),
               kSeries4 = series_coefficients(4);

// The closed forms lose about log10(3 / x^2) digits to cancellation: 2 digits at the switch
// x = 0.2, on terms that are then small against the integral's scale.
RadialIntegrals radial_integrals(double x) {
  RadialIntegrals r;
  const double x2 = x * x, q = 1 / (1 + x2);
  r.a2J1 = 0.5 * x2 * q;
  if (x < 0.2) {
    double s2 = 0, s3 = 0, s4 = 0;
    for (int k = kSeriesTerms; k >= 1; --k) {  // Horner in y = x^2
      s2 = (s2 + kSeries2[static_cast<std::size_t>(k)]) * x2;
      s3 = (s3 + kSeries3[static_cast<std::size_t>(k)]) * x2;
      s4 = (s4 + kSeries4[static_cast<std::size_t>(k)]) * x2;
    }
    r.aJ2 = x * s2;
    r.J3 = s3;
    r.J4_a = x * s4;
  } else {  // with q = 1 / (1 + x^2): x^2 q = 1 - q
    const double at = std::atan(x);
    r.aJ2 = 0.5 * (at - x * q);
    r.J3 = 0.5 * (std::log1p(x2) - 1 + q);
    r.J4_a = x - 1.5 * at + 0.5 * x * q;
  }
  return r;
}

// Int_w0^w1 g by Gauss-Legendre panels of kGaussPoints points and length <= kPanelLength, a
// panel whose estimate exceeds its share (by length) of max(abs_tol, rel_tol |value|) halved.
// The estimate uses what is known of g: it is analytic in the strip |Im w| < pi/2 (its
// singularities are the isolated points Re w = 0 and +-asinh(|h| / d) of Im w = +-pi/2). On a
// panel of length len the Bernstein ellipse with semi-minor axis 3/4 of the strip's
// (b = 0.75 pi / len in the panel's variable on [-1, 1], rho = b + sqrt(1 + b^2)) lies inside
// it, and for |g| <= M there the n-point rule's error is at most (64/15) M rho^(-2n) /
// (rho^2 - 1) times len/2 (Trefethen, Approximation Theory and Approximation Practice,
// Thm 19.3). M is estimated from the rule's own values: the Legendre coefficients c_k of the
// interpolant (k = n-4 .. n-1, four to see past parity) obey |c_k| <= (2k + 1) M rho^(-k), and
// M = max |c_k| rho^k (without the factor 1/(2k+1): conservative). Plus the rounding floor
// 50 eps Int |g|. kPanelLength = 2.5 and n = 14 were chosen by measuring the evaluation count
// on the paper's cube (lengths 1.5 .. 3, n = 12 .. 18 and the pairs (8, 12) .. (14, 18) with
// |G_high - G_low| as the estimate tried; the pairs cost 60 % more); the errors against a
// reference of panels 0.4 long with 28 points were below 5e-15 of the integral.
constexpr double kPanelLength = 2.5;
constexpr int kGaussPoints = 14;

// Rows of the Legendre coefficients c_(n-4) .. c_(n-1) from the n Gauss values:
// c_k = (2k + 1)/2 sum_j W_j P_k(t_j) g_j, t_j the nodes on [-1, 1], W_j = 2 w_j.
const std::array<std::array<double, 4>, kGaussPoints>& legendre_tail_rows() {
  static const std::array<std::array<double, 4>, kGaussPoints> rows = [] {
    const GaussLegendreRule& r = gauss_legendre_01(kGaussPoints);
    std::array<std::array<double, 4>, kGaussPoints> m{};
    for (std::size_t j = 0; j < static_cast<std::size_t>(kGaussPoints); ++j) {
      const double t = 2 * r.node[j] - 1;
      std::array<double, kGaussPoints> P{};
      P[0] = 1;
      P[1] = t;
      for (int k = 2; k < kGaussPoints; ++k)  // Bonnet's recurrence
        P[static_cast<std::size_t>(k)] = ((2 * k - 1) * t * P[static_cast<std::size_t>(k - 1)] -
                                          (k - 1) * P[static_cast<std::size_t>(k - 2)]) / k;
      for (std::size_t i = 0; i < 4; ++i) {
        const int k = kGaussPoints - 4 + static_cast<int>(i);
        m[j][i] = (2 * k + 1) * r.weight[j] * P[static_cast<std::size_t>(k)];
      }
    }
    return m;
  }();
  return rows;
}

template <class G>
Integral1D gauss_panels(G& g, double w0, double w1, double rel_tol, double abs_tol,
                        int& evaluations) {
  Integral1D r;
  if (!(w1 > w0)) return r;
  const GaussLegendreRule& rule_01 = gauss_legendre_01(kGaussPoints);
  const auto& tail = legendre_tail_rows();
  struct Panel1 {
    double a, b, value, error, l1;
  };
  auto rule = [&](double a, double b) {
    const double len = b - a;
    double value = 0, l1 = 0;
    std::array<double, 4> c{};
    for (std::size_t j = 0; j < static_cast<std::size_t>(kGaussPoints); ++j) {
      const double v = g(a + len * rule_01.node[j]);
      value += rule_01.weight[j] * v;
      l1 += rule_01.weight[j] * std::abs(v);
      for (std::size_t i = 0; i < 4; ++i) c[i] += tail[j][i] * v;
    }
    evaluations += kGaussPoints;
    const double bp = 0.75 * kPi / len, rho = bp + std::sqrt(1 + bp * bp);
    double rn = 1;  // rho^(n - 4)
    for (int k = 0; k < kGaussPoints - 4; ++k) rn *= rho;
    double M = 0, rk = rn;
    for (std::size_t i = 0; i < 4; ++i, rk *= rho) M = std::max(M, std::abs(c[i]) * rk);
    // rk = rho^n now
    const double bound = 0.5 * len * (64.0 / 15.0) * M / (rk * rk * (rho * rho - 1));
    const double round = 50.0 * std::numeric_limits<double>::epsilon() * l1 * len;
    return Panel1{a, b, value * len, std::max(bound, round), l1 * len};
  };
  const double total = w1 - w0;
  const int m = std::max(1, static_cast<int>(std::ceil(total / kPanelLength)));
  std::vector<Panel1> done, work;
  for (int i = 0; i < m; ++i)
    work.push_back(rule(w0 + total * i / m, i + 1 == m ? w1 : w0 + total * (i + 1) / m));
  double value = 0;
  for (const Panel1& p : work) value += p.value;
  // At most kMaxPanels panels (then the part is reported as not converged by its estimate).
  constexpr std::size_t kMaxPanels = 256;
  for (int round = 0; !work.empty() && round < 30; ++round) {
    if (done.size() + 2 * work.size() > kMaxPanels) break;
    const double target = std::max(abs_tol, rel_tol * std::abs(value));
    std::vector<Panel1> next;
    for (const Panel1& p : work) {
      const double mid = 0.5 * (p.a + p.b);
      if (p.error <= target * (p.b - p.a) / total || !(mid > p.a && mid < p.b)) {
        done.push_back(p);
        continue;
      }
      value -= p.value;
      next.push_back(rule(p.a, mid));
      next.push_back(rule(mid, p.b));
      value += next[next.size() - 2].value + next.back().value;
    }
    work.swap(next);
  }
  for (const auto* list : {&done, &work})
    for (const Panel1& p : *list) {
      r.value += p.value;
      r.error += p.error;
      r.l1 += p.l1;
    }
  return r;
}

// Points where f - p is checked (barycentric): the centroid, (0.6, 0.2, 0.2) and
// (0.1, 0.45, 0.45) with their permutations. None is a quadratic Lagrange node, and a cubic or
// higher part of f (such as the bubble l1 l2 l3, zero at all the nodes) shows there.
constexpr double kQuadraticCheckPoints[7][3] = {{1.0 / 3, 1.0 / 3, 1.0 / 3}, {0.6, 0.2, 0.2},
                                                {0.2, 0.6, 0.2},             {0.2, 0.2, 0.6},
                                                {0.1, 0.45, 0.45},           {0.45, 0.1, 0.45},
                                                {0.45, 0.45, 0.1}};

class QuadraticPolarIntegrator {
 public:
  // values: f at a, b, c and at the midpoints of a-b, b-c, c-a (the quadratic Lagrange nodes).
  QuadraticPolarIntegrator(const std::array<double, 6>& values, const Vec3& P, const Vec3& nP,
                           const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& nQ, double h)
      : h_(h), ah_(std::abs(h)) {
    const Vec3 foot = P - h * nQ;
    foot_ = foot;
    nQ_ = nQ;
    // The rounding error of the foot, foot + foot_error_ = P - h nQ exactly (for the h
    // computed): the product's by fma, the difference's by Knuth's two-sum.
    for (int i = 0; i < 3; ++i) {
      const double prod = h * nQ[i], eprod = std::fma(h, nQ[i], -prod);
      const double s = P[i] - prod, bb = s - P[i];
      const double esum = (P[i] - (s - bb)) + (-prod - bb);
      foot_error_[i] = esum - eprod;
    }
    Vec3 e1 = (b - a) - (b - a).dot(nQ) * nQ;
    e1.normalize();
    const Vec3 e2 = nQ.cross(e1);
    e1_ = e1;
    e2_ = e2;
    V_[0] = a;
    V_[1] = b;
    V_[2] = c;
    fmax_ = 0;
    for (double v : values) fmax_ = std::max(fmax_, std::abs(v));
    t_[0] = nP.dot(e1);
    t_[1] = nP.dot(e2);
    nu_ = nP.dot(nQ);
    const Vec3* V[3] = {&a, &b, &c};
    for (int k = 0; k < 3; ++k) {
      const Vec3 w = *V[k] - foot;
      v_[k][0] = w.dot(e1);
      v_[k][1] = w.dot(e2);
    }
    // p(xi, eta) = c0 + c1 xi + c2 eta + c3 xi^2 + c4 xi eta + c5 eta^2 from the Lagrange form
    // sum_i f_i l_i (2 l_i - 1) + sum_(i<j) 4 f_ij l_i l_j, l_i the barycentric coordinates
    // (affine in xi, eta: l_i = al_i + be_i xi + ga_i eta).
    const double det = (v_[1][0] - v_[0][0]) * (v_[2][1] - v_[0][1]) -
                       (v_[1][1] - v_[0][1]) * (v_[2][0] - v_[0][0]);
    std::array<std::array<double, 3>, 3> l{};  // l[i] = {al, be, ga}
    for (int i = 0; i < 3; ++i) {
      const auto& p = v_[(i + 1) % 3];
      const auto& q = v_[(i + 2) % 3];
      // l_i(x) = cross(q - p, x - p) / det, orientation as (v0, v1, v2)
      l[i][1] = -(q[1] - p[1]) / det;
      l[i][2] = (q[0] - p[0]) / det;
      l[i][0] = -(l[i][1] * p[0] + l[i][2] * p[1]);
    }
    auto product = [](const std::array<double, 3>& u, const std::array<double, 3>& w) {
      return std::array<double, 6>{u[0] * w[0], u[0] * w[1] + u[1] * w[0],
                                   u[0] * w[2] + u[2] * w[0], u[1] * w[1],
                                   u[1] * w[2] + u[2] * w[1], u[2] * w[2]};
    };
    coef_.fill(0);
    for (int i = 0; i < 3; ++i) {
      const auto sq = product(l[i], l[i]);
      for (int m = 0; m < 6; ++m) coef_[m] += values[i] * 2 * sq[m];
      for (int m = 0; m < 3; ++m) coef_[m] -= values[i] * l[i][m];
    }
    const int pair[3][2] = {{0, 1}, {1, 2}, {2, 0}};
    for (int e = 0; e < 3; ++e) {
      const auto pr = product(l[pair[e][0]], l[pair[e][1]]);
      for (int m = 0; m < 6; ++m) coef_[m] += 4 * values[3 + e] * pr[m];
    }
    if (det < 0) {  // counter-clockwise for the signed decomposition below
      std::swap(v_[1], v_[2]);
      std::swap(V_[1], V_[2]);
    }
  }

  /// Int f G dS (without 1/pi); l1 = sum of |signed parts|, error = summed estimates.
  /// Over the triangle (a, b, c) of the constructor.
  SingularIntegralResult run(double tol, double abs_tol, double& l1) {
    const std::array<std::pair<Vec3, Vec3>, 3> edges = {
        std::pair{V_[0], V_[1]}, std::pair{V_[1], V_[2]}, std::pair{V_[2], V_[0]}};
    return run(edges, tol, abs_tol, l1);
  }

  /// Over the polygon bounded by `edges` (directed segments, counter-clockwise about nQ, in
  /// the triangle's plane), with the same quadratic p: the signed sum of (F, A, B).
  SingularIntegralResult run(std::span<const std::pair<Vec3, Vec3>> edges, double tol,
                             double abs_tol, double& l1) {
    SingularIntegralResult res;
    l1 = 0;
    struct Sliver {
      std::size_t edge;
      double d, len;
    };
    std::vector<Sliver> slivers;
    for (std::size_t k = 0; k < edges.size(); ++k) {
      // In 3-D: the distance d = |(A - F) x (B - A)| / |B - A| from F to the line of the edge
      // A-B (exactly 0 when F lies on it with A - F and B - A computed exactly, as for the
      // foot of P on a cube's edge), the foot of F on the line and the positions tau of A, B.
      const Vec3& A = edges[k].first;
      const Vec3& B = edges[k].second;
      const double len = (B - A).norm();
      const Vec3 t = (B - A) / len;
      const double signed_d = signed_distance(A, B) / len;
      const double d = std::abs(signed_d);
      if (d == 0) continue;  // (F, A, B) has no area
      const double tauA = (A - foot_).dot(t), tauB = (B - foot_).dot(t);
      if (d <= 1e-3 * len) {  // decided below, once the other parts are known
        slivers.push_back({k, signed_d, len});
        continue;
      }
      add_part(in_plane_normal(t, signed_d), t, d, tauA, tauB, tol, abs_tol, res, l1);
    }
    // A sliver (F within d << |AB| of the edge's line): with |integrand of Int f G dS| <=
    // sqrt 2 max|f| |h| rho / (rho^2 + h^2)^(3/2), its radial integral is below sqrt 2 max|f|
    // min(1, L^2 / 2h^2), and over the angle (dtheta = d dtau / L^2) the part is below
    // 3 sqrt 2 max|f| d / |h|; also below sqrt 2 max|f| / h^2 times its area d |AB| / 2. max|f|
    // <= 5/3 max|values| (the Lebesgue constant of the quadratic Lagrange nodes) on the
    // triangle of the nodes. A sliver under 0.05 tol |value| is left out, its bound counted in
    // the estimate; others are integrated (F close to the line but not within rounding).
    for (const Sliver& sl : slivers) {
      const double d = std::abs(sl.d);
      const double bound = fmax_ * (5.0 / 3.0) * d *
                           std::min(3 * std::sqrt(2.0) / ah_, std::sqrt(0.5) * sl.len / (ah_ * ah_));
      if (bound <= 0.05 * tol * std::abs(res.value)) {
        res.error_estimate += bound;
        continue;
      }
      const Vec3& A = edges[sl.edge].first;
      const Vec3& B = edges[sl.edge].second;
      const Vec3 t = (B - A) / sl.len;
      const double tauA = (A - foot_).dot(t), tauB = (B - foot_).dot(t);
      add_part(in_plane_normal(t, sl.d), t, d, tauA, tauB, tol, abs_tol, res, l1);
    }
    res.evaluations = evaluations_;
    return res;
  }

  bool converged() const { return converged_; }

  /// max|f| for the slivers' bound (run): by default the largest |value| at the nodes; over a
  /// facet, the largest over the nodes of all its triangles.
  void set_max_value(double m) { fmax_ = m; }

  /// The quadratic p at a point X of the plane, from the coefficients the rule integrates.
  double polynomial(const Vec3& X) const {
    const Vec3 w = X - foot_;
    const double xi = w.dot(e1_), eta = w.dot(e2_);
    return coef_[0] + coef_[1] * xi + coef_[2] * eta + coef_[3] * xi * xi + coef_[4] * xi * eta +
           coef_[5] * eta * eta;
  }

 private:
  // ((A - F) x (B - A)).nQ for the exact foot F of P (F = foot_ + foot_error_), to a few
  // eps of its value plus eps^2 |A - F| |B - A|: A - F and B - A by two-sum with their errors,
  // the products by fma. Near an edge's line the integral's sensitivity to F is 1 / |h|, so
  // that the side of the line and the distance d must be those of P itself, not of a rounded
  // cross product (whose error eps |A - F| |B - A| would be amplified by |A - F| / |h|).
  double signed_distance(const Vec3& A, const Vec3& B) const {
    auto two_diff = [](double x, double y, double& err) {
      const double s = x - y, bb = s - x;
      err = (x - (s - bb)) + (-y - bb);
      return s;
    };
    double p[3], ep[3], q[3], eq[3];
    for (int i = 0; i < 3; ++i) {
      p[i] = two_diff(A[i], foot_[i], ep[i]);
      ep[i] -= foot_error_[i];
      q[i] = two_diff(B[i], A[i], eq[i]);
    }
    double c[3];
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      const double p1 = p[j] * q[k], e1 = std::fma(p[j], q[k], -p1);
      const double p2 = p[k] * q[j], e2 = std::fma(p[k], q[j], -p2);
      c[i] = (p1 - p2) + ((e1 - e2) + (p[j] * eq[k] + ep[j] * q[k] - p[k] * eq[j] - ep[k] * q[j]));
    }
    return c[0] * nQ_[0] + c[1] * nQ_[1] + c[2] * nQ_[2];
  }

  // The unit vector n of the plane from F towards the edge's line, perpendicular to t, from
  // the sign of ((A - F) x (B - A)).nQ = d |B - A| (n x t).nQ: n x t = +-nQ gives
  // n = t x (+-nQ).
  Vec3 in_plane_normal(const Vec3& t, double signed_d) const {
    return t.cross(signed_d > 0 ? nQ_ : Vec3(-nQ_));
  }

  // The signed part of the triangle (F, A, B): n the unit vector from F to its foot on the
  // line, t the edge's direction, tau along t from that foot (tau = d sinh w).
  void add_part(const Vec3& n, const Vec3& t, double d, double tauA, double tauB, double tol,
                double abs_tol, SingularIntegralResult& res, double& l1) {
    nx_ = n.dot(e1_);
    ny_ = n.dot(e2_);
    tx_ = t.dot(e1_);
    ty_ = t.dot(e2_);
    d_over_a_ = d / ah_;
    const double sg = h_ > 0 ? 1.0 : -1.0;
    ut_n_ = sg * (nx_ * t_[0] + ny_ * t_[1]);
    ut_t_ = sg * (tx_ * t_[0] + ty_ * t_[1]);
    p1_n_ = coef_[1] * nx_ + coef_[2] * ny_;
    p1_t_ = coef_[1] * tx_ + coef_[2] * ty_;
    p2_nn_ = coef_[3] * nx_ * nx_ + coef_[4] * nx_ * ny_ + coef_[5] * ny_ * ny_;
    p2_nt_ = 2 * coef_[3] * nx_ * tx_ + coef_[4] * (nx_ * ty_ + ny_ * tx_) + 2 * coef_[5] * ny_ * ty_;
    p2_tt_ = coef_[3] * tx_ * tx_ + coef_[4] * tx_ * ty_ + coef_[5] * ty_ * ty_;
    // orientation of (F, A, B) against the triangle's (counter-clockwise in (e1, e2))
    const double sign = nx_ * ty_ - ny_ * tx_ > 0 ? 1.0 : -1.0;
    auto g = [this](double w) { return angular(w); };
    const Integral1D part =
        gauss_panels(g, std::asinh(tauA / d), std::asinh(tauB / d), tol, abs_tol, evaluations_);
    res.value += sign * part.value;
    res.error_estimate += part.error;
    l1 += std::abs(part.value);
    if (!(part.error <= std::max(abs_tol, tol * std::abs(part.value)))) converged_ = false;
  }

  // sech w times the radial integral along u(w) = sech w n + tanh w t, from 0 to L = d cosh w.
  // With u = sech w n + tanh w t: (u.t) = sech w (n.t) + tanh w (t.t), likewise p1(u) = grad p.u
  // and p2(u) = u^T H u; their coefficients are set per part (add_part).
  double angular(double w) {
    const double ew = std::exp(w), ch = 0.5 * (ew + 1 / ew), sech = 1 / ch;
    const double th = 0.5 * (ew - 1 / ew) * sech;
    const double ut = sech * ut_n_ + th * ut_t_;  // times sign(h)
    const double p1 = sech * p1_n_ + th * p1_t_;
    const double p2 = sech * (sech * p2_nn_ + th * p2_nt_) + th * th * p2_tt_;
    const RadialIntegrals J = radial_integrals(d_over_a_ * ch);
    // h rho (rho ut - h nu) / (rho^2 + h^2)^2 against 1, rho, rho^2 (h^2 = a^2, h = sign a)
    const double i0 = ut * J.aJ2 - nu_ * J.a2J1;
    const double i1 = ah_ * (ut * J.J3 - nu_ * J.aJ2);
    const double i2 = ah_ * ah_ * (ut * J.J4_a - nu_ * J.J3);
    return sech * (coef_[0] * i0 + p1 * i1 + p2 * i2);
  }

  double h_, ah_;
  double t_[2], nu_;
  std::array<double, 2> v_[3];
  std::array<double, 6> coef_;
  Vec3 foot_, foot_error_, e1_, e2_, nQ_;
  Vec3 V_[3];
  double fmax_ = 0;
  double nx_ = 0, ny_ = 0, tx_ = 0, ty_ = 0, d_over_a_ = 0;
  double ut_n_ = 0, ut_t_ = 0, p1_n_ = 0, p1_t_ = 0, p2_nn_ = 0, p2_nt_ = 0, p2_tt_ = 0;
  int evaluations_ = 0;
  bool converged_ = true;
};

}  // namespace

SingularIntegralResult integrate_kernel_times_quadratic(const std::array<double, 6>& values,
                                                        const Vec3& P, const Vec3& nP,
                                                        const Vec3& a, const Vec3& b,
                                                        const Vec3& c, const Vec3& nQ,
                                                        double rel_tol) {
  if (!(rel_tol > 0) || !std::isfinite(rel_tol))
    throw std::invalid_argument(
        "integrate_kernel_times_quadratic: rel_tol must be positive and finite, got " +
        std::to_string(rel_tol));
  if (!P.allFinite() || !nP.allFinite() || !a.allFinite() || !b.allFinite() || !c.allFinite() ||
      !nQ.allFinite())
    throw std::invalid_argument(
        "integrate_kernel_times_quadratic: non-finite point or normal (P = " + vec_str(P) +
        ", triangle " + vec_str(a) + " " + vec_str(b) + " " + vec_str(c) + ")");
  for (double v : values)
    if (!std::isfinite(v))
      throw std::invalid_argument("integrate_kernel_times_quadratic: non-finite value of f at a node of "
                                  "the triangle " + vec_str(a) + " " + vec_str(b) + " " + vec_str(c));
  if ((b - a).cross(c - a).squaredNorm() == 0)
    throw std::invalid_argument("integrate_kernel_times_quadratic: degenerate (zero-area) triangle " +
                                vec_str(a) + " " + vec_str(b) + " " + vec_str(c));
  SingularIntegralResult r;
  const double tol = std::max(rel_tol, 1e-12);
  const double h = (P - a).dot(nQ);
  if (h == 0) return r;  // paper 4.2, case (a)
  // Absolute floor as in integrate_kernel_times (for p changing sign or G changing sign).
  double fmag = 0;
  for (double v : values) fmag = std::max(fmag, std::abs(v));
  if (!(fmag > 0)) fmag = 1;
  const double abs_floor = 0.1 * tol * kPi * std::abs(form_factor(P, nP, a, b, c, nQ)) * fmag;
  QuadraticPolarIntegrator integ(values, P, nP, a, b, c, nQ, h);
  double l1 = 0;
  r = integ.run(0.2 * tol, abs_floor / 3, l1);
  r.value *= kInvPi;
  r.error_estimate *= kInvPi;
  // The signed parts cancel when the foot of P lies outside the triangle and |h| is small
  // against its distance (sum |part| >> |value|): their rounding (in the estimate) then exceeds
  // the tolerance, which the rule cannot certify.
  if (!std::isfinite(r.value) || !integ.converged() ||
      !(r.error_estimate <= std::max(tol * std::abs(r.value), kInvPi * abs_floor))) {
    std::ostringstream os;
    os.precision(3);
    os << "integrate_kernel_times_quadratic: the estimate " << r.error_estimate
       << " for the value " << r.value << " misses rel_tol " << rel_tol
       << " (the signed parts, sum |part| = " << kInvPi * l1
       << ", cancel?) for P = " << vec_str(P) << ", triangle " << vec_str(a) << " " << vec_str(b)
       << " " << vec_str(c) << "; integrate_kernel_times applies";
    throw std::runtime_error(os.str());
  }
  return r;
}

std::optional<SingularIntegralResult> integrate_kernel_times_quadratic_facet(
    const std::function<double(const Vec3&)>& f, const Vec3& P, const Vec3& nP,
    std::span<const Vec3> vertices, std::span<const std::array<geometry::Index, 3>> triangles,
    const Vec3& nQ, double rel_tol) {
  if (!f || triangles.empty() || !(rel_tol > 0) || !std::isfinite(rel_tol)) return std::nullopt;
  const double tol = std::max(rel_tol, 1e-12);
  auto vertex = [&](geometry::Index i) -> const Vec3& {
    return vertices[static_cast<std::size_t>(i)];
  };
  for (const auto& t : triangles)
    for (geometry::Index i : t)
      if (i < 0 || static_cast<std::size_t>(i) >= vertices.size() || !vertex(i).allFinite())
        return std::nullopt;
  if (!P.allFinite() || !nP.allFinite() || !nQ.allFinite()) return std::nullopt;
  // The facet's size, its plane (every vertex within 1e-12 diam of the plane through the
  // first one) and the one sign of (Q - P).nP (affine in Q: its sign at the vertices holds on
  // the facet, so that G has one sign and |form factor| = Int |G| / pi).
  const Vec3& origin = vertex(triangles[0][0]);
  double diam = 0;
  int positive = 0, negative = 0;
  for (const auto& t : triangles)
    for (geometry::Index i : t) {
      diam = std::max(diam, (vertex(i) - origin).norm());
      const double rn = (vertex(i) - P).dot(nP);
      positive += rn > 0;
      negative += rn < 0;
    }
  if (positive > 0 && negative > 0) return std::nullopt;
  for (const auto& t : triangles)
    for (geometry::Index i : t)
      if (!(std::abs((vertex(i) - origin).dot(nQ)) <= 1e-12 * diam)) return std::nullopt;
  const double h = (P - origin).dot(nQ);
  if (!(std::abs(h) > 1e-10 * diam)) return std::nullopt;  // P (nearly) in the plane

  // The triangle of the largest area carries the Lagrange nodes of p (the best conditioned
  // interpolation); f - p is checked at the 6 nodes of every other triangle and at 7 interior
  // points of every triangle (as integrate_kernel_times does for one triangle).
  std::size_t fit = 0;
  double best = -1;
  std::vector<std::array<Vec3, 3>> corners(triangles.size());
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    corners[k] = {vertex(triangles[k][0]), vertex(triangles[k][1]), vertex(triangles[k][2])};
    const auto& [A, B, C] = corners[k];
    const double area2 = (B - A).cross(C - A).squaredNorm();
    if (area2 == 0) return std::nullopt;
    if (area2 > best) {
      best = area2;
      fit = k;
    }
  }
  const auto& [a, b, c] = corners[fit];
  long evaluations = 0;
  const std::array<double, 6> values = {f(a), f(b), f(c), f(Vec3(0.5 * (a + b))),
                                        f(Vec3(0.5 * (b + c))), f(Vec3(0.5 * (c + a)))};
  evaluations += 6;
  double fmag = 0;
  for (double v : values) fmag = std::max(fmag, std::abs(v));
  if (!std::isfinite(fmag)) return std::nullopt;
  QuadraticPolarIntegrator quad(values, P, nP, a, b, c, nQ, h);
  const double limit = 64 * std::numeric_limits<double>::epsilon();
  double node_max = fmag;  // max |f| over the nodes of all the triangles
  auto matches = [&](const Vec3& X, bool node) {
    const double fx = f(X);
    ++evaluations;
    if (node) node_max = std::max(node_max, std::abs(fx));
    return std::abs(fx - quad.polynomial(X)) <= limit * std::max(fmag, std::abs(fx));
  };
  for (std::size_t k = 0; k < corners.size(); ++k) {
    const auto& [A, B, C] = corners[k];
    if (k != fit)
      for (const Vec3& X : {A, B, C, Vec3(0.5 * (A + B)), Vec3(0.5 * (B + C)), Vec3(0.5 * (C + A))})
        if (!matches(X, true)) return std::nullopt;
    for (const auto& l : kQuadraticCheckPoints)
      if (!matches(Vec3(l[0] * A + l[1] * B + l[2] * C), false)) return std::nullopt;
  }
  if (!std::isfinite(node_max)) return std::nullopt;
  quad.set_max_value(node_max);

  // The boundary: the directed edges of the triangles (each counter-clockwise about nQ) whose
  // reverse is not an edge too; an edge found twice in one direction (inconsistent orientation
  // or a non-manifold facet) leaves the rule.
  std::vector<std::pair<geometry::Index, geometry::Index>> directed;
  for (const auto& t : triangles) {
    const bool ccw = (vertex(t[1]) - vertex(t[0])).cross(vertex(t[2]) - vertex(t[0])).dot(nQ) > 0;
    const std::array<geometry::Index, 3> o = ccw ? t : std::array<geometry::Index, 3>{t[0], t[2], t[1]};
    for (int e = 0; e < 3; ++e) directed.emplace_back(o[static_cast<std::size_t>(e)], o[static_cast<std::size_t>((e + 1) % 3)]);
  }
  std::vector<std::pair<geometry::Index, geometry::Index>> sorted = directed;
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return std::nullopt;
  std::vector<std::pair<Vec3, Vec3>> boundary;
  for (const auto& [i, j] : directed)
    if (!std::binary_search(sorted.begin(), sorted.end(), std::pair{j, i}))
      boundary.emplace_back(vertex(i), vertex(j));

  // Relative tolerance 0.2 tol per part, so that with sum |part| <= 4 |value| (no
  // cancellation, else the rule is left) the parts' errors sum to at most 0.8 tol |value|; no
  // absolute floor is needed (G has one sign, so that |value| is the integral's scale).
  double l1 = 0;
  SingularIntegralResult r = quad.run(boundary, 0.2 * tol, 0.0, l1);
  if (!quad.converged() || !std::isfinite(r.value) || !(l1 <= 4 * std::abs(r.value)))
    return std::nullopt;
  r.value *= kInvPi;
  r.error_estimate *= kInvPi;
  r.evaluations += static_cast<int>(evaluations);
  return r;
}

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

  // Absolute floor of the tolerance, for integrals that cancel (f changing sign): 0.1 tol times
  // pi |form factor| (the integral for f = 1) times the largest |f| at the vertices and the
  // centroid. Without it, the rounding of f itself (eps |f(Q)| where f(Q) is a small difference)
  // would stop convergence.
  double fmag = 0;
  for (const Vec3& q : {a, b, c, Vec3((a + b + c) / 3.0)}) fmag = std::max(fmag, std::abs(f(q)));
  if (!(fmag > 0) || !std::isfinite(fmag)) fmag = 1;
  const double abs_floor = 0.1 * tol * kPi * std::abs(form_factor(P, nP, a, b, c, nQ)) * fmag;

  HierarchicalIntegrator integ(f, P, nP, nQ, h, tol, abs_floor);
  result = integ.run(a, b, c);
  const long evaluations = integ.evaluations() + 4;
  result.value *= kInvPi;
  result.error_estimate *= kInvPi;
  if (!std::isfinite(result.value))
    throw std::runtime_error("integrate_kernel_times: non-finite result (f returned NaN/Inf?) for P = " +
                             vec_str(P));
  if (evaluations > kMaxEvaluations) {
    std::ostringstream os;
    os.precision(3);
    os << "integrate_kernel_times: more than " << kMaxEvaluations
       << " evaluations without reaching rel_tol " << rel_tol << " (estimate "
       << result.error_estimate << " for the value " << result.value
       << "; is f smooth on the triangle?) for P = " << vec_str(P) << ", triangle " << vec_str(a)
       << " " << vec_str(b) << " " << vec_str(c);
    throw std::runtime_error(os.str());
  }
  return result;
}

}  // namespace panelrad::quadrature

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

// Far field of the fast product (paper section 4.1, (44)-(48)) in local coordinates of a cluster's
// plane: Taylor coefficients of the kernel, exact triangle moments, and the shift of moments.
// Everything here is allocation-free (fixed-size stack arrays for M <= kMaxTaylorDegree).
#include <panelrad/operator/far_field.hpp>

#include <Eigen/Geometry>

#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

namespace panelrad {

namespace {

constexpr int kMaxTerms = num_taylor_terms(kMaxTaylorDegree);

void check_degree(int M, const char* where) {
  if (M < 0 || M > kMaxTaylorDegree)
    throw std::invalid_argument(std::string(where) + ": Taylor degree M = " + std::to_string(M) +
                                " outside [0, " + std::to_string(kMaxTaylorDegree) + "]");
}

// Binomial coefficients C(n, k), n <= kMaxTaylorDegree, exact in double.
struct BinomialTable {
  double v[kMaxTaylorDegree + 1][kMaxTaylorDegree + 1]{};
  constexpr BinomialTable() {
    for (int n = 0; n <= kMaxTaylorDegree; ++n) {
      v[n][0] = 1.0;
      for (int k = 1; k <= n; ++k) v[n][k] = v[n - 1][k - 1] + (k <= n - 1 ? v[n - 1][k] : 0.0);
    }
  }
};
constexpr BinomialTable kBinomial{};

// Recurrence weights of the homogeneous Gegenbauer terms of (1 - 2u + w)^-2 (lambda = 2):
//   n F_n = 2(n+1) u F_{n-1} - (n+2) w F_{n-2}.
struct GegenbauerWeights {
  double a[kMaxTaylorDegree + 1]{}, b[kMaxTaylorDegree + 1]{};
  constexpr GegenbauerWeights() {
    for (int n = 1; n <= kMaxTaylorDegree; ++n) {
      a[n] = 2.0 * (n + 1) / n;
      b[n] = static_cast<double>(n + 2) / n;
    }
  }
};
constexpr GegenbauerWeights kGegenbauer{};

// p! q! / (p+q+2)! for p + q <= kMaxTaylorDegree (factorials up to 14! are exact in double).
struct MomentWeights {
  double v[kMaxTerms]{};
  constexpr MomentWeights() {
    double fact[kMaxTaylorDegree + 3]{};
    fact[0] = 1.0;
    for (int k = 1; k <= kMaxTaylorDegree + 2; ++k) fact[k] = fact[k - 1] * k;
    for (int n = 0; n <= kMaxTaylorDegree; ++n)
      for (int q = 0; q <= n; ++q) v[taylor_index(n - q, q)] = fact[n - q] * fact[q] / fact[n + 2];
  }
};
constexpr MomentWeights kMomentWeights{};

// Calls f(std::integral_constant<int, M>{}) for the runtime degree M in [0, kMaxTaylorDegree]:
// the bodies below are compiled once per degree, so that their loops unroll.
template <class F, int... Ms>
void dispatch_degree(int M, F&& f, std::integer_sequence<int, Ms...>) {
  (void)((M == Ms ? (f(std::integral_constant<int, Ms>{}), true) : false) || ...);
}
template <class F>
void with_degree(int M, F&& f) {
  dispatch_degree(M, f, std::make_integer_sequence<int, kMaxTaylorDegree + 1>{});
}

}  // namespace

PlaneFrame make_plane_frame(const Vec3& origin, const Vec3& normal) {
  const double len = normal.norm();
  if (!(len > 0.0) || !std::isfinite(len) || !origin.allFinite())
    throw std::invalid_argument("make_plane_frame: normal must be finite and nonzero and the origin finite");
  PlaneFrame f;
  f.origin = origin;
  f.normal = normal / len;
  // The coordinate axis least aligned with the normal: a deterministic function of the normal only.
  const Vec3 a = f.normal.cwiseAbs();
  int k = 0;
  if (a[1] < a[k]) k = 1;
  if (a[2] < a[k]) k = 2;
  const Vec3 axis = Vec3::Unit(k);
  f.e1 = f.normal.cross(axis).normalized();
  f.e2 = f.normal.cross(f.e1);  // unit up to rounding: normal and e1 are orthonormal
  return f;
}

// G(P, A + x e1 + y e2) = h L(x,y) / |P-Q|^4 (paper (2), (44)-(45)) with h = (P-A).nQ constant
// over the plane and L = (Q-P).nP linear. With d = P - A, rho = |d|, X = x/rho, Y = y/rho:
//   |P-Q|^2 = rho^2 (1 - 2u + w),  u = X a1 + Y a2,  w = X^2 + Y^2,  a_i = d.e_i / rho,
// and (1 - 2u + w)^-2 = sum_n F_n(X,Y), F_n homogeneous of degree n, from the Gegenbauer
// recurrence (lambda = 2) n F_n = 2(n+1) u F_{n-1} - (n+2) w F_{n-2}, F_0 = 1, F_1 = 4u.
// Since a1^2 + a2^2 <= 1 this is the Legendre-like, forward-stable regime; every scaled quantity
// is O(1), and the only large numbers are the final powers rho^-(2+p+q) of the unscaling.
namespace {

// The body, with the degree M a compile-time constant so that every loop unrolls and F stays in
// registers (dispatched below; the call sits in the innermost loop of the fast product).
template <int M>
void taylor_coefficients_of_degree(const Vec3& P, const Vec3& nP, const PlaneFrame& frame, double* c) {
  const Vec3 d = P - frame.origin;
  const double rho = d.norm();
  if (!(rho > 0.0) || !std::isfinite(rho))
    throw std::invalid_argument("kernel_taylor_coefficients: P coincides with the expansion centre A(tau) or is not finite");
  const double inv = 1.0 / rho;
  const Vec3 dn = d * inv;                        // unit vector (P - A)/rho
  const double a1 = dn.dot(frame.e1), a2 = dn.dot(frame.e2);
  const double hn = dn.dot(frame.normal);         // h / rho, |hn| <= 1
  const double l0 = -dn.dot(nP);                  // (A - P).nP / rho
  const double l1 = frame.e1.dot(nP), l2 = frame.e2.dot(nP);

  // F_n in graded order (coefficient of X^(n-q) Y^q at taylor_index(n-q, q)).
  double F[num_taylor_terms(M)];
  F[0] = 1.0;
  if constexpr (M >= 1) {
    F[1] = 4.0 * a1;
    F[2] = 4.0 * a2;
  }
  for (int n = 2; n <= M; ++n) {
    double* Fn = F + taylor_index(n, 0);
    const double* F1 = F + taylor_index(n - 1, 0);
    const double* F2 = F + taylor_index(n - 2, 0);
    const double ca = kGegenbauer.a[n], cb = kGegenbauer.b[n];
    // [X^(n-q) Y^q] of u F_{n-1} = a1 F1[q] + a2 F1[q-1]; of w F_{n-2} = F2[q] + F2[q-2].
    Fn[0] = ca * a1 * F1[0] - cb * F2[0];
    Fn[n] = ca * a2 * F1[n - 1] - cb * F2[n - 2];
    if (n >= 3) Fn[1] = ca * (a1 * F1[1] + a2 * F1[0]) - cb * F2[1];
    if (n >= 3) Fn[n - 1] = ca * (a1 * F1[n - 1] + a2 * F1[n - 2]) - cb * F2[n - 3];
    else Fn[1] = ca * (a1 * F1[1] + a2 * F1[0]);  // n = 2: w F_0 has no X Y term
    for (int q = 2; q <= n - 2; ++q) Fn[q] = ca * (a1 * F1[q] + a2 * F1[q - 1]) - cb * (F2[q] + F2[q - 2]);
  }

  // (l0 + l1 X + l2 Y) * sum F_n, truncated at degree M, times hn, unscaled by rho^-(2+n).
  double scale = hn * inv * inv;  // hn / rho^2
  c[0] = l0 * scale;
  for (int n = 1; n <= M; ++n) {
    scale *= inv;
    const double* Fn = F + taylor_index(n, 0);
    const double* F1 = F + taylor_index(n - 1, 0);
    double* cn = c + taylor_index(n, 0);
    // X * X^(n-1-q) Y^q contributes l1 F1[q] (q < n); Y * X^(n-q) Y^(q-1) contributes l2 F1[q-1] (q > 0).
    cn[0] = (l0 * Fn[0] + l1 * F1[0]) * scale;
    for (int q = 1; q < n; ++q) cn[q] = (l0 * Fn[q] + l1 * F1[q] + l2 * F1[q - 1]) * scale;
    cn[n] = (l0 * Fn[n] + l2 * F1[n - 1]) * scale;
  }
}

}  // namespace

void kernel_taylor_coefficients(const Vec3& P, const Vec3& nP, const PlaneFrame& frame, int M, double* c) {
  check_degree(M, "kernel_taylor_coefficients");
  with_degree(M, [&](auto degree) { taylor_coefficients_of_degree<decltype(degree)::value>(P, nP, frame, c); });
}

// Int_Delta x^p y^q dS with x = sum_k l_k x_k, y = sum_k l_k y_k (barycentric l_k) and
// Int l1^i l2^j l3^k dS = 2|Delta| i! j! k! / (i+j+k+2)!: expanding multinomially,
//   Int x^p y^q dS = 2|Delta| p! q!/(p+q+2)! * [s^p t^q] prod_k 1/(1 - x_k s - y_k t),
// since [s^i t^j] 1/(1 - x s - y t) = C(i+j, i) x^i y^j turns (i+j)!/(i! j!) into the weights.
namespace {

template <int M>
void triangle_moments_of_degree(const std::array<double, 2> (&v)[3], double twice_area, double* m) {
  constexpr int T = num_taylor_terms(M);
  // H = prod_k 1/(1 - z_k), z_k = x_k s + y_k t, by three in-place divisions G = A/(1 - z), i.e.
  // G_n = A_n + z G_{n-1} degree by degree (O(M^2) each); coefficient of s^(n-q) t^q at index q.
  for (int t = 0; t < T; ++t) m[t] = 0.0;
  m[0] = 1.0;
  for (int k = 0; k < 3; ++k) {
    const double x = v[k][0], y = v[k][1];
    for (int n = 1; n <= M; ++n) {
      double* Gn = m + taylor_index(n, 0);
      const double* G1 = m + taylor_index(n - 1, 0);
      Gn[0] += x * G1[0];
      for (int q = 1; q < n; ++q) Gn[q] += x * G1[q] + y * G1[q - 1];
      Gn[n] += y * G1[n - 1];
    }
  }
  for (int t = 0; t < T; ++t) m[t] *= twice_area * kMomentWeights.v[t];
}

}  // namespace

void triangle_moments(const PlaneFrame& frame, const Vec3& a, const Vec3& b, const Vec3& c, int M, double* m) {
  check_degree(M, "triangle_moments");
  const std::array<double, 2> v[3] = {frame.local(a), frame.local(b), frame.local(c)};
  const double twice_area = std::abs((v[1][0] - v[0][0]) * (v[2][1] - v[0][1]) - (v[2][0] - v[0][0]) * (v[1][1] - v[0][1]));
  with_degree(M, [&](auto degree) { triangle_moments_of_degree<decltype(degree)::value>(v, twice_area, m); });
}

// (x_parent = x_child + dx): m'_pq = sum_{i<=p, j<=q} C(p,i) C(q,j) dx^(p-i) dy^(q-j) m_ij (48),
// done separably: first along x, then along y (O(M^3) instead of O(M^4)).
namespace {

template <int M>
void shift_moments_of_degree(const double* m_child, double dx, double dy, double* m_parent) {
  constexpr int K = M + 1;
  double xp[K], yp[K];
  xp[0] = yp[0] = 1.0;
  for (int i = 1; i <= M; ++i) {
    xp[i] = xp[i - 1] * dx;
    yp[i] = yp[i - 1] * dy;
  }
  // The weights C(p,i) dx^(p-i) and C(q,j) dy^(q-j), once per shift (each product rounded as in
  // C(p,i) dx^(p-i) m_ij evaluated left to right).
  double wx[K][K], wy[K][K];
  for (int p = 0; p <= M; ++p)
    for (int i = 0; i <= p; ++i) {
      wx[p][i] = kBinomial.v[p][i] * xp[p - i];
      wy[p][i] = kBinomial.v[p][i] * yp[p - i];
    }
  // The child's moments in a square array, ms[j][i] = m_ij (i + j <= M): contiguous in i.
  double ms[K][K];
  for (int n = 0; n <= M; ++n)
    for (int j = 0; j <= n; ++j) ms[j][n - j] = m_child[taylor_index(n - j, j)];
  // t[p][j] = sum_{i<=p} C(p,i) dx^(p-i) m_ij, for p + j <= M: contiguous in i and in j.
  double t[K][K];
  for (int j = 0; j <= M; ++j)
    for (int p = 0; p + j <= M; ++p) {
      double s = 0.0;
#pragma GCC unroll 16
      for (int i = 0; i <= p; ++i) s += wx[p][i] * ms[j][i];
      t[p][j] = s;
    }
  // m'_pq = sum_{j<=q} C(q,j) dy^(q-j) t_pj.
  for (int n = 0; n <= M; ++n)
    for (int q = 0; q <= n; ++q) {
      const int p = n - q;
      double s = 0.0;
#pragma GCC unroll 16
      for (int j = 0; j <= q; ++j) s += wy[q][j] * t[p][j];
      m_parent[taylor_index(p, q)] += s;
    }
}

}  // namespace

void shift_moments_add(const double* m_child, double dx, double dy, int M, double* m_parent) {
  check_degree(M, "shift_moments_add");
  with_degree(M, [&](auto degree) { shift_moments_of_degree<decltype(degree)::value>(m_child, dx, dy, m_parent); });
}

}  // namespace panelrad

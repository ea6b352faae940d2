// Local expansions of target clusters (local_expansion.hpp): Chebyshev points, the barycentric
// Lagrange basis and the tensor interpolant on a rectangle of a cluster's plane.
#include <panelrad/operator/local_expansion.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace panelrad {

namespace {

void check_local_degree(int d, const char* where) {
  if (d < 0 || d > kMaxLocalDegree)
    throw std::invalid_argument(std::string(where) + ": local expansion degree d = " + std::to_string(d) +
                                " outside [0, " + std::to_string(kMaxLocalDegree) + "]");
}

// The nodes and barycentric weights of every degree, computed once.
struct ChebyshevTable {
  double t[kMaxLocalDegree + 1][kMaxLocalDegree + 1]{};
  double w[kMaxLocalDegree + 1][kMaxLocalDegree + 1]{};
  ChebyshevTable() {
    for (int d = 0; d <= kMaxLocalDegree; ++d)
      for (int j = 0; j <= d; ++j) {
        const double angle = (2 * j + 1) * std::numbers::pi / (2 * (d + 1));
        t[d][j] = std::cos(angle);
        w[d][j] = (j % 2 ? -1.0 : 1.0) * std::sin(angle);
      }
  }
};

const ChebyshevTable& chebyshev_table() {
  static const ChebyshevTable table;
  return table;
}

}  // namespace

std::array<double, kMaxLocalDegree + 1> chebyshev_points(int d) {
  check_local_degree(d, "chebyshev_points");
  std::array<double, kMaxLocalDegree + 1> out{};
  std::copy_n(chebyshev_table().t[d], d + 1, out.begin());
  return out;
}

// a_j(s) = (w_j / (s - t_j)) / sum_k (w_k / (s - t_k)): the second (true) barycentric form,
// stable for the Chebyshev points (Higham 2004) and exact at the nodes.
void chebyshev_basis(int d, double s, double* a) {
  check_local_degree(d, "chebyshev_basis");
  const ChebyshevTable& table = chebyshev_table();
  const double* t = table.t[d];
  const double* w = table.w[d];
  for (int j = 0; j <= d; ++j)
    if (s == t[j]) {
      for (int k = 0; k <= d; ++k) a[k] = k == j ? 1.0 : 0.0;
      return;
    }
  double sum = 0;
  for (int j = 0; j <= d; ++j) {
    a[j] = w[j] / (s - t[j]);
    sum += a[j];
  }
  const double inv = 1.0 / sum;
  for (int j = 0; j <= d; ++j) a[j] *= inv;
}

LocalBox LocalBox::bounding(const PlaneFrame& frame, const Vec3& a, const Vec3& b, const Vec3& c) {
  const std::array<double, 2> v[3] = {frame.local(a), frame.local(b), frame.local(c)};
  double lo[2], hi[2];
  for (int k = 0; k < 2; ++k) {
    lo[k] = std::min({v[0][k], v[1][k], v[2][k]});
    hi[k] = std::max({v[0][k], v[1][k], v[2][k]});
  }
  LocalBox box;
  box.cx = 0.5 * (lo[0] + hi[0]);
  box.cy = 0.5 * (lo[1] + hi[1]);
  constexpr double widen = 1.0 + 0x1p-40;
  box.hx = 0.5 * (hi[0] - lo[0]) * widen;
  box.hy = 0.5 * (hi[1] - lo[1]) * widen;
  if (!(box.hx > 0 && box.hy > 0) || !std::isfinite(box.hx) || !std::isfinite(box.hy) || !std::isfinite(box.cx) ||
      !std::isfinite(box.cy))
    throw std::invalid_argument("LocalBox::bounding: the triangle's rectangle is degenerate or not finite");
  return box;
}

double LocalBox::half_diagonal() const { return std::hypot(hx, hy) * (1.0 + 0x1p-50); }

Vec3 LocalBox::centre(const PlaneFrame& frame) const { return frame.origin + cx * frame.e1 + cy * frame.e2; }

void LocalBox::points(const PlaneFrame& frame, int d, Vec3* out) const {
  check_local_degree(d, "LocalBox::points");
  const double* t = chebyshev_table().t[d];
  for (int i = 0; i <= d; ++i)
    for (int j = 0; j <= d; ++j)
      out[i * (d + 1) + j] = frame.origin + (cx + hx * t[i]) * frame.e1 + (cy + hy * t[j]) * frame.e2;
}

void LocalBox::interpolate(const PlaneFrame& frame, int d, const double* values, int C, const Vec3& P,
                           double* out) const {
  check_local_degree(d, "LocalBox::interpolate");
  if (C < 1 || C > 4) throw std::invalid_argument("LocalBox::interpolate: " + std::to_string(C) + " series, outside [1, 4]");
  const std::array<double, 2> x = frame.local(P);
  double a[kMaxLocalDegree + 1], b[kMaxLocalDegree + 1];
  chebyshev_basis(d, (x[0] - cx) / hx, a);
  chebyshev_basis(d, (x[1] - cy) / hy, b);
  for (int c = 0; c < C; ++c) out[c] = 0;
  const int n = d + 1;
  for (int i = 0; i < n; ++i) {
    double row[4] = {0, 0, 0, 0};
    const double* vi = values + static_cast<std::size_t>(i * n) * static_cast<std::size_t>(C);
    for (int j = 0; j < n; ++j)
      for (int c = 0; c < C; ++c) row[c] += b[j] * vi[j * C + c];
    for (int c = 0; c < C; ++c) out[c] += a[i] * row[c];
  }
}

}  // namespace panelrad

#include <panelrad/operator/self_check.hpp>

#include "visible_covering.hpp"
#include <panelrad/operator/near_field.hpp>
#include <panelrad/quadrature/exact_integrals.hpp>
#include <panelrad/support/resources.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace panelrad {

using geometry::Cluster;
using geometry::Index;

SelfCheckVectors self_check_vectors(const geometry::ClusterTree& tree) {
  SelfCheckVectors out;
  const Index n = tree.num_elements();
  if (n == 0) return out;
  const auto elements = tree.elements();
  // Coordinates scaled to the bounding box of the collocation points: s in [0, 1]^3.
  const std::span<const Vec3> points = tree.collocation_points();
  Vec3 lo = points.front(), hi = points.front();
  for (const Vec3& P : points) {
    lo = lo.cwiseMin(P);
    hi = hi.cwiseMax(P);
  }
  Vec3 inv_extent;
  for (int a = 0; a < 3; ++a) inv_extent[a] = hi[a] > lo[a] ? 1.0 / (hi[a] - lo[a]) : 0.0;
  const auto scaled = [&](Index j) -> Vec3 { return (points[static_cast<std::size_t>(j)] - lo).cwiseProduct(inv_extent); };
  const auto make = [&](const std::string& name, auto&& value) {
    Eigen::VectorXd v(n);
#pragma omp parallel for schedule(static)
    for (Index j = 0; j < n; ++j) v[j] = value(j);
    out.emplace_back(name, std::move(v));
  };
  make("1", [](Index) { return 1.0; });
  make("x", [&](Index j) { return scaled(j).x(); });
  make("x^2 + y^2 + z^2", [&](Index j) { return scaled(j).squaredNorm(); });
  make("cos 7x + sin(5y) z", [&](Index j) {
    const Vec3 s = scaled(j);
    return std::cos(7 * s.x()) + std::sin(5 * s.y()) * s.z();
  });
  // Sign per facet from a fixed 64-bit mix of the facet index (splitmix64's finalizer).
  const auto mix = [](std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  make("+-1 by facet", [&](Index j) {
    const auto f = static_cast<std::uint64_t>(elements[static_cast<std::size_t>(j)].facet);
    return (mix(f + 0x9e3779b97f4a7c15ULL) >> 63) ? 1.0 : -1.0;
  });
  make("random +-1", [&](Index j) {
    return (mix(static_cast<std::uint64_t>(j) * 0x9e3779b97f4a7c15ULL + 1) >> 63) ? 1.0 : -1.0;
  });
  return out;
}

std::vector<Index> self_check_rows(const geometry::ClusterTree& tree, Index first, Index end, int samples) {
  const auto elements = tree.elements();
  const int L = tree.finest_level();
  const Index m = end - first;
  std::vector<Index> rows;
  if (samples >= m) {
    rows.resize(static_cast<std::size_t>(m));
    for (Index r = 0; r < m; ++r) rows[static_cast<std::size_t>(r)] = first + r;
    return rows;
  }
  samples = std::max(samples, 1);
  const Index even = std::max(1, samples - samples / 2);
  for (Index k = 0; k < even; ++k)
    rows.push_back(first + static_cast<Index>((static_cast<std::int64_t>(k) * m) / even + (m / even) / 2));
  std::vector<Index> corners;  // elements sharing a vertex with their input triangle (level-0 ancestor)
  for (Index e = first; e < end; ++e) {
    const Cluster& root = tree.cluster(0, e >> (2 * L));
    const Cluster& c = elements[static_cast<std::size_t>(e)];
    bool corner = false;
    for (const Vec3& p : c.vertex)
      for (const Vec3& q : root.vertex) corner = corner || p == q;
    if (corner) corners.push_back(e);
  }
  const Index at_corners = std::min<Index>(samples - even, static_cast<Index>(corners.size()));
  for (Index k = 0; k < at_corners; ++k)
    rows.push_back(corners[static_cast<std::size_t>((static_cast<std::int64_t>(k) * static_cast<std::int64_t>(corners.size())) / at_corners)]);
  std::sort(rows.begin(), rows.end());
  rows.erase(std::unique(rows.begin(), rows.end()), rows.end());
  return rows;
}

namespace {

// v_k(j) and |v_k(j)| interleaved per element j (index (j V + k) 2 and + 1): the exact rows'
// inner loop reads them in order.
std::vector<double> interleaved_values(const SelfCheckVectors& vectors, Index n) {
  const std::size_t V = vectors.size();
  std::vector<double> values(static_cast<std::size_t>(n) * 2 * V);
#pragma omp parallel for schedule(static)
  for (Index j = 0; j < n; ++j)
    for (std::size_t k = 0; k < V; ++k) {
      values[(static_cast<std::size_t>(j) * V + k) * 2] = vectors[k].second[j];
      values[(static_cast<std::size_t>(j) * V + k) * 2 + 1] = std::abs(vectors[k].second[j]);
    }
  return values;
}

// Per sampled row r and vector k (index r * V + k): (K v_k)_r and (K |v_k|)_r from the exact
// closed-form entries (one form factor per element, O(n) per row).
void exact_rows(const geometry::ClusterTree& tree, std::span<const double> weights,
                const geometry::Occluders* occluders, SelfCheckReference& reference) {
  const Index n = tree.num_elements();
  const auto elements = tree.elements();
  const int L = tree.finest_level();
  const auto& rows = reference.rows;
  const std::size_t V = reference.vectors.size(), S = rows.size();
  const std::vector<double> values = interleaved_values(reference.vectors, n);
  reference.exact.assign(S * V, 0.0);
  reference.scale.assign(S * V, 0.0);
  const NearFieldIntegrator exact_near(NearFieldOptions{}, tree.mesh_size());  // the closed form
#pragma omp parallel
  {
    VisibleCoveringScratch covering;
    // A row's sums are held by its thread until the row is done: the rows of neighbouring
    // entries of `exact` and `scale` share cache lines, and go to other threads.
    std::vector<double> sums(2 * V);
#pragma omp for schedule(dynamic, 1)
    for (std::size_t r = 0; r < S; ++r) {
      const Index i = rows[r];
      const double rho = weights[static_cast<std::size_t>(i)];
      if (rho == 0) continue;
      double* ex = sums.data();
      double* sc = sums.data() + V;
      std::fill(sums.begin(), sums.end(), 0.0);
      const Vec3& P = tree.collocation_point(i);
      const Vec3& nP = elements[static_cast<std::size_t>(i)].normal;
      const auto add = [&](Index j, double form_factor) {
        const double kij = rho * form_factor;
        const double* vj = &values[static_cast<std::size_t>(j) * 2 * V];
        for (std::size_t k = 0; k < V; ++k) {
          ex[k] += kij * vj[2 * k];
          sc[k] += kij * vj[2 * k + 1];
        }
      };
      if (occluders) {
        // The exact row with V: every element's closed-form form factor over its visible part,
        // by the walk with nothing admissible (eta = 0).
        VisibilityCounts counts;
        cover_visible(tree, *occluders, P, nP, tree.plane(L, i), 0.0, exact_near, [](int, Index) {}, add, counts,
                      covering);
      } else {
        const Index plane = tree.plane(L, i);
        for (Index j = 0; j < n; ++j) {
          const Cluster& e = elements[static_cast<std::size_t>(j)];
          if (tree.plane(L, j) == plane) continue;  // coplanar: G = 0
          add(j, quadrature::form_factor(P, nP, e.vertex[0], e.vertex[1], e.vertex[2], e.normal));
        }
      }
      std::copy(ex, ex + V, reference.exact.begin() + static_cast<std::ptrdiff_t>(r * V));
      std::copy(sc, sc + V, reference.scale.begin() + static_cast<std::ptrdiff_t>(r * V));
    }
  }
}

// Vector k's worst error over the sampled rows, relative to max_r (K |v_k|)_r.
SelfCheckVector compare(const SelfCheckReference& reference, const std::vector<double>& product, std::size_t k) {
  const auto& rows = reference.rows;
  const std::size_t V = reference.vectors.size(), S = rows.size();
  SelfCheckVector c;
  c.name = reference.vectors[k].first;
  double err = 0, ref = 0;
  for (std::size_t r = 0; r < S; ++r) {
    // NaN-aware: a non-finite product is an infinite error, never ignored by max().
    double d = std::abs(product[r * V + k] - reference.exact[r * V + k]);
    if (!std::isfinite(d)) d = std::numeric_limits<double>::infinity();
    if (c.row < 0 || d > err) {
      err = d;
      c.row = rows[r];
    }
    ref = std::max(ref, reference.scale[r * V + k]);
  }
  c.relative_error = ref > 0 ? err / ref : err;
  return c;
}

}  // namespace

SelfCheckReference self_check_reference(const geometry::ClusterTree& tree, std::span<const double> weights,
                                        const geometry::Occluders* occluders, int samples, Index first, Index end) {
  const Index n = tree.num_elements();
  if (end == -1) end = n;
  if (first < 0 || first > end || end > n)
    throw std::invalid_argument("self_check_reference: rows [" + std::to_string(first) + ", " + std::to_string(end) +
                                ") are not within [0, n) = [0, " + std::to_string(n) + ")");
  if (weights.size() != static_cast<std::size_t>(n))
    throw std::invalid_argument("self_check_reference: " + std::to_string(weights.size()) + " row weights for n = " +
                                std::to_string(n));
  SelfCheckReference reference;
  if (end == first) return reference;
  Stopwatch clock;
  reference.rows = self_check_rows(tree, first, end, samples);
  reference.vectors = self_check_vectors(tree);
  exact_rows(tree, weights, occluders, reference);
  reference.seconds = clock.seconds();
  return reference;
}

SelfCheckReference self_check_reference(const Collocation& collocation, const geometry::Occluders* occluders,
                                        int samples) {
  const Eigen::VectorXd& rho = collocation.reflectivity();
  return self_check_reference(collocation.tree(), {rho.data(), static_cast<std::size_t>(rho.size())}, occluders,
                              samples);
}

// Exact entries of a row are cheap (one closed-form form factor per element, O(n)): the product's
// rows are compared with them for every test vector.
SelfCheck measure_self_check(const SelfCheckReference& reference, Index n, const SampledProduct& product) {
  SelfCheck check;
  Stopwatch clock;
  const auto& rows = reference.rows;
  const auto& vectors = reference.vectors;
  const std::size_t V = vectors.size(), S = rows.size();
  for (const auto& v : vectors)
    if (v.second.size() != n) throw std::invalid_argument("self_check: reference vector size differs from n");
  if (reference.exact.size() != S * V || reference.scale.size() != S * V)
    throw std::invalid_argument("self_check: reference rows and vectors do not match its values");
  std::vector<double> fast(S * V, 0.0), row_values(S);
  for (std::size_t k = 0; k < V; ++k) {
    product(vectors[k].second, rows, row_values);
    for (std::size_t r = 0; r < S; ++r) fast[r * V + k] = row_values[r];
  }
  check.rows = static_cast<int>(S);
  check.sampled_rows = rows;
  for (std::size_t k = 0; k < V; ++k) {
    check.vectors.push_back(compare(reference, fast, k));
    check.relative_error = std::max(check.relative_error, check.vectors.back().relative_error);
  }
  check.seconds = clock.seconds() + reference.seconds;
  return check;
}

SelfCheck self_check(const RadiosityOperator& op, const SelfCheckReference& reference) {
  const Index n = op.size();
  for (const Index i : reference.rows)
    if (i < 0 || i >= n)
      throw std::invalid_argument("self_check: reference row " + std::to_string(i) + " is not a row of the operator");
  Eigen::VectorXd y;
  return measure_self_check(reference, n, [&](const Eigen::VectorXd& v, std::span<const Index> rows, std::span<double> out) {
    op.apply(v, y);
    for (std::size_t r = 0; r < rows.size(); ++r) out[r] = y[rows[r]];
  });
}

SelfCheck self_check(const RadiosityOperator& op, const Collocation& collocation, const geometry::Occluders* occluders,
                     int samples) {
  if (op.size() != collocation.size())
    throw std::invalid_argument("self_check: the operator's order " + std::to_string(op.size()) +
                                " differs from the collocation's n = " + std::to_string(collocation.size()));
  if (op.size() == 0) return {};
  return self_check(op, self_check_reference(collocation, occluders, samples));
}

}  // namespace panelrad

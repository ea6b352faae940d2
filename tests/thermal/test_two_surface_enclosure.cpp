// Two gray surfaces, one inside the other: a geodesic polyhedron (T1, eps1) inside a concentric
// larger one (T2, eps2), both refined towards spheres. For concentric spheres the radiosity of
// each surface is uniform and the textbook two-surface formula is exact:
//   Q1 = A1 sigma (T1^4 - T2^4) / (1/eps1 + (A1/A2) (1/eps2 - 1)),
// with A1, A2 the areas (here the polyhedra's own). For polyhedra it holds in the limit: the
// thermal solve's net rate of the inner body must approach it as the polyhedra approach spheres,
// and the energy balance of the closed scene must hold at every step.
#include <panelrad/thermal/thermal_solve.hpp>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <utility>
#include <vector>

namespace panelrad {
namespace {

using geometry::Index;
using geometry::TriangleMesh;
using geometry::Vec3;
using Given = SurfaceCondition::Given;

double sigma_t4(double T) { return kStefanBoltzmann * std::pow(T, 4); }

/// The icosahedron subdivided `k` times, each new corner pushed onto the unit sphere: corners and
/// triangles counter-clockwise seen from outside.
std::pair<std::vector<Vec3>, std::vector<std::array<Index, 3>>> geodesic_sphere(int k) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                         {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  for (Vec3& p : v) p.normalize();
  std::vector<std::array<Index, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                         {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                         {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                         {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < k; ++level) {
    std::map<std::pair<Index, Index>, Index> middle;
    const auto mid = [&](Index a, Index b) {
      const auto key = std::minmax(a, b);
      const auto it = middle.find(key);
      if (it != middle.end()) return it->second;
      v.push_back((v[static_cast<std::size_t>(a)] + v[static_cast<std::size_t>(b)]).normalized());
      return middle[key] = static_cast<Index>(v.size() - 1);
    };
    std::vector<std::array<Index, 3>> finer;
    for (const auto& tri : f) {
      const Index ab = mid(tri[0], tri[1]), bc = mid(tri[1], tri[2]), ca = mid(tri[2], tri[0]);
      finer.push_back({tri[0], ab, ca});
      finer.push_back({ab, tri[1], bc});
      finer.push_back({ca, bc, tri[2]});
      finer.push_back({ab, bc, ca});
    }
    f = std::move(finer);
  }
  return {v, f};
}

/// The inner polyhedron (radius 1, front outside) and the outer one (radius 2, front inside),
/// each triangle a facet; the inner body's facets first.
TriangleMesh nested_spheres(int k, Index& inner_facets) {
  const auto [v, f] = geodesic_sphere(k);
  TriangleMesh m;
  m.source = "nested geodesic spheres";
  for (const double r : {1.0, 2.0}) {
    const Index base = static_cast<Index>(m.vertices.size());
    for (const Vec3& p : v) m.vertices.push_back(r * p);
    for (const auto& t : f) {
      if (r == 1.0) m.triangles.push_back({base + t[0], base + t[1], base + t[2]});
      else m.triangles.push_back({base + t[0], base + t[2], base + t[1]});  // seen from inside
      m.facet_of_triangle.push_back(m.num_facets++);
    }
  }
  inner_facets = static_cast<Index>(f.size());
  return m;
}

TEST(TwoSurfaceEnclosure, NestedPolyhedraApproachTheTextbookFormula) {
  const double T1 = 800, T2 = 300, eps1 = 0.4, eps2 = 0.7;
  std::vector<double> errors, closures;
  for (int k = 0; k <= 2; ++k) {
    Index inner = 0;
    const Scene scene(nested_spheres(k, inner));
    SurfaceGroups g;
    g.names = {"inner", "outer"};
    for (Index facet = 0; facet < 2 * inner; ++facet) g.of_facet.push_back(facet < inner ? 0 : 1);
    ThermalOptions o;
    o.solve.level = 0;
    o.solve.op.method = OperatorMethod::dense;
    o.tolerance = 1e-12;
    const ThermalSolution s = solve_thermal(scene, g, {SurfaceCondition{Given::temperature, T1, eps1, {}},
                                                       SurfaceCondition{Given::temperature, T2, eps2, {}}},
                                            o);
    ASSERT_TRUE(s.iteration.converged());
    const double A1 = s.group_area[0], A2 = s.group_area[1];
    const double textbook = A1 * (sigma_t4(T1) - sigma_t4(T2)) / (1 / eps1 + (A1 / A2) * (1 / eps2 - 1));
    errors.push_back(std::abs(s.group_Q[0] - textbook) / textbook);
    // Closed: what the inner body gives, the outer one takes, to the closure defect of the
    // discretization (rows of H 1 fall short of 1 by the collocation's error).
    closures.push_back(std::abs(s.group_Q[0] + s.group_Q[1]) / textbook);
  }
  std::printf("two-surface enclosure, k = 0, 1, 2: relative error of Q1 %.3e %.3e %.3e, of Q1 + Q2 %.3e %.3e %.3e\n",
              errors[0], errors[1], errors[2], closures[0], closures[1], closures[2]);
  // Second order in the polyhedra's edge length, which halves with k: the error falls about 4
  // times a step (measured, Release, 2026-12-07: 9.2e-3, 1.9e-3, 4.7e-4 at k = 0, 1, 2, and
  // 1.2e-4 at k = 3, left out here for its time; Q1 + Q2 2.2e-1, 4.5e-2, 1.1e-2); asked to fall
  // at least 3 times a step, and the balance to close as well.
  for (std::size_t k = 1; k < errors.size(); ++k) {
    EXPECT_LT(3 * errors[k], errors[k - 1]) << "k = " << k;
    EXPECT_LT(closures[k], closures[k - 1]) << "k = " << k;
  }
  EXPECT_LT(errors.back(), 1e-3);
}

}  // namespace
}  // namespace panelrad

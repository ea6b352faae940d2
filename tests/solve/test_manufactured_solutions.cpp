// Manufactured solutions (the paper's test method, section 3: E = u - K u for a known u) on
// meshes read from files with rounded (17-digit) coordinates, slanted faces and every triangle
// its own facet: a planar rectangle given as two triangles then has one triangle's collocation
// points at a distance ~1e-17 (rounding, not 0) from the other triangle's plane.
// Independent truths: for u = 1, K u = 1 on a closed convex surface (Lemma 1: the form factors of
// the whole surface sum to 1), so E = 1 - rho exactly; the same prism with its rectangles as one
// facet each (coplanar triangles skipped exactly, section 4.2 case (a)); the same cube rotated
// (u = |Q - centre|^2 is invariant); and the O(h) convergence of the centroid method (Table 1).
#include <panelrad/operator/collocation.hpp>
#include <panelrad/operator/dense_operator.hpp>
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/mesh_io.hpp>
#include <panelrad/geometry/validation.hpp>
#include <panelrad/scene/scene.hpp>
#include <panelrad/solve/solvers.hpp>

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using namespace panelrad;

const std::string kMeshDir = std::string(PANELRAD_SOURCE_DIR) + "/tests/data/meshes/";

// The rounded meshes of tests/data/meshes (make_rounded_meshes.py): every face a triangle.
const std::vector<std::string> kRoundedMeshes = {"prism_rounded.off", "oblique_prism_rotated.off",
                                                 "cube_rotated.off", "octahedron_rotated.off"};

geometry::TriangleMesh read_valid(const std::string& file) {
  geometry::TriangleMesh mesh = geometry::read_mesh(kMeshDir + file);
  const geometry::ValidationReport report = geometry::validate_closed_convex(mesh);
  EXPECT_TRUE(report.valid) << file << ": " << report.message;
  return mesh;
}

// rho differing per facet, in [0.2, 0.8): E = u - rho K u then differs per facet too.
std::vector<double> facet_reflectivity(Index facets) {
  std::vector<double> rho(static_cast<std::size_t>(facets));
  for (std::size_t f = 0; f < rho.size(); ++f)
    rho[f] = 0.2 + 0.6 * static_cast<double>(f) / static_cast<double>(rho.size());
  return rho;
}

Vec3 centroid(const geometry::TriangleMesh& mesh) {
  Vec3 c = Vec3::Zero();
  for (const Vec3& v : mesh.vertices) c += v;
  return c / static_cast<double>(mesh.vertices.size());
}

// u = 1: E = 1 - rho at every collocation point. Each triangle's integral is requested to 1e-11
// relative and all are positive with sum 1, so |K u - 1| <= 1e-11 plus rounding.
TEST(ManufacturedSolutions, ConstantSolutionGivesOneMinusRhoOnRoundedMeshes) {
  for (const std::string& file : kRoundedMeshes) {
    Scene scene(read_valid(file));
    scene.set_reflectivity(facet_reflectivity(scene.num_facets()));
    scene.set_manufactured_solution([](const Vec3&, Index) { return 1.0; });
    for (int level = 1; level <= 3; ++level) {
      const Collocation col(scene, level);
      for (Index i = 0; i < col.size(); ++i)
        ASSERT_NEAR(col.emissivity()[i], 1.0 - col.reflectivity()[i], 1e-11)
            << file << " level " << level << " point " << i;
    }
  }
}

// The rounded right prism with its rectangles as one facet each (facet ids of the triangle pairs
// merged): the coplanar partner triangle is then skipped exactly instead of integrated with
// h ~ 1e-17. The collocation points are the same, and E must agree to rounding: the
// differences are the partner's contribution, at the 1e-30 level (for |h| ~ 1e-17, see
// test_singular_integration), and the rounding of the facets' boundary rules (u is quadratic,
// so each facet is integrated over its boundary, integrate_kernel_times_quadratic_facet: the
// split triangles' diagonal parts, absent from the whole rectangle, cancel to a few eps of
// their size) and of the summation (16 terms of size <= 4 u_max): 5e-14 (1.4e-14 measured).
TEST(ManufacturedSolutions, SplitRectanglesGiveTheSameEmissivityAsWholeRectangles) {
  const geometry::TriangleMesh split = read_valid("prism_rounded.off");
  ASSERT_EQ(split.num_facets, 8);
  geometry::TriangleMesh whole = split;
  // prism_rounded.off: caps are triangles 0 and 1, rectangle j is triangles 2 + 2j, 3 + 2j.
  whole.facet_of_triangle = {0, 1, 2, 2, 3, 3, 4, 4};
  whole.num_facets = 5;
  ASSERT_TRUE(geometry::validate_closed_convex(whole).valid);
  ASSERT_EQ(geometry::count_planar_facets(whole), 5u);  // the pairs are exactly coplanar
  const auto u = [](const Vec3& q, Index) { return q.squaredNorm(); };
  Scene a(split), b(whole);
  a.set_reflectivity(0.5);
  b.set_reflectivity(0.5);
  a.set_manufactured_solution(u);
  b.set_manufactured_solution(u);
  const Collocation ca(a, 3), cb(b, 3);
  ASSERT_EQ(ca.size(), cb.size());
  for (Index i = 0; i < ca.size(); ++i) {
    ASSERT_EQ(ca.collocation_point(i), cb.collocation_point(i)) << "point " << i;
    EXPECT_NEAR(ca.emissivity()[i], cb.emissivity()[i], 5e-14) << "point " << i;
  }
}

// The rotated, rounded cube against the axis-aligned unit cube with the same triangles (vertex i
// of cube_rotated.off is the rotation of corner (i & 1, i >> 1 & 1, i >> 2 & 1) about the centre)
// for u = |Q - centre|^2, invariant under the rotation: E agrees at corresponding points. Both are
// integrated to 1e-11 relative over triangles whose contributions sum to K u <= 0.75 (u <= 3/4),
// so 3e-11 covers both errors; the rounding of the rotated data adds ~1e-15.
TEST(ManufacturedSolutions, RotatedCubeEmissivityMatchesAxisAlignedCube) {
  const geometry::TriangleMesh rotated = read_valid("cube_rotated.off");
  geometry::TriangleMesh aligned = rotated;
  for (std::size_t i = 0; i < aligned.vertices.size(); ++i)
    aligned.vertices[i] = Vec3(static_cast<double>(i & 1), static_cast<double>((i >> 1) & 1),
                               static_cast<double>((i >> 2) & 1));
  ASSERT_TRUE(geometry::validate_closed_convex(aligned).valid);
  const Vec3 cr = centroid(rotated), ca = centroid(aligned);
  Scene sr(rotated), sa(aligned);
  sr.set_reflectivity(0.5);
  sa.set_reflectivity(0.5);
  sr.set_manufactured_solution([cr](const Vec3& q, Index) { return (q - cr).squaredNorm(); });
  sa.set_manufactured_solution([ca](const Vec3& q, Index) { return (q - ca).squaredNorm(); });
  const Collocation colr(sr, 3), cola(sa, 3);
  ASSERT_EQ(colr.size(), cola.size());
  for (Index i = 0; i < colr.size(); ++i) {
    // corresponding points: same distance to the centre and to the first vertex
    ASSERT_NEAR((colr.collocation_point(i) - cr).norm(), (cola.collocation_point(i) - ca).norm(), 1e-14);
    ASSERT_NEAR((colr.collocation_point(i) - rotated.vertices[0]).norm(),
                (cola.collocation_point(i) - aligned.vertices[0]).norm(), 1e-14);
    EXPECT_NEAR(colr.emissivity()[i], cola.emissivity()[i], 3e-11) << "point " << i;
  }
}

// A smooth u = |Q - c|^2 (the paper's (31) about the centroid c): the centroid method's error
// max_k |u(P_k) - u_n(P_k)| (dense exact operator, LU) falls like O(h), halving per level as in
// Table 1 (ratios 1.88-1.96 from level 1 on). Measured here, levels 1->2 and 2->3: prism
// 1.66, 1.78; oblique prism 1.54, 1.76; cube 1.83, 1.84; octahedron 2.40, 2.00. Accepted: a
// decrease by at least 1.4 from level 1 (still pre-asymptotic on the elongated oblique
// triangles), then a ratio in [1.6, 2.6] about the O(h) rate 2. A wrong E (an error in K u)
// would stall the decrease at the size of that error.
TEST(ManufacturedSolutions, SmoothSolutionConvergesOnRoundedMeshes) {
  for (const std::string& file : kRoundedMeshes) {
    const geometry::TriangleMesh mesh = read_valid(file);
    const Vec3 c = centroid(mesh);
    Scene scene(mesh);
    scene.set_reflectivity(facet_reflectivity(scene.num_facets()));
    scene.set_manufactured_solution([c](const Vec3& q, Index) { return (q - c).squaredNorm(); });
    std::vector<double> errors;
    for (int level = 1; level <= 3; ++level) {
      const Collocation col(scene, level);
      const DenseOperator K(col, NearFieldOptions{});
      errors.push_back(col.max_error(solve_lu(K, col.emissivity()).u));
    }
    const double first = errors[0] / errors[1], second = errors[1] / errors[2];
    EXPECT_GE(first, 1.4) << file << " errors " << errors[0] << " " << errors[1];
    EXPECT_GE(second, 1.6) << file << " errors " << errors[1] << " " << errors[2];
    EXPECT_LE(second, 2.6) << file << " errors " << errors[1] << " " << errors[2];
  }
}

}  // namespace

namespace {

// A u that no quadrature resolves (1 or 1.5 by a hash of the bits of Q, discontinuous
// everywhere) is a clear error naming the point, its facet, the triangle and the mesh, not a
// hang or a silent value.
TEST(ManufacturedSolutions, UnresolvableSolutionIsAClearErrorNamingTheTriangle) {
  Scene scene(read_valid("prism_rounded.off"));
  scene.set_reflectivity(0.5);
  scene.set_manufactured_solution([](const Vec3& q, Index) {
    const std::uint64_t bits = std::bit_cast<std::uint64_t>(q.x()) ^
                               (std::bit_cast<std::uint64_t>(q.y()) * 0x9E3779B97F4A7C15ull);
    return 1.0 + 0.5 * static_cast<double>((bits * 0xBF58476D1CE4E5B9ull) >> 63);
  });
  const geometry::TriangleMesh& mesh = scene.mesh();
  const auto& t0 = mesh.triangles[0];
  const Vec3 P = (mesh.vertices[static_cast<std::size_t>(t0[0])] +
                  mesh.vertices[static_cast<std::size_t>(t0[1])] +
                  mesh.vertices[static_cast<std::size_t>(t0[2])]) / 3.0;
  try {
    scene.manufactured_emissivity(P, mesh.facet_of_triangle[0], scene.triangle_inner_normal(0));
    FAIL() << "no error for an unresolvable manufactured solution";
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("of facet " + std::to_string(mesh.facet_of_triangle[0])), std::string::npos) << msg;
    EXPECT_NE(msg.find("over triangle 1 (facet "), std::string::npos) << msg;
    EXPECT_NE(msg.find("prism_rounded.off"), std::string::npos) << msg;
    EXPECT_NE(msg.find("more than 50000000 evaluations"), std::string::npos) << msg;
  }
}

}  // namespace

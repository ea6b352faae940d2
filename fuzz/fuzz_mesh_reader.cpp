// libFuzzer target for the mesh reader: the bytes are read as an OFF file, an OBJ file and an
// STL file (geometry::read_off / read_obj / read_stl), and whatever parses is validated as a scene
// (geometry::validate_scene: the convex check, then the general rules) and, when valid,
// subdivided once into a cluster tree; a valid general scene's faces also become occluders, and
// the shafts from a few centroids to a few faces are classified and clipped.
//
// The contract (mesh_io.hpp, validation.hpp): bad input is a geometry::MeshError, never a crash,
// a hang, another exception or a partial result. So only MeshError is caught here: any other
// exception escapes and libFuzzer reports it as a crash ("deadly signal" after std::terminate),
// as it does for sanitizer reports, timeouts (-timeout) and excessive memory (-rss_limit_mb).
#include <panelrad/geometry/cluster_tree.hpp>
#include <panelrad/geometry/mesh_io.hpp>
#include <panelrad/geometry/occluders.hpp>
#include <panelrad/geometry/scene_validation.hpp>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace panelrad::geometry;

void check_mesh(TriangleMesh& mesh) {
  // A parsed mesh is consistent: every face index in range, one facet id per triangle.
  for (const auto& t : mesh.triangles)
    for (Index v : t)
      if (v < 0 || static_cast<std::size_t>(v) >= mesh.vertices.size()) std::abort();
  if (mesh.facet_of_triangle.size() != mesh.triangles.size()) std::abort();
  for (Index f : mesh.facet_of_triangle)
    if (f < 0 || f >= mesh.num_facets) std::abort();
  for (const auto& p : mesh.vertices)
    if (!p.allFinite()) std::abort();  // the readers refuse non-finite coordinates
  const SceneValidationReport report = validate_scene(mesh);
  if (report.valid != report.rule.empty()) std::abort();  // a verdict names its rule
  if (!report.valid) return;
  // A valid mesh must subdivide without complaint (small: the fuzzer keeps inputs small).
  const ClusterTree tree(mesh, 1);
  if (tree.num_elements() != 4 * static_cast<Index>(mesh.triangles.size())) std::abort();
  if (report.shape != SceneShape::general) return;
  // Visible parts lie within their triangle: area in [0, area(tau)] up to rounding.
  const Occluders occluders(mesh);
  const auto roots = tree.level(0);
  const std::size_t m = std::min<std::size_t>(roots.size(), 6);
  std::vector<Index> among, meeting;
  VisiblePart part;
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = 0; j < m; ++j) {
      const Cluster& p = roots[i];
      const Cluster& t = roots[j];
      const Vec3 P = (p.vertex[0] + p.vertex[1] + p.vertex[2]) / 3.0;
      occluders.candidates(P, p.normal, t.vertex, t.normal, among);
      occluders.visible_part(P, p.normal, t.vertex, t.normal, among, part);
      const double area = 0.5 * (t.vertex[1] - t.vertex[0]).cross(t.vertex[2] - t.vertex[0]).norm();
      if (!std::isfinite(part.area) || part.area < 0 || part.area > area * (1 + 1e-9)) std::abort();
      (void)occluders.classify(P, p.normal, t.vertex, t.normal, among, meeting);
    }
}

enum class Format { off, obj, stl };

void read_as(Format format, const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> notes;
  try {
    TriangleMesh mesh = format == Format::obj   ? read_obj(in, "fuzz.obj", &notes)
                        : format == Format::off ? read_off(in, "fuzz.off", &notes)
                                                : read_stl(in, "fuzz.stl", &notes);
    check_mesh(mesh);
  } catch (const MeshError&) {
    // The documented outcome for bad input.
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  read_as(Format::off, text);
  read_as(Format::obj, text);
  read_as(Format::stl, text);
  return 0;
}

// libFuzzer target for the mesh reader: the bytes are read as an OFF file and as an OBJ
// file (geometry::read_off / read_obj), and whatever parses is validated
// (geometry::validate_closed_convex) and, when valid, subdivided once into a cluster tree.
//
// The contract (mesh_io.hpp, validation.hpp): bad input is a geometry::MeshError, never a crash,
// a hang, another exception or a partial result. So only MeshError is caught here: any other
// exception escapes and libFuzzer reports it as a crash ("deadly signal" after std::terminate),
// as it does for sanitizer reports, timeouts (-timeout) and excessive memory (-rss_limit_mb).
#include <panelrad/geometry/cluster_tree.hpp>
#include <panelrad/geometry/mesh_io.hpp>
#include <panelrad/geometry/validation.hpp>

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
  const ValidationReport report = validate_closed_convex(mesh);
  if (report.valid != report.rule.empty()) std::abort();  // a verdict names its rule
  if (!report.valid) return;
  // A valid mesh must subdivide without complaint (small: the fuzzer keeps inputs small).
  const ClusterTree tree(mesh, 1);
  if (tree.num_elements() != 4 * static_cast<Index>(mesh.triangles.size())) std::abort();
}

void read_as(bool obj, const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> notes;
  try {
    TriangleMesh mesh = obj ? read_obj(in, "fuzz.obj", &notes) : read_off(in, "fuzz.off", &notes);
    check_mesh(mesh);
  } catch (const MeshError&) {
    // The documented outcome for bad input.
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  read_as(false, text);
  read_as(true, text);
  return 0;
}

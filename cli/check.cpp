// panelrad check: read and validate a mesh file or a built-in scene, print what it is.
#include "commands.hpp"

#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/mesh_io.hpp>
#include <panelrad/geometry/validation.hpp>

#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace panelrad::cli {
namespace {

void check_usage(std::ostream& os) {
  os << "usage: panelrad check MESH\n"
        "       panelrad check --builtin cube|prism:K|tetrahedron|octahedron\n"
        "Reads an OFF or OBJ mesh (or builds a built-in scene) and validates it exactly as a closed\n"
        "convex polyhedron. Exit status: 0 valid, 1 invalid or unreadable, 2 usage error.\n";
}

int usage_error(const std::string& what) {
  std::cerr << "panelrad check: " << what << "\n";
  check_usage(std::cerr);
  return 2;
}

}  // namespace

int run_check(int argc, char** argv) {
  std::optional<std::string> file, builtin;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      check_usage(std::cout);
      return 0;
    }
    if (arg == "--builtin" || arg.rfind("--builtin=", 0) == 0) {
      if (builtin) return usage_error("--builtin given twice");
      if (arg == "--builtin") {
        if (i + 1 >= argc) return usage_error("--builtin needs a scene name");
        builtin = argv[++i];
      } else {
        builtin = arg.substr(10);
      }
      continue;
    }
    if (arg.size() > 1 && arg[0] == '-') return usage_error("unknown option '" + arg + "'");
    if (file) return usage_error("too many arguments ('" + *file + "' and '" + arg + "')");
    file = arg;
  }
  if (!file && !builtin) return usage_error("no mesh given");
  if (file && builtin) return usage_error("give either a mesh file or --builtin, not both");

  geometry::TriangleMesh mesh;
  std::vector<std::string> notes;
  if (builtin) {
    try {
      mesh = geometry::make_builtin(*builtin);
    } catch (const geometry::MeshError& e) {
      return usage_error(e.what());
    }
  } else {
    try {
      mesh = geometry::read_mesh(*file, &notes);
    } catch (const geometry::MeshError& e) {
      std::cout << "source: " << *file << "\n";
      std::cout << "unreadable: " << e.what() << "\n";
      return 1;
    }
  }

  const std::size_t input_faces = static_cast<std::size_t>(mesh.num_facets);
  geometry::ValidationReport report = geometry::validate_closed_convex(mesh);
  bool finite = true;
  for (const auto& p : mesh.vertices) finite = finite && p.allFinite();

  std::cout << "source: " << mesh.source << "\n";
  std::cout << "vertices: " << mesh.vertices.size() << "\n";
  std::cout << "triangles: " << mesh.triangles.size() << "\n";
  std::cout << "input faces: " << input_faces << "\n";
  if (finite) {
    std::cout << "planar facets: " << geometry::count_planar_facets(mesh) << "\n";
    std::cout.precision(12);
    std::cout << "surface area: " << geometry::surface_area(mesh) << "\n";
  } else {
    std::cout << "planar facets: (not computed: non-finite coordinates)\n";
    std::cout << "surface area: (not computed: non-finite coordinates)\n";
  }
  for (const std::string& n : notes) std::cout << "note: " << n << "\n";
  for (const std::string& n : report.notes) std::cout << "note: " << n << "\n";
  if (report.valid) {
    std::cout << "valid: closed convex polyhedron\n";
    return 0;
  }
  std::cout << "invalid: " << report.message << "\n";
  return 1;
}

}  // namespace panelrad::cli

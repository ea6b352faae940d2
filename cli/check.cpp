// panelrad check: read and validate a mesh file or a built-in scene, print what it is.
#include "commands.hpp"
#include "options.hpp"

#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/mesh_io.hpp>
#include <panelrad/geometry/scene_validation.hpp>

#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace panelrad::cli {
namespace {

const char* kCheckUsage =
    "usage: panelrad check MESH\n"
    "       panelrad check --builtin cube|prism:K|tetrahedron|octahedron\n"
    "Reads an OFF or OBJ mesh (or builds a built-in scene) and validates it as a scene: a closed\n"
    "convex polyhedron (proven exactly: no visibility to compute), or any set of planar polygons\n"
    "that do not cross, each piece consistently oriented (the visibility V(P,Q) is computed).\n"
    "Exit status: 0 valid, 1 invalid or unreadable, 2 usage error.\n";

/// What the command line says.
struct CheckCommandLine {
  std::string file;     ///< MESH
  std::string builtin;  ///< --builtin NAME
};

int run_check(const CLI::App& app, const CheckCommandLine& line) {
  const bool file_given = app.count("MESH") > 0, builtin_given = app.count("--builtin") > 0;
  if (!file_given && !builtin_given) throw UsageError("no mesh given");
  std::optional<std::string> file, builtin;
  if (file_given) file = line.file;
  if (builtin_given) builtin = line.builtin;

  geometry::TriangleMesh mesh;
  std::vector<std::string> notes;
  if (builtin) {
    try {
      mesh = geometry::make_builtin(*builtin);
    } catch (const geometry::MeshError& e) {
      throw UsageError(e.what());
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
  geometry::SceneValidationReport report = geometry::validate_scene(mesh);
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
  if (report.valid && report.shape == geometry::SceneShape::convex) {
    std::cout << "front side: inward (the closed convex surface is an enclosure, seen from inside)\n";
    std::cout << "valid: closed convex polyhedron\n";
    return 0;
  }
  if (report.valid) {
    if (report.t_junctions_split > 0) std::cout << "T-junctions split: " << report.t_junctions_split << "\n";
    std::cout << "pieces against the file's winding: " << report.pieces_against_file << "\n";
    std::cout << "faces in contact: " << report.contacts.size() << " pairs, area removed " << report.contact_area_removed
              << "\n";
    std::cout << "light: "
              << (report.closed     ? "closed (every ray from a front side ends on a front side: emitted = absorbed)"
                  : report.enclosed ? "enclosed (none leaves the scene, but open surfaces take light on their back sides)"
                                    : "open (light leaves the scene)")
              << "\n";
    std::cout << "valid: general scene (" << report.pieces << " piece" << (report.pieces == 1 ? "" : "s") << ", "
              << report.closed_pieces << " closed): the visibility V(P,Q) is computed\n";
    return 0;
  }
  std::cout << "invalid: " << report.message << "\n";
  return 1;
}

}  // namespace

Command add_check(CLI::App& panelrad) {
  auto line = std::make_shared<CheckCommandLine>();
  CLI::App* app = panelrad.add_subcommand("check", "validate a scene mesh (OFF or OBJ): convex, or general with its visibility computed");
  set_usage(*app, kCheckUsage);
  CLI::Option* mesh = app->add_option("MESH", line->file, "an OFF or OBJ mesh");
  CLI::Option* builtin =
      app->add_option("--builtin", line->builtin, "cube|prism:K|tetrahedron|octahedron")->type_name("NAME");
  mesh->excludes(builtin);
  return {app, [app, line] { return run_check(*app, *line); }};
}

}  // namespace panelrad::cli

// Writes an icosphere scene (OFF with its JSON sidecar) for `panelrad solve`, to measure the
// operator methods on inputs with many facets:
//   - convex (default): the icosahedron inscribed in the unit sphere, each triangle split into 4 by
//     its edge midpoints S times and the new vertices pushed onto the sphere: 20 4^S facets, one per
//     triangle; rho 0.5 everywhere, E = 1 on the facets whose centroid has z > 1/2 (a cap lamp). A
//     closed convex surface: V = 1 for every pair (unoccluded).
//   - --room: the same sphere inside the room [-2, 2]^3 (six square walls, two triangles each, seen
//     from inside), rho 0.5 everywhere, E = 1 on the ceiling z = 2, the sphere unlit: 6 + 20 4^S
//     facets; the sphere hides parts of the room from each other (occluded), and its own faces,
//     seen from outside, see none of each other.
//   - --enclosure: the sphere as the room, seen from inside, around the box [-0.3, 0.3]^3 (seen
//     from outside), rho 0.5 everywhere, E = 1 on the sphere's facets with z > 1/2: 20 4^S + 6
//     facets; every two faces of the sphere see each other except where the box hides them.
// Facet ids: the sphere's triangles first, then the six squares (-x, +x, -y, +y, -z, +z).
// --rho R: that reflectivity everywhere instead of 0.5 (0 <= R < 1).
//   usage: sphere_scene --subdivisions S [--room | --enclosure] [--rho R] --out PREFIX
//          (writes PREFIX.off, PREFIX.json)
// Example: sphere_scene --subdivisions 4 --out /tmp/ico5120 writes the 5,120-facet sphere; then
//   panelrad solve /tmp/ico5120.off --levels 0 --method auto
#include <panelrad/geometry/builtin_scenes.hpp>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace {

using Vec3 = Eigen::Vector3d;
using Face = std::vector<int>;

struct Surface {
  std::vector<Vec3> vertices;
  std::vector<Face> faces;  // counter-clockwise seen from the front
};

/// geometry::make_icosphere as vertices and faces.
Surface icosphere(int subdivisions) {
  const panelrad::geometry::TriangleMesh m = panelrad::geometry::make_icosphere(subdivisions);
  Surface s;
  s.vertices = m.vertices;
  for (const auto& t : m.triangles) s.faces.push_back({t[0], t[1], t[2]});
  return s;
}

int usage() {
  std::cerr << "usage: sphere_scene --subdivisions S [--room | --enclosure] [--rho R] --out PREFIX\n"
               "  (S in 0..6, 0 <= R < 1; writes PREFIX.off and PREFIX.json)\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  int subdivisions = -1;
  bool room = false, enclosure = false;
  double rho = 0.5;
  std::string prefix;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--subdivisions") && i + 1 < argc) {
      subdivisions = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--room")) {
      room = true;
    } else if (!std::strcmp(argv[i], "--enclosure")) {
      enclosure = true;
    } else if (!std::strcmp(argv[i], "--rho") && i + 1 < argc) {
      rho = std::atof(argv[++i]);
    } else if (!std::strcmp(argv[i], "--out") && i + 1 < argc) {
      prefix = argv[++i];
    } else {
      return usage();
    }
  }
  if (subdivisions < 0 || subdivisions > 6 || prefix.empty() || (room && enclosure) || !(rho >= 0 && rho < 1))
    return usage();

  Surface s = icosphere(subdivisions);
  const std::size_t sphere_faces = s.faces.size();
  if (enclosure)  // the sphere as a room: counter-clockwise seen from inside
    for (Face& f : s.faces) std::reverse(f.begin(), f.end());
  std::vector<std::size_t> lit;  // facets with E = 1
  for (std::size_t f = 0; f < sphere_faces; ++f) {
    const Face& t = s.faces[f];
    const double z = (s.vertices[static_cast<std::size_t>(t[0])] + s.vertices[static_cast<std::size_t>(t[1])] +
                      s.vertices[static_cast<std::size_t>(t[2])]).z() / 3;
    if (!room && z > 0.5) lit.push_back(f);
  }
  if (room || enclosure) {
    // Corners of the cube [-c, c]^3, numbered by the bits (x, y, z); each square counter-clockwise
    // seen from its front: from inside the room, from outside the box (reversed below).
    const double c = room ? 2 : 0.3;
    const int base = static_cast<int>(s.vertices.size());
    for (int k = 0; k < 8; ++k) s.vertices.emplace_back(k & 1 ? c : -c, k & 2 ? c : -c, k & 4 ? c : -c);
    const std::array<Face, 6> walls = {{{0, 2, 6, 4},    // x = -c, seen from +x
                                        {1, 5, 7, 3},    // x = +c, seen from -x
                                        {0, 4, 5, 1},    // y = -c, seen from +y
                                        {2, 3, 7, 6},    // y = +c, seen from -y
                                        {0, 1, 3, 2},    // z = -c (floor), seen from +z
                                        {4, 6, 7, 5}}};  // z = +c (ceiling), seen from -z
    for (const Face& w : walls) {
      Face f;
      for (int v : w) f.push_back(base + v);
      if (enclosure) std::reverse(f.begin(), f.end());
      s.faces.push_back(f);
    }
    if (room) lit.push_back(s.faces.size() - 1);
  }

  std::ofstream off(prefix + ".off");
  const char* mode = room ? " --room" : enclosure ? " --enclosure" : "";
  off << "OFF\n# sphere_scene --subdivisions " << subdivisions << mode << ": " << sphere_faces << " sphere facets"
      << (room ? " in the room [-2, 2]^3" : enclosure ? " around the box [-0.3, 0.3]^3" : "") << "\n";
  off << s.vertices.size() << ' ' << s.faces.size() << " 0\n";
  char buf[128];
  for (const Vec3& p : s.vertices) {
    std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g\n", p.x(), p.y(), p.z());
    off << buf;
  }
  for (const Face& f : s.faces) {
    off << f.size();
    for (int v : f) off << ' ' << v;
    off << '\n';
  }
  std::ofstream json(prefix + ".json");
  char rho_text[32];  // shortest round-trip form
  const auto end = std::to_chars(rho_text, rho_text + sizeof rho_text, rho).ptr;
  json << "{\n  \"channels\": [\"value\"],\n  \"default\": { \"rho\": " << std::string(rho_text, end)
       << ", \"E\": 0 },\n"
       << "  \"facets\": [\n    { \"ids\": [";
  for (std::size_t k = 0; k < lit.size(); ++k) json << (k ? ", " : "") << lit[k];
  json << "], \"E\": 1 }\n  ]\n}\n";
  if (!off || !json) {
    std::cerr << "sphere_scene: could not write " << prefix << ".off / .json\n";
    return 1;
  }
  std::cout << prefix << ".off: " << s.vertices.size() << " vertices, " << s.faces.size() << " facets ("
            << sphere_faces << " on the sphere" << (room ? ", 6 walls" : enclosure ? ", 6 box faces" : "") << "), "
            << lit.size() << " lit\n";
  return 0;
}

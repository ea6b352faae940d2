// Builds the cluster tree (paper section 4, (39)-(40)) of the paper's cube for levels 0..L and
// prints the build time, n, the bytes held and the bytes per element of each level.
//   usage: subdivision_memory [L]   (default 7: n = 196,608)
#include <panelrad/geometry/builtin_scenes.hpp>
#include <panelrad/geometry/cluster_tree.hpp>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

int main(int argc, char** argv) {
  using namespace panelrad::geometry;
  int finest = 7;
  if (argc > 2) {
    std::fprintf(stderr, "usage: %s [finest_level]\n", argv[0]);
    return 2;
  }
  if (argc == 2) {
    char* end = nullptr;
    const long value = std::strtol(argv[1], &end, 10);
    if (end == argv[1] || *end != '\0' || value < 0 || value > 15) {
      std::fprintf(stderr, "subdivision_memory: level '%s' is not an integer in [0, 15]\n", argv[1]);
      return 2;
    }
    finest = static_cast<int>(value);
  }
  try {
    const TriangleMesh cube = make_cube();
    std::printf("%5s %10s %10s %14s %12s %12s\n", "level", "n", "build_s", "bytes", "bytes/elem", "estimate");
    for (int level = 0; level <= finest; ++level) {
      const auto start = std::chrono::steady_clock::now();
      const ClusterTree tree(cube, level);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::printf("%5d %10d %10.3f %14zu %12.1f %12zu\n", level, tree.num_elements(), seconds, tree.bytes(),
                  tree.bytes_per_element(), ClusterTree::estimate_bytes(tree.num_roots(), level));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "subdivision_memory: %s\n", e.what());
    return 1;
  }
  return 0;
}

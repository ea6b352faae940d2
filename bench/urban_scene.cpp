// Writes an urban-like open scene (OBJ) for `panelrad viewfactors --groups object`: a K x K grid
// of box buildings of different heights on a ground plane, open to the sky.
//   - buildings: footprint W x W (W = 1) on a grid of pitch P = 2 (streets of width 1 between
//     them), heights in [1, 4] from a fixed pseudo-random sequence (--seed), each building's four
//     walls and roof an object of its own ("b<i>_<j> roof", "... west", "... east", "... south",
//     "... north"), front sides outside; no bottom (it stands on the ground);
//   - ground: the street cells of the grid lines x, y in {0, 1, 2, ..., 2K + 1} that no building
//     stands on, each a unit square facing up, all one object "ground"; a margin of one street
//     around the blocks;
//   - groups: 5 K^2 + 1 (K = 14: 981), input triangles 10 K^2 + 2 ((2K + 1)^2 - K^2).
// Faces are wound counter-clockwise seen from their front side.
// Every wall stands on the ground's cell edges, so no face crosses another and the scene is open
// (the sky sees everything from above).
//   usage: urban_scene --blocks K [--seed S] --out FILE.obj
// Example: urban_scene --blocks 14 --out /tmp/city.obj; then
//   panelrad viewfactors /tmp/city.obj --groups object --levels 2 --no-estimate
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

namespace {

struct Options {
  int blocks = 0;
  std::uint64_t seed = 1;
  std::string out;
};

[[noreturn]] void usage(const std::string& why) {
  std::cerr << "urban_scene: " << why << "\nusage: urban_scene --blocks K [--seed S] --out FILE.obj\n";
  std::exit(2);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (a + 1 >= argc) usage("option " + arg + " needs a value");
    const std::string value = argv[++a];
    if (arg == "--blocks") {
      char* end = nullptr;
      const long k = std::strtol(value.c_str(), &end, 10);
      if (*end != '\0' || k < 1 || k > 200) usage("--blocks must be an integer in [1, 200]");
      o.blocks = static_cast<int>(k);
    } else if (arg == "--seed") {
      char* end = nullptr;
      o.seed = std::strtoull(value.c_str(), &end, 10);
      if (*end != '\0') usage("--seed must be a non-negative integer");
    } else if (arg == "--out") {
      o.out = value;
    } else {
      usage("unknown option " + arg);
    }
  }
  if (o.blocks == 0) usage("--blocks is required");
  if (o.out.empty()) usage("--out is required");
  return o;
}

/// The OBJ being written: vertices shared by position on the integer grid (and the heights).
class Obj {
 public:
  int vertex(double x, double y, double z) {
    text_ << "v " << x << ' ' << y << ' ' << z << '\n';
    return ++vertices_;
  }
  void object(const std::string& name) { text_ << "o " << name << '\n'; }
  void quad(int a, int b, int c, int d) { text_ << "f " << a << ' ' << b << ' ' << c << ' ' << d << '\n'; }
  std::string str() const { return text_.str(); }

 private:
  std::ostringstream text_;
  int vertices_ = 0;
};

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  const int K = o.blocks, lines = 2 * K + 2;  // grid lines 0 .. 2K + 1
  std::uint64_t state = o.seed * 6364136223846793005ULL + 1442695040888963407ULL;
  const auto next_height = [&state] {  // 1 + 3 u, u uniform in [0, 1): PCG-style LCG, top bits
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return 1.0 + 3.0 * static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  Obj obj;
  std::vector<int> ground(static_cast<std::size_t>(lines * lines));  // the ground's vertex at (x, y)
  for (int y = 0; y < lines; ++y)
    for (int x = 0; x < lines; ++x) ground[static_cast<std::size_t>(y * lines + x)] = obj.vertex(x, y, 0);
  const auto at = [&](int x, int y) { return ground[static_cast<std::size_t>(y * lines + x)]; };
  // A building on cell (x, y) with x, y odd: block (i, j) = ((x - 1) / 2, (y - 1) / 2).
  const auto built = [](int x, int y) { return x % 2 == 1 && y % 2 == 1; };
  obj.object("ground");
  for (int y = 0; y + 1 < lines; ++y)
    for (int x = 0; x + 1 < lines; ++x)
      if (!built(x, y)) obj.quad(at(x, y), at(x + 1, y), at(x + 1, y + 1), at(x, y + 1));  // up
  for (int y = 1; y < lines - 1; y += 2)
    for (int x = 1; x < lines - 1; x += 2) {
      const double h = next_height();
      std::ostringstream label;
      label << 'b' << (x - 1) / 2 << '_' << (y - 1) / 2;
      const std::string name = label.str();
      const int t00 = obj.vertex(x, y, h), t10 = obj.vertex(x + 1, y, h), t11 = obj.vertex(x + 1, y + 1, h),
                t01 = obj.vertex(x, y + 1, h);
      const int g00 = at(x, y), g10 = at(x + 1, y), g11 = at(x + 1, y + 1), g01 = at(x, y + 1);
      obj.object(name + " roof");
      obj.quad(t00, t10, t11, t01);  // +z
      obj.object(name + " west");
      obj.quad(g00, t00, t01, g01);  // -x
      obj.object(name + " east");
      obj.quad(g10, g11, t11, t10);  // +x
      obj.object(name + " south");
      obj.quad(g00, g10, t10, t00);  // -y
      obj.object(name + " north");
      obj.quad(g01, t01, t11, g11);  // +y
    }
  std::ofstream out(o.out, std::ios::binary);
  out << "# urban_scene --blocks " << K << " --seed " << o.seed << ": " << K * K << " buildings, " << 5 * K * K + 1
      << " objects\n"
      << obj.str();
  out.close();
  if (!out) {
    std::cerr << "urban_scene: cannot write " << o.out << "\n";
    return 1;
  }
  std::printf("wrote %s: %d buildings, %d objects, %d input triangles\n", o.out.c_str(), K * K, 5 * K * K + 1,
              10 * K * K + 2 * (lines - 1) * (lines - 1) - 2 * K * K);
  return 0;
}

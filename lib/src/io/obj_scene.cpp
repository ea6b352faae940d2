// OBJ + MTL scenes: the OBJ's faces take the material of the last usemtl; the MTL files it names
// (mtllib) give rho = Kd and E = Ke per material, in channels R, G, B. Every error names the file
// and the line.
#include "scene_reading.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <system_error>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string_view>
#include <utility>

namespace panelrad::io_detail {

namespace {

namespace fs = std::filesystem;

/// One non-blank content line, split into tokens.
struct Line {
  long number = 0;
  std::vector<std::string> tokens;
};

/// Content lines of an MTL file: '#' starts a comment, blank lines are skipped.
std::vector<Line> split_lines(const std::string& text) {
  std::vector<Line> lines;
  long number = 0;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    ++number;
    std::string_view line(text.data() + pos, end - pos);
    pos = end + 1;
    const std::size_t hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    Line l{number, {}};
    for (std::size_t i = 0; i < line.size();) {
      while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
      std::size_t j = i;
      while (j < line.size() && !std::isspace(static_cast<unsigned char>(line[j]))) ++j;
      if (j > i) l.tokens.emplace_back(line.substr(i, j - i));
      i = j;
    }
    if (!l.tokens.empty()) lines.push_back(std::move(l));
  }
  return lines;
}

/// Tokens from `first` on, joined by single spaces (material names).
std::string join_from(const std::vector<std::string>& tokens, std::size_t first) {
  std::string s;
  for (std::size_t t = first; t < tokens.size(); ++t) s += (s.empty() ? "" : " ") + tokens[t];
  return s;
}


struct Material {
  std::string file;
  long line = 0;  ///< of newmtl
  std::optional<std::array<double, 3>> kd;
  long kd_line = 0;
  std::array<double, 3> ke{0.0, 0.0, 0.0};
  long ke_line = 0;
};

/// MTL statements that do not enter diffuse radiosity and are read over: ambient, specular and
/// transmission colours, specular exponent, refraction index, dissolve, illumination model, bump,
/// displacement and reflection maps, and the PBR extension (roughness, metallic, sheen,
/// clearcoat, anisotropy, normal map). Texture maps (map_*) are recognised by their prefix.
constexpr const char* kIgnoredMtl[] = {"Ka",  "Ks", "Ns", "Ni",  "d",   "Tr",    "Tf",     "illum", "sharpness",
                                       "bump", "disp", "decal", "refl", "Pr", "Pm", "Ps", "Pc", "Pcr",
                                       "aniso", "anisor", "norm"};

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

/// "Kd r g b" / "Ke r g b": exactly three numbers (a single grey value is not standard MTL).
std::array<double, 3> colour(const Line& l, const std::string& file) {
  const std::string& key = l.tokens[0];
  if (l.tokens.size() != 4)
    fail(file, l.number, key + " needs three numbers r g b, found " +
                             (l.tokens.size() > 1 ? in_quotes(join_from(l.tokens, 1)) : "none"));
  std::array<double, 3> c{};
  for (std::size_t k = 0; k < 3; ++k) {
    std::string_view tok = l.tokens[k + 1];
    if (tok.size() > 1 && tok[0] == '+' && tok[1] != '-') tok.remove_prefix(1);
    const char* last = tok.data() + tok.size();
    const auto [ptr, ec] = std::from_chars(tok.data(), last, c[k], std::chars_format::general);
    if (ec == std::errc::result_out_of_range || (ec == std::errc() && ptr == last && !std::isfinite(c[k])))
      fail(file, l.number, key + " component " + in_quotes(l.tokens[k + 1]) + " is not a finite number");
    if (ec != std::errc() || ptr != last)
      fail(file, l.number, key + " component " + in_quotes(l.tokens[k + 1]) + " is not a number");
  }
  return c;
}

/// Parses one MTL file into `materials` (name -> material). MTL statements are case-sensitive:
/// newmtl, Kd (rho) and Ke (E) are read; a statement given twice in one material, a miscased
/// newmtl/Kd/Ke (`kd`, `KE`: read as nothing they would silently leave rho or E at another value)
/// and an unknown statement are errors naming the line; the statements in kIgnoredMtl and texture
/// maps are read over, with a note where ignoring them changes what the file means (map_Kd,
/// map_Ke: textured rho or E; d < 1 or Tr > 0: a transparent surface, while the radiosity equation
/// has opaque ones; a miscased ignored statement).
void parse_mtl(const std::string& path, const std::string& role, std::map<std::string, Material>& materials,
               std::size_t& defined, std::vector<std::string>& notes, const TextReadOptions& options) {
  const std::string text = read_text(path, role, options);
  Material* current = nullptr;
  std::string current_name;
  const auto note = [&](long line, const std::string& what) {
    notes.push_back(path + ":" + std::to_string(line) + ": " + what);
  };
  for (const Line& l : split_lines(text)) {
    const std::string& key = l.tokens[0];
    const std::string key_lower = lower(key);
    if (key == "newmtl") {
      if (l.tokens.size() < 2) fail(path, l.number, "newmtl without a material name");
      current_name = join_from(l.tokens, 1);
      const auto [it, inserted] = materials.try_emplace(current_name, Material{path, l.number, {}, 0, {}, 0});
      if (!inserted)
        fail(path, l.number, "material " + in_quotes(current_name) + " is defined twice (first at " + it->second.file +
                                 ":" + std::to_string(it->second.line) + ")");
      current = &it->second;
      ++defined;
    } else if (key == "Kd" || key == "Ke") {
      if (!current) fail(path, l.number, key + " before any newmtl");
      const long first = key == "Kd" ? current->kd_line : current->ke_line;
      if (first > 0)
        fail(path, l.number, key + " given twice in material " + in_quotes(current_name) + " (lines " +
                                 std::to_string(first) + " and " + std::to_string(l.number) +
                                 "): which one is meant is not clear");
      const std::array<double, 3> c = colour(l, path);
      if (key == "Kd") {
        current->kd = c;
        current->kd_line = l.number;
      } else {
        current->ke = c;
        current->ke_line = l.number;
      }
    } else if (key_lower == "newmtl" || key_lower == "kd" || key_lower == "ke") {
      const std::string meant = key_lower == "newmtl" ? "newmtl" : key_lower == "kd" ? "Kd" : "Ke";
      fail(path, l.number, "unknown MTL statement " + in_quotes(key) + ": MTL statements are case-sensitive; write " +
                               in_quotes(meant) + (meant == "Kd"   ? " (the reflectivity rho)"
                                                   : meant == "Ke" ? " (the emission E)"
                                                                   : ""));
    } else if (key_lower.rfind("map_", 0) == 0) {
      if (key_lower == "map_kd" || key_lower == "map_ke")
        note(l.number, key + " ignored: a texture is not applied; " +
                           (key_lower == "map_kd" ? "rho is the constant Kd" : "E is the constant Ke") +
                           " of material " + in_quotes(current_name));
    } else {
      const auto known = std::find_if(std::begin(kIgnoredMtl), std::end(kIgnoredMtl),
                                      [&](const char* k) { return key_lower == lower(k); });
      if (known == std::end(kIgnoredMtl))
        fail(path, l.number, "unknown MTL statement " + in_quotes(key) +
                                 " (read: newmtl, Kd, Ke; read over: Ka, Ks, Ns, Ni, d, Tr, Tf, illum, map_*, bump, ...)");
      if (key != *known) note(l.number, in_quotes(key) + " read as " + in_quotes(*known) + " and ignored");
      double value = 0;
      if ((*known == std::string("d") || *known == std::string("Tr")) && l.tokens.size() == 2) {
        const std::string& tok = l.tokens[1];
        const auto [ptr, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), value);
        const bool transparent = *known == std::string("d") ? value < 1.0 : value > 0.0;
        if (ec == std::errc() && ptr == tok.data() + tok.size() && transparent)
          note(l.number, key + " " + tok + " ignored: material " + in_quotes(current_name) +
                             " is read as opaque (the radiosity equation has no transmission)");
      }
    }
  }
}

/// Every face has a material: the reader counted as many faces as the mesh has facets, and each
/// comes after a usemtl.
void check_face_materials(const geometry::ObjMaterialUse& use, std::size_t nf, const std::string& path) {
  if (use.face_material.size() != nf)
    fail(path, 0, "internal error: " + std::to_string(use.face_material.size()) + " faces but the mesh has " +
                      std::to_string(nf) + " facets");
  for (std::size_t f = 0; f < nf; ++f)
    if (use.face_material[f].empty())
      fail(path, use.face_line[f], "facet " + std::to_string(f) + " comes before any usemtl (every face needs a material)");
}

/// The MTL files the OBJ names (path relative to the OBJ's folder, mtllib line), each file once.
std::vector<std::pair<std::string, long>> mtl_libraries(const geometry::ObjMaterialUse& use, const std::string& path) {
  std::vector<std::pair<std::string, long>> libraries;  // MTL path, mtllib line; each file once
  for (const geometry::ObjMaterialUse::Library& l : use.libraries) {
    const std::string lib = (fs::path(path).parent_path() / l.file).string();
    const bool seen = std::any_of(libraries.begin(), libraries.end(), [&](const auto& x) { return x.first == lib; });
    if (!seen) libraries.emplace_back(lib, l.line);
  }
  if (libraries.empty()) fail(path, 0, "no mtllib statement: the scene's materials (Kd = rho, Ke = E) are needed");
  return libraries;
}

/// The materials of all MTL files of an OBJ.
struct MaterialLibrary {
  std::map<std::string, Material> materials;
  std::size_t defined = 0;
  std::string file_names;  ///< "a.mtl, b.mtl", for messages
};

MaterialLibrary read_materials(const std::vector<std::pair<std::string, long>>& libraries, const std::string& path,
                               std::vector<std::string>& notes, const TextReadOptions& options) {
  MaterialLibrary library;
  for (const auto& [lib, line] : libraries) {
    parse_mtl(lib, "MTL file named by " + path + ":" + std::to_string(line), library.materials, library.defined, notes,
              options);
    library.file_names += (library.file_names.empty() ? "" : ", ") + fs::path(lib).filename().string();
  }
  return library;
}

/// Checks rho = Kd and E = Ke of material `name` in each of R, G, B; `facet` is its first user.
void check_material_values(const Material& m, const std::string& name, const std::string& facet) {
  static const char* const kChannel[3] = {"R", "G", "B"};
  for (int c = 0; c < 3; ++c) {
    const std::string rho_problem = value_problem(true, (*m.kd)[c]);
    if (!rho_problem.empty())
      fail(m.file, m.kd_line, "material " + in_quotes(name) + ": rho = Kd " + kChannel[c] + " = " +
                                  number((*m.kd)[c]) + " " + rho_problem + "; first used by " + facet);
    const std::string e_problem = value_problem(false, m.ke[c]);
    if (!e_problem.empty())
      fail(m.file, m.ke_line, "material " + in_quotes(name) + ": E = Ke " + kChannel[c] + " = " +
                                  number(m.ke[c]) + " " + e_problem + "; first used by " + facet);
  }
}

/// rho and E of every facet in channels R, G, B, from its usemtl material's Kd and Ke.
void assign_materials(SceneData& scene, const geometry::ObjMaterialUse& use, const MaterialLibrary& library,
                      const std::string& path) {
  const auto nf = static_cast<std::size_t>(scene.mesh->mesh().num_facets);
  scene.channels = {"R", "G", "B"};
  scene.rho.assign(3, std::vector<double>(nf, 0.0));
  scene.emission.assign(3, std::vector<double>(nf, 0.0));
  scene.facet_material = use.face_material;
  std::set<std::string> checked;
  for (std::size_t f = 0; f < nf; ++f) {
    const std::string& name = use.face_material[f];
    const std::string facet = "facet " + std::to_string(f) + " (" + path + ":" + std::to_string(use.face_line[f]) + ")";
    const auto it = library.materials.find(name);
    if (it == library.materials.end())
      fail(path, use.usemtl_line[f], "usemtl " + in_quotes(name) + ": unknown material (not defined in " +
                                         library.file_names + "), used by " + facet);
    const Material& m = it->second;
    if (!m.kd)
      fail(m.file, m.line, "material " + in_quotes(name) + " has no Kd (its reflectivity rho), used by " + facet);
    if (checked.insert(name).second) check_material_values(m, name, facet);  // first facet using it
    for (std::size_t c = 0; c < 3; ++c) {
      scene.rho[c][f] = (*m.kd)[c];
      scene.emission[c][f] = m.ke[c];
    }
  }
  scene.notes.push_back("materials: " + std::to_string(library.defined) + " from " + library.file_names + ", " +
                        std::to_string(checked.size()) + " used by " + std::to_string(nf) + " facets");
}

}  // namespace

SceneData load_obj_scene(const std::string& path, const TextReadOptions& options) {
  SceneData scene;
  geometry::ObjMaterialUse use;  // mtllib and per-face usemtl, as the reader counted the faces
  scene.mesh = load_mesh(path, scene.notes, options, &use);
  check_face_materials(use, static_cast<std::size_t>(scene.mesh->mesh().num_facets), path);
  const std::vector<std::pair<std::string, long>> libraries = mtl_libraries(use, path);
  const MaterialLibrary library = read_materials(libraries, path, scene.notes, options);
  assign_materials(scene, use, library, path);
  return scene;
}

}  // namespace panelrad::io_detail

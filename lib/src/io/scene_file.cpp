// Scene files: a validated closed convex mesh with rho and E per input facet (the data of the
// radiosity equation, paper (7)), in one or more channels, from OBJ + MTL or OFF + JSON sidecar.
// Every error names the file and the line or facet; nothing is returned partially.
#include <panelrad/geometry/mesh_io.hpp>
#include <panelrad/support/text_file.hpp>
#include <panelrad/geometry/scene_validation.hpp>
#include <panelrad/io/scene_file.hpp>

#include "scene_file_internal.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cfloat>
#include <cmath>
#include <filesystem>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <system_error>
#include <unordered_map>

namespace panelrad {
namespace {

namespace fs = std::filesystem;

// A scene file's data as it is read; a Scene once complete (to_scene).
struct SceneData {
  std::optional<geometry::ValidatedMesh> mesh;  // set by load_mesh
  std::vector<std::string> channels;
  std::vector<std::vector<double>> rho, emission;  // [channel][facet], checked as read
  std::vector<std::string> facet_material;
  std::vector<std::string> notes;
};

Scene to_scene(SceneData&& data) {
  Scene scene(std::move(*data.mesh), std::move(data.channels));
  for (std::size_t c = 0; c < data.rho.size(); ++c) {
    scene.set_reflectivity(std::move(data.rho[c]), c);
    scene.set_emissivity(std::move(data.emission[c]), c);
  }
  scene.set_facet_material(std::move(data.facet_material));
  for (std::string& note : data.notes) scene.add_note(std::move(note));
  return scene;
}
using geometry::Index;
using Json = nlohmann::json;

[[noreturn]] void fail(const std::string& file, long line, const std::string& what) {
  if (line > 0) throw SceneFileError(file + ":" + std::to_string(line) + ": " + what);
  throw SceneFileError(file + ": " + what);
}

std::string in_quotes(const std::string& s) { return "'" + s + "'"; }

/// Shortest round-trip text of a number (inf, nan as such).
std::string number(double v) {
  char buf[40];
  const auto [ptr, ec] = std::to_chars(buf, buf + sizeof buf, v);
  return ec == std::errc() ? std::string(buf, ptr) : std::to_string(v);
}

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

/// The whole file, by the bounded reader (text_file.hpp: regular files only, size limit, no NUL
/// byte); `role` says what it is for in messages ("MTL file named by x.obj:3").
std::string read_text(const std::string& path, const std::string& role, const TextReadOptions& options) {
  try {
    return read_text_file(path, role, options);
  } catch (const TextFileError& e) {
    throw SceneFileError(e.what());
  }
}

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

/// Checks one value of rho or E; returns what is wrong, or "" when fine.
std::string value_problem(bool is_rho, double v) { return is_rho ? reflectivity_problem(v) : emission_problem(v); }

/// Reads and validates the mesh as a scene (geometry::try_validate: convex, or general with its
/// visibility computed); notes get the reader's and the validator's notes. For an OBJ,
/// `materials` (when given) gets its mtllib and per-face usemtl statements.
geometry::ValidatedMesh load_mesh(const std::string& path, std::vector<std::string>& notes,
                                  const TextReadOptions& options, geometry::ObjMaterialUse* materials = nullptr) {
  geometry::TriangleMesh mesh;
  try {
    mesh = materials ? geometry::read_obj_with_materials(path, *materials, &notes, options)
                     : geometry::read_mesh(path, &notes, options);
  } catch (const geometry::MeshError& e) {
    throw SceneFileError(e.what());
  }
  geometry::SceneValidationReport report;
  std::optional<geometry::ValidatedMesh> validated = geometry::try_validate(std::move(mesh), report);
  if (!validated) fail(path, 0, "invalid scene mesh: " + report.message);
  for (const std::string& n : report.notes) notes.push_back(path + ": " + n);
  return std::move(*validated);
}

// ---------------------------------------------------------------------------------------------
// OBJ + MTL

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
                             (l.tokens.size() > 1 ? "'" + join_from(l.tokens, 1) + "'" : "none"));
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

// ---------------------------------------------------------------------------------------------
// OFF + JSON sidecar

/// A character iterator over the JSON text that records how far nlohmann's lexer has read: the
/// parser callback then knows where each key and value ends, and so its line.
class TrackedChar {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;
  TrackedChar(const char* p, const char** read) : p_(p), read_(read) {}
  reference operator*() const { return *p_; }
  TrackedChar& operator++() {
    *read_ = ++p_;
    return *this;
  }
  TrackedChar operator++(int) {
    TrackedChar before = *this;
    ++*this;
    return before;
  }
  friend bool operator==(const TrackedChar& a, const TrackedChar& b) { return a.p_ == b.p_; }

 private:
  const char* p_;
  const char** read_;
};

/// Where things are in the JSON sidecar: the line of each value down to the facet entries' keys
/// ("facets[3].rho"; array elements inside those are not recorded, which keeps a large sidecar
/// cheap), and the first duplicate key. JSON allows duplicate keys but does not say which value
/// counts (nlohmann keeps the last): a duplicate is an error here.
struct JsonLayout {
  std::unordered_map<std::string, long> line_of;
  std::string duplicate;  ///< message for the first duplicate key; empty when none
  long duplicate_line = 0;

  long line(const std::string& path) const {
    const auto it = line_of.find(path);
    return it == line_of.end() ? 0 : it->second;
  }
};

/// Records a JsonLayout from nlohmann's parse events: each container keeps its path, the index of
/// its next element or its current key, and the lines of its keys (for duplicates).
class JsonLayoutRecorder {
 public:
  JsonLayoutRecorder(const std::string& text, JsonLayout& layout)
      : begin_(text.data()), counted_(text.data()), layout_(layout) {}

  /// One parse event; `read` is one past the last character the lexer has taken.
  void on_event(nlohmann::json::parse_event_t event, Json& parsed, const char* read) {
    using Event = nlohmann::json::parse_event_t;
    switch (event) {
      case Event::object_start:
      case Event::array_start: {
        const long at = line_before(read);
        const std::string path = child_path();
        record(path, at);
        stack_.push_back(Frame{event == Event::array_start, path, 0, "", {}});
        break;
      }
      case Event::object_end:
      case Event::array_end:
        if (!stack_.empty()) stack_.pop_back();
        break;
      case Event::key:
        on_key(parsed.get<std::string>(), line_before(read));
        break;
      case Event::value: {
        // A number is ended by the character after it, which the lexer has read already.
        const long at = line_before(parsed.is_number() && read > begin_ ? read - 1 : read);
        record(child_path(), at);
        break;
      }
    }
  }

 private:
  struct Frame {
    bool is_array = false;
    std::string path;
    std::size_t next_index = 0;
    std::string key;
    std::map<std::string, long> key_lines;
  };
  static constexpr std::size_t kRecordedDepth = 3;  // root object, "facets" array, facet entry

  // The line of the character before `end` (the last one of the token just read).
  long line_before(const char* end) {
    if (end > begin_) --end;
    if (end < counted_) return line_;  // the lexer never goes back; keep what is counted
    line_ += static_cast<long>(std::count(counted_, end, '\n'));
    counted_ = end;
    return line_;
  }

  // The path of a value that starts now inside the innermost container.
  std::string child_path() {
    if (stack_.empty()) return "";
    Frame& parent = stack_.back();
    if (parent.is_array) return parent.path + "[" + std::to_string(parent.next_index++) + "]";
    return parent.path.empty() ? parent.key : parent.path + "." + parent.key;
  }

  void record(const std::string& path, long at) {
    if (stack_.size() <= kRecordedDepth && !path.empty()) layout_.line_of.emplace(path, at);
  }

  void on_key(const std::string& key, long at) {
    Frame& object = stack_.back();
    object.key = key;
    const auto [it, inserted] = object.key_lines.try_emplace(object.key, at);
    if (!inserted && layout_.duplicate.empty())
      layout_.duplicate = "duplicate key " + in_quotes(object.key) +
                          (object.path.empty() ? std::string(" at the top level") : " in " + object.path) +
                          " (lines " + std::to_string(it->second) + " and " + std::to_string(at) +
                          "): a JSON object's keys must be unique (the later value would silently replace "
                          "the earlier)";
    if (!inserted && layout_.duplicate_line == 0) layout_.duplicate_line = at;
  }

  const char* begin_;
  long line_ = 1;  // the line of counted_[-1]
  const char* counted_;
  JsonLayout& layout_;
  std::vector<Frame> stack_;
};

/// Parses the JSON text, filling `layout`. Throws nlohmann's exceptions for bad JSON.
Json parse_json(const std::string& text, JsonLayout& layout) {
  const char* read = text.data();  // one past the last character the lexer has taken
  JsonLayoutRecorder recorder(text, layout);
  const Json::parser_callback_t callback = [&](int, nlohmann::json::parse_event_t event, Json& parsed) {
    recorder.on_event(event, parsed, read);
    return true;
  };
  return Json::parse(TrackedChar(text.data(), &read), TrackedChar(text.data() + text.size(), &read), callback);
}

/// A value for all channels: a number, or an array of one number per channel.
std::vector<double> channel_values(const Json& v, std::size_t channels, const std::string& file, long line,
                                   const std::string& where) {
  if (v.is_number()) return std::vector<double>(channels, v.get<double>());
  if (!v.is_array())
    fail(file, line, where + " is " + v.dump() + ": expected a number" +
                      (channels > 1 ? " or an array of " + std::to_string(channels) + " numbers (one per channel)" : ""));
  if (v.size() != channels)
    fail(file, line, where + " has " + std::to_string(v.size()) + " values, expected " + std::to_string(channels) +
                      " (one per channel)");
  std::vector<double> out;
  for (std::size_t c = 0; c < channels; ++c) {
    if (!v[c].is_number()) fail(file, line, where + "[" + std::to_string(c) + "] is " + v[c].dump() + ": not a number");
    out.push_back(v[c].get<double>());
  }
  return out;
}

/// Checks rho or E values of `where`; `channel_names` for messages.
void check_values(const std::vector<double>& values, bool is_rho, const std::vector<std::string>& channel_names,
                  const std::string& file, long line, const std::string& where) {
  for (std::size_t c = 0; c < values.size(); ++c) {
    const std::string problem = value_problem(is_rho, values[c]);
    if (!problem.empty())
      fail(file, line, where + ": " + (is_rho ? "rho" : "E") + " (channel " + channel_names[c] + ") = " +
                        number(values[c]) + " " + problem);
  }
}

/// The JSON sidecar's path: `materials_path`, or the OFF's path with extension .json; it must exist.
std::string sidecar_path(const std::string& path, const std::string& materials_path) {
  const std::string file =
      materials_path.empty() ? fs::path(path).replace_extension(".json").string() : materials_path;
  std::error_code ec;
  if (!fs::exists(file, ec))
    fail(file, 0, "facet data not found: expected this JSON sidecar for " + path +
                      (materials_path.empty() ? " (the OFF's path with extension .json)" : ""));
  return file;
}

/// Reads and parses the sidecar `file` of the OFF `path`: a JSON object with no duplicate key and
/// only the keys "channels", "default", "facets".
Json read_sidecar(const std::string& file, const std::string& path, const TextReadOptions& options,
                  JsonLayout& layout) {
  Json doc;
  {
    TextReadOptions json_options = options;
    json_options.strip_utf8_bom = false;  // nlohmann skips it; byte positions stay the file's
    const std::string text = read_text(file, "JSON sidecar of " + path, json_options);
    try {
      doc = parse_json(text, layout);
    } catch (const Json::parse_error& e) {
      fail(file, 0, "JSON parse error at byte " + std::to_string(e.byte) + ": " + e.what());
    } catch (const Json::exception& e) {  // e.g. a number too large for a double
      fail(file, 0, std::string("JSON error: ") + e.what());
    }
  }
  if (!layout.duplicate.empty()) fail(file, layout.duplicate_line, layout.duplicate);
  if (!doc.is_object()) fail(file, 0, "expected a JSON object with \"channels\", \"default\", \"facets\"");
  for (const auto& [key, value] : doc.items())
    if (key != "channels" && key != "default" && key != "facets")
      fail(file, layout.line(key), "unknown key " + in_quotes(key) + " (expected \"channels\", \"default\", \"facets\")");
  return doc;
}

/// The channel names: "channels", distinct and non-empty, or the one channel "value".
std::vector<std::string> read_channels(const Json& doc, const std::string& file, const JsonLayout& layout) {
  if (!doc.contains("channels")) return {"value"};
  std::vector<std::string> channels;
  const Json& ch = doc["channels"];
  if (!ch.is_array() || ch.empty()) fail(file, layout.line("channels"), "\"channels\" must be a non-empty array of names");
  for (std::size_t c = 0; c < ch.size(); ++c) {
    const std::string at = "channels[" + std::to_string(c) + "]";
    if (!ch[c].is_string() || ch[c].get<std::string>().empty())
      fail(file, layout.line(at), at + " is " + ch[c].dump() + ": expected a non-empty name");
    const std::string name = ch[c].get<std::string>();
    if (std::find(channels.begin(), channels.end(), name) != channels.end())
      fail(file, layout.line(at), "channel " + in_quotes(name) + " is named twice");
    channels.push_back(name);
  }
  return channels;
}

/// rho and E of "default", each per channel, when given.
struct DefaultValues {
  std::optional<std::vector<double>> rho, e;
};

DefaultValues read_defaults(const Json& doc, const std::vector<std::string>& channels, const std::string& file,
                            const JsonLayout& layout) {
  DefaultValues defaults;
  if (!doc.contains("default")) return defaults;
  const Json& d = doc["default"];
  if (!d.is_object())
    fail(file, layout.line("default"), "\"default\" is " + d.dump() + ": expected an object {\"rho\": .., \"E\": ..}");
  for (const auto& [key, value] : d.items()) {
    const long at = layout.line("default." + key);
    if (key != "rho" && key != "E")
      fail(file, at, "unknown key " + in_quotes(key) + " in \"default\" (expected \"rho\", \"E\")");
    std::vector<double> v = channel_values(value, channels.size(), file, at, "default " + key);
    check_values(v, key == "rho", channels, file, at, "default");
    (key == "rho" ? defaults.rho : defaults.e) = std::move(v);
  }
  return defaults;
}

/// rho and E per facet as the entries of "facets" give them, and the entry naming each facet
/// (-1: none).
struct FacetEntries {
  std::vector<std::optional<std::vector<double>>> rho, e;
  std::vector<long> entry_of;
};

/// Where the facet values are read: the sidecar `file` of the OFF `path` with nf facets.
struct SidecarContext {
  const std::string& file;
  const std::string& path;
  std::size_t nf;
  const std::vector<std::string>& channels;
  const JsonLayout& layout;
};

/// Checks the keys of entry `at`: only "id" or "ids" (exactly one), "rho", "E" (at least one).
void check_entry_keys(const Json& entry, const std::string& at, const SidecarContext& ctx) {
  const long at_line = ctx.layout.line(at);
  if (!entry.is_object()) fail(ctx.file, at_line, at + " is " + entry.dump() + ": expected an object");
  for (const auto& [key, value] : entry.items())
    if (key != "id" && key != "ids" && key != "rho" && key != "E")
      fail(ctx.file, ctx.layout.line(at + "." + key),
           at + ": unknown key " + in_quotes(key) + " (expected \"id\" or \"ids\", \"rho\", \"E\")");
  if (entry.contains("id") == entry.contains("ids"))
    fail(ctx.file, at_line, at + ": needs exactly one of \"id\" (a facet) or \"ids\" (a list of facets)");
  if (!entry.contains("rho") && !entry.contains("E")) fail(ctx.file, at_line, at + ": gives neither \"rho\" nor \"E\"");
}

/// The facets entry k (`at`) names, each in range and named by no earlier id; marks them in entry_of.
std::vector<std::size_t> entry_facets(const Json& entry, std::size_t k, const std::string& at,
                                      std::vector<long>& entry_of, const SidecarContext& ctx) {
  std::vector<Json> ids;
  const std::string id_key = entry.contains("id") ? "id" : "ids";
  const long id_line = ctx.layout.line(at + "." + id_key);
  if (entry.contains("id")) {
    ids.push_back(entry["id"]);
  } else {
    const Json& list = entry["ids"];
    if (!list.is_array() || list.empty())
      fail(ctx.file, id_line, at + ": \"ids\" must be a non-empty array of facet ids");
    ids.assign(list.begin(), list.end());
  }
  std::vector<std::size_t> targets;
  for (const Json& id : ids) {
    if (!id.is_number_integer()) fail(ctx.file, id_line, at + ": facet id " + id.dump() + " is not an integer");
    const auto value = id.get<long long>();
    if (value < 0 || static_cast<unsigned long long>(value) >= ctx.nf)
      fail(ctx.file, id_line, at + ": facet " + std::to_string(value) + " is out of range [0, " +
                                  std::to_string(ctx.nf - 1) + "] (" + ctx.path + " has " + std::to_string(ctx.nf) +
                                  " faces)");
    const auto f = static_cast<std::size_t>(value);
    if (entry_of[f] >= 0) {
      const bool same = entry_of[f] == static_cast<long>(k);
      const std::string other = "facets[" + std::to_string(entry_of[f]) + "]";
      const long other_line = ctx.layout.line(other);
      fail(ctx.file, id_line,
           at + ": facet " + std::to_string(f) + " is given twice (also in " +
               (same ? std::string("this entry")
                     : other + (other_line > 0 ? " at line " + std::to_string(other_line) : std::string())) +
               ")");
    }
    entry_of[f] = static_cast<long>(k);
    targets.push_back(f);
  }
  return targets;
}

/// Reads entry k of "facets" into `entries`.
void read_facet_entry(const Json& entry, std::size_t k, FacetEntries& entries, const SidecarContext& ctx) {
  const std::string at = "facets[" + std::to_string(k) + "]";
  check_entry_keys(entry, at, ctx);
  const std::vector<std::size_t> targets = entry_facets(entry, k, at, entries.entry_of, ctx);
  const std::string who = at + " (facet " + std::to_string(targets.front()) +
                          (targets.size() > 1 ? " and " + std::to_string(targets.size() - 1) + " more" : "") + ")";
  for (const char* key : {"rho", "E"}) {
    if (!entry.contains(key)) continue;
    const bool is_rho = std::string(key) == "rho";
    const long key_line = ctx.layout.line(at + "." + key);
    const std::vector<double> v = channel_values(entry[key], ctx.channels.size(), ctx.file, key_line, who + " " + key);
    check_values(v, is_rho, ctx.channels, ctx.file, key_line, who);
    for (std::size_t f : targets) (is_rho ? entries.rho : entries.e)[f] = v;
  }
}

/// The entries of "facets" (an array of {"id" or "ids", "rho", "E"}), when given.
FacetEntries read_facet_entries(const Json& doc, const SidecarContext& ctx) {
  FacetEntries entries{std::vector<std::optional<std::vector<double>>>(ctx.nf),
                       std::vector<std::optional<std::vector<double>>>(ctx.nf), std::vector<long>(ctx.nf, -1)};
  if (!doc.contains("facets")) return entries;
  const Json& facets = doc["facets"];
  if (!facets.is_array())
    fail(ctx.file, ctx.layout.line("facets"), "\"facets\" must be an array of {\"id\" or \"ids\", \"rho\", \"E\"}");
  for (std::size_t k = 0; k < facets.size(); ++k) read_facet_entry(facets[k], k, entries, ctx);
  return entries;
}

/// Every facet needs both values, from its entry or the default.
void assign_facet_values(SceneData& scene, const FacetEntries& entries, const DefaultValues& defaults,
                         const SidecarContext& ctx) {
  const std::size_t nf = ctx.nf, nc = scene.channels.size();
  const std::vector<long>& entry_of = entries.entry_of;
  scene.rho.assign(nc, std::vector<double>(nf, 0.0));
  scene.emission.assign(nc, std::vector<double>(nf, 0.0));
  scene.facet_material.assign(nf, "");
  std::size_t listed = 0;
  for (std::size_t f = 0; f < nf; ++f) {
    if (entry_of[f] >= 0) ++listed;
    for (const bool is_rho : {true, false}) {
      const auto& given = (is_rho ? entries.rho : entries.e)[f];
      const auto& fallback = is_rho ? defaults.rho : defaults.e;
      if (!given && !fallback)
        fail(ctx.file, entry_of[f] >= 0 ? ctx.layout.line("facets[" + std::to_string(entry_of[f]) + "]") : 0,
             "facet " + std::to_string(f) + " has no " + (is_rho ? "rho" : "E") +
                 (entry_of[f] >= 0 ? " (in facets[" + std::to_string(entry_of[f]) + "])" : " (not listed)") +
                 " and there is no default " + (is_rho ? "rho" : "E"));
      const std::vector<double>& v = given ? *given : *fallback;
      for (std::size_t c = 0; c < nc; ++c) (is_rho ? scene.rho : scene.emission)[c][f] = v[c];
    }
  }
  scene.notes.push_back("facet data: " + ctx.file + ", " + std::to_string(nc) + " channel" + (nc > 1 ? "s" : "") +
                        ", " + std::to_string(listed) + " of " + std::to_string(nf) + " facets listed");
}

SceneData load_off_scene(const std::string& path, const std::string& materials_path,
                            const TextReadOptions& options) {
  SceneData scene;
  scene.mesh = load_mesh(path, scene.notes, options);
  const auto nf = static_cast<std::size_t>(scene.mesh->mesh().num_facets);
  const std::string file = sidecar_path(path, materials_path);
  JsonLayout layout;
  const Json doc = read_sidecar(file, path, options, layout);
  scene.channels = read_channels(doc, file, layout);
  const DefaultValues defaults = read_defaults(doc, scene.channels, file, layout);
  const SidecarContext ctx{file, path, nf, scene.channels, layout};
  const FacetEntries entries = read_facet_entries(doc, ctx);
  assign_facet_values(scene, entries, defaults, ctx);
  return scene;
}

}  // namespace

Scene load_channel_scene(const std::string& path, const std::string& materials_path,
                         const TextReadOptions& options) {
  const std::string ext = lower_extension(path);
  if (ext == ".obj") {
    if (!materials_path.empty())
      fail(path, 0, "a materials file (" + materials_path + ") applies to OFF scenes only; an OBJ names its MTL "
                    "files with mtllib");
    return to_scene(load_obj_scene(path, options));
  }
  if (ext == ".off") return to_scene(load_off_scene(path, materials_path, options));
  fail(path, 0, "unknown scene format " + in_quotes(ext.empty() ? "(no extension)" : ext) +
                    ": expected .obj (with MTL) or .off (with a JSON sidecar)");
}

}  // namespace panelrad

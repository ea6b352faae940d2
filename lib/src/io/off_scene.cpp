// OFF + JSON sidecar scenes: the sidecar gives the channels, default rho and E, and rho and E per
// facet (entries naming facets by id). Every error names the file and the line, or the facet.
#include "json_layout.hpp"
#include "scene_reading.hpp"

#include <cstddef>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <system_error>
#include <vector>

namespace panelrad::io_detail {

namespace {

namespace fs = std::filesystem;
using geometry::Index;

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
/// only the keys "channels", "default", "facets", "environment".
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
  if (!doc.is_object())
    fail(file, 0, "expected a JSON object with \"channels\", \"default\", \"facets\", \"environment\"");
  for (const auto& [key, value] : doc.items())
    if (key != "channels" && key != "default" && key != "facets" && key != "environment")
      fail(file, layout.line(key),
           "unknown key " + in_quotes(key) + " (expected \"channels\", \"default\", \"facets\", \"environment\")");
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

/// "environment": the environment's radiosity, a number (every channel) or one per channel,
/// checked as E is; empty when not given.
std::vector<double> read_environment(const Json& doc, const std::vector<std::string>& channels, const std::string& file,
                                     const JsonLayout& layout) {
  if (!doc.contains("environment")) return {};
  const long at = layout.line("environment");
  std::vector<double> v = channel_values(doc["environment"], channels.size(), file, at, "environment");
  check_values(v, false, channels, file, at, "the environment");
  return v;
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

}  // namespace

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
  scene.environment = read_environment(doc, scene.channels, file, layout);
  return scene;
}

}  // namespace panelrad::io_detail

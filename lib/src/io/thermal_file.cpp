// The boundary conditions of a thermal solve as a JSON file (io/thermal_file.hpp).
#include "json_layout.hpp"
#include "scene_reading.hpp"

#include <panelrad/io/thermal_file.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace panelrad {

namespace {

using io_detail::fail;
using io_detail::in_quotes;
using io_detail::Json;
using io_detail::JsonLayout;

/// The list of the groups, for messages ("'a', 'b', ... (12 in all)").
std::string group_list(const SurfaceGroups& groups) {
  std::string out;
  const std::size_t shown = std::min<std::size_t>(groups.names.size(), 6);
  for (std::size_t g = 0; g < shown; ++g) out += (g ? ", " : "") + in_quotes(groups.names[g]);
  if (shown < groups.names.size()) out += ", ... (" + std::to_string(groups.names.size()) + " in all)";
  return out;
}

/// The number at `key` of `entry` (at `where`), checked by `ok` (what it must be: `rule`).
double number_at(const Json& entry, const std::string& key, const std::string& where, const std::string& file, long line,
                 bool (*ok)(double), const std::string& rule) {
  const Json& v = entry[key];
  if (!v.is_number()) fail(file, line, where + ": \"" + key + "\" is " + v.dump() + ", not a number");
  const double x = v.get<double>();
  if (!ok(x)) fail(file, line, where + ": \"" + key + "\" = " + io_detail::number(x) + " must be " + rule);
  return x;
}

/// The emissivities per band at "emissivity" (an array): each in [0, 1], one per band of `bands`.
std::vector<double> band_emissivities(const Json& v, const std::string& where, const std::string& file, long line,
                                      std::size_t bands) {
  if (bands == 0)
    fail(file, line, where + ": \"emissivity\" is an array (one per wavelength band), but the file gives no "
                             "\"band_edges_um\"");
  if (v.size() != bands)
    fail(file, line, where + ": \"emissivity\" has " + std::to_string(v.size()) + " values for " + std::to_string(bands) +
                         " bands (\"band_edges_um\" has " + std::to_string(bands - 1) + " edges)");
  std::vector<double> out;
  for (std::size_t k = 0; k < v.size(); ++k) {
    if (!v[k].is_number()) fail(file, line, where + ": emissivity " + std::to_string(k + 1) + " is " + v[k].dump() + ", not a number");
    const double x = v[k].get<double>();
    if (!(x >= 0 && x <= 1))
      fail(file, line, where + ": the emissivity of band " + std::to_string(k + 1) + " = " + io_detail::number(x) +
                           " must be in [0, 1]");
    out.push_back(x);
  }
  if (std::all_of(out.begin(), out.end(), [](double x) { return x == 0; }))
    fail(file, line, where + ": every band emissivity is 0 (the surface would neither emit nor absorb)");
  return out;
}

SurfaceCondition read_condition(const Json& entry, const std::string& name, const std::string& file,
                                const JsonLayout& layout, std::size_t bands) {
  const std::string at = "groups." + name, where = "group " + in_quotes(name);
  const long line = layout.line(at);
  if (!entry.is_object()) fail(file, line, where + " is " + entry.dump() + ": expected {\"T\" or \"q\", \"emissivity\"}");
  for (const auto& [key, value] : entry.items())
    if (key != "T" && key != "q" && key != "emissivity")
      fail(file, layout.line(at + "." + key), where + ": unknown key " + in_quotes(key) + " (expected \"T\" or \"q\", \"emissivity\")");
  if (entry.contains("T") == entry.contains("q"))
    fail(file, line, where + ": needs exactly one of \"T\" (a temperature, K) and \"q\" (a net flux leaving, W/m^2)");
  SurfaceCondition c;
  const auto key_line = [&](const char* key) { return layout.line(at + "." + key) ? layout.line(at + "." + key) : line; };
  if (entry.contains("T")) {
    c.given = SurfaceCondition::Given::temperature;
    c.value = number_at(entry, "T", where, file, key_line("T"), [](double x) { return std::isfinite(x) && x > 0; },
                        "a temperature in K, finite and > 0");
    if (!entry.contains("emissivity")) fail(file, line, where + ": a temperature needs an \"emissivity\" in (0, 1]");
  } else {
    c.given = SurfaceCondition::Given::heat_flux;
    c.value = number_at(entry, "q", where, file, key_line("q"), [](double x) { return std::isfinite(x); },
                        "a finite net flux in W/m^2");
  }
  if (entry.contains("emissivity") && entry["emissivity"].is_array())
    c.band_emissivity = band_emissivities(entry["emissivity"], where, file, key_line("emissivity"), bands);
  else
    c.emissivity = entry.contains("emissivity")
                       ? number_at(entry, "emissivity", where, file, key_line("emissivity"),
                                   [](double x) { return x > 0 && x <= 1; }, "in (0, 1]")
                       : 1.0;
  return c;
}

std::optional<double> read_environment(const Json& doc, const std::string& file, const JsonLayout& layout) {
  if (!doc.contains("environment")) return std::nullopt;
  const Json& e = doc["environment"];
  const long line = layout.line("environment");
  if (e.is_string() && e.get<std::string>() == "none") return std::nullopt;
  if (!e.is_object() || e.size() != 1 || !e.contains("T"))
    fail(file, line, "\"environment\" is " + e.dump() + ": expected {\"T\": kelvin} or \"none\"");
  return number_at(e, "T", "the environment", file, line, [](double x) { return std::isfinite(x) && x > 0; },
                   "a temperature in K, finite and > 0");
}

/// "band_edges_um": finite, > 0, increasing (micrometres); none: a gray model.
std::vector<double> read_band_edges(const Json& doc, const std::string& file, const JsonLayout& layout) {
  if (!doc.contains("band_edges_um")) return {};
  const Json& e = doc["band_edges_um"];
  const long line = layout.line("band_edges_um");
  if (!e.is_array() || e.empty())
    fail(file, line, "\"band_edges_um\" is " + e.dump() + ": expected the wavelengths between the bands in micrometres, "
                     "increasing, e.g. [3, 8] for [0, 3], [3, 8] and [8, infinity)");
  std::vector<double> out;
  for (std::size_t k = 0; k < e.size(); ++k) {
    const double x = e[k].is_number() ? e[k].get<double>() : std::nan("");
    if (!(std::isfinite(x) && x > 0 && (out.empty() || x > out.back())))
      fail(file, line, "\"band_edges_um\": edge " + std::to_string(k + 1) + " is " + e[k].dump() +
                           ": the edges must be finite, > 0 and increasing (micrometres)");
    out.push_back(x);
  }
  return out;
}

}  // namespace

ThermalConditions read_thermal_conditions(const std::string& path, const SurfaceGroups& groups) {
  TextReadOptions options;
  options.strip_utf8_bom = false;  // nlohmann skips it; byte positions stay the file's
  const std::string text = io_detail::read_text(path, "boundary conditions", options);
  JsonLayout layout;
  Json doc;
  try {
    doc = io_detail::parse_json(text, layout);
  } catch (const Json::parse_error& e) {
    fail(path, 0, "JSON parse error at byte " + std::to_string(e.byte) + ": " + e.what());
  } catch (const Json::exception& e) {
    fail(path, 0, std::string("JSON error: ") + e.what());
  }
  if (!layout.duplicate.empty()) fail(path, layout.duplicate_line, layout.duplicate);
  if (!doc.is_object()) fail(path, 0, "expected a JSON object with \"groups\" and \"environment\"");
  for (const auto& [key, value] : doc.items())
    if (key != "groups" && key != "environment" && key != "band_edges_um")
      fail(path, layout.line(key),
           "unknown key " + in_quotes(key) + " (expected \"groups\", \"environment\", \"band_edges_um\")");
  if (!doc.contains("groups") || !doc["groups"].is_object())
    fail(path, layout.line("groups"), "\"groups\" must be an object {NAME: {\"T\" or \"q\", \"emissivity\"}}");
  const Json& given = doc["groups"];
  ThermalConditions out;
  out.band_edges_um = read_band_edges(doc, path, layout);
  const std::size_t bands = out.band_edges_um.empty() ? 0 : out.band_edges_um.size() + 1;
  for (const auto& [name, entry] : given.items())
    if (std::find(groups.names.begin(), groups.names.end(), name) == groups.names.end())
      fail(path, layout.line("groups." + name), "group " + in_quotes(name) + " is not a group of the scene (" +
                                                    group_list(groups) + ")");
  for (const std::string& name : groups.names) {
    if (!given.contains(name)) fail(path, layout.line("groups"), "group " + in_quotes(name) + " has no condition");
    out.conditions.push_back(read_condition(given[name], name, path, layout, bands));
  }
  out.environment_temperature = read_environment(doc, path, layout);
  return out;
}

}  // namespace panelrad

#pragma once
// A JSON text parsed with the line of each value (internal to panelrad_io), so that the sidecar's
// errors can name the line.
#include <nlohmann/json.hpp>

#include <string>
#include <unordered_map>

namespace panelrad::io_detail {

using Json = nlohmann::json;

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

/// Parses the JSON text, filling `layout`. Throws nlohmann's exceptions for bad JSON.
Json parse_json(const std::string& text, JsonLayout& layout);

}  // namespace panelrad::io_detail

#pragma once
// Memory sizes in messages (estimates refused against the memory available).
#include <string>

namespace panelrad {

/// A byte count for messages, in decimal units: "309.24 GB" (>= 1e9, two decimals),
/// "12.3 MB" (>= 1e6), "4.1 kB" (>= 1e3), "512 B".
std::string format_bytes(double bytes);

}  // namespace panelrad

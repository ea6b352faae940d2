#pragma once
// CSV fields shared by the writers of panelrad_io (internal): names quoted as RFC 4180 asks, and
// numbers with 17 significant digits (each double read back exactly).
#include <string>

namespace panelrad::io_detail {

/// A CSV field: quoted (with inner quotes doubled) when it holds a comma, a quote or a line break,
/// or starts or ends with a space.
std::string csv_field(const std::string& s);

/// %.17g.
std::string g17(double x);

}  // namespace panelrad::io_detail

// View factors as CSV and .npy files, written as one set (view_factor_output.hpp).
#include "csv_fields.hpp"

#include <panelrad/io/view_factor_output.hpp>
#include <panelrad/io/scene_output.hpp>

#include <panelrad/io/text_output.hpp>

#include <bit>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <sstream>

namespace panelrad {

using io_detail::csv_field;

namespace {

std::string number(double x) { return io_detail::g17(x); }

}  // namespace

std::vector<std::string> view_factor_paths(const std::string& prefix, bool with_error, bool with_elements) {
  std::vector<std::string> paths{prefix + ".csv"};
  if (with_error) paths.push_back(prefix + "_error.csv");
  paths.push_back(prefix + ".npy");
  if (with_elements) {
    paths.push_back(prefix + "_elements.csv");
    paths.push_back(prefix + "_elements.vtk");
    paths.push_back(prefix + "_elements.ply");
  }
  return paths;
}

std::string element_sky_csv(const ViewFactors& v) {
  const ElementSky& e = v.elements;
  std::ostringstream out;
  out << "element,facet,group,x,y,z,area,sky";
  for (const std::string& name : e.target_names) out << ',' << csv_field("F_" + name);
  out << '\n';
  for (std::size_t i = 0; i < e.facet.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    out << i << ',' << e.facet[i] << ',' << csv_field(v.names[static_cast<std::size_t>(e.group[i])]);
    for (int c = 0; c < 3; ++c) out << ',' << number(e.centroid[i][c]);
    out << ',' << number(e.area[k]) << ',' << number(e.sky[k]);
    for (Eigen::Index t = 0; t < e.to.cols(); ++t) out << ',' << number(e.to(k, t));
    out << '\n';
  }
  return out.str();
}

namespace {

/// The per-element values of PREFIX_elements.vtk and .ply.
std::vector<CellValues> element_cells(const ViewFactors& v) {
  const ElementSky& e = v.elements;
  std::vector<CellValues> cells{{"group", [&e](std::size_t i) { return static_cast<double>(e.group[i]); }},
                                {"area", [&e](std::size_t i) { return e.area[static_cast<Eigen::Index>(i)]; }},
                                {"sky", [&e](std::size_t i) { return e.sky[static_cast<Eigen::Index>(i)]; }}};
  for (std::size_t t = 0; t < e.target_names.size(); ++t)
    cells.push_back({"F_" + e.target_names[t], [&e, t](std::size_t i) {
                       return e.to(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(t));
                     }});
  return cells;
}

}  // namespace

std::string element_sky_vtk(const ViewFactors& v) {
  return cells_vtk("panelrad view factors per element", v.elements.triangle, v.elements.facet, element_cells(v));
}

std::string element_sky_ply(const ViewFactors& v) {
  return cells_ply("panelrad view factors per element", v.elements.triangle, v.elements.facet, element_cells(v));
}

std::string view_factor_csv(const ViewFactors& v, const Eigen::MatrixXd& values, const Eigen::VectorXd& uncovered) {
  std::ostringstream out;
  out << "group,area";
  for (const std::string& name : v.names) out << ',' << csv_field(name);
  out << ',' << (v.enclosed ? "closure_defect" : "sky") << '\n';
  for (std::size_t I = 0; I < v.names.size(); ++I) {
    const auto i = static_cast<Eigen::Index>(I);
    out << csv_field(v.names[I]) << ',' << number(v.area[i]);
    for (Eigen::Index J = 0; J < values.cols(); ++J) out << ',' << number(values(i, J));
    out << ',' << number(uncovered[i]) << '\n';
  }
  return out.str();
}

std::string npy_bytes(const Eigen::MatrixXd& m) {
  static_assert(std::endian::native == std::endian::little, "the .npy writer assumes a little-endian host ('<f8')");
  std::string header = "{'descr': '<f8', 'fortran_order': False, 'shape': (" + std::to_string(m.rows()) + ", " +
                       std::to_string(m.cols()) + "), }";
  // Magic (6) + version (2) + header length (2) + header, padded with spaces and ended by a
  // newline to a multiple of 64 bytes.
  const std::size_t unpadded = 10 + header.size() + 1;
  header.append((64 - unpadded % 64) % 64, ' ');
  header += '\n';
  std::string out("\x93NUMPY\x01\x00", 8);
  const auto length = static_cast<std::uint16_t>(header.size());
  out += static_cast<char>(length & 0xff);
  out += static_cast<char>(length >> 8);
  out += header;
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) {
      const double x = m(i, j);
      char bytes[sizeof(double)];
      std::memcpy(bytes, &x, sizeof x);
      out.append(bytes, sizeof bytes);
    }
  return out;
}

std::vector<std::string> write_view_factors(const ViewFactors& v, const std::string& prefix) {
  const bool with_error = v.error.size() > 0, with_elements = v.elements.sky.size() > 0;
  const std::vector<std::string> paths = view_factor_paths(prefix, with_error, with_elements);
  OutputSet set;
  set.add(paths[0], view_factor_csv(v, v.F, v.uncovered));
  if (with_error) set.add(paths[1], view_factor_csv(v, v.error, v.uncovered_error));
  set.add(paths[with_error ? 2 : 1], npy_bytes(v.F));
  if (with_elements) {
    set.add(paths[paths.size() - 3], element_sky_csv(v));
    set.add(paths[paths.size() - 2], element_sky_vtk(v));
    set.add(paths.back(), element_sky_ply(v));
  }
  set.commit();
  return paths;
}

}  // namespace panelrad

#pragma once
// View factors (viewfactors/view_factors.hpp) written as one set of files, all or none
// (text_output.hpp's OutputSet):
//   PREFIX.csv        one row per group: its name, area A_I, F_IJ for every J (columns named by
//                     the groups), and the uncovered part 1 - sum_J F_IJ (column "sky" in an open
//                     scene, "closure_defect" in an enclosed one); names quoted as RFC 4180 asks;
//   PREFIX_error.csv  the same layout with the error estimates |F(L) - F(L - 1)| (when computed);
//   PREFIX.npy        the matrix F as a G x G array of float64 (numpy.load);
//   PREFIX_elements.csv  with the elements kept (ViewFactorOptions::elements): per element of the
//                     finest level `element,facet,group,x,y,z,area,sky` (its collocation point,
//                     area and sky view factor 1 - (H 1)_i), then F_<J> for each group J of
//                     ViewFactorOptions::element_targets;
//   PREFIX_elements.vtk  the same per element on its triangle (legacy VTK, ParaView): facet,
//                     group (index), area, sky and F_<J> as cell data;
//   PREFIX_elements.ply  the same as face properties (ASCII PLY, MeshLab and ParaView).
// Numbers are written with 17 significant digits (each double read back exactly).
#include <panelrad/viewfactors/view_factors.hpp>

#include <string>
#include <vector>

namespace panelrad {

/// The paths write_view_factors writes for `prefix` (with the error file when `with_error`, the
/// elements' file when `with_elements`).
std::vector<std::string> view_factor_paths(const std::string& prefix, bool with_error, bool with_elements = false);

/// The CSV text of PREFIX_elements.csv, the VTK text of PREFIX_elements.vtk and the PLY text of
/// PREFIX_elements.ply.
std::string element_sky_csv(const ViewFactors& v);
std::string element_sky_vtk(const ViewFactors& v);
std::string element_sky_ply(const ViewFactors& v);

/// The CSV text of PREFIX.csv (`values` = v.F and v.uncovered) or PREFIX_error.csv (v.error and
/// v.uncovered_error).
std::string view_factor_csv(const ViewFactors& v, const Eigen::MatrixXd& values, const Eigen::VectorXd& uncovered);

/// The bytes of a .npy file (format version 1.0) holding `m` as a C-ordered float64 array.
std::string npy_bytes(const Eigen::MatrixXd& m);

/// Writes the set (view_factor_paths(prefix, with the estimates, with the elements)); a failure leaves the previous
/// files in place and throws std::runtime_error naming the path. Returns the paths written.
std::vector<std::string> write_view_factors(const ViewFactors& v, const std::string& prefix);

}  // namespace panelrad

// The scalar features of an indentation test with unloading, the quantities that dimensional
// analysis and its inverse methods work with (Y.-T. Cheng, C.-M. Cheng, Mater. Sci. Eng. R 44,
// 2004; M. Dao et al., Acta Mater. 49, 2001; L. Lu et al., PNAS 117, 2020), and what a
// calibration compares when a laboratory reports them instead of the curves (docs/calibration.md):
//   loading curvature    C = P / h^2 of Kick's law, fitted to the loading branch by least
//                        squares, C = sum P h^2 / sum h^4 (the deep points weigh most) [GPa]
//   unloading stiffness  S = dP/dh at h_max, from the Oliver-Pharr fit of the upper unloading
//                        (analysis/OliverPharr.h, P >= 0.5 P_max) [mN/um]
//   plastic work ratio   W_p / W_t = 1 - W_e / W_t [-]
// For a self-similar (sharp) tip and a material without a length scale, C and W_p/W_t do not
// depend on the depth and S grows in proportion to it: a test's S measured at depth h_m is
// compared as S h_max / h_m, with the simulated h_max (exact for a sharp tip, an approximation for
// a rounded one; h_m must lie within max_depth_mismatch of h_max).
//
// A measured table has one row per test and a column per feature, found by its name without the
// unit (case-insensitive): C | loading_curvature (GPa, MPa); dP/dh | S | stiffness |
// unloading_stiffness (N/m, mN/um, uN/nm, mN/nm); Wp/Wt | plastic_work_ratio (no unit); and
// optionally hm | h_max | max_depth (um, nm) for the scaling of S. Other columns are ignored.
// Units: um, mN, GPa.
#pragma once

#include "calibration/CalibrationFile.h"
#include "case/Case.h"
#include "io/LoadCurveCsv.h"

#include <array>
#include <string>
#include <vector>

namespace indentsim::calibration
{
  // A measured depth may differ from the simulated one by this fraction at most.
  inline constexpr double max_depth_mismatch = 0.1;

  std::string feature_name(Feature feature);  // "C" | "S" | "Wp/Wt"
  std::string feature_unit(Feature feature);  // "GPa" | "mN/um" | "-"
  std::string feature_label(Feature feature); // "loading curvature C [GPa]"

  // The features of a curve with a full unloading (partial unloads are left out), in the order
  // of the Feature enumeration; the simulated h_max is `depth`. Throws std::invalid_argument (named
  // by curve.source) if the curve has no analysable unloading.
  struct CurveFeatures
  {
    std::array<double, 3> value{};       // C [GPa], S [mN/um], W_p/W_t [-]
    double                max_depth = 0; // h_max [um]
  };
  CurveFeatures curve_features(const io::LoadCurve &curve);

  // Reads data_set.file (a table of tests, see above) against the case that simulates it and
  // fills data_set.features (all the file has, unless the calibration file chose them), .x (the
  // feature's index, per test and feature), .measured and .point_scale. Throws
  // CalibrationFileError naming `where`, the file, the column and the row.
  void read_measured_features(DataSet &data_set, const io::Case &simulated_case,
                              const std::string &where);

  // The simulated features of a finished run (its load_penetration.csv) at data_set's points.
  std::vector<double> simulated_features(const DataSet &data_set, const std::string &run_directory);

  // The feature a calibration file names ("C", "S", "Wp/Wt" or their long names), if any.
  std::optional<Feature> feature_from_name(const std::string &name);
} // namespace indentsim::calibration

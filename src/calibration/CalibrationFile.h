// Calibration files: which keys of a base case to fit, within which bounds, to which measured
// curves (`indentsim calibrate`, calibration/CalibrationRunner.h; docs/calibration.md).
// Units everywhere: lengths um, forces mN, stresses and moduli GPa (1 GPa*um^2 = 1 mN).
//
//   base_case: ../examples/paper_j2_axisymmetric.yaml   # relative to this file
//   output: results/calibration                          # relative to the working directory
//   parameters:                                          # numeric keys of the case
//     material.yield_stress:      {start: 0.25, min: 0.05, max: 1.0}
//     material.hardening_modulus: {start: 1.0,  min: 0.0,  max: 5.0, step: 0.05}
//   data:
//     - {kind: load_penetration, file: measured/ph.csv, branch: loading, weight: 1.0}
//     - {kind: load_penetration, file: measured/ph.csv, branch: unloading, weight: 0.5}
//     - {kind: tensile, file: measured/tensile.csv, case: tensile.yaml}
//     - {kind: pileup_profile, file: measured/afm_line.csv}
//     - {kind: indentation_features, file: measured/tests.csv}    # C, dP/dh, Wp/Wt per test
//     - {kind: hardness_depth, file: measured/csm.csv}            # needs partial unloads
//   solver: {max_iterations: 30, finite_difference_step: 1.0e-3}
//
// Every parameter is a `number` key of the case-file schema (docs/case-file-reference.md); the
// start and both bounds are checked as values of that key in every case they enter, so a
// bound the key does not admit (a negative yield stress) is refused before any run. Bad input
// raises CalibrationFileError naming the file, the line, the key, the value and what is
// allowed.
#pragma once

#include "case/CaseFile.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace indentsim::calibration
{
  // Bad input in a calibration file, a data file or a case it refers to (exit code 1).
  class CalibrationFileError : public io::CaseFileError
  {
  public:
    using io::CaseFileError::CaseFileError;
  };

  // A fitted key with its start and bounds (in the key's unit).
  struct Parameter
  {
    std::string key; // "material.yield_stress"
    std::string unit;
    double      start = 0., min = 0., max = 0.;
    // The finite-difference step in the key's unit, or 0: solver.finite_difference_step
    // relative to the value (LeastSquaresFit.h). A forward model whose output moves in small
    // jumps (contact nodes) needs a step that sees through them.
    double step = 0.;
  };

  enum class DataKind
  {
    load_penetration,     // force [mN] against depth [um], one branch of the base case's curve
    tensile,              // true stress [GPa] against log strain, of its own tensile case
    pileup_profile,       // height [um] against radius [um] of the imprint after unloading
    indentation_features, // C [GPa], S [mN/um], W_p/W_t per test (IndentationFeatures.h)
    hardness_depth        // Oliver-Pharr hardness [GPa] against depth [um] (partial unloads)
  };

  // The scalar features of a load-penetration curve with unloading (IndentationFeatures.h).
  enum class Feature
  {
    loading_curvature,   // C of P = C h^2 [GPa]
    unloading_stiffness, // S = dP/dh at h_max [mN/um]
    plastic_work_ratio   // W_p/W_t [-]
  };

  enum class Branch
  {
    loading,
    unloading
  };

  // A measured curve resampled onto the points where the simulation is compared with it.
  struct DataSet
  {
    DataKind    kind = DataKind::load_penetration;
    Branch      branch = Branch::loading; // load_penetration only
    std::string file;                     // absolute
    std::string case_file;                // the case that simulates it (absolute)
    double      weight = 1.;
    double      azimuth_deg = 0.; // pileup_profile: the simulated profile's nearest azimuth
    // indentation_features: the features compared (in this order within each test), and the
    // factor on the measured stiffness (a Berkovich S brought to the equivalent cone's).
    std::vector<Feature> features;
    double               stiffness_scale = 1.;
    unsigned int         points = 40; // at most this many comparison points (CurveData.h)
    // Compare only within [lo, hi] of the abscissa (depth um, log strain, radius um), e.g. the
    // pile-up beyond the imprint, or a curve without its shallow part.
    std::optional<std::array<double, 2>> range;
    std::string                          label; // "data[0] load_penetration loading (ph.csv)"
    int line = -1;                              // 0-based line of the entry in the calibration file

    std::vector<double> x; // the comparison points: depth [um], log strain or radius [um]
    // The measured abscissae averaged into each comparison point (CurveData.h).
    std::vector<std::vector<double>> group_x;
    std::vector<double> measured;   // the measured curve there: force [mN] or stress [GPa]
    double              scale = 1.; // max |measured|: residuals are relative to it
    // indentation_features: each point's own scale (its feature's mean measured |value|),
    // replacing `scale`.
    std::vector<double> point_scale;
    double scale_at(std::size_t i) const { return point_scale.empty() ? scale : point_scale[i]; }

    std::string x_name() const; // "depth_um" | "log_strain" | "r_um" | "feature"
    // "force_mN" | "true_stress_GPa" | "height_um" | "value" | "hardness_GPa"
    std::string y_name() const;
    std::string kind_name() const;
    std::string units() const; // of the comparison points and values, for files' headers
  };

  struct SolverSettings
  {
    unsigned int max_iterations = 30;
    // Forward-difference step, relative to max(|x|, 1e-3 (max - min)) of each parameter.
    double finite_difference_step = 1.e-3;
    // Ceres' convergence tolerances (relative change of the cost, and of the parameters).
    double function_tolerance = 1.e-6;
    double parameter_tolerance = 1.e-4;
    // The step of the central differences of the Jacobian behind the statistics, relative to
    // max(|x|, 1e-3 (max - min)) (a parameter's own `step` if that is larger): wide enough that
    // the small jumps of a forward model do not decorrelate the columns (LeastSquaresFit.h).
    double statistics_step = 0.1;
  };

  struct Calibration
  {
    std::string            source_file;      // the calibration file as given
    std::string            output_directory; // absolute
    std::string            base_case_file;   // absolute
    std::vector<Parameter> parameters;
    std::vector<DataSet>   data;
    SolverSettings         solver;

    // The distinct case files the data need (the base case first), and for each data set
    // its index in that list.
    std::vector<std::string> forward_cases() const;
    std::size_t              forward_case_of(const DataSet &data_set) const;
  };

  // Reads and checks a calibration file: the keys, the bounds, every case at the start and at
  // each bound, the data files and their overlap with the simulated range. `output_override`
  // (the command line's --output), if not empty, replaces `output`. Throws CalibrationFileError.
  Calibration read_calibration_file(const std::string &path,
                                    const std::string &output_override = "");

  // The same from YAML text; paths are relative to the directory of `source_name`.
  Calibration parse_calibration_yaml(const std::string &yaml_text, const std::string &source_name,
                                     const std::string &output_override = "");
} // namespace indentsim::calibration

// The curves a calibration compares: the measured ones, read and resampled onto comparison
// points, and the simulated ones, read from a forward run's output at the same points.
// Units: depth um, force mN, stress GPa, strain dimensionless (log strain).
//
// Comparison points (docs/calibration.md): the measured points within the range the case
// simulates, in at most `points` groups of consecutive points of nearly equal count, each group
// its mean abscissa and mean value (a sparse curve keeps every point; a dense one is averaged, so
// that every measured point counts once and the comparison points' errors are independent).
// The range:
//   load_penetration, loading: depths above 0 up to min(deepest measured point,
//     loading.max_depth of the case);
//   load_penetration, unloading: from the shallowest measured unloading point to min(measured
//     maximum depth, loading.max_depth); shallower than the depth at which the simulated unloading
//     ends, the simulated force is 0 (the tip has left the surface);
//   tensile: log strains above 0 up to min(largest measured strain, log(1 + loading.max_strain));
//   hardness_depth: from the first partial unload's depth (loading.partial_unloads.every) to the
//     smaller of the last one's and the deepest measured point; the simulated hardness is the
//     Oliver-Pharr hardness of the run's partial unloads (hardness_depth.csv), linear between them.
// indentation_features are scalars per test, not curves: IndentationFeatures.h reads and
// simulates them.
// A data set's `range` narrows this range further (both ends included).
// The simulated value of a comparison point is the mean of the simulated curve (interpolated
// linearly) over the group's measured abscissae, so that a curved curve is compared without the
// bias of its mean abscissa. Fewer than 3 measured
// points inside the simulated range is an error (the data set does not overlap what the case
// simulates).
#pragma once

#include "calibration/CalibrationFile.h"
#include "case/Case.h"

#include <string>
#include <vector>

namespace indentsim::calibration
{
  // A curve sorted by x, without repeated x; y linear between the points.
  struct SampledCurve
  {
    std::vector<double> x, y;
    // y at `at`; outside [x.front(), x.back()] the end value (callers keep inside).
    double at(double at) const;
  };

  // Sorts by x and averages points with the same x.
  SampledCurve sorted_curve(std::vector<double> x, std::vector<double> y);

  // Reads data_set.file, chooses the comparison points against `simulated_case` (its maximum
  // depth or strain) and fills data_set.x, .measured and .scale. Throws CalibrationFileError
  // naming `where` (the data entry), the file and the ranges.
  void read_measured(DataSet &data_set, const io::Case &simulated_case, const std::string &where);

  // The simulated curve of a finished forward run in `run_directory` at the comparison points
  // (load_penetration.csv or stress_strain.csv). Throws std::runtime_error if the run's file
  // is missing or does not reach the comparison points.
  std::vector<double> simulated_values(const DataSet &data_set, const std::string &run_directory);
} // namespace indentsim::calibration

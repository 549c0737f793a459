// A computed load-penetration curve against a measured one (output.experimental_curve).
// Units: depths um, forces mN.
//
// Both loading branches (from the start to the largest depth, the points where the depth
// grows) are compared at the measured depths that the computation covers: the computed force
// is interpolated linearly at each such depth. Reported: the RMS of the force difference, the
// same relative to the computed force at the largest computed depth, and the two forces at the
// largest computed depth (the measured one interpolated, if the measurement reaches it).
#pragma once

#include "analysis/OliverPharr.h"

#include <optional>
#include <string>

namespace indentsim::analysis
{
  struct CurveDeviation
  {
    unsigned int          n_points = 0;       // measured loading points compared
    double                rms_mN = 0;         // sqrt(mean (P_computed - P_measured)^2)
    double                rms_relative = 0;   // rms_mN / computed force at max depth
    double                max_depth = 0;      // largest computed depth [um]
    double                computed_force = 0; // [mN] at max_depth
    std::optional<double> measured_force;     // [mN] at max_depth, if measured that deep
    std::optional<double> deviation_at_max_depth_percent; // 100 (computed - measured)/measured
  };

  // Throws std::invalid_argument (naming measured.source) if no measured loading point lies
  // within the computed depth range.
  CurveDeviation compare_loading(const LoadCurve &computed, const LoadCurve &measured);

  // comparison_with_experiment.json
  std::string to_json(const CurveDeviation &deviation, const std::string &measured_source);

  // The curve as depth_um,force_mN CSV text (the measured curve converted, for the plot).
  std::string to_csv(const LoadCurve &curve);
} // namespace indentsim::analysis

// `indentsim calibrate CONFIG.yaml`: reads the calibration file (calibration/CalibrationFile.h),
// fits the parameters (calibration/LeastSquaresFit.h) through forward runs that are study cases
// (calibration/ForwardRuns.h), judges the result (calibration/FitStatistics.h) and writes, into
// the calibration's output directory:
//   calibration.json   the fitted values, standard errors, 95 % intervals, correlations,
//                      identifiability and its warnings, the residual per data set, the forward
//                      runs and the wall time;
//   iterations.csv     the history: cost and parameters per iteration;
//   fit_data<k>.csv    per data set: the comparison points, measured, simulated at the start and
//                      at the fit;
//   report.md, *.png   python/calibration_report.py: every data set against the fit, the history;
//   forward/cases/     the forward runs (kept: a rerun reuses them), forward_runs.log.
// Units: lengths um, forces mN, stresses GPa, times s.
#pragma once

#include "calibration/CalibrationFile.h"
#include "study/StudyRunner.h"

#include <ostream>

namespace indentsim::calibration
{
  // Exit codes besides study's: 0 the fit ran (identifiable or not: see the warnings);
  // 3 the forward runs at the start failed; 130 interrupted (rerun to continue).
  int run_calibration(const Calibration &calibration, const study::StudyRunSettings &settings,
                      std::ostream &out, std::ostream &warnings);
} // namespace indentsim::calibration

// `indentsim analyze` and the Oliver-Pharr step at the end of an indentation run: find the
// curve and the indenter, run analysis/OliverPharr.h, write oliver_pharr.json and the plot
// oliver_pharr.png; and the hardness-depth profile of a run's partial unloads. Units: um, mN, GPa (1 GPa*um^2 = 1 mN).
#pragma once

#include "analysis/OliverPharr.h"
#include "case/Case.h"
#include "indenter/IndenterSurface.h"
#include "io/CommandLine.h"

#include <optional>
#include <string>

namespace indentsim::analysis
{
  // Analyses options.target (a run directory with load_penetration.csv and resolved_case.yaml,
  // or a CSV file) and writes oliver_pharr.json/png into output_directory, or else into the run
  // directory or the CSV's directory; a curve with partial unloads (a run's `segment` column)
  // also gets its hardness-depth profile (write_hardness_profile). Prints a summary. Returns the JSON's path. Throws
  // std::invalid_argument (bad input, named), io::CaseFileError (bad indenter case) or
  // output::OutputError (a file that cannot be written).
  std::string analyze_command(const io::AnalyzeOptions         &options,
                              const std::optional<std::string> &output_directory);

  // The same for the curve of a finished indentation run, in memory, with the run's own case and
  // indenter; writes into the case's output directory. Returns false (and says why on
  // `warnings`) if the curve has no analysable unloading; a file that cannot be written throws
  // output::OutputError.
  bool analyze_run(const LoadCurve &curve, const io::Case &the_case,
                   const indenter::IndenterSurface &indenter, std::ostream &summary,
                   std::ostream &warnings);

  // The partial unloads of a finished indentation run's curve (loading.partial_unloads),
  // analysed (analysis/HardnessDepth.h): writes hardness_depth.csv, hardness_depth.json and the
  // plot hardness_depth.png into the case's output directory and prints a summary. Returns
  // false (and says why on `warnings`) if no partial unload could be analysed; a partial unload
  // left out is named on `warnings`.
  bool analyze_partial_unloads_of_run(const LoadCurve &curve, const io::Case &the_case,
                                      const indenter::IndenterSurface &indenter,
                                      std::ostream &summary, std::ostream &warnings);

  // The hardness-depth profile of a curve's partial unloads with the given Oliver-Pharr
  // settings, written into `directory` (the same files and summary as above).
  bool write_hardness_profile(const LoadCurve &curve, const indenter::IndenterSurface &indenter,
                              const OliverPharrSettings &settings, const std::string &directory,
                              std::ostream &summary, std::ostream &warnings);

  // A finished run's curve against a measured curve (output.experimental_curve): writes
  // comparison_with_experiment.json and the measured curve in um and mN
  // (experimental_curve.csv, for the plot overlay) into `run_directory`; prints the deviation.
  // Returns false (and says why on `warnings`) if the comparison is impossible; a file that
  // cannot be written throws output::OutputError.
  bool compare_with_experiment(const LoadCurve &computed, const std::string &run_directory,
                               const std::string &measured_csv, std::ostream &summary,
                               std::ostream &warnings);
} // namespace indentsim::analysis

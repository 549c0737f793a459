// Where the program finds its Python helpers (the plotting scripts and the study report).
//
// The folder is the first of these that holds the script:
//   1. $INDENTSIM_PYTHON_DIR, if set (an override, e.g. for edited copies of the scripts);
//   2. <folder of the executable>/../share/indentsim/python: the installed layout
//      (<prefix>/bin/indentsim), and in the build tree the layout seen from build/tests/;
//   3. <folder of the executable>/share/indentsim/python: the build tree seen from build/
//      (CMake links build/share/indentsim/python to the source folder python/).
// The executable is found through /proc/self/exe, so no source path is compiled in.
#pragma once

#include <ostream>
#include <string>
#include <vector>

namespace indentsim::output
{
  // The folders searched, in order (see above).
  std::vector<std::string> python_script_folders();

  // The full path of the helper `name` (e.g. "plot_pileup.py"). If no folder holds it, a
  // warning on std::cerr names the folders searched and the first candidate path is returned,
  // so that the caller's command fails and reports as it does for a missing Python.
  std::string python_script(const std::string &name);

  // Whether runs draw their PNG plots (output.plots of the case; true unless switched off).
  // A calibration's forward runs switch them off: a plot costs about a second of Python, several
  // times the computation of a small axisymmetric run. The CSV and JSON files are written either
  // way.
  void set_plots_enabled(bool enabled);
  bool plots_enabled();

  // Runs `python3 <helper script> <arguments...>` to draw `what` (a file or folder, for the
  // message) unless plots are switched off. A missing Python, matplotlib or script leaves a
  // warning on `warnings` naming `what` and the command, never an error: the results are in the
  // CSV and JSON files. Returns whether the plot was drawn.
  bool draw_plot(const std::string &script_name, const std::vector<std::string> &arguments,
                 const std::string &what, std::ostream &warnings);
} // namespace indentsim::output

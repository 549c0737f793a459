// A load-penetration curve and its CSV reader (measured curves and the runs' own
// load_penetration.csv). Units: depth um, force mN, area um^2.
#pragma once

#include <string>
#include <vector>

namespace indentsim::io
{
  // A load-penetration curve in the order it was recorded. contact_area (um^2, the simulation's
  // true projected contact area) is empty for measured curves.
  struct LoadCurve
  {
    std::vector<double>      depth;        // [um]
    std::vector<double>      force;        // [mN]
    std::vector<double>      contact_area; // [um^2], empty or one per point
    std::vector<std::string> segment;      // the run's `segment` column, empty or one per point
    std::vector<std::size_t> line;         // line of each point in `source` (1-based), or empty
    std::string              source;       // file it came from (for messages)

    // "line N" of the point's line in the file, or "point N" (1-based) for a curve in memory.
    std::string row_name(std::size_t index) const;
    // Whether the point belongs to a partial unload or its reload (segment partial_unload or
    // reload): not part of the loading and unloading branches.
    bool in_partial_unload(std::size_t index) const;
  };

  // The curve without its partial unloads and reloads (the same curve if it has none): the
  // loading and unloading branches that the Oliver-Pharr analysis of the whole curve reads.
  LoadCurve without_partial_unloads(const LoadCurve &curve);

  // Reads a CSV with a header line (lines starting with '#' are comments; a UTF-8 byte-order
  // mark before the first line and CRLF line endings are accepted). The depth and force
  // columns are the named ones, or else the first header starting with depth/h/displacement/
  // penetration and force/load/p. Units come from the column name (depth_um, depth_nm,
  // "depth (nm)", force_mN, load_uN, force_N, ...) unless given ("um", "nm", "mm"; "mN", "uN",
  // "N"). Columns contact_area_um2 and segment (a run's own), if present, are read as well. Throws std::invalid_argument
  // naming the file, the column and the value on bad input.
  LoadCurve read_load_curve_csv(const std::string &path, const std::string &depth_column = "",
                                const std::string &force_column = "",
                                const std::string &depth_unit = "",
                                const std::string &force_unit = "");

} // namespace indentsim::io

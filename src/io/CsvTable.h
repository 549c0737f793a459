// The CSV input of the program (measured curves, hardening tables, damage profiles): a header
// of column names and rows of fields, and the units written into column names. Units: the
// factors convert to um, mN and GPa.
//
// Format: blank lines and lines starting with '#' are skipped; a UTF-8 byte-order mark before
// the first line and CRLF line endings are accepted; the first other line is the header. The
// delimiter is the header's: ',' if it has one, else tab, else ';', else runs of spaces.
// Surrounding spaces and double quotes are trimmed from every field.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace indentsim::io
{
  struct CsvTable
  {
    std::vector<std::string>              header;
    std::size_t                           header_line = 0; // its line in the file (1-based)
    std::vector<std::vector<std::string>> rows;            // the fields of each data line
    std::vector<std::size_t>              line;            // each row's line in the file (1-based)

    // "line N" of row i.
    std::string row_name(std::size_t i) const { return "line " + std::to_string(line.at(i)); }
  };

  // Throws std::invalid_argument ("cannot open the file", "no header line (column names)") without
  // the path: the caller names the file, or the case key that gave it.
  CsvTable read_csv_table(const std::string &path);

  // The fields joined by ',' (a row or the header as messages quote it).
  std::string join_fields(const std::vector<std::string> &fields);
  std::string lowered(std::string text);
  // Without surrounding spaces, tabs, carriage returns and double quotes.
  std::string trimmed(const std::string &text);
  // The unit written into a column name, lower case: the text in () or [], else after the last
  // '_' ("depth_nm" -> "nm", "stress (MPa)" -> "mpa"); "" if there is none.
  std::string unit_in_name(const std::string &name);

  // Factors to um, mN and GPa of a unit as unit_in_name gives it (case-insensitive); 0 for a
  // unit that is not known.
  double length_factor(const std::string &unit); // um, nm, mm (and µm, micron)
  double force_factor(const std::string &unit);  // mN, uN, N (and µN)
  double stress_factor(const std::string &unit); // GPa, MPa
} // namespace indentsim::io

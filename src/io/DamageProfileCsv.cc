// Reading a damage profile from CSV (see DamageProfileCsv.h).
#include "io/DamageProfileCsv.h"

#include "io/CsvTable.h"
#include "io/TextNumber.h"

#include <stdexcept>

namespace indentsim::io
{
  namespace
  {
    // The first column whose lower-case name starts with one of the prefixes, or header.size().
    std::size_t column_starting(const std::vector<std::string>     &header,
                                std::initializer_list<const char *> prefixes)
    {
      for (std::size_t c = 0; c < header.size(); ++c)
        for (const char *prefix : prefixes)
          if (lowered(header[c]).rfind(prefix, 0) == 0)
            return c;
      return header.size();
    }
  } // namespace

  DamageProfileTable read_damage_profile_csv(const std::string &path)
  {
    const CsvTable    csv = read_csv_table(path);
    const std::string header_rule = "the header must name a depth column with its unit "
                                    "(depth_um, depth_nm, \"depth (nm)\") and a dpa column, "
                                    "e.g. depth_nm,dpa";
    const std::string header_line =
        "line " + std::to_string(csv.header_line) + ": header '" + join_fields(csv.header) + "': ";
    const std::size_t depth_column = column_starting(csv.header, {"depth"});
    const std::size_t dpa_column = column_starting(csv.header, {"dpa", "damage"});
    if (depth_column == csv.header.size() || dpa_column == csv.header.size())
      throw std::invalid_argument(
          header_line + (depth_column == csv.header.size() ? "no depth column" : "no dpa column") +
          "; " + header_rule);
    const std::string unit = unit_in_name(csv.header[depth_column]);
    const double      factor = length_factor(unit);
    if (factor == 0.0)
      throw std::invalid_argument(header_line + "the depth column '" + csv.header[depth_column] +
                                  "' has " +
                                  (unit.empty() ? std::string("no unit in its name")
                                                : "the unit '" + unit + "', not one of") +
                                  " um, nm, mm; " + header_rule);
    DamageProfileTable table;
    for (std::size_t i = 0; i < csv.rows.size(); ++i)
      {
        const std::vector<std::string> &row = csv.rows[i];
        const std::string               where = csv.row_name(i) + " '" + join_fields(row) + "': ";
        if (row.size() <= std::max(depth_column, dpa_column))
          throw std::invalid_argument(where + std::to_string(row.size()) +
                                      " fields, the header has " +
                                      std::to_string(csv.header.size()));
        for (const std::size_t column : {depth_column, dpa_column})
          if (!parse_finite_number(row[column]))
            throw std::invalid_argument(where + "column '" + csv.header[column] + "': '" +
                                        row[column] + "' is not a finite number");
        table.depth.push_back(factor * *parse_finite_number(row[depth_column]));
        table.dpa.push_back(*parse_finite_number(row[dpa_column]));
      }
    if (table.depth.size() < 2)
      throw std::invalid_argument("it has " + std::to_string(table.depth.size()) +
                                  " points; a profile needs at least 2");
    return table;
  }
} // namespace indentsim::io

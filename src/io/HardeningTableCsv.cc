// Reading the J2 hardening table from CSV (see HardeningTableCsv.h).
#include "io/HardeningTableCsv.h"

#include "io/CsvTable.h"
#include "io/TextNumber.h"

#include <stdexcept>

namespace indentsim::io
{
  HardeningTable read_hardening_table_csv(const std::string &path)
  {
    const CsvTable    csv = read_csv_table(path);
    const std::string header_rule =
        "the header must name two columns, the plastic strain and the true stress with its unit, "
        "e.g. plastic_strain,true_stress_GPa (or _MPa)";
    const std::string header_line = "line " + std::to_string(csv.header_line) + ": ";
    if (csv.header.size() != 2 || lowered(csv.header[0]).rfind("plastic_strain", 0) != 0)
      throw std::invalid_argument(header_line + "header '" + join_fields(csv.header) + "'; " +
                                  header_rule);
    const double factor = stress_factor(unit_in_name(csv.header[1]));
    if (factor == 0.0)
      throw std::invalid_argument(header_line + "the stress column '" + csv.header[1] +
                                  "' has no unit in its name (GPa or MPa); " + header_rule);
    HardeningTable table;
    for (std::size_t i = 0; i < csv.rows.size(); ++i)
      {
        const std::vector<std::string> &row = csv.rows[i];
        const std::string               where = csv.row_name(i) + ": '" + join_fields(row) + "': ";
        if (row.size() != 2)
          throw std::invalid_argument(where + "expected two numbers, plastic strain and stress");
        const auto strain = parse_finite_number(row[0]), stress = parse_finite_number(row[1]);
        if (!strain || !stress)
          throw std::invalid_argument(where +
                                      "expected two finite numbers, plastic strain and stress");
        table.plastic_strain.push_back(*strain);
        table.stress.push_back(*stress * factor);
      }
    if (table.stress.size() < 2)
      throw std::invalid_argument("it has " + std::to_string(table.stress.size()) +
                                  " points; a table needs at least 2");
    return table;
  }
} // namespace indentsim::io

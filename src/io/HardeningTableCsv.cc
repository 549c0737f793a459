// Reading the J2 hardening table from CSV (see HardeningTableCsv.h).
#include "io/HardeningTableCsv.h"

#include "io/TextNumber.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace indentsim::io
{
  namespace
  {
    std::string trimmed(const std::string &text)
    {
      const auto begin = text.find_first_not_of(" \t\r\"");
      if (begin == std::string::npos)
        return "";
      const auto end = text.find_last_not_of(" \t\r\"");
      return text.substr(begin, end - begin + 1);
    }

    std::string lowered(std::string text)
    {
      std::transform(text.begin(), text.end(), text.begin(),
                     [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      return text;
    }

    std::vector<std::string> fields(const std::string &line)
    {
      std::vector<std::string> result;
      std::stringstream        stream(line);
      std::string              field;
      while (std::getline(stream, field, ','))
        result.push_back(trimmed(field));
      return result;
    }

    // The factor to GPa of the unit in a stress column's name (in () or [], or after the last
    // '_'); 0 if there is none that is known.
    double stress_factor(const std::string &name)
    {
      std::string       unit;
      const std::string lower = lowered(name);
      const auto        open = lower.find_first_of("(["), close = lower.find_first_of(")]");
      if (open != std::string::npos && close != std::string::npos && close > open)
        unit = trimmed(lower.substr(open + 1, close - open - 1));
      else if (const auto underscore = lower.rfind('_'); underscore != std::string::npos)
        unit = lower.substr(underscore + 1);
      if (unit == "gpa")
        return 1.0;
      if (unit == "mpa")
        return 1e-3;
      return 0.0;
    }
  } // namespace

  HardeningTable read_hardening_table_csv(const std::string &path)
  {
    std::ifstream file(path);
    if (!file)
      throw std::invalid_argument("cannot open the file");
    const std::string header_rule =
        "the header must name two columns, the plastic strain and the true stress with its unit, "
        "e.g. plastic_strain,true_stress_GPa (or _MPa)";
    HardeningTable table;
    double         factor = 0.0;
    bool           has_header = false;
    std::string    line;
    for (unsigned int number = 1; std::getline(file, line); ++number)
      {
        if (number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0)
          line.erase(0, 3);
        const std::string content = trimmed(line);
        if (content.empty() || content[0] == '#')
          continue;
        const std::vector<std::string> row = fields(content);
        const std::string              where = "line " + std::to_string(number) + ": ";
        if (!has_header)
          {
            if (row.size() != 2 || lowered(row[0]).rfind("plastic_strain", 0) != 0)
              throw std::invalid_argument(where + "header '" + content + "'; " + header_rule);
            factor = stress_factor(row[1]);
            if (factor == 0.0)
              throw std::invalid_argument(where + "the stress column '" + row[1] +
                                          "' has no unit in its name (GPa or MPa); " + header_rule);
            has_header = true;
            continue;
          }
        if (row.size() != 2)
          throw std::invalid_argument(where + "'" + content +
                                      "': expected two numbers, plastic strain and stress");
        const auto strain = parse_finite_number(row[0]), stress = parse_finite_number(row[1]);
        if (!strain || !stress)
          throw std::invalid_argument(where + "'" + content +
                                      "': expected two finite numbers, plastic strain and stress");
        table.plastic_strain.push_back(*strain);
        table.stress.push_back(*stress * factor);
      }
    if (!has_header)
      throw std::invalid_argument("no header; " + header_rule);
    if (table.stress.size() < 2)
      throw std::invalid_argument("it has " + std::to_string(table.stress.size()) +
                                  " points; a table needs at least 2");
    return table;
  }
} // namespace indentsim::io

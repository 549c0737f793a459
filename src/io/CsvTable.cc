// Reading CSV input (see CsvTable.h).
#include "io/CsvTable.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace indentsim::io
{
  namespace
  {
    std::vector<std::string> split(const std::string &line, const char delimiter)
    {
      std::vector<std::string> fields;
      std::istringstream       in(line);
      std::string              field;
      if (delimiter == ' ')
        {
          while (in >> field)
            fields.push_back(trimmed(field));
          return fields;
        }
      while (std::getline(in, field, delimiter))
        fields.push_back(trimmed(field));
      return fields;
    }

    char delimiter_of(const std::string &header)
    {
      for (const char candidate : {',', '\t', ';'})
        if (header.find(candidate) != std::string::npos)
          return candidate;
      return ' ';
    }
  } // namespace

  std::string join_fields(const std::vector<std::string> &fields)
  {
    std::string text;
    for (const std::string &field : fields)
      text += (text.empty() ? "" : ",") + field;
    return text;
  }

  std::string lowered(std::string text)
  {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return text;
  }

  std::string trimmed(const std::string &text)
  {
    const auto begin = text.find_first_not_of(" \t\r\"");
    if (begin == std::string::npos)
      return "";
    const auto end = text.find_last_not_of(" \t\r\"");
    return text.substr(begin, end - begin + 1);
  }

  std::string unit_in_name(const std::string &name)
  {
    const std::string lower = lowered(name);
    for (const auto &[open, close] : {std::pair{'(', ')'}, std::pair{'[', ']'}})
      {
        const auto begin = lower.find(open), end = lower.find(close);
        if (begin != std::string::npos && end != std::string::npos && end > begin)
          return trimmed(lower.substr(begin + 1, end - begin - 1));
      }
    const auto underscore = lower.rfind('_');
    return underscore == std::string::npos ? "" : lower.substr(underscore + 1);
  }

  double length_factor(const std::string &unit)
  {
    const std::string u = lowered(unit);
    if (u == "um" || u == "\xc2\xb5m" || u == "\xce\xbcm" || u == "micron" || u == "microns")
      return 1.0;
    if (u == "nm")
      return 1e-3;
    if (u == "mm")
      return 1e3;
    return 0.0;
  }

  double force_factor(const std::string &unit)
  {
    const std::string u = lowered(unit);
    if (u == "mn")
      return 1.0;
    if (u == "un" || u == "\xc2\xb5n" || u == "\xce\xbcn")
      return 1e-3;
    if (u == "n")
      return 1e3;
    return 0.0;
  }

  double stress_factor(const std::string &unit)
  {
    const std::string u = lowered(unit);
    if (u == "gpa")
      return 1.0;
    if (u == "mpa")
      return 1e-3;
    return 0.0;
  }

  CsvTable read_csv_table(const std::string &path)
  {
    std::ifstream in(path);
    if (!in)
      throw std::invalid_argument("cannot open the file");
    CsvTable    table;
    char        delimiter = ',';
    std::string line;
    for (std::size_t number = 1; std::getline(in, line); ++number)
      {
        // A spreadsheet's "CSV UTF-8" starts with the byte-order mark EF BB BF; it is not part
        // of the first column's name.
        if (number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0)
          line.erase(0, 3);
        const std::string content = trimmed(line);
        if (content.empty() || content[0] == '#')
          continue;
        if (table.header.empty())
          {
            delimiter = delimiter_of(content);
            table.header = split(content, delimiter);
            table.header_line = number;
            continue;
          }
        table.rows.push_back(split(content, delimiter));
        table.line.push_back(number);
      }
    if (table.header.empty())
      throw std::invalid_argument("no header line (column names)");
    return table;
  }
} // namespace indentsim::io

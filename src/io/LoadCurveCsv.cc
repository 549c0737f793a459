// Reading a load-penetration curve from CSV (see LoadCurveCsv.h).
#include "io/LoadCurveCsv.h"

#include "io/TextNumber.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace indentsim::io
{
  namespace
  {
    std::string lower(std::string text)
    {
      std::transform(text.begin(), text.end(), text.begin(),
                     [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
      return text;
    }

    std::string trim(const std::string &text)
    {
      const auto begin = text.find_first_not_of(" \t\r\"");
      if (begin == std::string::npos)
        return "";
      const auto end = text.find_last_not_of(" \t\r\"");
      return text.substr(begin, end - begin + 1);
    }

    // The unit written into a column name: the text in () or [] or after the last '_'.
    std::string unit_in_name(const std::string &name)
    {
      const std::string lowered = lower(name);
      for (const auto &[open, close] : {std::pair{'(', ')'}, std::pair{'[', ']'}})
        {
          const auto begin = lowered.find(open), end = lowered.find(close);
          if (begin != std::string::npos && end != std::string::npos && end > begin)
            return trim(lowered.substr(begin + 1, end - begin - 1));
        }
      const auto underscore = lowered.rfind('_');
      return underscore == std::string::npos ? "" : lowered.substr(underscore + 1);
    }

    // Factor to um or mN; 0 if the unit is not known.
    double depth_factor(const std::string &unit)
    {
      const std::string u = lower(unit);
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
      const std::string u = lower(unit);
      if (u == "mn")
        return 1.0;
      if (u == "un" || u == "\xc2\xb5n" || u == "\xce\xbcn")
        return 1e-3;
      if (u == "n")
        return 1e3;
      return 0.0;
    }

    bool starts_with_any(const std::string &name, std::initializer_list<const char *> prefixes)
    {
      const std::string lowered = lower(name);
      for (const char *prefix : prefixes)
        if (lowered.rfind(prefix, 0) == 0)
          return true;
      return false;
    }

    std::vector<std::string> split(const std::string &line, const char delimiter)
    {
      std::vector<std::string> fields;
      if (delimiter == ' ')
        {
          std::istringstream in(line);
          std::string        field;
          while (in >> field)
            fields.push_back(field);
          return fields;
        }
      std::string        field;
      std::istringstream in(line);
      while (std::getline(in, field, delimiter))
        fields.push_back(trim(field));
      return fields;
    }
  } // namespace

  std::string LoadCurve::row_name(const std::size_t index) const
  {
    return index < line.size() ? "line " + std::to_string(line[index])
                               : "point " + std::to_string(index + 1);
  }

  bool LoadCurve::in_partial_unload(const std::size_t index) const
  {
    return index < segment.size() &&
           (segment[index] == "partial_unload" || segment[index] == "reload");
  }

  LoadCurve without_partial_unloads(const LoadCurve &curve)
  {
    LoadCurve kept;
    kept.source = curve.source;
    for (std::size_t i = 0; i < curve.depth.size(); ++i)
      {
        if (curve.in_partial_unload(i))
          continue;
        kept.depth.push_back(curve.depth[i]);
        kept.force.push_back(curve.force[i]);
        if (i < curve.contact_area.size())
          kept.contact_area.push_back(curve.contact_area[i]);
        if (i < curve.segment.size())
          kept.segment.push_back(curve.segment[i]);
        // Messages name the row of the file, or else the point of the whole curve.
        kept.line.push_back(i < curve.line.size() ? curve.line[i] : i + 1);
      }
    return kept;
  }

  LoadCurve read_load_curve_csv(const std::string &path, const std::string &depth_column,
                                const std::string &force_column, const std::string &depth_unit,
                                const std::string &force_unit)
  {
    std::ifstream in(path);
    if (!in)
      throw std::invalid_argument(path + ": cannot open the file");
    std::string              line;
    std::size_t              line_number = 0;
    std::vector<std::string> header;
    char                     delimiter = ',';
    while (std::getline(in, line))
      {
        ++line_number;
        // A spreadsheet's "CSV UTF-8" starts with the byte-order mark EF BB BF; it is not part
        // of the first column's name. CRLF endings: trim() and split() drop the '\r'.
        if (line_number == 1 && line.rfind("\xEF\xBB\xBF", 0) == 0)
          line.erase(0, 3);
        if (trim(line).empty() || trim(line)[0] == '#')
          continue;
        delimiter = line.find(',') != std::string::npos    ? ','
                    : line.find('\t') != std::string::npos ? '\t'
                    : line.find(';') != std::string::npos  ? ';'
                                                           : ' ';
        header = split(line, delimiter);
        break;
      }
    if (header.empty())
      throw std::invalid_argument(path + ": no header line (column names) found");

    const auto find_column = [&](const std::string                  &requested,
                                 std::initializer_list<const char *> prefixes,
                                 const char                         *what) -> std::size_t {
      for (std::size_t c = 0; c < header.size(); ++c)
        if (requested.empty() ? starts_with_any(header[c], prefixes) : header[c] == requested)
          return c;
      std::string names;
      for (const auto &name : header)
        names += (names.empty() ? "" : ", ") + name;
      throw std::invalid_argument(
          path + ": " +
          (requested.empty() ? std::string("no ") + what + " column found by name"
                             : std::string("no column named '") + requested + "'") +
          "; the header has: " + names + " (name the column with --" + what + "-column)");
    };
    const std::size_t depth_index = find_column(
        depth_column, {"depth", "h_", "h ", "h(", "h[", "displacement", "penetration"}, "depth");
    const std::size_t force_index =
        find_column(force_column, {"force", "load", "p_", "p ", "p(", "p["}, "force");
    std::size_t area_index = header.size(), segment_index = header.size();
    for (std::size_t c = 0; c < header.size(); ++c)
      {
        if (header[c] == "contact_area_um2")
          area_index = c;
        if (header[c] == "segment")
          segment_index = c;
      }

    const std::string d_unit = depth_unit.empty() ? unit_in_name(header[depth_index]) : depth_unit;
    const std::string f_unit = force_unit.empty() ? unit_in_name(header[force_index]) : force_unit;
    const double      d_factor = depth_factor(d_unit), f_factor = force_factor(f_unit);
    if (d_factor == 0)
      throw std::invalid_argument(path + ": column '" + header[depth_index] + "': depth unit '" +
                                  d_unit +
                                  "' is not known; allowed: um, nm, mm (write it into "
                                  "the column name, e.g. depth_nm, or pass --depth-unit)");
    if (f_factor == 0)
      throw std::invalid_argument(path + ": column '" + header[force_index] + "': force unit '" +
                                  f_unit +
                                  "' is not known; allowed: mN, uN, N (write it into "
                                  "the column name, e.g. force_mN, or pass --force-unit)");

    LoadCurve curve;
    curve.source = path;
    const auto number = [&](const std::vector<std::string> &fields, const std::size_t index) {
      const std::optional<double> value = parse_finite_number(fields[index]);
      if (!value)
        throw std::invalid_argument(path + ", line " + std::to_string(line_number) + ", column '" +
                                    header[index] + "': '" + fields[index] +
                                    "' is not a finite number");
      return *value;
    };
    while (std::getline(in, line))
      {
        ++line_number;
        if (trim(line).empty() || trim(line)[0] == '#')
          continue;
        const std::vector<std::string> fields = split(line, delimiter);
        const std::size_t              needed = std::max(depth_index, force_index) + 1;
        if (fields.size() < needed)
          throw std::invalid_argument(path + ", line " + std::to_string(line_number) + ": " +
                                      std::to_string(fields.size()) + " fields, the header has " +
                                      std::to_string(header.size()));
        curve.depth.push_back(d_factor * number(fields, depth_index));
        curve.force.push_back(f_factor * number(fields, force_index));
        curve.line.push_back(line_number);
        if (area_index < header.size() && area_index < fields.size())
          curve.contact_area.push_back(number(fields, area_index));
        if (segment_index < fields.size())
          curve.segment.push_back(trim(fields[segment_index]));
      }
    if (curve.contact_area.size() != curve.depth.size())
      curve.contact_area.clear();
    if (curve.segment.size() != curve.depth.size())
      curve.segment.clear();
    return curve;
  }
} // namespace indentsim::io

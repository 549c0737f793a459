// Reading a load-penetration curve from CSV (see LoadCurveCsv.h).
#include "io/LoadCurveCsv.h"

#include "io/CsvTable.h"
#include "io/TextNumber.h"

#include <algorithm>
#include <initializer_list>
#include <optional>
#include <stdexcept>

namespace indentsim::io
{
  namespace
  {
    bool starts_with_any(const std::string &name, std::initializer_list<const char *> prefixes)
    {
      const std::string lower = lowered(name);
      for (const char *prefix : prefixes)
        if (lower.rfind(prefix, 0) == 0)
          return true;
      return false;
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
    CsvTable csv;
    try
      {
        csv = read_csv_table(path);
      }
    catch (const std::invalid_argument &error)
      {
        throw std::invalid_argument(path + ": " + error.what());
      }
    const std::vector<std::string> &header = csv.header;

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
    const double      d_factor = length_factor(d_unit), f_factor = force_factor(f_unit);
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
    for (std::size_t row = 0; row < csv.rows.size(); ++row)
      {
        const std::vector<std::string> &fields = csv.rows[row];
        const std::string               where = path + ", " + csv.row_name(row);
        const auto                      number = [&](const std::size_t index) {
          const std::optional<double> value = parse_finite_number(fields[index]);
          if (!value)
            throw std::invalid_argument(where + ", column '" + header[index] + "': '" +
                                                             fields[index] + "' is not a finite number");
          return *value;
        };
        const std::size_t needed = std::max(depth_index, force_index) + 1;
        if (fields.size() < needed)
          throw std::invalid_argument(where + ": " + std::to_string(fields.size()) +
                                      " fields, the header has " + std::to_string(header.size()));
        curve.depth.push_back(d_factor * number(depth_index));
        curve.force.push_back(f_factor * number(force_index));
        curve.line.push_back(csv.line[row]);
        if (area_index < header.size() && area_index < fields.size())
          curve.contact_area.push_back(number(area_index));
        if (segment_index < fields.size())
          curve.segment.push_back(fields[segment_index]);
      }
    if (curve.contact_area.size() != curve.depth.size())
      curve.contact_area.clear();
    if (curve.segment.size() != curve.depth.size())
      curve.segment.clear();
    return curve;
  }
} // namespace indentsim::io

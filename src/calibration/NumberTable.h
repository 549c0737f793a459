// A measured table of numbers for the calibration: a CSV (io/CsvTable.h) whose columns are found
// by the start of their names, with the units written into the names, every error naming the
// file, the line and the column. Units: the factors convert to um, mN and GPa.
#pragma once

#include "io/CsvTable.h"
#include "io/TextNumber.h"

#include <initializer_list>
#include <stdexcept>
#include <string>

namespace indentsim::calibration
{
  class NumberTable
  {
  public:
    explicit NumberTable(const std::string &path)
      : path_(path)
    {
      try
        {
          csv_ = io::read_csv_table(path);
        }
      catch (const std::invalid_argument &error)
        {
          throw std::invalid_argument(path + ": " + error.what());
        }
    }

    std::size_t column(std::initializer_list<const char *> prefixes, const std::string &what) const
    {
      for (const char *prefix : prefixes)
        for (std::size_t c = 0; c < csv_.header.size(); ++c)
          if (io::lowered(csv_.header[c]).rfind(prefix, 0) == 0)
            return c;
      throw std::invalid_argument(path_ + ": no " + what + " column in the header '" +
                                  io::join_fields(csv_.header) + "'");
    }

    // The factor of the unit in column c's name (`factor_of` returns 0 for an unknown one).
    double unit_factor(const std::size_t  c, double (*factor_of)(const std::string &),
                       const std::string &spellings) const
    {
      const double factor = factor_of(io::unit_in_name(csv_.header[c]));
      if (factor == 0.)
        throw std::invalid_argument(path_ + ": column '" + csv_.header[c] +
                                    "': no known unit in the name; write it as " + spellings);
      return factor;
    }

    std::size_t        rows() const { return csv_.rows.size(); }
    std::size_t        columns() const { return csv_.header.size(); }
    const std::string &name(const std::size_t c) const { return csv_.header.at(c); }
    const std::string &path() const { return path_; }
    std::string        row_name(const std::size_t r) const { return csv_.row_name(r); }
    const std::string &text(const std::size_t r, const std::size_t c) const
    {
      if (c >= csv_.rows[r].size())
        throw std::invalid_argument(path_ + ", " + csv_.row_name(r) + ": no value in column '" +
                                    csv_.header[c] + "'");
      return csv_.rows[r][c];
    }
    double number(const std::size_t r, const std::size_t c) const
    {
      const auto value = io::parse_finite_number(text(r, c));
      if (!value)
        throw std::invalid_argument(path_ + ", " + csv_.row_name(r) + ", column '" +
                                    csv_.header[c] + "': '" + text(r, c) +
                                    "' is not a finite number");
      return *value;
    }

  private:
    std::string  path_;
    io::CsvTable csv_;
  };
} // namespace indentsim::calibration

// A string as a JSON string literal (quoted, with JSON escapes), for the JSON files the tool
// writes (study index, Oliver-Pharr analysis, comparison with a measured curve).
#pragma once

#include <cmath>
#include <iomanip>
#include <optional>
#include <sstream>
#include <string>

namespace indentsim::io
{
  // A number for a JSON file: 10 significant digits; null if not finite (JSON has no NaN).
  inline std::string json_number(const double value)
  {
    if (!std::isfinite(value))
      return "null";
    std::ostringstream out;
    out << std::setprecision(10) << value;
    return out.str();
  }

  // An optional number: null when absent.
  inline std::string json_number(const std::optional<double> &value)
  {
    return value ? json_number(*value) : std::string("null");
  }

  inline std::string json_string(const std::string &text)
  {
    std::ostringstream out;
    out << '"';
    for (const unsigned char c : text)
      switch (c)
        {
        case '"':
          out << "\\\"";
          break;
        case '\\':
          out << "\\\\";
          break;
        case '\n':
          out << "\\n";
          break;
        case '\t':
          out << "\\t";
          break;
        default:
          if (c < 0x20)
            out << "\\u" << std::hex << std::setw(4) << std::setfill('0') << int(c) << std::dec
                << std::setfill(' ');
          else
            out << c;
        }
    out << '"';
    return out.str();
  }
} // namespace indentsim::io

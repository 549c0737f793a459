// Reading a number from text for the command line and CSV input: the whole text must be one
// finite number (no trailing characters, no NaN or infinity).
#pragma once

#include <cmath>
#include <optional>
#include <string>

namespace indentsim::io
{
  inline std::optional<double> parse_finite_number(const std::string &text)
  {
    std::size_t used = 0;
    double      value = 0;
    try
      {
        value = std::stod(text, &used);
      }
    catch (const std::exception &)
      {
        return std::nullopt;
      }
    if (used == 0 || used != text.size() || !std::isfinite(value))
      return std::nullopt;
    return value;
  }
} // namespace indentsim::io

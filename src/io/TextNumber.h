// Reading a number from text for the command line and CSV input: the whole text must be one
// finite number (no trailing characters, no NaN or infinity).
#pragma once

#include <charconv>
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

  // A YAML scalar of a case or study file as a number: the whole text in C's plain decimal or
  // exponent form with an optional leading '+', finite (YAML's .inf and .nan spellings and hex
  // are not numbers here).
  inline std::optional<double> parse_yaml_number(const std::string &text)
  {
    const std::size_t start = (!text.empty() && text[0] == '+') ? 1 : 0;
    double            value = 0.;
    const auto result = std::from_chars(text.data() + start, text.data() + text.size(), value);
    if (result.ec != std::errc() || result.ptr != text.data() + text.size() ||
        !std::isfinite(value))
      return std::nullopt;
    return value;
  }
} // namespace indentsim::io

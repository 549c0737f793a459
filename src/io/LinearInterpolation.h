// Linear interpolation in a table read from a file (a damage profile, a measured or simulated
// curve): the value between the rows, the end values beyond them. Units: those of the table.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace indentsim::io
{
  // y at `at` from the table (x strictly increasing, y of the same length, not empty): linear
  // between the rows, y.front() at and before x.front(), y.back() at and after x.back().
  inline double interpolate_clamped(const std::vector<double> &x, const std::vector<double> &y,
                                    const double at)
  {
    if (at <= x.front())
      return y.front();
    if (at >= x.back())
      return y.back();
    const std::size_t i = std::upper_bound(x.begin(), x.end(), at) - x.begin();
    const double      t = (at - x[i - 1]) / (x[i] - x[i - 1]);
    return (1 - t) * y[i - 1] + t * y[i];
  }
} // namespace indentsim::io

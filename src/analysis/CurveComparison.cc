#include "analysis/CurveComparison.h"

#include "io/LinearInterpolation.h"

#include "io/JsonText.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace indentsim::analysis
{
  namespace
  {
    // The loading branch: from the first point to the (first) largest depth, keeping the points
    // where the depth grows strictly (holds and noise reversals dropped).
    void loading_branch(const LoadCurve &curve, std::vector<double> &depth,
                        std::vector<double> &force)
    {
      const auto        largest = std::max_element(curve.depth.begin(), curve.depth.end());
      const std::size_t end = static_cast<std::size_t>(largest - curve.depth.begin()) + 1;
      for (std::size_t i = 0; i < end; ++i)
        if (depth.empty() || curve.depth[i] > depth.back())
          {
            depth.push_back(curve.depth[i]);
            force.push_back(curve.force[i]);
          }
    }

    std::string number(const double value)
    {
      std::ostringstream out;
      out << std::setprecision(10) << value;
      return out.str();
    }
  } // namespace

  CurveDeviation compare_loading(const LoadCurve &computed, const LoadCurve &measured)
  {
    if (computed.depth.size() < 2 || measured.depth.size() < 2)
      throw std::invalid_argument("a curve comparison needs at least two points on each curve");
    std::vector<double> h_computed, p_computed, h_measured, p_measured;
    loading_branch(computed, h_computed, p_computed);
    loading_branch(measured, h_measured, p_measured);
    CurveDeviation result;
    result.max_depth = h_computed.back();
    result.computed_force = p_computed.back();
    double sum = 0;
    for (std::size_t i = 0; i < h_measured.size(); ++i)
      if (h_measured[i] >= h_computed.front() && h_measured[i] <= result.max_depth)
        {
          const double difference =
              io::interpolate_clamped(h_computed, p_computed, h_measured[i]) - p_measured[i];
          sum += difference * difference;
          ++result.n_points;
        }
    if (result.n_points == 0)
      throw std::invalid_argument(measured.source +
                                  ": no measured loading point lies within the "
                                  "computed depths 0 ... " +
                                  number(result.max_depth) +
                                  " um (check the depth unit of its column name)");
    result.rms_mN = std::sqrt(sum / result.n_points);
    result.rms_relative = result.computed_force > 0 ? result.rms_mN / result.computed_force : 0.0;
    if (h_measured.back() >= result.max_depth)
      {
        result.measured_force = io::interpolate_clamped(h_measured, p_measured, result.max_depth);
        if (*result.measured_force != 0)
          result.deviation_at_max_depth_percent =
              100.0 * (result.computed_force - *result.measured_force) / *result.measured_force;
      }
    return result;
  }

  std::string to_json(const CurveDeviation &d, const std::string &measured_source)
  {
    const auto optional = [](const std::optional<double> &value) {
      return value ? number(*value) : std::string("null");
    };
    std::ostringstream out;
    out << "{\n"
        << "  \"units\": \"depths um, forces mN\",\n"
        << "  \"measured_curve\": " << io::json_string(measured_source) << ",\n"
        << "  \"compared\": \"loading branches at the measured depths within the computed range; "
           "computed force interpolated linearly\",\n"
        << "  \"n_points\": " << d.n_points << ",\n"
        << "  \"rms_deviation_mN\": " << number(d.rms_mN) << ",\n"
        << "  \"rms_deviation_relative\": " << number(d.rms_relative) << ",\n"
        << "  \"max_depth_um\": " << number(d.max_depth) << ",\n"
        << "  \"computed_force_at_max_depth_mN\": " << number(d.computed_force) << ",\n"
        << "  \"measured_force_at_max_depth_mN\": " << optional(d.measured_force) << ",\n"
        << "  \"deviation_at_max_depth_percent\": " << optional(d.deviation_at_max_depth_percent)
        << "\n}\n";
    return out.str();
  }

  std::string to_csv(const LoadCurve &curve)
  {
    std::ostringstream out;
    out << "depth_um,force_mN\n" << std::setprecision(10);
    for (std::size_t i = 0; i < curve.depth.size(); ++i)
      out << curve.depth[i] << ',' << curve.force[i] << '\n';
    return out.str();
  }
} // namespace indentsim::analysis

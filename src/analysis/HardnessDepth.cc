#include "analysis/HardnessDepth.h"

#include "io/JsonText.h"

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace indentsim::analysis
{
  namespace
  {
    using io::json_number;

    // The rows of each partial unload: the row where it starts (the last before it) and its own.
    struct PartialUnloadRows
    {
      std::size_t              top;
      std::vector<std::size_t> rows;
    };

    std::vector<PartialUnloadRows> partial_unload_rows(const LoadCurve &curve)
    {
      std::vector<PartialUnloadRows> found;
      for (std::size_t i = 1; i < curve.segment.size(); ++i)
        {
          if (curve.segment[i] != "partial_unload")
            continue;
          if (curve.segment[i - 1] != "partial_unload")
            found.push_back({i - 1, {}});
          found.back().rows.push_back(i);
        }
      return found;
    }

    HardnessPoint analyze_one(const LoadCurve &curve, const PartialUnloadRows &unload,
                              const std::function<double(double)> &area,
                              const OliverPharrSettings           &settings)
    {
      HardnessPoint point;
      point.depth = curve.depth[unload.top];
      point.force = curve.force[unload.top];
      std::vector<double> depth{point.depth}, force{point.force};
      for (const std::size_t row : unload.rows)
        {
          depth.push_back(curve.depth[row]);
          force.push_back(curve.force[row]);
        }
      point.unloaded_fraction = (point.force - force.back()) / point.force;
      point.fit = fit_power_law(depth, force);
      point.stiffness = point.fit.stiffness(point.depth);
      if (!(point.stiffness > 0))
        throw std::invalid_argument("the fitted unloading stiffness is " +
                                    json_number(point.stiffness) + " mN/um");
      point.estimate = contact_estimate(point.depth, point.force, point.stiffness, area, settings);
      if (!(point.estimate.contact_area > 0))
        throw std::invalid_argument(
            "the contact depth h_c = " + json_number(point.estimate.contact_depth) +
            " um gives no contact area");
      if (unload.top < curve.contact_area.size() && curve.contact_area[unload.top] > 0 &&
          curve.contact_area[unload.top] >= settings.min_true_contact_area)
        {
          point.true_contact_area = curve.contact_area[unload.top];
          point.true_hardness = point.force / *point.true_contact_area;
        }
      return point;
    }

    // Least squares of y on the columns of `basis` (one row per point); the residual's sum of
    // squares in `sse`. Returns false if the normal matrix is singular.
    bool least_squares(const std::vector<std::vector<double>> &basis, const std::vector<double> &y,
                       std::vector<double> &coefficients, double &sse)
    {
      const unsigned int         n = basis.front().size();
      dealii::FullMatrix<double> normal(n, n);
      dealii::Vector<double>     rhs(n);
      for (std::size_t i = 0; i < y.size(); ++i)
        for (unsigned int a = 0; a < n; ++a)
          {
            rhs(a) += basis[i][a] * y[i];
            for (unsigned int b = 0; b < n; ++b)
              normal(a, b) += basis[i][a] * basis[i][b];
          }
      try
        {
          normal.gauss_jordan();
        }
      catch (...)
        {
          return false;
        }
      dealii::Vector<double> solution(n);
      normal.vmult(solution, rhs);
      coefficients.assign(solution.begin(), solution.end());
      sse = 0;
      for (std::size_t i = 0; i < y.size(); ++i)
        {
          double fitted = 0;
          for (unsigned int a = 0; a < n; ++a)
            fitted += coefficients[a] * basis[i][a];
          sse += (y[i] - fitted) * (y[i] - fitted);
        }
      return std::isfinite(sse);
    }
  } // namespace

  std::vector<HardnessPoint> analyze_partial_unloads(const LoadCurve                     &curve,
                                                     const std::function<double(double)> &area,
                                                     const OliverPharrSettings           &settings,
                                                     std::vector<std::string>            &skipped)
  {
    std::vector<HardnessPoint> points;
    for (const PartialUnloadRows &unload : partial_unload_rows(curve))
      try
        {
          points.push_back(analyze_one(curve, unload, area, settings));
        }
      catch (const std::exception &e)
        {
          skipped.push_back("the partial unload at " + json_number(curve.depth[unload.top]) +
                            " um (" + curve.row_name(unload.top) + "): " + e.what());
        }
    return points;
  }

  std::optional<NixGaoFit> fit_nix_gao(const std::vector<double> &depth,
                                       const std::vector<double> &hardness)
  {
    const std::size_t n = depth.size();
    if (n < 2 * min_branch_points)
      return std::nullopt;
    // Points in order of x = 1/h, deep (small x) first.
    std::vector<std::size_t> order(n);
    for (std::size_t i = 0; i < n; ++i)
      order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return depth[a] > depth[b]; });
    std::vector<double> x(n), y(n);
    for (std::size_t i = 0; i < n; ++i)
      {
        x[i] = 1 / depth[order[i]];
        y[i] = hardness[order[i]] * hardness[order[i]];
      }

    NixGaoFit best;
    double    best_sse = std::numeric_limits<double>::infinity();
    {
      std::vector<std::vector<double>> line(n);
      for (std::size_t i = 0; i < n; ++i)
        line[i] = {1.0, x[i]};
      std::vector<double> c;
      double              sse = 0;
      if (least_squares(line, y, c, sse))
        best.single_line_rms = std::sqrt(sse / n);
    }
    // The knee between deep point k - 1 and shallow point k, searched on a grid of each
    // interval (the sum of squares is smooth in x_k there).
    constexpr unsigned int grid = 20;
    for (std::size_t k = min_branch_points; k + min_branch_points <= n; ++k)
      for (unsigned int g = 0; g <= grid; ++g)
        {
          const double                     knee = x[k - 1] + (x[k] - x[k - 1]) * g / grid;
          std::vector<std::vector<double>> hinge(n);
          for (std::size_t i = 0; i < n; ++i)
            hinge[i] = {1.0, x[i], std::max(0.0, knee - x[i])};
          std::vector<double> c;
          double              sse = 0;
          if (!least_squares(hinge, y, c, sse) || !(sse < best_sse) || !(c[0] > 0))
            continue;
          best_sse = sse;
          best.knee_depth = 1 / knee;
          best.layer_hardness = std::sqrt(c[0]);
          best.layer_characteristic = c[1] / c[0];
          best.deep_slope = c[1] - c[2];
          best.deep_intercept = c[0] + c[2] * knee;
          best.deep_range[0] = 1 / x[k - 1];
          best.deep_range[1] = 1 / x[0];
          best.layer_range[0] = 1 / x[n - 1];
          best.layer_range[1] = 1 / x[k];
        }
    if (!std::isfinite(best_sse))
      return std::nullopt;
    best.rms = std::sqrt(best_sse / n);
    const double single_sse = n * best.single_line_rms * best.single_line_rms;
    best.f_statistic = best_sse > 0 ? (single_sse - best_sse) / 2 / (best_sse / (n - 4))
                                    : std::numeric_limits<double>::infinity();
    return best;
  }

  bool NixGaoFit::knee_significant() const
  {
    return f_statistic > knee_f_threshold;
  }

  std::string to_csv(const std::vector<HardnessPoint> &points)
  {
    std::ostringstream out;
    out << "depth_um,force_mN,stiffness_mN_per_um,contact_depth_um,contact_area_um2,hardness_GPa,"
           "reduced_modulus_GPa,true_contact_area_um2,true_hardness_GPa,unloaded_fraction,"
           "fit_points,fit_exponent\n";
    out << std::setprecision(10);
    for (const HardnessPoint &p : points)
      out << p.depth << ',' << p.force << ',' << p.stiffness << ',' << p.estimate.contact_depth
          << ',' << p.estimate.contact_area << ',' << p.estimate.hardness << ','
          << p.estimate.reduced_modulus << ','
          << (p.true_contact_area ? json_number(*p.true_contact_area) : "") << ','
          << (p.true_hardness ? json_number(*p.true_hardness) : "") << ',' << p.unloaded_fraction
          << ',' << p.fit.n_points << ',' << p.fit.m << '\n';
    return out.str();
  }

  std::string to_json(const std::vector<HardnessPoint> &points,
                      const std::optional<NixGaoFit>   &nix_gao,
                      const std::vector<std::string> &skipped, const std::string &source)
  {
    std::ostringstream out;
    const auto         list = [&](const auto &value) {
      std::string text = "[";
      for (std::size_t i = 0; i < points.size(); ++i)
        text += (i ? ", " : "") + value(points[i]);
      return text + "]";
    };
    out << "{\n"
        << "  \"units\": \"depths um, forces mN, stiffness mN/um, areas um^2, hardness and "
           "moduli GPa\",\n"
        << "  \"source\": " << io::json_string(source) << ",\n"
        << "  \"method\": \"each partial unload: P = alpha (h - h_f)^m on its start and its "
           "points, S = dP/dh at its start, h_c = h - epsilon P/S, H = P/A(h_c), E_r = "
           "sqrt(pi)/(2 beta) S/sqrt(A(h_c)); Nix-Gao: H^2 against 1/h (h where the partial "
           "unload starts), bilinear and continuous at the knee\",\n"
        << "  \"depth_um\": " << list([](const auto &p) { return json_number(p.depth); }) << ",\n"
        << "  \"force_mN\": " << list([](const auto &p) { return json_number(p.force); }) << ",\n"
        << "  \"stiffness_mN_per_um\": "
        << list([](const auto &p) { return json_number(p.stiffness); }) << ",\n"
        << "  \"hardness_GPa\": "
        << list([](const auto &p) { return json_number(p.estimate.hardness); }) << ",\n"
        << "  \"reduced_modulus_GPa\": "
        << list([](const auto &p) { return json_number(p.estimate.reduced_modulus); }) << ",\n"
        << "  \"true_hardness_GPa\": "
        << list([&](const auto &p) { return json_number(p.true_hardness); }) << ",\n";
    out << "  \"nix_gao\": ";
    if (nix_gao)
      {
        const NixGaoFit &f = *nix_gao;
        out << "{\"knee_depth_um\": " << json_number(f.knee_depth)
            << ", \"layer_hardness_GPa\": " << json_number(f.layer_hardness)
            << ", \"layer_characteristic_depth_um\": " << json_number(f.layer_characteristic)
            << ", \"layer_range_um\": [" << json_number(f.layer_range[0]) << ", "
            << json_number(f.layer_range[1]) << "], \"deep_range_um\": ["
            << json_number(f.deep_range[0]) << ", " << json_number(f.deep_range[1])
            << "], \"deep_intercept_GPa2\": " << json_number(f.deep_intercept)
            << ", \"deep_slope_GPa2_um\": " << json_number(f.deep_slope)
            << ", \"rms_GPa2\": " << json_number(f.rms)
            << ", \"single_line_rms_GPa2\": " << json_number(f.single_line_rms)
            << ", \"f_statistic\": " << json_number(f.f_statistic)
            << ", \"knee_significant\": " << (f.knee_significant() ? "true" : "false") << "},\n";
      }
    else
      out << "null,\n";
    out << "  \"skipped\": [";
    for (std::size_t i = 0; i < skipped.size(); ++i)
      out << (i ? ", " : "") << io::json_string(skipped[i]);
    out << "]\n}\n";
    return out.str();
  }
} // namespace indentsim::analysis

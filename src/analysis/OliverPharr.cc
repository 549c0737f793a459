// Oliver-Pharr analysis (see OliverPharr.h for the equations and units).
#include "analysis/OliverPharr.h"

#include "io/JsonText.h"
#include "io/TextNumber.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace indentsim::analysis
{
  namespace
  {
    // Bounds of the power-law fit's search (wider than the physical range below, so that a
    // defective curve shows its exponent in the refusal).
    constexpr double min_exponent = 1.0, max_exponent = 6.0;

    double sum_of_squares(const std::vector<double> &depth, const std::vector<double> &force,
                          const PowerLawFit &fit)
    {
      double sum = 0;
      for (std::size_t i = 0; i < depth.size(); ++i)
        {
          const double r = force[i] - fit.force(depth[i]);
          sum += r * r;
        }
      return sum;
    }

    // For fixed h_f and m the best alpha is linear least squares: sum P x^m / sum x^2m.
    double best_alpha(const std::vector<double> &depth, const std::vector<double> &force,
                      const double h_f, const double m)
    {
      double numerator = 0, denominator = 0;
      for (std::size_t i = 0; i < depth.size(); ++i)
        {
          const double xm = std::pow(depth[i] - h_f, m);
          numerator += force[i] * xm;
          denominator += xm * xm;
        }
      return numerator / denominator;
    }

    // The start of the Levenberg-Marquardt polish: h_f on a logarithmic grid below the
    // smallest fitted depth, m from the straight line log P = log alpha + m log(h - h_f).
    PowerLawFit profile_start(const std::vector<double> &depth, const std::vector<double> &force)
    {
      const double h_min = *std::min_element(depth.begin(), depth.end());
      const double h_max = *std::max_element(depth.begin(), depth.end());
      const double span = std::max(h_max - h_min, 1e-12 * std::max(1.0, std::abs(h_max)));
      PowerLawFit  best;
      double       best_sum = std::numeric_limits<double>::infinity();
      for (int k = 0; k <= 120; ++k)
        {
          const double h_f = h_min - span * std::pow(10.0, -4.0 + 6.0 * k / 120.0);
          double       sx = 0, sy = 0, sxx = 0, sxy = 0;
          const double n = static_cast<double>(depth.size());
          for (std::size_t i = 0; i < depth.size(); ++i)
            {
              const double x = std::log(depth[i] - h_f), y = std::log(force[i]);
              sx += x;
              sy += y;
              sxx += x * x;
              sxy += x * y;
            }
          const double denominator = n * sxx - sx * sx;
          double       m = denominator > 0 ? (n * sxy - sx * sy) / denominator : 1.5;
          m = std::clamp(m, min_exponent, max_exponent);
          PowerLawFit candidate;
          candidate.h_f = h_f;
          candidate.m = m;
          candidate.alpha = best_alpha(depth, force, h_f, m);
          const double sum = sum_of_squares(depth, force, candidate);
          if (sum < best_sum)
            {
              best_sum = sum;
              best = candidate;
            }
        }
      return best;
    }

    // Solves the 3x3 system A d = b by Gaussian elimination with partial pivoting.
    bool solve3(std::array<std::array<double, 3>, 3> a, std::array<double, 3> b,
                std::array<double, 3> &d)
    {
      for (int c = 0; c < 3; ++c)
        {
          int pivot = c;
          for (int r = c + 1; r < 3; ++r)
            if (std::abs(a[r][c]) > std::abs(a[pivot][c]))
              pivot = r;
          if (a[pivot][c] == 0.0)
            return false;
          std::swap(a[c], a[pivot]);
          std::swap(b[c], b[pivot]);
          for (int r = c + 1; r < 3; ++r)
            {
              const double factor = a[r][c] / a[c][c];
              for (int k = c; k < 3; ++k)
                a[r][k] -= factor * a[c][k];
              b[r] -= factor * b[c];
            }
        }
      for (int r = 2; r >= 0; --r)
        {
          double value = b[r];
          for (int k = r + 1; k < 3; ++k)
            value -= a[r][k] * d[k];
          d[r] = value / a[r][r];
        }
      return std::isfinite(d[0]) && std::isfinite(d[1]) && std::isfinite(d[2]);
    }

    std::string format(const double value)
    {
      return io::json_number(value);
    }

    std::string depth_at(const LoadCurve &curve, const std::size_t i)
    {
      return format(curve.depth[i]) + " um (" + curve.row_name(i) + ")";
    }

    // The analysed unloading [begin, end) of a curve after the checks of its order (see
    // analyze() in OliverPharr.h and the user guide): rows [0, begin] are the loading (with
    // earlier cycles and holds), begin is the last point of the largest depth.
    struct UnloadingBranch
    {
      std::size_t begin = 0, end = 0;
      double      depth_tolerance = 0; // [um]
    };

    UnloadingBranch identify_branches(const LoadCurve &curve)
    {
      const std::string where = curve.source.empty() ? "the curve" : curve.source;
      const std::size_t n = curve.depth.size();
      if (curve.force.size() != n || n < 4)
        throw std::invalid_argument(where +
                                    ": a load-penetration curve with unloading needs at "
                                    "least 4 points (it has " +
                                    std::to_string(n) + ")");
      for (std::size_t i = 0; i < n; ++i)
        if (!std::isfinite(curve.depth[i]) || !std::isfinite(curve.force[i]))
          throw std::invalid_argument(where + ", " + curve.row_name(i) + ": depth " +
                                      format(curve.depth[i]) + " um, force " +
                                      format(curve.force[i]) + " mN: not finite numbers");
      const auto [lowest, highest] = std::minmax_element(curve.depth.begin(), curve.depth.end());
      const double    h_max = *highest;
      UnloadingBranch branch;
      branch.depth_tolerance = depth_noise_fraction * (h_max - *lowest);
      const double tolerance = branch.depth_tolerance;

      // The unloading starts at the last point of the largest depth (after a hold at it).
      std::size_t begin = 0;
      for (std::size_t i = 0; i < n; ++i)
        if (curve.depth[i] >= h_max - 1e-12 * std::abs(h_max))
          begin = i;
      if (!(curve.force[begin] > 0))
        throw std::invalid_argument(where + ": the force at the largest depth " + format(h_max) +
                                    " um (" + curve.row_name(begin) + ") is " +
                                    format(curve.force[begin]) +
                                    " mN; an indentation curve needs a positive maximum force");

      // Loading: a depth that falls for a single row while the next row is deeper than the one
      // before the fall is a pair of rows out of order (a cycle's unloading takes more rows).
      for (std::size_t i = 1; i + 1 <= begin; ++i)
        if (curve.depth[i] < curve.depth[i - 1] - tolerance &&
            curve.depth[i + 1] > curve.depth[i - 1])
          throw std::invalid_argument(
              where + ", " + curve.row_name(i) + ": the loading's depth falls to " +
              depth_at(curve, i) + " after " + depth_at(curve, i - 1) +
              " and rises at once beyond it to " + depth_at(curve, i + 1) +
              ": two rows out of order. The depth must grow on the loading in the recorded "
              "order (the rows are never re-sorted); restore the recorded order");

      // Unloading: the depth falls from h_max until the force reaches zero (the contact is
      // lost: later rows are ignored) or the curve reloads (a later cycle that stays below
      // h_max). A rise that falls back at once is a pair of rows out of order.
      std::size_t end = begin + 1;
      double      shallowest = curve.depth[begin];
      std::size_t shallowest_index = begin;
      while (end < n && curve.force[end - 1] > 0)
        {
          const double h = curve.depth[end];
          if (h > shallowest + tolerance)
            {
              const bool reload = end + 1 < n && curve.depth[end + 1] >= h - tolerance;
              if (!reload)
                throw std::invalid_argument(
                    where + ", " + curve.row_name(end) + ": on the unloading from h_max = " +
                    depth_at(curve, begin) + " the depth rises to " + depth_at(curve, end) +
                    " after " + depth_at(curve, shallowest_index) +
                    (end + 1 < n ? " and falls again to " + depth_at(curve, end + 1) : "") +
                    ": rows out of order. The depth must fall on the unloading in the recorded "
                    "order (by at most " +
                    format(tolerance) +
                    " um of noise, 0.1 % of the depth range; the rows are never re-sorted)");
              break;
            }
          if (h < shallowest)
            {
              shallowest = h;
              shallowest_index = end;
            }
          ++end;
        }

      // A curve starts at the surface with its loading: a first row deeper than the end of the
      // unloading is a file in reverse order (or one whose loading is missing).
      if (curve.depth.front() > curve.depth[end - 1] + tolerance)
        throw std::invalid_argument(
            where + ": the curve starts at depth " + depth_at(curve, 0) +
            " and its unloading from h_max = " + depth_at(curve, begin) + " ends at " +
            depth_at(curve, end - 1) +
            ", shallower than its start: are the rows in reverse order, or is the start of "
            "the loading missing? A curve must begin at the surface with the loading and end "
            "with the unloading, in the recorded order (it is never re-sorted)");
      branch.begin = begin;
      branch.end = end;
      return branch;
    }

    // Results outside the bounds of an elasto-plastic indentation are refused (see
    // OliverPharr.h): they come from a curve that is not one (columns, units, order, fit
    // range), never from a material.
    // With `stage_fit_only` only the fit's exponent (checked before anything is derived from it).
    void check_physical_bounds(const OliverPharrResult &r, const std::string &where,
                               const double depth_tolerance, const bool stage_fit_only)
    {
      const auto refuse = [&](const std::string &what) {
        throw std::invalid_argument(where + ": " + what +
                                    "; the Oliver-Pharr result is not written. Check the order "
                                    "of the rows, the depth and force columns and their units, "
                                    "and the fit range (--fit-range)");
      };
      if (r.fit.m > max_physical_exponent)
        refuse("the fitted unloading exponent m = " + format(r.fit.m) +
               " (P = alpha (h - h_f)^m, " + std::to_string(r.fit.n_points) +
               " points) is outside 1 <= m <= " + format(max_physical_exponent) +
               " (elastic unloading: 1 for a flat punch, 1.5 for a paraboloid, 2 for a cone)");
      if (!stage_fit_only)
        {
          if (!(r.contact_depth >= 0 && r.contact_depth <= r.max_depth))
            refuse("the contact depth h_c = " + format(r.contact_depth) +
                   " um is outside 0 <= h_c <= h_max = " + format(r.max_depth) + " um");
          if (!(r.residual_depth >= -depth_tolerance &&
                r.residual_depth <= r.max_depth + depth_tolerance))
            refuse("the residual depth h_r = " + format(r.residual_depth) + " um (" +
                   r.residual_depth_source +
                   ") is outside 0 <= h_r <= h_max = " + format(r.max_depth) + " um");
          if (!(r.plastic_work_ratio >= -work_ratio_tolerance && r.plastic_work_ratio <= 1.0))
            refuse("the plastic work ratio W_p/W_t = " + format(r.plastic_work_ratio) +
                   " (W_t = " + format(r.total_work) + ", W_e = " + format(r.elastic_work) +
                   " mN um) is outside 0 <= W_p/W_t <= 1 (tolerance " +
                   format(work_ratio_tolerance) + " for the trapezoid rule)");
        }
    }
  } // namespace

  double PowerLawFit::force(const double h) const
  {
    return h > h_f ? alpha * std::pow(h - h_f, m) : 0.0;
  }

  double PowerLawFit::stiffness(const double h) const
  {
    return h > h_f ? alpha * m * std::pow(h - h_f, m - 1.0) : 0.0;
  }

  PowerLawFit fit_power_law(const std::vector<double> &depth, const std::vector<double> &force)
  {
    if (depth.size() != force.size() || depth.size() < 3)
      throw std::invalid_argument("the power-law fit P = alpha (h - h_f)^m needs at least 3 "
                                  "points; it got " +
                                  std::to_string(std::min(depth.size(), force.size())));
    for (std::size_t i = 0; i < depth.size(); ++i)
      if (!(force[i] > 0) || !std::isfinite(depth[i]))
        throw std::invalid_argument("the power-law fit needs positive forces and finite depths; "
                                    "point " +
                                    std::to_string(i) + " has depth " + format(depth[i]) +
                                    " um, force " + format(force[i]) + " mN");
    const double h_min = *std::min_element(depth.begin(), depth.end());
    PowerLawFit  fit = profile_start(depth, force);
    double       sum = sum_of_squares(depth, force, fit);
    double       lambda = 1e-3;
    for (int iteration = 0; iteration < 500 && sum > 0; ++iteration)
      {
        // Gauss-Newton normal equations in (alpha, h_f, m) with Marquardt's diagonal scaling.
        std::array<std::array<double, 3>, 3> normal{};
        std::array<double, 3>                gradient{};
        for (std::size_t i = 0; i < depth.size(); ++i)
          {
            const double                x = depth[i] - fit.h_f, xm = std::pow(x, fit.m);
            const std::array<double, 3> row = {
                {xm, -fit.alpha * fit.m * xm / x, fit.alpha * xm * std::log(x)}};
            const double residual = force[i] - fit.alpha * xm;
            for (int a = 0; a < 3; ++a)
              {
                gradient[a] += row[a] * residual;
                for (int b = 0; b < 3; ++b)
                  normal[a][b] += row[a] * row[b];
              }
          }
        bool improved = false;
        for (int attempt = 0; attempt < 30 && !improved; ++attempt)
          {
            auto damped = normal;
            for (int a = 0; a < 3; ++a)
              damped[a][a] += lambda * normal[a][a];
            std::array<double, 3> step{};
            if (!solve3(damped, gradient, step))
              {
                lambda *= 10;
                continue;
              }
            PowerLawFit trial = fit;
            trial.alpha += step[0];
            trial.h_f += step[1];
            trial.m += step[2];
            const bool admissible = trial.alpha > 0 && trial.h_f < h_min &&
                                    trial.m >= min_exponent && trial.m <= max_exponent;
            const double trial_sum = admissible ? sum_of_squares(depth, force, trial)
                                                : std::numeric_limits<double>::infinity();
            if (trial_sum < sum)
              {
                const double relative_change = (sum - trial_sum) / sum;
                fit = trial;
                sum = trial_sum;
                lambda = std::max(lambda / 10, 1e-12);
                improved = true;
                if (relative_change < 1e-14)
                  iteration = 500; // converged
              }
            else
              lambda *= 10;
          }
        if (!improved)
          break;
      }
    fit.n_points = static_cast<unsigned int>(depth.size());
    fit.rms_error = std::sqrt(sum / depth.size());
    return fit;
  }

  double default_epsilon(const std::string &shape)
  {
    // Oliver and Pharr (1992, table 1): 0.72 conical, 0.75 paraboloid of revolution (and
    // Berkovich/Vickers by their recommendation), 1 flat punch.
    if (shape == "cone" || shape == "rounded_cone")
      return 2.0 * (M_PI - 2.0) / M_PI;
    if (shape == "flat_punch")
      return 1.0;
    return 0.75;
  }

  ContactEstimate contact_estimate(const double depth, const double force, const double stiffness,
                                   const std::function<double(double)> &area_function,
                                   const OliverPharrSettings           &settings)
  {
    ContactEstimate e;
    e.contact_depth = depth - settings.epsilon * force / stiffness; // eq. 11 of 2004
    e.contact_area = e.contact_depth > 0 ? area_function(e.contact_depth) : 0.0;
    if (e.contact_area > 0)
      {
        e.hardness = force / e.contact_area;
        e.reduced_modulus =
            std::sqrt(M_PI) / (2.0 * settings.beta) * stiffness / std::sqrt(e.contact_area);
      }
    return e;
  }

  OliverPharrResult analyze(const LoadCurve                     &curve,
                            const std::function<double(double)> &area_function,
                            const OliverPharrSettings           &settings)
  {
    const std::string where = curve.source.empty() ? "the curve" : curve.source;
    if (!(settings.fit_lower >= 0 && settings.fit_lower < settings.fit_upper &&
          settings.fit_upper <= 1.0))
      throw std::invalid_argument("the fit range [" + format(settings.fit_lower) + ", " +
                                  format(settings.fit_upper) +
                                  "] of P_max is not allowed: 0 <= lower < upper <= 1");
    const UnloadingBranch branch = identify_branches(curve);
    const std::size_t     begin = branch.begin, end = branch.end;
    OliverPharrResult     result;
    result.unloading_begin = static_cast<unsigned int>(begin);
    result.unloading_end = static_cast<unsigned int>(end);
    result.max_depth = curve.depth[begin];
    result.max_force = curve.force[begin];

    std::vector<double> fit_depth, fit_force;
    for (std::size_t i = begin; i < end; ++i)
      if (curve.force[i] >= settings.fit_lower * result.max_force &&
          curve.force[i] <= settings.fit_upper * result.max_force && curve.force[i] > 0)
        {
          fit_depth.push_back(curve.depth[i]);
          fit_force.push_back(curve.force[i]);
        }
    if (fit_depth.size() < min_fit_points)
      throw std::invalid_argument(
          where + ": the unloading branch (" + std::to_string(end - begin) + " points from " +
          depth_at(curve, begin) + ") has " + std::to_string(fit_depth.size()) +
          " points between " + format(100 * settings.fit_lower) + " % and " +
          format(100 * settings.fit_upper) + " % of P_max = " + format(result.max_force) +
          " mN; the power-law fit needs at least " + std::to_string(min_fit_points) +
          ": record more unloading points "
          "(loading.unload_points) or widen the fit range");
    result.fit = fit_power_law(fit_depth, fit_force);
    check_physical_bounds(result, where, branch.depth_tolerance, true);
    result.stiffness = result.fit.stiffness(result.max_depth);
    if (!(result.stiffness > 0))
      throw std::invalid_argument(where + ": the fitted unloading stiffness at h_max is " +
                                  format(result.stiffness) + " mN/um; it must be positive");
    const ContactEstimate estimate = contact_estimate(result.max_depth, result.max_force,
                                                      result.stiffness, area_function, settings);
    result.contact_depth = estimate.contact_depth;
    result.contact_area = estimate.contact_area;
    if (!(result.contact_area > 0))
      throw std::invalid_argument(where +
                                  ": the contact depth h_c = " + format(result.contact_depth) +
                                  " um gives no contact area; the unloading is too soft for "
                                  "this indenter (check the units and --epsilon)");
    result.hardness = estimate.hardness;
    result.reduced_modulus = estimate.reduced_modulus;
    if (settings.sample_poisson_ratio)
      {
        const double nu = *settings.sample_poisson_ratio;
        const double indenter_compliance =
            std::isfinite(settings.indenter_modulus)
                ? (1.0 - settings.indenter_poisson_ratio * settings.indenter_poisson_ratio) /
                      settings.indenter_modulus
                : 0.0;
        result.sample_modulus =
            (1.0 - nu * nu) / (1.0 / result.reduced_modulus - indenter_compliance);
      }

    // Work: the loading path up to h_max (previous cycles included) and the unloading branch
    // down to zero force; if the data stop above zero force, the fitted power law closes it.
    for (std::size_t i = 0; i < begin; ++i)
      result.total_work +=
          0.5 * (curve.force[i] + curve.force[i + 1]) * (curve.depth[i + 1] - curve.depth[i]);
    result.residual_depth_source = "fit h_f";
    result.residual_depth = result.fit.h_f;
    bool reached_zero = false;
    for (std::size_t i = begin; i + 1 < end && !reached_zero; ++i)
      {
        const double f0 = curve.force[i], f1 = curve.force[i + 1];
        const double h0 = curve.depth[i], h1 = curve.depth[i + 1];
        if (f1 > 0)
          result.elastic_work += 0.5 * (f0 + f1) * (h0 - h1);
        else
          {
            // zero force between h1 and h0 (linear interpolation)
            const double h_zero = f0 > 0 ? h0 - (h0 - h1) * f0 / (f0 - f1) : h0;
            result.elastic_work += 0.5 * std::max(f0, 0.0) * (h0 - h_zero);
            result.residual_depth = h_zero;
            result.residual_depth_source = "curve";
            reached_zero = true;
          }
      }
    if (!reached_zero)
      {
        const double h_last = curve.depth[end - 1], f_last = curve.force[end - 1];
        if (f_last <= 1e-3 * result.max_force)
          {
            result.residual_depth = h_last;
            result.residual_depth_source = "curve";
          }
        else if (h_last > result.fit.h_f)
          result.elastic_work += result.fit.alpha *
                                 std::pow(h_last - result.fit.h_f, result.fit.m + 1) /
                                 (result.fit.m + 1);
      }
    result.plastic_work_ratio =
        result.total_work > 0 ? (result.total_work - result.elastic_work) / result.total_work : 0.0;
    check_physical_bounds(result, where, branch.depth_tolerance, false);

    if (!curve.contact_area.empty() && curve.contact_area[begin] > 0 &&
        curve.contact_area[begin] < settings.min_true_contact_area)
      {
        std::ostringstream note;
        note << "the recorded contact area " << curve.contact_area[begin]
             << " um^2 is below one contact element's circle (" << settings.min_true_contact_area
             << " um^2): the mesh does not resolve the contact, so there is no comparison with "
                "the true contact area";
        result.true_area_note = note.str();
      }
    else if (!curve.contact_area.empty() && curve.contact_area[begin] > 0)
      {
        result.true_contact_area = curve.contact_area[begin];
        result.true_hardness = result.max_force / *result.true_contact_area;
        result.area_error_percent =
            100.0 * (result.contact_area - *result.true_contact_area) / *result.true_contact_area;
      }
    return result;
  }

  std::string to_json(const OliverPharrResult &r, const OliverPharrSettings &settings,
                      const std::string &indenter_description, const std::string &source,
                      const LoadCurve *curve)
  {
    std::ostringstream out;
    out << "{\n"
        << "  \"units\": \"depths um, forces mN, areas um^2, stiffness mN/um, hardness and moduli "
           "GPa, work mN*um (= nJ)\",\n"
        << "  \"source\": " << io::json_string(source) << ",\n"
        << "  \"indenter\": " << io::json_string(indenter_description) << ",\n"
        << "  \"method\": \"Oliver-Pharr: P = alpha (h - h_f)^m on the unloading points with "
        << format(100 * settings.fit_lower) << "-" << format(100 * settings.fit_upper)
        << " % of P_max; S = dP/dh at h_max; h_c = h_max - epsilon P_max/S; "
           "E_r = sqrt(pi)/(2 beta) S/sqrt(A(h_c))\",\n"
        << "  \"epsilon\": " << format(settings.epsilon) << ",\n"
        << "  \"beta\": " << format(settings.beta) << ",\n"
        << "  \"fit_range_of_max_force\": [" << format(settings.fit_lower) << ", "
        << format(settings.fit_upper) << "],\n"
        << "  \"max_depth_um\": " << format(r.max_depth) << ",\n"
        << "  \"max_force_mN\": " << format(r.max_force) << ",\n"
        << "  \"fit\": {\"alpha_mN_per_um_m\": " << format(r.fit.alpha)
        << ", \"h_f_um\": " << format(r.fit.h_f) << ", \"m\": " << format(r.fit.m)
        << ", \"rms_error_mN\": " << format(r.fit.rms_error) << ", \"n_points\": " << r.fit.n_points
        << "},\n"
        << "  \"stiffness_mN_per_um\": " << format(r.stiffness) << ",\n"
        << "  \"contact_depth_um\": " << format(r.contact_depth) << ",\n"
        << "  \"contact_area_um2\": " << format(r.contact_area) << ",\n"
        << "  \"hardness_GPa\": " << format(r.hardness) << ",\n"
        << "  \"reduced_modulus_GPa\": " << format(r.reduced_modulus) << ",\n"
        << "  \"sample_poisson_ratio\": " << io::json_number(settings.sample_poisson_ratio) << ",\n"
        << "  \"sample_modulus_GPa\": " << io::json_number(r.sample_modulus) << ",\n"
        << "  \"residual_depth_um\": " << format(r.residual_depth) << ",\n"
        << "  \"residual_depth_source\": \"" << r.residual_depth_source << "\",\n"
        << "  \"residual_depth_ratio\": " << format(r.residual_depth / r.max_depth) << ",\n"
        << "  \"total_work_mN_um\": " << format(r.total_work) << ",\n"
        << "  \"elastic_work_mN_um\": " << format(r.elastic_work) << ",\n"
        << "  \"plastic_work_ratio\": " << format(r.plastic_work_ratio) << ",\n"
        << "  \"true_contact_area_um2\": " << io::json_number(r.true_contact_area) << ",\n"
        << "  \"true_hardness_GPa\": " << io::json_number(r.true_hardness) << ",\n"
        << "  \"area_error_percent\": " << io::json_number(r.area_error_percent) << ",\n"
        << (r.true_area_note.empty()
                ? std::string()
                : "  \"true_area_note\": " + io::json_string(r.true_area_note) + ",\n")
        << "  \"unloading_points\": [" << r.unloading_begin << ", " << r.unloading_end << "]";
    if (curve != nullptr)
      {
        const auto array = [&out](const std::vector<double> &values) {
          out << '[';
          for (std::size_t i = 0; i < values.size(); ++i)
            out << (i ? ", " : "") << format(values[i]);
          out << ']';
        };
        out << ",\n  \"curve\": {\"depth_um\": ";
        array(curve->depth);
        out << ", \"force_mN\": ";
        array(curve->force);
        out << '}';
      }
    out << "\n}\n";
    return out.str();
  }
} // namespace indentsim::analysis

// Measured and simulated curves at the comparison points (see CurveData.h).
// Units: depth um, force mN, stress GPa, strain dimensionless.
#include "calibration/CurveData.h"

#include "io/LinearInterpolation.h"

#include "calibration/IndentationFeatures.h"
#include "calibration/NumberTable.h"
#include "case/OutputDirectory.h"
#include "io/CsvTable.h"
#include "io/LoadCurveCsv.h"
#include "io/TextNumber.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace indentsim::calibration
{
  namespace
  {
    std::string number_text(const double value)
    {
      std::ostringstream out;
      out << value;
      return out.str();
    }

    double strain_factor(const std::string &unit)
    {
      return unit.empty() || unit == "strain" ? 1. : unit == "%" || unit == "percent" ? 0.01 : 0.;
    }

    // A column of a measured curve: the first whose name starts with one of `prefixes`, its
    // unit (in the name) converted by `factor_of`; `what` and `spellings` for the messages.
    struct ColumnSpec
    {
      std::initializer_list<const char *> prefixes;
      const char                         *what;
      double (*factor_of)(const std::string &);
      const char *spellings;
    };

    // The curve y(x) of two columns in their units, sorted by x (|x| if `fold_x`).
    SampledCurve read_curve(const std::string &path, const ColumnSpec &x_column,
                            const ColumnSpec &y_column, const bool fold_x = false)
    {
      const NumberTable   table(path);
      const std::size_t   cx = table.column(x_column.prefixes, x_column.what);
      const std::size_t   cy = table.column(y_column.prefixes, y_column.what);
      const double        to_x = table.unit_factor(cx, x_column.factor_of, x_column.spellings);
      const double        to_y = table.unit_factor(cy, y_column.factor_of, y_column.spellings);
      std::vector<double> x, y;
      for (std::size_t r = 0; r < table.rows(); ++r)
        {
          const double value = table.number(r, cx) * to_x;
          x.push_back(fold_x ? std::abs(value) : value);
          y.push_back(table.number(r, cy) * to_y);
        }
      return sorted_curve(x, y);
    }

    // A measured or simulated stress-strain curve: the first column named log_strain*,
    // true_strain*, strain* or eps* (dimensionless, or in % when the name says so) and the first
    // named true_stress*, stress* or sigma* with its unit (GPa or MPa) in the name.
    SampledCurve read_stress_strain(const std::string &path)
    {
      return read_curve(path,
                        {{"log_strain", "true_strain", "strain", "eps"},
                         "strain (log_strain, true_strain, strain)",
                         strain_factor,
                         "strain or strain_%"},
                        {{"true_stress", "stress", "sigma"},
                         "stress (stress_GPa, true_stress_MPa, ...)",
                         io::stress_factor,
                         "stress_GPa or stress_MPa"});
    }

    // A measured height profile across the residual imprint: the first column named radius*,
    // r_*, distance*, x_* or position* and the first named height* or z_*, each with its length
    // unit (um, nm, mm) in the name. A line through the centre has negative positions: the
    // profile is taken against |position|.
    SampledCurve read_height_profile(const std::string &path)
    {
      return read_curve(path,
                        {{"radius", "r_", "distance", "x_", "position"},
                         "radius (radius_um, r_um, x_nm, distance_um)",
                         io::length_factor,
                         "r_um or r_nm"},
                        {{"height", "z_"},
                         "height (height_nm, z_um)",
                         io::length_factor,
                         "height_um or height_nm"},
                        true);
    }

    // A hardness-depth profile: the first column named depth*, displacement* or h_* with its
    // length unit (um, nm, mm) and the first named hardness* with its stress unit (GPa, MPa):
    // a measured one (continuous stiffness measurement) or a run's hardness_depth.csv.
    SampledCurve read_hardness_profile(const std::string &path)
    {
      return read_curve(path,
                        {{"depth", "displacement", "h_", "h ("},
                         "depth (depth_nm, depth_um, displacement (nm))",
                         io::length_factor,
                         "depth_um or depth_nm"},
                        {{"hardness"},
                         "hardness (hardness_GPa, H_MPa)",
                         io::stress_factor,
                         "hardness_GPa or hardness_MPa"});
    }

    // The simulated profile after unloading (pileup_profiles.csv of a run, stage `unloaded`)
    // along the azimuth nearest to `azimuth_deg`.
    SampledCurve simulated_height_profile(const std::string &path, const double azimuth_deg)
    {
      const NumberTable table(path);
      const std::size_t stage = table.column({"stage"}, "stage");
      const std::size_t azimuth = table.column({"azimuth_deg"}, "azimuth_deg");
      const std::size_t radius = table.column({"r_um"}, "r_um");
      const std::size_t height = table.column({"height_um"}, "height_um");
      double            nearest = 0., distance = std::numeric_limits<double>::infinity();
      for (std::size_t r = 0; r < table.rows(); ++r)
        if (table.text(r, stage) == "unloaded")
          {
            const double d = std::abs(std::remainder(table.number(r, azimuth) - azimuth_deg, 360.));
            if (d < distance)
              distance = d, nearest = table.number(r, azimuth);
          }
      std::vector<double> x, y;
      for (std::size_t r = 0; r < table.rows(); ++r)
        if (table.text(r, stage) == "unloaded" && table.number(r, azimuth) == nearest)
          {
            x.push_back(table.number(r, radius));
            y.push_back(table.number(r, height));
          }
      return sorted_curve(x, y);
    }

    // The loading and unloading branches of a load-penetration curve, split at its deepest
    // point (which belongs to both); partial unloads and their reloads left out.
    std::pair<SampledCurve, SampledCurve> branches(const io::LoadCurve &whole)
    {
      const io::LoadCurve curve = io::without_partial_unloads(whole);
      if (curve.depth.empty())
        return {};
      const std::size_t deepest =
          std::max_element(curve.depth.begin(), curve.depth.end()) - curve.depth.begin();
      const auto part = [&](const std::size_t from, const std::size_t to) {
        return sorted_curve({curve.depth.begin() + from, curve.depth.begin() + to},
                            {curve.force.begin() + from, curve.force.begin() + to});
      };
      return {part(0, deepest + 1), part(deepest, curve.depth.size())};
    }

    // The measured points within [from, to] (from excluded when `open_from`), in at most
    // `bins` groups of consecutive points of nearly equal count: each group's mean abscissa and
    // mean value, and its members' abscissae. Every measured point counts once, and the groups'
    // errors are independent.
    struct Groups
    {
      SampledCurve                     means;
      std::vector<std::vector<double>> members;
    };

    Groups binned(const SampledCurve &curve, const double from, const double to,
                  const bool open_from, const unsigned int bins)
    {
      std::vector<std::size_t> inside;
      for (std::size_t i = 0; i < curve.x.size(); ++i)
        if ((open_from ? curve.x[i] > from : curve.x[i] >= from) && curve.x[i] <= to)
          inside.push_back(i);
      const std::size_t groups = std::min<std::size_t>(bins, inside.size());
      Groups            result;
      for (std::size_t g = 0; g < groups; ++g)
        {
          const std::size_t begin = g * inside.size() / groups,
                            end = (g + 1) * inside.size() / groups;
          double              x = 0., y = 0.;
          std::vector<double> members;
          for (std::size_t k = begin; k < end; ++k)
            {
              x += curve.x[inside[k]], y += curve.y[inside[k]];
              members.push_back(curve.x[inside[k]]);
            }
          result.means.x.push_back(x / double(end - begin));
          result.means.y.push_back(y / double(end - begin));
          result.members.push_back(members);
        }
      return result;
    }
  } // namespace

  double SampledCurve::at(const double at) const
  {
    return x.empty() ? 0. : io::interpolate_clamped(x, y, at);
  }

  SampledCurve sorted_curve(std::vector<double> x, std::vector<double> y)
  {
    std::vector<std::size_t> order(x.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](const std::size_t a, const std::size_t b) { return x[a] < x[b]; });
    SampledCurve curve;
    for (std::size_t k = 0; k < order.size();)
      {
        std::size_t same = k;
        double      sum = 0.;
        while (same < order.size() && x[order[same]] == x[order[k]])
          sum += y[order[same++]];
        curve.x.push_back(x[order[k]]);
        curve.y.push_back(sum / double(same - k));
        k = same;
      }
    return curve;
  }

  void read_measured(DataSet &data_set, const io::Case &simulated_case, const std::string &where)
  {
    if (data_set.kind == DataKind::indentation_features)
      return read_measured_features(data_set, simulated_case, where);
    const std::string what = where + ": file " + data_set.file;
    SampledCurve      measured;
    double            from = 0., to = 0.;
    std::string       simulated_range;
    try
      {
        if (data_set.kind == DataKind::load_penetration)
          {
            const auto [loading, unloading] = branches(io::read_load_curve_csv(data_set.file));
            const double max_depth = simulated_case.loading.max_depth;
            simulated_range = "0 to " + number_text(max_depth) + " um (loading.max_depth)";
            if (data_set.branch == Branch::loading)
              {
                measured = loading;
                to = std::min(measured.x.empty() ? 0. : measured.x.back(), max_depth);
              }
            else
              {
                measured = unloading;
                if (measured.x.size() < 3)
                  throw CalibrationFileError(
                      what + ": branch: unloading, but the curve has " +
                      std::to_string(measured.x.size()) +
                      " point(s) after its deepest one; an unloading branch needs at least 3");
                to = std::min(measured.x.back(), max_depth);
                from = measured.x.front();
                if (!simulated_case.loading.unload)
                  throw CalibrationFileError(where + ": branch: unloading, but the case " +
                                             data_set.case_file +
                                             " does not unload (loading.unload: false)");
              }
          }
        else if (data_set.kind == DataKind::pileup_profile)
          {
            if (!simulated_case.loading.unload)
              throw CalibrationFileError(where +
                                         ": kind: pileup_profile is the imprint after "
                                         "unloading, but the case " +
                                         data_set.case_file +
                                         " does not unload (loading.unload: false)");
            measured = read_height_profile(data_set.file);
            // The simulated profile spans the specimen's top face (its outer radius).
            const double outer = simulated_case.specimen.size[0] / 2.;
            simulated_range = "r from 0 to " + number_text(outer) + " um (the specimen's radius)";
            to = std::min(measured.x.empty() ? 0. : measured.x.back(), outer);
          }
        else if (data_set.kind == DataKind::hardness_depth)
          {
            // The simulated profile: a point at every multiple of partial_unloads.every below
            // the maximum depth.
            const io::PartialUnloads &partial = simulated_case.loading.partial_unloads;
            if (!partial.enabled())
              throw CalibrationFileError(where +
                                         ": kind: hardness_depth needs partial unloads, "
                                         "but the case " +
                                         data_set.case_file +
                                         " has none (loading.partial_unloads.every: 0)");
            measured = read_hardness_profile(data_set.file);
            const double max_depth = simulated_case.loading.max_depth;
            from = partial.every;
            to = partial.every * std::ceil(max_depth / partial.every - 1. - 1e-9);
            simulated_range = "depths " + number_text(from) + " to " + number_text(to) +
                              " um (the partial unloads, loading.partial_unloads.every " +
                              number_text(partial.every) + " um)";
            if (!measured.x.empty())
              to = std::min(to, measured.x.back());
          }
        else
          {
            measured = read_stress_strain(data_set.file);
            const double max_strain = std::log1p(simulated_case.loading.max_strain);
            simulated_range = "log strain 0 to " + number_text(max_strain) +
                              " (loading.max_strain " +
                              number_text(simulated_case.loading.max_strain) + ")";
            to = std::min(measured.x.empty() ? 0. : measured.x.back(), max_strain);
          }
      }
    catch (const std::invalid_argument &error)
      {
        throw CalibrationFileError(where + ": " + error.what());
      }
    // Loading and tensile curves from above 0 (the origin says nothing), unloading from the
    // shallowest measured unloading point, hardness from the first partial unload.
    bool from_origin =
        data_set.kind == DataKind::tensile ||
        (data_set.kind == DataKind::load_penetration && data_set.branch == Branch::loading);
    // The user's range narrows the simulated one (both ends included).
    if (data_set.range)
      {
        // Both ends included, whatever the rounding of a unit conversion (700 nm to um).
        const auto [lo, hi] = *data_set.range;
        const double slack = 1e-9 * (hi - lo);
        if (lo - slack >= from)
          from = lo - slack, from_origin = false;
        to = std::min(to, hi + slack);
        simulated_range += ", within range [" + number_text((*data_set.range)[0]) + ", " +
                           number_text((*data_set.range)[1]) + "]";
      }
    const Groups points =
        to > from ? binned(measured, from, to, from_origin, data_set.points) : Groups();
    const std::size_t inside = points.means.x.size();
    if (inside < 3)
      throw CalibrationFileError(
          what + ": only " + std::to_string(inside) + " measured point(s) within the range the " +
          "case simulates (" + simulated_range + "); the measured curve spans " +
          (measured.x.empty()
               ? std::string("nothing")
               : number_text(measured.x.front()) + " to " + number_text(measured.x.back())) +
          ". A data set must overlap the simulated range with at least 3 points");
    data_set.x = points.means.x;
    data_set.measured = points.means.y;
    data_set.group_x = points.members;
    data_set.scale = 0.;
    for (const double y : data_set.measured)
      data_set.scale = std::max(data_set.scale, std::abs(y));
    if (!(data_set.scale > 0.))
      throw CalibrationFileError(what + ": the measured values are all 0 within the simulated "
                                        "range; nothing to fit");
  }

  std::vector<double> simulated_values(const DataSet &data_set, const std::string &run_directory)
  {
    if (data_set.kind == DataKind::indentation_features)
      return simulated_features(data_set, run_directory);
    SampledCurve simulated;
    double       end = 0.;
    if (data_set.kind == DataKind::load_penetration)
      {
        const std::string path = run_directory + "/" + io::output_files::load_penetration_csv;
        const auto [loading, unloading] = branches(io::read_load_curve_csv(path));
        simulated = data_set.branch == Branch::loading ? loading : unloading;
        end = simulated.x.empty() ? 0. : simulated.x.back();
        if (data_set.branch == Branch::unloading && !simulated.x.empty())
          {
            // Shallower than where the unloading ended, the tip has left the surface: P = 0.
            simulated.x.insert(simulated.x.begin(), 0.);
            simulated.y.insert(simulated.y.begin(), 0.);
            if (simulated.x.size() > 2 && simulated.x[1] > 0.)
              {
                simulated.x.insert(simulated.x.begin() + 1, simulated.x[1] * (1. - 1e-12));
                simulated.y.insert(simulated.y.begin() + 1, 0.);
              }
          }
      }
    else if (data_set.kind == DataKind::hardness_depth)
      {
        simulated =
            read_hardness_profile(run_directory + "/" + io::output_files::hardness_depth_csv);
        end = simulated.x.empty() ? 0. : simulated.x.back();
        if (!simulated.x.empty() && simulated.x.front() > data_set.x.front() * (1. + 1e-9))
          throw std::runtime_error(run_directory + ": the simulated hardness starts at " +
                                   number_text(simulated.x.front()) +
                                   " um, after the first comparison point " +
                                   number_text(data_set.x.front()));
      }
    else if (data_set.kind == DataKind::pileup_profile)
      {
        // Beyond the profile's last point the height is its last value (the far surface).
        simulated = simulated_height_profile(
            run_directory + "/" + io::output_files::pileup_profiles_csv, data_set.azimuth_deg);
        end = std::numeric_limits<double>::infinity();
      }
    else
      {
        const std::string path = run_directory + "/" + io::output_files::stress_strain_csv;
        simulated = read_stress_strain(path);
        end = simulated.x.empty() ? 0. : simulated.x.back();
      }
    if (simulated.x.empty() || end < data_set.x.back() * (1. - 1e-9))
      throw std::runtime_error(run_directory + ": the simulated curve ends at " + number_text(end) +
                               ", before the last comparison point " +
                               number_text(data_set.x.back()));
    std::vector<double> values;
    // The mean of the simulated curve over each group's measured abscissae, as the measured
    // value is their mean: the two agree exactly when the curves do, however curved they are.
    for (const std::vector<double> &members : data_set.group_x)
      {
        double sum = 0.;
        for (const double x : members)
          sum += simulated.at(x);
        values.push_back(sum / double(members.size()));
      }
    return values;
  }
} // namespace indentsim::calibration

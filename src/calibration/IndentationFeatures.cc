// The scalar features of indentation tests (see IndentationFeatures.h). Units: um, mN, GPa.
#include "calibration/IndentationFeatures.h"

#include "analysis/OliverPharr.h"
#include "calibration/NumberTable.h"
#include "case/OutputDirectory.h"
#include "case/Schema.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace indentsim::calibration
{
  namespace
  {
    constexpr std::array<Feature, 3> all_features = {
        Feature::loading_curvature, Feature::unloading_stiffness, Feature::plastic_work_ratio};

    // The names a column of each feature may have (without its unit), and of the depth.
    const std::vector<std::string> curvature_names = {"c", "loading_curvature"};
    const std::vector<std::string> stiffness_names = {"dp/dh", "s", "stiffness",
                                                      "unloading_stiffness"};
    const std::vector<std::string> ratio_names = {"wp/wt", "plastic_work_ratio"};
    const std::vector<std::string> depth_names = {"hm", "h_max", "max_depth"};

    const std::vector<std::string> &names_of(const Feature f)
    {
      return f == Feature::loading_curvature     ? curvature_names
             : f == Feature::unloading_stiffness ? stiffness_names
                                                 : ratio_names;
    }

    // A column name without its unit: the text before "(" or "[", and, for a name with an
    // underscore unit, also the text before the last "_" ("C_GPa" -> "c").
    bool column_is(const std::string &column, const std::vector<std::string> &names)
    {
      const std::string lower = io::lowered(column);
      const std::string stem = io::trimmed(lower.substr(0, lower.find_first_of("([")));
      const auto        underscore = stem.rfind('_');
      for (const std::string &name : names)
        if (stem == name || (underscore != std::string::npos && stem.substr(0, underscore) == name))
          return true;
      return false;
    }

    std::optional<std::size_t> find_column(const NumberTable              &table,
                                           const std::vector<std::string> &names)
    {
      for (std::size_t c = 0; c < table.columns(); ++c)
        if (column_is(table.name(c), names))
          return c;
      return std::nullopt;
    }

    // mN/um of a stiffness unit "force/length" (N/m, mN/um, uN/nm, ...); 0 if unknown.
    double stiffness_factor(const std::string &unit)
    {
      const auto slash = unit.find('/');
      if (slash == std::string::npos)
        return 0.;
      const std::string length = unit.substr(slash + 1);
      const double      to_um = length == "m" ? 1e6 : io::length_factor(length);
      const double      to_mN = io::force_factor(unit.substr(0, slash));
      return to_um > 0. ? to_mN / to_um : 0.;
    }

    double ratio_factor(const std::string &)
    {
      return 1.;
    }

    // The factor to the feature's unit of column c's name, or an error naming the spellings.
    double feature_factor(const NumberTable &table, const std::size_t c, const Feature f)
    {
      if (f == Feature::loading_curvature)
        return table.unit_factor(c, io::stress_factor, "C (GPa) or C_MPa");
      if (f == Feature::unloading_stiffness)
        return table.unit_factor(c, stiffness_factor, "dP/dh (N/m), S_mN/um or S (uN/nm)");
      return table.unit_factor(c, ratio_factor, "Wp/Wt (no unit)");
    }

    std::string text(const double value)
    {
      return io::format_number(value);
    }
  } // namespace

  std::string feature_name(const Feature f)
  {
    return f == Feature::loading_curvature     ? "C"
           : f == Feature::unloading_stiffness ? "S"
                                               : "Wp/Wt";
  }

  std::string feature_unit(const Feature f)
  {
    return f == Feature::loading_curvature     ? "GPa"
           : f == Feature::unloading_stiffness ? "mN/um"
                                               : "-";
  }

  std::string feature_label(const Feature f)
  {
    return f == Feature::loading_curvature     ? "loading curvature C [GPa]"
           : f == Feature::unloading_stiffness ? "unloading stiffness S [mN/um]"
                                               : "plastic work ratio Wp/Wt [-]";
  }

  std::optional<Feature> feature_from_name(const std::string &name)
  {
    for (const Feature f : all_features)
      if (column_is(name, names_of(f)) || io::lowered(name) == io::lowered(feature_name(f)))
        return f;
    return std::nullopt;
  }

  CurveFeatures curve_features(const io::LoadCurve &recorded)
  {
    const io::LoadCurve curve = io::without_partial_unloads(recorded);
    // The features use neither the contact depth nor the area: any area function serves.
    analysis::OliverPharrSettings     settings;
    const analysis::OliverPharrResult op = analysis::analyze(
        curve, [](const double h) { return h * h; }, settings);
    double sum_ph2 = 0., sum_h4 = 0.; // Kick's law P = C h^2 by least squares
    for (std::size_t i = 0; i <= op.unloading_begin; ++i)
      {
        const double h2 = curve.depth[i] * curve.depth[i];
        sum_ph2 += curve.force[i] * h2, sum_h4 += h2 * h2;
      }
    if (!(sum_h4 > 0.))
      throw std::invalid_argument(curve.source + ": no loading branch below the deepest point");
    CurveFeatures features;
    features.value = {sum_ph2 / sum_h4, op.stiffness, op.plastic_work_ratio};
    features.max_depth = op.max_depth;
    return features;
  }

  void read_measured_features(DataSet &d, const io::Case &simulated_case, const std::string &where)
  {
    const std::string what = where + ": file " + d.file;
    const double      max_depth = simulated_case.loading.max_depth;
    try
      {
        const NumberTable table(d.file);
        // The features: those chosen, each of which the file must have, or all it has.
        std::vector<std::pair<Feature, std::size_t>> columns;
        for (const Feature f : all_features)
          {
            const bool chosen =
                d.features.empty() ||
                std::find(d.features.begin(), d.features.end(), f) != d.features.end();
            const auto column = find_column(table, names_of(f));
            if (chosen && column)
              columns.push_back({f, *column});
            else if (chosen && !d.features.empty())
              throw std::invalid_argument(d.file + ": no column of the feature " +
                                          feature_label(f) + " (named " + io::join(names_of(f)) +
                                          ") in the header");
          }
        if (columns.empty())
          throw std::invalid_argument(
              d.file + ": no feature column; expected C (GPa), dP/dh (N/m) or Wp/Wt");
        if (table.rows() == 0)
          throw std::invalid_argument(d.file + ": no tests (rows) under the header");
        d.features.clear();
        for (const auto &[f, c] : columns)
          d.features.push_back(f);
        const bool needs_unloading =
            std::any_of(d.features.begin(), d.features.end(),
                        [](Feature f) { return f != Feature::loading_curvature; });
        if (needs_unloading && !simulated_case.loading.unload)
          throw CalibrationFileError(where +
                                     ": the features S and Wp/Wt need the unloading, but "
                                     "the case " +
                                     d.case_file + " does not unload (loading.unload: false)");
        const auto   depth = find_column(table, depth_names);
        const double to_um =
            depth ? table.unit_factor(*depth, io::length_factor, "hm (um) or h_max_nm") : 0.;

        d.x.clear(), d.measured.clear(), d.point_scale.clear(), d.group_x.clear();
        std::vector<double> sum(columns.size(), 0.);
        for (std::size_t r = 0; r < table.rows(); ++r)
          {
            double depth_ratio = 1.; // h_max / h_m of this test
            if (depth)
              {
                const double h_m = table.number(r, *depth) * to_um;
                depth_ratio = max_depth / h_m;
                if (!(h_m > 0.) || std::abs(depth_ratio - 1.) > max_depth_mismatch)
                  throw std::invalid_argument(
                      d.file + ", " + table.row_name(r) + ": the test's depth " + text(h_m) +
                      " um is not within " + text(100. * max_depth_mismatch) +
                      " % of the simulated loading.max_depth " + text(max_depth) +
                      " um; simulate the measured depth");
              }
            for (std::size_t k = 0; k < columns.size(); ++k)
              {
                const auto [f, c] = columns[k];
                double value = table.number(r, c) * feature_factor(table, c, f);
                if (f == Feature::unloading_stiffness)
                  value *= d.stiffness_scale * depth_ratio;
                const bool in_range =
                    f == Feature::plastic_work_ratio ? value >= 0. && value <= 1. : value > 0.;
                if (!in_range)
                  throw std::invalid_argument(d.file + ", " + table.row_name(r) + ", column '" +
                                              table.name(c) + "': " + table.text(r, c) +
                                              (f == Feature::plastic_work_ratio
                                                   ? " is not a ratio between 0 and 1"
                                                   : " must be > 0"));
                d.x.push_back(double(k));
                d.measured.push_back(value);
                sum[k] += std::abs(value);
              }
          }
        for (std::size_t i = 0; i < d.x.size(); ++i)
          d.point_scale.push_back(sum[std::size_t(d.x[i])] / double(table.rows()));
        d.scale = 1.;
      }
    catch (const CalibrationFileError &)
      {
        throw;
      }
    catch (const std::invalid_argument &error)
      {
        throw CalibrationFileError(where + ": " + error.what());
      }
    for (const double s : d.point_scale)
      if (!(s > 0.))
        throw CalibrationFileError(what + ": a feature is 0 in every test; nothing to fit");
  }

  std::vector<double> simulated_features(const DataSet &d, const std::string &run_directory)
  {
    const CurveFeatures features = curve_features(
        io::read_load_curve_csv(run_directory + "/" + io::output_files::load_penetration_csv));
    std::vector<double> values;
    for (const double k : d.x)
      values.push_back(features.value[std::size_t(d.features.at(std::size_t(k)))]);
    return values;
  }
} // namespace indentsim::calibration

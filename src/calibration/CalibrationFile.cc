// Reading and checking calibration files (see CalibrationFile.h). Units: those of the keys.
#include "calibration/CalibrationFile.h"

#include "calibration/CurveData.h"
#include "calibration/ForwardRuns.h"
#include "calibration/IndentationFeatures.h"
#include "calibration/ParameterKey.h"
#include "case/Schema.h"
#include "io/TextNumber.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace indentsim::calibration
{
  namespace
  {
    namespace fs = std::filesystem;

    const std::vector<std::string> top_keys = {"base_case", "output", "parameters", "data",
                                               "solver"};
    const std::vector<std::string> bound_keys = {"start", "min", "max", "step"};
    const std::vector<std::string> data_keys = {
        "kind",   "file",        "branch",   "weight",          "case",
        "points", "azimuth_deg", "features", "stiffness_scale", "range"};
    const std::vector<std::string> solver_keys = {"max_iterations", "finite_difference_step",
                                                  "function_tolerance", "parameter_tolerance",
                                                  "statistics_step"};
    // Each data kind's name in the file, and the names and units of its comparison points
    // (fit_data<k>.csv); the order is that of the messages.
    struct KindText
    {
      DataKind    kind;
      const char *name, *x_name, *y_name, *units;
    };
    constexpr std::array<KindText, 5> kind_texts = {{
        {DataKind::load_penetration, "load_penetration", "depth_um", "force_mN",
         "depth um, force mN"},
        {DataKind::tensile, "tensile", "log_strain", "true_stress_GPa",
         "log strain, true stress GPa"},
        {DataKind::pileup_profile, "pileup_profile", "r_um", "height_um", "radius um, height um"},
        {DataKind::indentation_features, "indentation_features", "feature", "value", ""},
        {DataKind::hardness_depth, "hardness_depth", "depth_um", "hardness_GPa",
         "depth um, hardness GPa"},
    }};

    const KindText &text_of(const DataKind kind)
    {
      return *std::find_if(kind_texts.begin(), kind_texts.end(),
                           [&](const KindText &t) { return t.kind == kind; });
    }

    class Reader
    {
    public:
      Reader(const std::string &source, const std::string &output_override)
        : source_(source)
        , output_override_(output_override)
      {
      }

      Calibration read(const YAML::Node &root) const
      {
        if (!root.IsMap())
          fail(root,
               "expected a mapping with base_case, parameters and data (docs/calibration.md)");
        check_names(root, top_keys, "");
        Calibration c;
        c.source_file = source_;
        c.base_case_file = path_of(required(root, "base_case"), "base_case", "a case file");
        const YAML::Node  output = root["output"];
        const std::string output_text =
            output.IsDefined() ? word(output, "output", "a directory")
                               : "results/calibration_" + fs::path(source_).stem().string();
        c.output_directory = fs::absolute(output_override_.empty() ? output_text : output_override_)
                                 .lexically_normal()
                                 .string();
        read_parameters(required(root, "parameters"), c);
        read_data(required(root, "data"), c);
        if (const YAML::Node solver = root["solver"]; solver.IsDefined())
          read_solver(solver, c.solver);
        check_cases(root, c);
        return c;
      }

    private:
      std::string source_, output_override_;

      [[noreturn]] void fail(const YAML::Node &node, const std::string &message) const
      {
        const bool has_line = node.IsDefined() && !node.Mark().is_null();
        throw CalibrationFileError(
            source_ + (has_line ? ":" + std::to_string(node.Mark().line + 1) : std::string()) +
            ": " + message);
      }

      void check_names(const YAML::Node &map, const std::vector<std::string> &allowed,
                       const std::string &where) const
      {
        for (const auto &entry : map)
          {
            const std::string name = entry.first.Scalar();
            if (std::find(allowed.begin(), allowed.end(), name) != allowed.end())
              continue;
            const std::string guess = io::closest_name(name, allowed);
            fail(entry.first, "unknown key '" + where + name + "'; allowed: " + io::join(allowed) +
                                  (guess.empty() ? "" : " (did you mean '" + guess + "'?)"));
          }
      }

      YAML::Node required(const YAML::Node &map, const std::string &key) const
      {
        const YAML::Node node = map[key];
        if (!node.IsDefined() || node.IsNull())
          fail(map, "missing key '" + key + "' (docs/calibration.md)");
        return node;
      }

      std::string word(const YAML::Node &node, const std::string &key,
                       const std::string &expected) const
      {
        if (!node.IsScalar() || node.Scalar().empty())
          fail(node, key + " = " + io::node_text(node) + ": expected " + expected);
        return node.Scalar();
      }

      double number(const YAML::Node &node, const std::string &key) const
      {
        const auto value = node.IsScalar() ? io::parse_yaml_number(node.Scalar()) : std::nullopt;
        if (!value || !std::isfinite(*value))
          fail(node, key + " = " + io::node_text(node) + ": expected a finite number");
        return *value;
      }

      // A path relative to the calibration file's directory, which must name a file.
      std::string path_of(const YAML::Node &node, const std::string &key,
                          const std::string &what) const
      {
        fs::path path(word(node, key, what + " (path relative to the calibration file)"));
        if (path.is_relative())
          path = fs::path(source_).parent_path() / path;
        const std::string absolute = fs::absolute(path).lexically_normal().string();
        std::error_code   error;
        if (!fs::is_regular_file(absolute, error))
          fail(node, key + " = " + node.Scalar() + ": no file '" + absolute +
                         "' (paths are relative to the calibration file)");
        return absolute;
      }

      void read_parameters(const YAML::Node &node, Calibration &c) const
      {
        if (!node.IsMap() || node.size() == 0)
          fail(node, "parameters: expected a mapping of case keys to {start, min, max}, e.g. "
                     "material.yield_stress: {start: 0.25, min: 0.05, max: 1.0}");
        for (const auto &entry : node)
          {
            Parameter p;
            p.key = entry.first.Scalar();
            const std::string where = "parameters." + p.key;
            ParameterKey      path;
            try
              {
                path = parse_parameter_key(p.key);
              }
            catch (const std::invalid_argument &error)
              {
                fail(entry.first, where + ": " + error.what());
              }
            const io::Key *key = nullptr;
            if (path.schema_path.empty())
              p.unit = "um"; // material.layers[i].thickness
            else
              {
                try
                  {
                    key = &io::find_key(path.schema_path);
                  }
                catch (const std::out_of_range &)
                  {
                    std::vector<std::string> numbers;
                    for (const io::Key &k : io::case_keys())
                      if (k.type == io::ValueType::number && k.determines_results)
                        numbers.push_back(k.path);
                    const std::string guess = io::closest_name(path.schema_path, numbers);
                    fail(entry.first,
                         where + ": '" + p.key + "' is not a key of a case file" +
                             (guess.empty() ? "" : " (did you mean '" + guess + "'?)") +
                             "; a parameter is a numeric key (docs/case-file-reference.md), "
                             "a slip family's (material.hardening.<family>.tau0) or a "
                             "layer's (material.layers[i].yield_stress, .thickness)");
                  }
                if (key->type != io::ValueType::number || !key->determines_results)
                  fail(entry.first, where + ": '" + p.key +
                                        "' is not a number that changes the result (a "
                                        "parameter must be one: the fit differentiates by it)");
                p.unit = key->unit;
              }
            const YAML::Node bounds = entry.second;
            if (!bounds.IsMap())
              fail(bounds, where + " = " + io::node_text(bounds) +
                               ": expected {start: S, min: LO, max: HI}");
            check_names(bounds, bound_keys, where + ".");
            p.start = number(required(bounds, "start"), where + ".start");
            p.min = number(required(bounds, "min"), where + ".min");
            p.max = number(required(bounds, "max"), where + ".max");
            if (!(p.min < p.max))
              fail(bounds, where + ": min = " + io::format_number(p.min) + ", max = " +
                               io::format_number(p.max) + ": the bounds must satisfy min < max");
            if (p.start < p.min || p.start > p.max)
              fail(bounds, where + ".start = " + io::format_number(p.start) +
                               ": outside the bounds [" + io::format_number(p.min) + ", " +
                               io::format_number(p.max) + "]");
            if (const YAML::Node step = bounds["step"]; step.IsDefined())
              {
                p.step = number(step, where + ".step");
                if (!(p.step > 0. && p.step <= 0.5 * (p.max - p.min)))
                  fail(step, where + ".step = " + step.Scalar() +
                                 ": must be > 0 and at most half the bounds' width, " +
                                 io::format_number(0.5 * (p.max - p.min)));
              }
            for (const Parameter &other : c.parameters)
              if (other.key == p.key)
                fail(entry.first, where + ": given twice");
            c.parameters.push_back(p);
          }
      }

      void read_data(const YAML::Node &node, Calibration &c) const
      {
        if (!node.IsSequence() || node.size() == 0)
          fail(node, "data: expected a list of data sets, e.g. - {kind: load_penetration, "
                     "file: measured.csv}");
        for (std::size_t i = 0; i < node.size(); ++i)
          {
            const YAML::Node  entry = node[i];
            const std::string where = "data[" + std::to_string(i) + "]";
            if (!entry.IsMap())
              fail(entry, where + ": expected a mapping {kind: ..., file: ...}");
            check_names(entry, data_keys, where + ".");
            DataSet d;
            d.line = entry.Mark().is_null() ? -1 : entry.Mark().line;
            const std::string kind = word(required(entry, "kind"), where + ".kind", "a kind");
            const auto        known = std::find_if(kind_texts.begin(), kind_texts.end(),
                                                   [&](const KindText &t) { return t.name == kind; });
            if (known == kind_texts.end())
              {
                std::vector<std::string> names;
                for (const KindText &t : kind_texts)
                  names.push_back(t.name);
                fail(entry["kind"], where + ".kind = " + kind + ": allowed: " + io::join(names));
              }
            d.kind = known->kind;
            d.file = path_of(required(entry, "file"), where + ".file", "a CSV file");
            if (const YAML::Node branch = entry["branch"]; branch.IsDefined())
              {
                const std::string b = word(branch, where + ".branch", "loading or unloading");
                if (d.kind != DataKind::load_penetration)
                  fail(branch, where + ".branch: only for kind: load_penetration");
                if (b != "loading" && b != "unloading")
                  fail(branch, where + ".branch = " + b + ": allowed: loading, unloading");
                d.branch = b == "unloading" ? Branch::unloading : Branch::loading;
              }
            if (const YAML::Node weight = entry["weight"]; weight.IsDefined())
              {
                d.weight = number(weight, where + ".weight");
                if (!(d.weight > 0.))
                  fail(weight, where + ".weight = " + weight.Scalar() + ": must be > 0");
              }
            if (const YAML::Node azimuth = entry["azimuth_deg"]; azimuth.IsDefined())
              {
                if (d.kind != DataKind::pileup_profile)
                  fail(azimuth, where + ".azimuth_deg: only for kind: pileup_profile");
                d.azimuth_deg = number(azimuth, where + ".azimuth_deg");
              }
            read_feature_keys(entry, where, d);
            if (const YAML::Node range = entry["range"]; range.IsDefined())
              {
                if (d.kind == DataKind::indentation_features)
                  fail(range, where + ".range: not for kind: indentation_features");
                if (!range.IsSequence() || range.size() != 2)
                  fail(range, where + ".range = " + io::node_text(range) +
                                  ": expected [lo, hi] in the abscissa's unit (depth um, log "
                                  "strain, radius um)");
                const double lo = number(range[0], where + ".range[0]"),
                             hi = number(range[1], where + ".range[1]");
                if (!(lo < hi))
                  fail(range, where + ".range = [" + range[0].Scalar() + ", " + range[1].Scalar() +
                                  "]: must satisfy lo < hi");
                d.range = std::array<double, 2>{lo, hi};
              }
            if (const YAML::Node points = entry["points"]; points.IsDefined())
              {
                if (d.kind == DataKind::indentation_features)
                  fail(points, where + ".points: not for kind: indentation_features (every test "
                                       "is compared)");
                const double n = number(points, where + ".points");
                if (n != std::floor(n) || n < 3 || n > 1000)
                  fail(points, where + ".points = " + points.Scalar() +
                                   ": must be a whole number from 3 to 1000");
                d.points = static_cast<unsigned int>(n);
              }
            if (const YAML::Node own = entry["case"]; own.IsDefined())
              d.case_file = path_of(own, where + ".case", "a case file");
            else if (d.kind == DataKind::tensile)
              fail(entry, where + ": kind: tensile needs its own case: case: a tensile case file "
                                  "(test: tensile), e.g. examples/tensile_27_grains.yaml");
            else
              d.case_file = c.base_case_file;
            d.label = where + " " + kind +
                      (d.kind == DataKind::load_penetration
                           ? std::string(d.branch == Branch::loading ? " loading" : " unloading")
                           : std::string()) +
                      " (" + fs::path(d.file).filename().string() + ")";
            c.data.push_back(d);
          }
      }

      // features: [C, S, Wp/Wt] (a subset) and stiffness_scale, for indentation_features only.
      void read_feature_keys(const YAML::Node &entry, const std::string &where, DataSet &d) const
      {
        const bool features_kind = d.kind == DataKind::indentation_features;
        for (const char *key : {"features", "stiffness_scale"})
          if (entry[key].IsDefined() && !features_kind)
            fail(entry[key], where + "." + key + ": only for kind: indentation_features");
        if (const YAML::Node list = entry["features"]; list.IsDefined())
          {
            if (!list.IsSequence() || list.size() == 0)
              fail(list, where + ".features = " + io::node_text(list) +
                             ": expected a list of C, S, Wp/Wt");
            for (const YAML::Node &item : list)
              {
                const auto f = item.IsScalar() ? feature_from_name(item.Scalar()) : std::nullopt;
                if (!f)
                  fail(item, where + ".features: " + io::node_text(item) +
                                 ": allowed: C (loading_curvature), S (dP/dh, "
                                 "unloading_stiffness), Wp/Wt (plastic_work_ratio)");
                if (std::find(d.features.begin(), d.features.end(), *f) != d.features.end())
                  fail(item, where + ".features: " + item.Scalar() + " given twice");
                d.features.push_back(*f);
              }
          }
        if (const YAML::Node scale = entry["stiffness_scale"]; scale.IsDefined())
          {
            d.stiffness_scale = number(scale, where + ".stiffness_scale");
            if (!(d.stiffness_scale > 0.))
              fail(scale, where + ".stiffness_scale = " + scale.Scalar() + ": must be > 0");
          }
      }

      void read_solver(const YAML::Node &node, SolverSettings &s) const
      {
        if (!node.IsMap())
          fail(node, "solver: expected a mapping with " + io::join(solver_keys));
        check_names(node, solver_keys, "solver.");
        const auto in = [&](const char *key, const double lo, const double hi) {
          const double value = number(node[key], std::string("solver.") + key);
          if (!(value >= lo && value <= hi))
            fail(node[key], std::string("solver.") + key + " = " + node[key].Scalar() +
                                ": must be between " + io::format_number(lo) + " and " +
                                io::format_number(hi));
          return value;
        };
        if (node["max_iterations"].IsDefined())
          {
            const double n = in("max_iterations", 1, 1000);
            if (n != std::floor(n))
              fail(node["max_iterations"], "solver.max_iterations: a whole number");
            s.max_iterations = static_cast<unsigned int>(n);
          }
        if (node["finite_difference_step"].IsDefined())
          s.finite_difference_step = in("finite_difference_step", 1e-8, 0.1);
        if (node["function_tolerance"].IsDefined())
          s.function_tolerance = in("function_tolerance", 1e-16, 0.1);
        if (node["parameter_tolerance"].IsDefined())
          s.parameter_tolerance = in("parameter_tolerance", 1e-16, 0.1);
        if (node["statistics_step"].IsDefined())
          s.statistics_step = in("statistics_step", 1e-6, 0.3);
      }

      // Every forward case at the start and with each parameter at each bound goes through the
      // case reader; the data are read against the case at the start.
      void check_cases(const YAML::Node &root, Calibration &c) const
      {
        Point start;
        for (const Parameter &p : c.parameters)
          start.push_back(p.start);
        const auto check_point = [&](const Point &point, const std::string &what,
                                     const YAML::Node &where) {
          try
            {
              forward_study(c, {point});
            }
          catch (const CalibrationFileError &error)
            {
              fail(where, what + " is refused by a case: " + error.what());
            }
        };
        check_point(start, "the start point", root["parameters"]);
        // A key inside an optional block (material.layers, material.damage_profile) changes
        // only the cases that have it, so the base case must have it. (The start point's
        // study above has read the base case, and refused one with too few layers.)
        const YAML::Node base = YAML::LoadFile(c.base_case_file);
        for (const Parameter &p : c.parameters)
          if (const ParameterKey key = parse_parameter_key(p.key); !key.enters(base))
            fail(root["parameters"][p.key], "parameters." + p.key + ": the base case " +
                                                c.base_case_file + " has no material." +
                                                key.optional_block +
                                                " (the key changes only cases "
                                                "that have it, and the base case must be one)");
        for (std::size_t j = 0; j < c.parameters.size(); ++j)
          for (const bool upper : {false, true})
            {
              Point            bound = start;
              const Parameter &p = c.parameters[j];
              bound[j] = upper ? p.max : p.min;
              check_point(bound,
                          "parameters." + p.key + "." + (upper ? "max" : "min") + " = " +
                              io::format_number(bound[j]),
                          root["parameters"][p.key]);
            }
        const ForwardBatch at_start = forward_study(c, {start});
        for (std::size_t i = 0; i < c.data.size(); ++i)
          {
            DataSet        &d = c.data[i];
            const io::Case &simulated =
                at_start.study.cases.at(at_start.index[0].at(c.forward_case_of(d))).resolved;
            const YAML::Node  entry = root["data"][i];
            const std::string where =
                source_ + ":" + std::to_string(d.line + 1) + ": data[" + std::to_string(i) + "]";
            const bool tensile = simulated.test == io::TestKind::tensile;
            if (tensile != (d.kind == DataKind::tensile))
              fail(entry, "data[" + std::to_string(i) + "]: kind " + d.kind_name() +
                              " needs a case with test: " + (tensile ? "indentation" : "tensile") +
                              "; " + d.case_file + " has test: " + io::to_string(simulated.test));
            if (!tensile && simulated.loading.control != io::Control::depth)
              fail(entry, "data[" + std::to_string(i) + "]: the case " + d.case_file +
                              " is force-controlled; calibration needs loading.control: depth "
                              "(the simulated depth range must be known before any run)");
            read_measured(d, simulated, where);
          }
      }
    };
  } // namespace

  std::string DataSet::x_name() const
  {
    return text_of(kind).x_name;
  }

  std::string DataSet::y_name() const
  {
    return text_of(kind).y_name;
  }

  std::string DataSet::kind_name() const
  {
    return text_of(kind).name;
  }

  std::string DataSet::units() const
  {
    if (kind != DataKind::indentation_features)
      return text_of(kind).units;
    std::string text = "feature";
    for (std::size_t k = 0; k < features.size(); ++k)
      text += " " + std::to_string(k) + " = " + feature_label(features[k]);
    return text + "; value in the feature's unit";
  }

  std::vector<std::string> Calibration::forward_cases() const
  {
    std::vector<std::string> cases = {base_case_file};
    for (const DataSet &d : data)
      if (std::find(cases.begin(), cases.end(), d.case_file) == cases.end())
        cases.push_back(d.case_file);
    return cases;
  }

  std::size_t Calibration::forward_case_of(const DataSet &data_set) const
  {
    const std::vector<std::string> cases = forward_cases();
    return std::find(cases.begin(), cases.end(), data_set.case_file) - cases.begin();
  }

  Calibration parse_calibration_yaml(const std::string &yaml_text, const std::string &source_name,
                                     const std::string &output_override)
  {
    try
      {
        return Reader(source_name, output_override).read(YAML::Load(yaml_text));
      }
    catch (const YAML::Exception &e)
      {
        throw CalibrationFileError(
            source_name +
            (e.mark.is_null() ? std::string() : ":" + std::to_string(e.mark.line + 1)) +
            ": YAML: " + e.msg);
      }
  }

  Calibration read_calibration_file(const std::string &path, const std::string &output_override)
  {
    std::error_code error;
    if (!fs::is_regular_file(path, error))
      throw CalibrationFileError(path + ": no such calibration file");
    std::ifstream      input(path);
    std::ostringstream text;
    text << input.rdbuf();
    if (!input)
      throw CalibrationFileError(path + ": cannot be read");
    return parse_calibration_yaml(text.str(), path, output_override);
  }
} // namespace indentsim::calibration

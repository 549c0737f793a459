// The calibrate command (see CalibrationRunner.h).
#include "calibration/CalibrationRunner.h"

#include "calibration/CurveData.h"
#include "calibration/FitStatistics.h"
#include "calibration/ForwardRuns.h"
#include "calibration/IndentationFeatures.h"
#include "calibration/LeastSquaresFit.h"
#include "case/CaseFile.h"
#include "io/JsonText.h"
#include "io/Version.h"
#include "output/OutputFile.h"
#include "output/PythonScripts.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <set>
#include <sstream>

namespace indentsim::calibration
{
  namespace
  {
    namespace fs = std::filesystem;
    using io::json_number;
    using io::json_string;

    // True when the minimiser tried steps and accepted none, so that the fit is its start.
    bool stayed_at_start(const FitResult &fit)
    {
      bool tried = false;
      for (const IterationRecord &record : fit.history)
        if (record.iteration > 0)
          {
            if (record.step_accepted)
              return false;
            tried = true;
          }
      return tried;
    }

    // What else would separate correlated parameters, from the data a calibration lacks.
    std::string suggestion(const Calibration &c)
    {
      std::set<std::string> have;
      for (const DataSet &d : c.data)
        {
          have.insert(d.kind != DataKind::load_penetration ? d.kind_name()
                      : d.branch == Branch::loading        ? "loading"
                                                           : "unloading");
          // S and W_p/W_t come from the unloading.
          if (d.kind == DataKind::indentation_features &&
              (d.features.size() > 1 || d.features.front() != Feature::loading_curvature))
            have.insert("unloading");
        }
      std::vector<std::string> add;
      if (!have.count("unloading"))
        add.push_back("the unloading branch of the curve (kind: load_penetration, branch: "
                      "unloading)");
      if (!have.count("tensile"))
        add.push_back("a tensile curve (kind: tensile)");
      if (!have.count("pileup_profile"))
        add.push_back("the residual imprint's height profile (kind: pileup_profile)");
      add.push_back("a curve with a second tip geometry (a sphere responds to hardening "
                    "differently from a cone)");
      std::string text = "data that would separate them: ";
      for (std::size_t i = 0; i < add.size(); ++i)
        text += (i == 0 ? "" : "; ") + add[i];
      return text;
    }

    void write_fit_curves(const Calibration &c, const std::vector<std::vector<double>> &start,
                          const std::vector<std::vector<double>> &fitted)
    {
      for (std::size_t k = 0; k < c.data.size(); ++k)
        {
          const DataSet &d = c.data[k];
          output::write_file(c.output_directory + "/fit_data" + std::to_string(k) + ".csv",
                             [&](std::ostream &out) {
                               out << "# " << d.label << ", measured in " << d.file
                                   << "\n# units: " << d.units() << "\n"
                                   << d.x_name() << ",measured_" << d.y_name() << ",start_"
                                   << d.y_name() << ",fitted_" << d.y_name() << "\n"
                                   << std::setprecision(10);
                               for (std::size_t i = 0; i < d.x.size(); ++i)
                                 out << d.x[i] << ',' << d.measured[i] << ',' << start[k][i] << ','
                                     << fitted[k][i] << '\n';
                             });
        }
    }

    void write_history(const Calibration &c, const FitResult &fit)
    {
      output::write_file(c.output_directory + "/iterations.csv", [&](std::ostream &out) {
        out << "# units: parameters in their keys' units, times s; cost = 1/2 sum r^2\n"
            << "iteration,cost,step_accepted";
        for (const Parameter &p : c.parameters)
          out << ',' << p.key;
        out << ",forward_runs,wall_time_s\n" << std::setprecision(10);
        for (const IterationRecord &r : fit.history)
          {
            out << r.iteration << ',' << r.cost << ',' << (r.step_accepted ? 1 : 0);
            for (const double v : r.x)
              out << ',' << v;
            out << ',' << r.forward_runs << ',' << r.wall_time_s << '\n';
          }
      });
    }

    void write_json(const Calibration &c, const FitResult &fit, const FitStatistics &s,
                    const std::vector<std::string> &warnings, const ForwardRuns &runs,
                    const double wall_time)
    {
      std::ostringstream out;
      out << "{\n  \"units\": \"parameters in the units of their case keys (lengths um, forces "
             "mN, stresses GPa); residuals relative to each data set's largest measured value; "
             "times s\",\n"
          << "  \"version\": " << json_string(std::string("indentsim ") + indentsim::version())
          << ",\n  \"calibration_file\": " << json_string(fs::absolute(c.source_file).string())
          << ",\n  \"base_case\": " << json_string(c.base_case_file) << ",\n  \"parameters\": {";
      for (std::size_t j = 0; j < c.parameters.size(); ++j)
        {
          const Parameter &p = c.parameters[j];
          out << (j == 0 ? "\n" : ",\n") << "    " << json_string(p.key)
              << ": {\"value\": " << json_number(fit.x[j])
              << ", \"standard_error\": " << json_number(s.standard_error[j]) << ", \"ci95\": ["
              << json_number(s.ci95[j][0]) << ", " << json_number(s.ci95[j][1])
              << "], \"unit\": " << json_string(p.unit) << ", \"start\": " << json_number(p.start)
              << ", \"min\": " << json_number(p.min) << ", \"max\": " << json_number(p.max) << "}";
        }
      out << "\n  },\n  \"identifiable\": " << (s.identifiable ? "true" : "false")
          << ",\n  \"warnings\": [";
      for (std::size_t w = 0; w < warnings.size(); ++w)
        out << (w == 0 ? "\n    " : ",\n    ") << json_string(warnings[w]);
      out << (warnings.empty() ? "" : "\n  ") << "],\n  \"correlation\": [";
      for (std::size_t a = 0; a < s.correlation.size(); ++a)
        {
          out << (a == 0 ? "" : ", ") << "[";
          for (std::size_t b = 0; b < s.correlation[a].size(); ++b)
            out << (b == 0 ? "" : ", ") << json_number(s.correlation[a][b]);
          out << "]";
        }
      out << "],\n  \"scaled_condition_number\": " << json_number(s.scaled_condition)
          << ",\n  \"residual_variance\": " << json_number(s.residual_variance)
          << ",\n  \"degrees_of_freedom\": " << s.degrees_of_freedom << ",\n  \"data\": [";
      std::size_t offset = 0;
      for (std::size_t k = 0; k < c.data.size(); ++k)
        {
          const DataSet &d = c.data[k];
          double         sum = 0.;
          for (std::size_t i = 0; i < d.x.size(); ++i)
            sum += fit.residuals[offset + i] * fit.residuals[offset + i];
          offset += d.x.size();
          // sum = w * mean square relative misfit; features have no common unit.
          const bool   features = d.kind == DataKind::indentation_features;
          const double rms_relative = std::sqrt(sum / d.weight);
          out << (k == 0 ? "\n" : ",\n") << "    {\"label\": " << json_string(d.label)
              << ", \"kind\": " << json_string(d.kind_name())
              << ", \"file\": " << json_string(d.file) << ", \"weight\": " << json_number(d.weight)
              << ", \"points\": " << d.x.size()
              << ", \"rms_relative_misfit\": " << json_number(rms_relative)
              << ", \"rms_misfit\": " << json_number(features ? NAN : rms_relative * d.scale)
              << ", \"misfit_unit\": "
              << json_string(features ? "-" : d.y_name().substr(d.y_name().rfind('_') + 1));
          if (features)
            {
              out << ", \"features\": [";
              for (std::size_t f = 0; f < d.features.size(); ++f)
                out << (f == 0 ? "" : ", ") << json_string(feature_label(d.features[f]));
              out << "]";
            }
          out << ", \"curve\": " << json_string("fit_data" + std::to_string(k) + ".csv") << "}";
        }
      out << "\n  ],\n  \"initial_cost\": " << json_number(fit.initial_cost)
          << ",\n  \"cost\": " << json_number(fit.cost) << ",\n  \"iterations\": " << fit.iterations
          << ",\n  \"converged\": " << (fit.converged ? "true" : "false")
          << ",\n  \"termination\": " << json_string(fit.termination)
          << ",\n  \"forward_runs\": " << runs.runs_computed()
          << ",\n  \"forward_runs_reused\": " << runs.runs_reused()
          << ",\n  \"forward_runs_failed\": " << runs.runs_failed()
          << ",\n  \"forward_runs_warned\": " << runs.runs_warned()
          << ",\n  \"wall_time_s\": " << json_number(wall_time) << "\n}\n";
      output::write_file(c.output_directory + "/calibration.json", out.str());
    }

    // A forward run that warned (its mesh does not resolve the contact, its plastic zone reaches
    // a face: user guide, "Guards") gives a curve the run itself cannot vouch for, and a fit to
    // that curve inherits the doubt. The runs at the fitted values are named one by one; the
    // others, which only steered the minimiser, are counted by topic.
    void add_forward_run_warnings(const ForwardRuns &runs, const Point &fitted,
                                  std::vector<std::string> &warnings)
    {
      for (const std::string &directory : runs.directories(fitted))
        {
          const std::vector<std::string> topics = study::warning_topics(directory);
          if (!topics.empty())
            warnings.push_back("the forward run at the fitted values, " + directory +
                               ", warned: " + io::join(topics) +
                               " (its run_summary.json says why); the fit is no more accurate "
                               "than that run");
        }
      if (runs.runs_warned() == 0)
        return;
      std::vector<std::string> counts;
      for (const auto &[topic, count] : runs.warned_topics())
        counts.push_back(topic + " " + std::to_string(count));
      warnings.push_back(std::to_string(runs.runs_warned()) + " of the " +
                         std::to_string(runs.runs_computed()) +
                         " forward runs computed warned (runs per topic: " + io::join(counts) +
                         "); forward_runs.log names each");
    }
  } // namespace

  int run_calibration(const Calibration &c, const study::StudyRunSettings &settings,
                      std::ostream &out, std::ostream &warnings_out)
  {
    const auto start_time = std::chrono::steady_clock::now();
    fs::create_directories(c.output_directory);
    std::ofstream log(c.output_directory + "/forward_runs.log", std::ios::app);
    out << "Calibration " << c.source_file << ": " << c.parameters.size() << " parameter(s), "
        << c.data.size() << " data set(s), " << c.forward_cases().size()
        << " forward case(s) per point; output " << c.output_directory << "\n";
    for (const DataSet &d : c.data)
      {
        out << "  " << d.label << ": " << d.x.size();
        if (d.kind == DataKind::indentation_features)
          {
            out << " values (" << d.x.size() / d.features.size() << " tests:";
            for (const Feature f : d.features)
              out << " " << feature_name(f);
            out << ")";
          }
        else
          out << " points from " << d.x.front() << " to " << d.x.back();
        out << ", weight " << d.weight << "\n";
      }
    out << std::flush;

    ForwardRuns   runs(c, settings, log, warnings_out);
    ResidualModel model(c, runs);
    FitResult     fit;
    try
      {
        fit = calibration::fit(c, model, runs, out);
      }
    catch (const study::StudyFileError &error) // interrupted
      {
        warnings_out << "indentsim calibrate: " << error.what() << "\n";
        return study::exit_interrupted;
      }
    catch (const std::runtime_error &error)
      {
        warnings_out << "indentsim calibrate: error: " << error.what() << "\n";
        return study::exit_case_failed;
      }

    std::vector<std::string>           names;
    std::vector<std::array<double, 2>> bounds;
    Point                              start;
    for (const Parameter &p : c.parameters)
      {
        names.push_back(p.key);
        bounds.push_back({p.min, p.max});
        start.push_back(p.start);
      }
    const FitStatistics statistics =
        fit_statistics(fit.x, fit.residuals, fit.jacobian, names, bounds);
    std::vector<std::string> warnings = statistics.warnings;
    if (!statistics.identifiable)
      warnings.push_back(suggestion(c));
    for (const std::string &bound : fit.at_bound)
      warnings.push_back(bound + ": the fit ends on a bound; the optimum may lie beyond it "
                                 "(widen the bounds if the physics allows)");
    if (!fit.converged)
      warnings.push_back("the minimiser did not converge: " + fit.termination);
    // A forward model whose outputs jump (contact nodes reaching the tip, partial unloads) by
    // more than a narrow finite difference changes them gives a Jacobian that points nowhere:
    // every trial step raises the cost and the fit ends where it began.
    if (stayed_at_start(fit))
      warnings.push_back(
          "no trial step lowered the cost, so the fitted values are the start values: the "
          "finite-difference Jacobian (solver.finite_difference_step = " +
          json_number(c.solver.finite_difference_step) +
          " of each value) may see the forward model's small jumps instead of its trend; give "
          "each parameter a `step` of a few per cent of its value (parameters.<key>.step)");
    if (runs.runs_failed() > 0)
      warnings.push_back(
          std::to_string(runs.runs_failed()) +
          " forward run(s) failed: a failed trial point counts as a rejected step, a "
          "difference through a failed run is taken on the other side; forward_runs.log "
          "names each with its last lines");

    add_forward_run_warnings(runs, fit.x, warnings);

    const auto   at_start = model.simulated(start), at_fit = model.simulated(fit.x);
    const double wall_time =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
    write_json(c, fit, statistics, warnings, runs, wall_time);
    write_history(c, fit);
    if (at_start && at_fit)
      write_fit_curves(c, *at_start, *at_fit);
    output::draw_plot("calibration_report.py", {c.output_directory},
                      "report of " + c.output_directory, warnings_out);

    out << "Fitted in " << std::fixed << std::setprecision(1) << wall_time << " s, "
        << runs.runs_computed() << " forward runs (" << runs.runs_reused() << " reused), "
        << fit.iterations << " iterations: " << fit.termination << "\n"
        << std::defaultfloat;
    for (std::size_t j = 0; j < c.parameters.size(); ++j)
      out << "  " << c.parameters[j].key << " = " << std::setprecision(6) << fit.x[j] << " "
          << c.parameters[j].unit << " +- " << std::setprecision(3) << statistics.standard_error[j]
          << " (95 %: " << std::setprecision(6) << statistics.ci95[j][0] << " to "
          << statistics.ci95[j][1] << ")\n";
    if (!warnings.empty())
      {
        std::string text = statistics.identifiable ? "WARNING:\n"
                                                   : "WARNING: the parameters are NOT "
                                                     "identifiable from these data:\n";
        for (const auto &w : warnings)
          text += "  - " + w + "\n";
        warnings_out << text << std::flush;
      }
    out << "Results: " << c.output_directory << "/calibration.json, iterations.csv, "
        << "fit_data*.csv, report.md\n"
        << std::flush;
    return 0;
  }
} // namespace indentsim::calibration

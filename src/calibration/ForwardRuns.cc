// Forward runs as study cases (see ForwardRuns.h). Units: those of the parameters' keys.
#include "calibration/ForwardRuns.h"

#include "calibration/ParameterKey.h"
#include "case/Schema.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

namespace indentsim::calibration
{
  namespace
  {
    namespace fs = std::filesystem;

    // The YAML of a forward case file, or a null node if it does not read (the study's own
    // reading of the case then names the file and the line).
    YAML::Node case_yaml(const std::string &file)
    {
      try
        {
          return YAML::LoadFile(file);
        }
      catch (const YAML::Exception &)
        {
          return YAML::Node();
        }
    }

    // {material: {yield_stress: 0.25}, output: {plots: false}} from the parameters' keys, for
    // the forward case `base` (a layer's key copies the case's own material.layers).
    YAML::Node overrides_of(const Calibration &calibration, const Point &point,
                            const std::string &base_file, const YAML::Node &base)
    {
      YAML::Node overrides(YAML::NodeType::Map);
      for (std::size_t j = 0; j < calibration.parameters.size(); ++j)
        {
          const std::string &key = calibration.parameters[j].key;
          try
            {
              write_parameter(parse_parameter_key(key), point[j], base, overrides);
            }
          catch (const std::invalid_argument &error)
            {
              throw CalibrationFileError(calibration.source_file + ": parameters." + key +
                                         ": in the case " + base_file + ": " + error.what());
            }
        }
      overrides["output"]["plots"] = false;
      return overrides;
    }
  } // namespace

  ForwardBatch forward_study(const Calibration &calibration, const std::vector<Point> &points)
  {
    const std::vector<std::string> cases = calibration.forward_cases();
    YAML::Node                     root(YAML::NodeType::Map);
    root["output"] = (fs::path(calibration.output_directory) / "forward").string();
    std::vector<YAML::Node> bases;
    for (const std::string &file : cases)
      bases.push_back(case_yaml(file));
    ForwardBatch batch;
    // Each case once: a case that no parameter of the points differs in (a tensile test under
    // a layer's key) is shared by them.
    std::vector<std::pair<std::size_t, std::string>> written; // (k, overrides) of each case
    for (std::size_t i = 0; i < points.size(); ++i)
      {
        batch.index.emplace_back();
        for (std::size_t k = 0; k < cases.size(); ++k)
          {
            const YAML::Node overrides = overrides_of(calibration, points[i], cases[k], bases[k]);
            YAML::Emitter    text;
            text << YAML::Flow << overrides;
            const std::pair<std::size_t, std::string> id(k, text.c_str());
            const auto same = std::find(written.begin(), written.end(), id);
            batch.index.back().push_back(same - written.begin());
            if (same != written.end())
              continue;
            written.push_back(id);
            YAML::Node entry(YAML::NodeType::Map);
            entry["name"] = "c" + std::to_string(k) + "_p" + std::to_string(i);
            entry["base"] = cases[k];
            entry["overrides"] = overrides;
            root["cases"].push_back(entry);
          }
      }
    YAML::Emitter emitter;
    emitter << root;
    study::Study &study = batch.study;
    try
      {
        study = study::parse_study_yaml(emitter.c_str(), calibration.source_file);
      }
    catch (const io::CaseFileError &error)
      {
        throw CalibrationFileError(error.what());
      }
    // The directory of a case depends on its forward case and its key only, not on where the
    // point stands in this batch: the same values find the same run in any later batch.
    for (study::StudyCase &c : study.cases)
      {
        c.directory = (fs::path(study.output_directory) / "cases" /
                       (c.name.substr(0, c.name.find('_')) + "-" + c.key))
                          .string();
        c.resolved.output.directory = c.directory;
      }
    return batch;
  }

  io::Case forward_case(const Calibration &calibration, const Point &point, const std::size_t k)
  {
    const ForwardBatch batch = forward_study(calibration, {point});
    return batch.study.cases.at(batch.index[0].at(k)).resolved;
  }

  std::vector<std::string> ForwardRuns::directories(const Point &point) const
  {
    const ForwardBatch       batch = forward_study(calibration_, {point});
    std::vector<std::string> of_point;
    for (const std::size_t i : batch.index[0])
      of_point.push_back(batch.study.cases.at(i).directory);
    return of_point;
  }

  ForwardRuns::ForwardRuns(const Calibration &calibration, const study::StudyRunSettings &settings,
                           std::ostream &log, std::ostream &warnings)
    : calibration_(calibration)
    , settings_(settings)
    , log_(log)
    , warnings_(warnings)
  {
    settings_.batch = true;
    settings_.dry_run = false;
    settings_.only.clear();
  }

  std::vector<std::optional<std::vector<std::string>>>
  ForwardRuns::run(const std::vector<Point> &points)
  {
    if (points.empty()) // no cases: no study to run
      return {};
    // Distinct points only: two equal points resolve to the same cases.
    std::vector<Point> distinct;
    for (const Point &point : points)
      if (std::find(distinct.begin(), distinct.end(), point) == distinct.end())
        distinct.push_back(point);
    const ForwardBatch            forward = forward_study(calibration_, distinct);
    const study::Study           &batch = forward.study;
    const std::size_t             n_cases = calibration_.forward_cases().size();
    std::vector<study::CaseState> before;
    for (const auto &c : batch.cases)
      before.push_back(study::case_state(c));
    const int code = study::StudyRunner(batch, settings_, log_).run();
    if (code == study::exit_interrupted)
      throw study::StudyFileError("interrupted (SIGINT or SIGTERM); the finished forward runs "
                                  "are kept in " +
                                  batch.output_directory +
                                  ": run the same command again to continue");

    std::vector<std::optional<std::vector<std::string>>> directories;
    for (const Point &point : points)
      {
        const std::size_t i = std::find(distinct.begin(), distinct.end(), point) - distinct.begin();
        std::vector<std::string> of_point;
        for (std::size_t k = 0; k < n_cases; ++k)
          {
            const study::StudyCase &c = batch.cases[forward.index[i][k]];
            if (study::case_state(c) == study::CaseState::finished)
              of_point.push_back(c.directory);
          }
        if (of_point.size() == n_cases)
          directories.emplace_back(of_point);
        else
          directories.emplace_back(std::nullopt);
      }
    for (std::size_t c = 0; c < batch.cases.size(); ++c)
      {
        // A process that never ran (no executable, a launcher not found) is no numerical
        // failure the minimiser could step around: the calibration stops.
        const int exit_code = study::case_exit_code(batch.cases[c]);
        if (exit_code == study::exit_not_found || exit_code == study::exit_cannot_execute)
          throw std::runtime_error(
              "the forward case " + batch.cases[c].directory + " could not be started (exit code " +
              std::to_string(exit_code) +
              "; its console.log says why): " + "check the program and the --launcher template");
        const bool finished = study::case_state(batch.cases[c]) == study::CaseState::finished;
        if (before[c] == study::CaseState::finished)
          ++reused_;
        else if (finished)
          {
            ++computed_;
            const std::vector<std::string> topics = study::warning_topics(batch.cases[c].directory);
            warned_ += topics.empty() ? 0 : 1;
            for (const std::string &topic : topics)
              ++warned_topics_[topic];
          }
        else
          {
            ++failed_;
            const std::string console =
                batch.cases[c].directory + "/" + study::study_files::console_log;
            warnings_ << "WARNING: the forward run " << batch.cases[c].directory
                      << " failed (exit code " << exit_code << "); the last lines of its "
                      << console << ":\n"
                      << study::last_lines(console, 6) << std::flush;
          }
      }
    return directories;
  }
} // namespace indentsim::calibration

// Forward runs as study cases (see ForwardRuns.h). Units: those of the parameters' keys.
#include "calibration/ForwardRuns.h"

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

    // {material: {yield_stress: 0.25}, output: {plots: false}} from the dotted keys.
    YAML::Node overrides_of(const Calibration &calibration, const Point &point)
    {
      YAML::Node overrides(YAML::NodeType::Map);
      for (std::size_t j = 0; j < calibration.parameters.size(); ++j)
        {
          const std::string       &key = calibration.parameters[j].key;
          std::vector<std::string> names;
          for (std::size_t start = 0;;)
            {
              const std::size_t dot = key.find('.', start);
              names.push_back(key.substr(start, dot - start));
              if (dot == std::string::npos)
                break;
              start = dot + 1;
            }
          YAML::Node node = overrides;
          for (std::size_t n = 0; n + 1 < names.size(); ++n)
            {
              if (!node[names[n]].IsMap())
                node[names[n]] = YAML::Node(YAML::NodeType::Map);
              node.reset(node[names[n]]);
            }
          // The shortest text that reads back to the same double: the case key sees the value.
          node[names.back()] = io::format_number(point[j]);
        }
      overrides["output"]["plots"] = false;
      return overrides;
    }
  } // namespace

  study::Study forward_study(const Calibration &calibration, const std::vector<Point> &points)
  {
    const std::vector<std::string> cases = calibration.forward_cases();
    YAML::Node                     root(YAML::NodeType::Map);
    root["output"] = (fs::path(calibration.output_directory) / "forward").string();
    for (std::size_t i = 0; i < points.size(); ++i)
      for (std::size_t k = 0; k < cases.size(); ++k)
        {
          YAML::Node entry(YAML::NodeType::Map);
          entry["name"] = "c" + std::to_string(k) + "_p" + std::to_string(i);
          entry["base"] = cases[k];
          entry["overrides"] = overrides_of(calibration, points[i]);
          root["cases"].push_back(entry);
        }
    YAML::Emitter emitter;
    emitter << root;
    study::Study study;
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
    return study;
  }

  io::Case forward_case(const Calibration &calibration, const Point &point, const std::size_t k)
  {
    return forward_study(calibration, {point}).cases.at(k).resolved;
  }

  ForwardRuns::ForwardRuns(const Calibration &calibration, const study::StudyRunSettings &settings,
                           std::ostream &log)
    : calibration_(calibration)
    , settings_(settings)
    , log_(log)
  {
    settings_.batch = true;
    settings_.dry_run = false;
    settings_.only.clear();
  }

  std::vector<std::optional<std::vector<std::string>>>
  ForwardRuns::run(const std::vector<Point> &points)
  {
    // Distinct points only: two equal points resolve to the same cases.
    std::vector<Point> distinct;
    for (const Point &point : points)
      if (std::find(distinct.begin(), distinct.end(), point) == distinct.end())
        distinct.push_back(point);
    const study::Study            batch = forward_study(calibration_, distinct);
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
            const study::StudyCase &c = batch.cases[i * n_cases + k];
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
          ++computed_;
        else
          ++failed_;
      }
    return directories;
  }
} // namespace indentsim::calibration

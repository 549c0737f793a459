// YAML case files: parse -> read (CaseReader.cc) -> validate (CaseValidator.cc); the resolved
// case is written by CaseWriter.cc. See CaseFile.h for the rules.
#include "case/CaseFile.h"
#include "case/CaseReading.h"
#include "output/OutputFile.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <system_error>

namespace indentsim::io
{
  namespace
  {
    namespace fs = std::filesystem;

    // Levenshtein distance, for "did you mean" suggestions (case-insensitive).
    std::size_t edit_distance(const std::string &a, const std::string &b)
    {
      std::vector<std::size_t> previous(b.size() + 1), current(b.size() + 1);
      for (std::size_t j = 0; j <= b.size(); ++j)
        previous[j] = j;
      for (std::size_t i = 1; i <= a.size(); ++i)
        {
          current[0] = i;
          for (std::size_t j = 1; j <= b.size(); ++j)
            {
              const std::size_t substitution =
                  previous[j - 1] + (std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                                             std::tolower(static_cast<unsigned char>(b[j - 1]))
                                         ? 0
                                         : 1);
              current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
            }
          std::swap(previous, current);
        }
      return previous[b.size()];
    }
  } // namespace

  void fail(const std::string &source, const int line, const std::string &message)
  {
    std::string location = source.empty() ? std::string("case file") : source;
    if (line >= 0)
      location += ":" + std::to_string(line + 1);
    throw CaseFileError(location + ": " + message);
  }

  std::string key_path(const std::string &section, const std::string &key)
  {
    return section.empty() ? key : section + "." + key;
  }

  std::string join(const std::vector<std::string> &words, const std::string &separator)
  {
    std::string text;
    for (std::size_t i = 0; i < words.size(); ++i)
      text += (i == 0 ? "" : separator) + words[i];
    return text;
  }

  std::string node_text(const YAML::Node &node)
  {
    if (!node.IsDefined() || node.IsNull())
      return "(no value)";
    if (node.IsScalar())
      return node.Scalar();
    YAML::Emitter emitter;
    emitter.SetSeqFormat(YAML::Flow);
    emitter.SetMapFormat(YAML::Flow);
    emitter << node;
    return emitter.c_str();
  }

  std::string closest_name(const std::string &word, const std::vector<std::string> &candidates)
  {
    std::string best;
    std::size_t best_distance = std::numeric_limits<std::size_t>::max();
    for (const auto &candidate : candidates)
      {
        const std::size_t distance = edit_distance(word, candidate);
        if (distance < best_distance)
          {
            best_distance = distance;
            best = candidate;
          }
      }
    const std::size_t threshold = std::max<std::size_t>(2, word.size() / 3);
    return best_distance <= threshold ? best : std::string();
  }

  Case parse_case_yaml(const std::string &yaml_text, const std::string &source_name)
  {
    YAML::Node root;
    try
      {
        root = YAML::Load(yaml_text);
      }
    catch (const YAML::ParserException &error)
      {
        std::string location = source_name;
        if (!error.mark.is_null())
          location += ":" + std::to_string(error.mark.line + 1) + ":" +
                      std::to_string(error.mark.column + 1);
        throw CaseFileError(location + ": YAML syntax error: " + error.msg);
      }

    OriginMap origins;
    Case      result;
    try
      {
        result = read_case_tree(root, source_name, origins);
      }
    catch (const YAML::Exception &error)
      {
        // yaml-cpp reports structural problems (e.g. an invalid node) as exceptions.
        fail(source_name, error.mark.is_null() ? -1 : error.mark.line, error.msg);
      }
    validate_values(result, &origins);
    return result;
  }

  Case read_case_file(const std::string &path)
  {
    std::error_code error;
    if (!fs::exists(path, error))
      throw CaseFileError("case file '" + path + "' does not exist");
    if (fs::is_directory(path, error))
      throw CaseFileError("case file '" + path + "' is a directory, expected a YAML file");
    std::ifstream input(path);
    if (!input)
      throw CaseFileError("case file '" + path + "' cannot be opened for reading");
    std::ostringstream text;
    text << input.rdbuf();
    return parse_case_yaml(text.str(), path);
  }

  void validate_case(const Case &resolved_case)
  {
    validate_values(resolved_case, nullptr);
  }

  void write_resolved_case(const Case &resolved_case, const std::string &path)
  {
    output::write_file(path, resolved_case_yaml(resolved_case));
  }
} // namespace indentsim::io

// YAML case files: parse -> read (CaseReader.cc) -> validate (CaseValidator.cc); the resolved
// case is written by CaseWriter.cc. See CaseFile.h for the rules.
#include "case/CaseFile.h"
#include "case/CaseReading.h"
#include "indenter/IndenterSurface.h"
#include "output/OutputFile.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <system_error>
#include <utility>

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

  std::optional<std::pair<int, std::string>> yaml_text_problem(const std::string &text)
  {
    int         line = 0;
    std::size_t line_start = 0;
    for (std::size_t i = 0; i < text.size();)
      {
        const unsigned char byte = static_cast<unsigned char>(text[i]);
        const std::string   column = std::to_string(i - line_start + 1);
        if (byte == 0)
          return std::pair{line, "binary content (a NUL byte at column " + column +
                                     "): a case or study file is YAML text; is this the "
                                     "right file?"};
        // UTF-8: the length of the sequence from its lead byte, then continuation bytes
        // 10xxxxxx (overlong and surrogate forms are not checked: they do not occur in files
        // written by editors).
        const std::size_t length = byte < 0x80                           ? 1
                                   : (byte >> 5) == 0x6 && byte >= 0xC2  ? 2
                                   : (byte >> 4) == 0xE                  ? 3
                                   : (byte >> 3) == 0x1E && byte <= 0xF4 ? 4
                                                                         : 0;
        bool              valid = length > 0 && i + length <= text.size();
        for (std::size_t k = 1; valid && k < length; ++k)
          valid = (static_cast<unsigned char>(text[i + k]) >> 6) == 0x2;
        if (!valid)
          {
            static const char *hex = "0123456789ABCDEF";
            return std::pair{line, std::string("binary content (byte 0x") + hex[byte >> 4] +
                                       hex[byte & 0xF] + " at column " + column +
                                       " is not UTF-8 text): a case or study file is YAML text "
                                       "in UTF-8; is this the right file, or was it saved in "
                                       "another encoding (e.g. Latin-1)?"};
          }
        if (byte == '\n')
          {
            ++line;
            line_start = i + 1;
          }
        i += length;
      }

    // Tabs in the indentation (YAML indents with spaces only) of lines with content.
    std::istringstream lines(text);
    std::string        content;
    for (int number = 0; std::getline(lines, content); ++number)
      {
        const std::size_t first = content.find_first_not_of(" \t\r");
        if (first == std::string::npos || content[first] == '#')
          continue;
        if (const std::size_t tab = content.find('\t'); tab < first)
          return std::pair{number, "a tab in the indentation (column " + std::to_string(tab + 1) +
                                       "): YAML indents with spaces only; replace the tab by "
                                       "spaces"};
      }
    return std::nullopt;
  }

  int second_document_line(const std::string &text)
  {
    std::istringstream lines(text);
    std::string        content;
    bool               seen_content = false;
    for (int number = 0; std::getline(lines, content); ++number)
      {
        if (!content.empty() && content.back() == '\r')
          content.pop_back();
        const bool marker =
            content.rfind("---", 0) == 0 && (content.size() == 3 || content[3] == ' ');
        if (marker && seen_content)
          return number;
        // Content after a marker ("--- key: value") starts the document on the marker's line.
        const std::size_t from = marker ? 3 : 0;
        const std::size_t first = content.find_first_not_of(" \t", from);
        if (first != std::string::npos && content[first] != '#' &&
            !(from == 0 && content[first] == '%'))
          seen_content = true;
      }
    return -1;
  }

  Case parse_case_text(const std::string &yaml_text, const std::string &source_name,
                       OriginMap &origins)
  {
    if (const auto problem = yaml_text_problem(yaml_text))
      fail(source_name, problem->first, problem->second);
    YAML::Node root;
    try
      {
        const std::vector<YAML::Node> documents = YAML::LoadAll(yaml_text);
        if (!documents.empty())
          root = documents.front();
        for (std::size_t d = 1; d < documents.size(); ++d)
          if (documents[d].IsDefined() && !documents[d].IsNull())
            {
              int line = second_document_line(yaml_text);
              if (line < 0 && !documents[d].Mark().is_null())
                line = documents[d].Mark().line;
              fail(source_name, line,
                   "a second YAML document (after '---'): a case file holds one document, and "
                   "the keys of a second one would be ignored; merge them into the first "
                   "document or put each case into its own file");
            }
      }
    catch (const YAML::ParserException &error)
      {
        std::string location = source_name;
        if (!error.mark.is_null())
          location += ":" + std::to_string(error.mark.line + 1) + ":" +
                      std::to_string(error.mark.column + 1);
        throw CaseFileError(location + ": YAML syntax error: " + error.msg);
      }

    try
      {
        return read_case_tree(root, source_name, origins);
      }
    catch (const YAML::Exception &error)
      {
        // yaml-cpp reports structural problems (e.g. an invalid node) as exceptions.
        fail(source_name, error.mark.is_null() ? -1 : error.mark.line, error.msg);
      }
  }

  Case parse_case_yaml(const std::string &yaml_text, const std::string &source_name)
  {
    OriginMap origins;
    Case      result = parse_case_text(yaml_text, source_name, origins);
    validate_values(result, &origins);
    return result;
  }

  namespace
  {
    std::string read_case_text(const std::string &path)
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
      return text.str();
    }
  } // namespace

  Case read_case_file(const std::string &path)
  {
    return parse_case_yaml(read_case_text(path), path);
  }

  RunCase read_case_for_run(const std::string                                     &path,
                            const std::function<std::vector<std::string>(Case &)> &adjust)
  {
    OriginMap origins;
    RunCase   result;
    result.the_case = parse_case_text(read_case_text(path), path, origins);
    // A value the command line set was not written on a line of the file.
    for (const std::string &key : adjust(result.the_case))
      origins.erase(key);
    result.indenter = validate_values(result.the_case, &origins, /*for_run=*/true);
    return result;
  }

  void validate_case(const Case &resolved_case)
  {
    Case checked = resolved_case;
    validate_values(checked, nullptr);
  }

  void write_resolved_case(const Case &resolved_case, const std::string &path)
  {
    output::write_file(path, resolved_case_yaml(resolved_case));
  }
} // namespace indentsim::io

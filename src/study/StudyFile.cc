// Study files: reading, validation, the merge of overrides onto base case files and the case
// key. See StudyFile.h for the format and the rules. Units: um, mN, GPa.
#include "study/StudyFile.h"

#include "case/CaseFile.h"
#include "case/Fingerprint.h"
#include "case/MaterialLayers.h"
#include "io/TextNumber.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <system_error>

namespace indentsim::study
{
  namespace
  {
    namespace fs = std::filesystem;

    const std::vector<std::string> top_level_keys = {"output", "report", "cases"};
    const std::vector<std::string> report_keys = {"title",           "depth_at_force_mN",
                                                  "tensile_strains", "paper_max_depth_um",
                                                  "paper_forces_mN", "paper_note"};
    const std::vector<std::string> case_keys = {"name", "base", "overrides", "group", "label"};
    const std::vector<std::string> mesh_groups = {"mesh_j2", "mesh_crystal"};

    using io::join;
    const auto &flow_text = io::node_text;

    int line_of(const YAML::Node &node)
    {
      if (!node.IsDefined())
        return -1;
      const YAML::Mark mark = node.Mark();
      return mark.is_null() ? -1 : mark.line;
    }

    bool contains(const std::vector<std::string> &words, const std::string &word)
    {
      return std::find(words.begin(), words.end(), word) != words.end();
    }

    // The one YAML document of a study or base case file. Binary content, tabs in the
    // indentation and a second document (which would be ignored) are refused by name, with the
    // line; `context` follows the message. Throws StudyFileError or YAML::ParserException.
    YAML::Node load_one_document(const std::string &text, const std::string &source,
                                 const std::string &context)
    {
      const auto at_line = [&](const int line) {
        return source + (line < 0 ? std::string() : ":" + std::to_string(line + 1));
      };
      if (const auto problem = io::yaml_text_problem(text))
        throw StudyFileError(at_line(problem->first) + ": " + problem->second + context);
      const std::vector<YAML::Node> documents = YAML::LoadAll(text);
      for (std::size_t d = 1; d < documents.size(); ++d)
        if (documents[d].IsDefined() && !documents[d].IsNull())
          throw StudyFileError(at_line(io::second_document_line(text)) +
                               ": a second YAML document (after '---'): the file holds one "
                               "document, and the keys of a second one would be ignored; merge "
                               "them into the first" +
                               context);
      return documents.empty() ? YAML::Node() : documents.front();
    }

    // Reads a study file's YAML into a Study; every problem throws StudyFileError.
    class StudyReader
    {
    public:
      StudyReader(std::string source_name, std::string output_override)
        : source(std::move(source_name))
        , output_override(std::move(output_override))
      {
      }

      Study read(const YAML::Node &root)
      {
        Study study;
        study.source_file = source;
        if (!root.IsDefined() || root.IsNull())
          fail(-1, "the study file is empty; expected the keys " + join(top_level_keys));
        if (!root.IsMap())
          fail(line_of(root), "a study file is a mapping of the keys " + join(top_level_keys) +
                                  ", got '" + flow_text(root) + "'");
        check_keys(root, "", top_level_keys);

        std::string output = "results/study_" + fs::path(source).stem().string();
        if (const YAML::Node node = root["output"]; node.IsDefined())
          output = read_word(node, "output", "a directory path");
        if (!output_override.empty())
          output = output_override;
        std::error_code error;
        const fs::path  absolute = fs::absolute(output, error);
        study.output_directory = (error ? fs::path(output) : absolute).lexically_normal().string();
        while (study.output_directory.size() > 1 && study.output_directory.back() == '/')
          study.output_directory.pop_back();

        read_report(root["report"], study.report);

        const YAML::Node cases = root["cases"];
        if (!cases.IsDefined() || cases.IsNull())
          fail(line_of(root), "missing key 'cases': a list of cases, each with name and base");
        if (!cases.IsSequence() || cases.size() == 0)
          fail(line_of(cases),
               "cases = " + flow_text(cases) +
                   ": expected a non-empty list of cases, each a mapping with the keys " +
                   join(case_keys) + " (name and base required)");
        for (std::size_t i = 0; i < cases.size(); ++i)
          study.cases.push_back(read_case(cases[i], i, study.output_directory));

        check_across_cases(study);
        return study;
      }

    private:
      std::string source;
      std::string output_override;

      [[noreturn]] void fail(const int line, const std::string &message) const
      {
        throw StudyFileError(source + (line >= 0 ? ":" + std::to_string(line + 1) : "") + ": " +
                             message);
      }

      void check_keys(const YAML::Node &map, const std::string &where,
                      const std::vector<std::string> &allowed) const
      {
        std::set<std::string> seen;
        for (const auto &entry : map)
          {
            const std::string key = entry.first.IsScalar() ? entry.first.Scalar() : "";
            const std::string shown = where.empty() ? key : where + "." + key;
            if (!entry.first.IsScalar())
              fail(line_of(entry.first),
                   "key '" + flow_text(entry.first) + "' is not a plain name; allowed keys" +
                       (where.empty() ? "" : " in '" + where + "'") + ": " + join(allowed));
            if (!seen.insert(key).second)
              fail(line_of(entry.first), "duplicate key '" + shown + "'; give each key once");
            if (contains(allowed, key))
              continue;
            const std::string guess = io::closest_name(key, allowed);
            fail(line_of(entry.first),
                 "unknown key '" + shown + "'" +
                     (guess.empty() ? std::string(".") : "; did you mean '" + guess + "'?") +
                     " Allowed keys" +
                     (where.empty() ? " at the top level" : " in '" + where + "'") + ": " +
                     join(allowed) + ".");
          }
      }

      std::string read_word(const YAML::Node &node, const std::string &path,
                            const std::string &meaning) const
      {
        if (node.IsNull())
          fail(line_of(node), path + " has no value; expected " + meaning);
        if (!node.IsScalar() || node.Scalar().empty())
          fail(line_of(node), path + " = " + flow_text(node) + ": expected " + meaning);
        return node.Scalar();
      }

      double read_number(const YAML::Node &node, const std::string &path,
                         const std::string &meaning) const
      {
        const std::string expected = "expected a number (" + meaning + ")";
        if (node.IsNull())
          fail(line_of(node), path + " has no value; " + expected);
        if (!node.IsScalar())
          fail(line_of(node), path + " = " + flow_text(node) + ": " + expected);
        const std::optional<double> value = io::parse_yaml_number(node.Scalar());
        if (!value)
          fail(line_of(node), path + " = \"" + node.Scalar() + "\": " + expected);
        return *value;
      }

      double read_positive(const YAML::Node &node, const std::string &path,
                           const std::string &meaning) const
      {
        const double value = read_number(node, path, meaning);
        if (!(value > 0.))
          fail(line_of(node), path + " = " + node.Scalar() + ": must be > 0 (" + meaning + ")");
        return value;
      }

      void read_report(const YAML::Node &node, StudyReportSettings &report) const
      {
        if (!node.IsDefined() || node.IsNull())
          return;
        if (!node.IsMap())
          fail(line_of(node), "report = " + flow_text(node) + ": expected a mapping of the keys " +
                                  join(report_keys));
        check_keys(node, "report", report_keys);
        if (const YAML::Node n = node["title"]; n.IsDefined())
          report.title = read_word(n, "report.title", "a title (text)");
        if (const YAML::Node n = node["paper_note"]; n.IsDefined())
          report.paper_note = read_word(n, "report.paper_note", "a note (text)");
        if (const YAML::Node n = node["depth_at_force_mN"]; n.IsDefined())
          report.depth_at_force_mN = read_positive(n, "report.depth_at_force_mN", "a force in mN");
        if (const YAML::Node n = node["paper_max_depth_um"]; n.IsDefined())
          report.paper_max_depth_um =
              read_positive(n, "report.paper_max_depth_um", "a depth in um");
        if (const YAML::Node n = node["tensile_strains"]; n.IsDefined())
          {
            if (!n.IsSequence() || n.size() == 0)
              fail(line_of(n), "report.tensile_strains = " + flow_text(n) +
                                   ": expected a list of logarithmic strains, e.g. [0.02, 0.05]");
            report.tensile_strains.clear();
            for (std::size_t i = 0; i < n.size(); ++i)
              report.tensile_strains.push_back(
                  read_positive(n[i], "report.tensile_strains[" + std::to_string(i) + "]",
                                "a logarithmic strain"));
          }
        if (const YAML::Node n = node["paper_forces_mN"]; n.IsDefined())
          {
            const std::string path = "report.paper_forces_mN";
            if (!n.IsMap())
              fail(line_of(n), path + " = " + flow_text(n) +
                                   ": expected {mesh_j2: {48: 821.2, ...}, mesh_crystal: {...}}");
            check_keys(n, path, mesh_groups);
            for (const auto &group : n)
              {
                const std::string group_path = path + "." + group.first.Scalar();
                if (!group.second.IsMap())
                  fail(line_of(group.second),
                       group_path + " = " + flow_text(group.second) +
                           ": expected {contact elements: force in mN, ...}, e.g. {48: 821.2}");
                for (const auto &entry : group.second)
                  {
                    const std::string text = entry.first.IsScalar() ? entry.first.Scalar() : "";
                    unsigned int      elements = 0;
                    const auto        parsed =
                        std::from_chars(text.data(), text.data() + text.size(), elements);
                    if (parsed.ec != std::errc() || parsed.ptr != text.data() + text.size() ||
                        elements < 4 || elements % 4 != 0)
                      fail(line_of(entry.first),
                           group_path + ": key '" + flow_text(entry.first) +
                               "': expected a number of contact elements (a positive multiple "
                               "of 4, as specimen.contact_elements)");
                    report.paper_forces_mN[group.first.Scalar()][elements] =
                        read_positive(entry.second, group_path + "." + text, "a force in mN");
                  }
              }
          }
      }

      StudyCase read_case(const YAML::Node &node, const std::size_t index,
                          const std::string &output_directory) const
      {
        const std::string where = "cases[" + std::to_string(index) + "]";
        if (!node.IsMap())
          fail(line_of(node), where + " = " + flow_text(node) +
                                  ": expected a mapping with the keys " + join(case_keys) +
                                  " (name and base required)");
        check_keys(node, where, case_keys);

        StudyCase result;
        result.line = line_of(node);
        read_name(node, where, result);
        const std::string the_case = "case '" + result.name + "'";
        result.label = result.name;
        if (const YAML::Node label = node["label"]; label.IsDefined())
          result.label = read_word(label, the_case + ": label", "a legend label (text)");
        read_groups(node, the_case, result);

        const YAML::Node base = node["base"];
        if (!base.IsDefined())
          fail(result.line, the_case + ": missing key 'base', the case file the overrides "
                                       "apply to (relative to the study file)");
        const std::string base_as_written =
            read_word(base, the_case + ": base", "a case file path (relative to the study file)");
        const YAML::Node base_root = read_base(base, base_as_written, the_case, result);
        const YAML::Node overrides = read_overrides(node, the_case, result);
        resolve(merge_overrides(base_root, overrides), base_as_written, the_case, result);
        check_groups_fit(the_case, result);

        result.resolved.source_file =
            source + ", case '" + result.name + "' (base " + result.base_file + ")";
        result.key = case_key(result.resolved);
        result.directory =
            (fs::path(output_directory) / "cases" / (result.name + "-" + result.key)).string();
        result.resolved.output.directory = result.directory;
        return result;
      }

      // name: letters, digits, _ and - (it names a directory), and not a group's name.
      void read_name(const YAML::Node &node, const std::string &where, StudyCase &result) const
      {
        const YAML::Node name = node["name"];
        if (!name.IsDefined())
          fail(result.line, where + ": missing key 'name' (letters, digits, _ and -)");
        result.name = read_word(name, where + ".name", "a case name (letters, digits, _ and -)");
        const bool plain = std::all_of(result.name.begin(), result.name.end(), [](char c) {
          return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
        });
        if (!plain)
          fail(line_of(name), where + ".name = \"" + result.name +
                                  "\": only letters, digits, _ and - are allowed (it names a "
                                  "directory)");
        if (contains(known_groups, result.name))
          fail(line_of(name), where + ".name = " + result.name +
                                  ": a group's name; choose another (--only accepts both names "
                                  "and groups: " +
                                  join(known_groups) + ")");
      }

      // group: one known group or a list of them, each once.
      void read_groups(const YAML::Node &node, const std::string &the_case, StudyCase &result) const
      {
        const YAML::Node group = node["group"];
        if (!group.IsDefined() || group.IsNull())
          return;
        std::vector<YAML::Node> items;
        if (group.IsSequence())
          for (const auto &item : group)
            items.push_back(item);
        else
          items.push_back(group);
        for (const auto &item : items)
          {
            const std::string value = item.IsScalar() ? item.Scalar() : flow_text(item);
            if (!item.IsScalar() || !contains(known_groups, value))
              {
                const std::string guess = io::closest_name(value, known_groups);
                fail(line_of(item), the_case + ": group = " + value +
                                        ": allowed groups: " + join(known_groups) +
                                        (guess.empty() ? "" : " (did you mean '" + guess + "'?)"));
              }
            if (contains(result.groups, value))
              fail(line_of(item), the_case + ": group " + value + " given twice");
            result.groups.push_back(value);
          }
      }

      // The base case file (relative to the study file) as a YAML tree; sets result.base_file.
      YAML::Node read_base(const YAML::Node &base, const std::string &base_as_written,
                           const std::string &the_case, StudyCase &result) const
      {
        fs::path base_path(base_as_written);
        if (base_path.is_relative())
          base_path = fs::path(source).parent_path() / base_path;
        result.base_file = base_path.lexically_normal().string();
        std::error_code error;
        if (!fs::exists(result.base_file, error) || fs::is_directory(result.base_file, error))
          fail(line_of(base), the_case + ": base = " + base_as_written + ": no case file '" +
                                  result.base_file + "' (paths are relative to the study file)");
        std::ifstream input(result.base_file);
        if (!input)
          fail(line_of(base), the_case + ": base = " + base_as_written + ": '" + result.base_file +
                                  "' cannot be opened for reading");
        std::ostringstream base_text;
        base_text << input.rdbuf();
        try
          {
            return load_one_document(base_text.str(), result.base_file,
                                     " (the base of " + the_case + " in " + source + ")");
          }
        catch (const YAML::ParserException &e)
          {
            throw StudyFileError(
                result.base_file +
                (e.mark.is_null() ? std::string() : ":" + std::to_string(e.mark.line + 1)) +
                ": YAML syntax error: " + e.msg + " (the base of " + the_case + " in " + source +
                ")");
          }
      }

      // overrides: a mapping merged onto the base; output.directory belongs to the study.
      YAML::Node read_overrides(const YAML::Node &node, const std::string &the_case,
                                StudyCase &result) const
      {
        YAML::Node overrides = node["overrides"];
        result.overrides_text = "{}";
        if (!overrides.IsDefined() || overrides.IsNull())
          return overrides;
        if (!overrides.IsMap())
          fail(line_of(overrides), the_case + ": overrides = " + flow_text(overrides) +
                                       ": expected a mapping merged onto the base case, e.g. "
                                       "{specimen: {contact_elements: 48}}");
        const YAML::Node output = overrides["output"];
        if (output.IsDefined() && output.IsMap() && output["directory"].IsDefined())
          fail(line_of(output["directory"]),
               the_case + ": overrides.output.directory = " + flow_text(output["directory"]) +
                   ": set by the study (<output>/cases/<name>-<key>); remove it");
        result.overrides_text = flow_text(overrides);
        return overrides;
      }

      // The merged case through the case-file reader (defaults, validation) into
      // result.resolved. Its messages name the study's entry.
      void resolve(const YAML::Node &merged, const std::string &base_as_written,
                   const std::string &the_case, StudyCase &result) const
      {
        YAML::Emitter emitter;
        emitter << merged;
        try
          {
            result.resolved = io::parse_case_yaml(emitter.c_str(), result.base_file);
          }
        catch (const io::CaseFileError &e)
          {
            // The reader names the base file and a line of the merged text, which no file
            // holds: name the study's entry instead, then the key, value and rule.
            std::string message = e.what();
            if (message.rfind(result.base_file, 0) == 0)
              {
                std::size_t position = result.base_file.size();
                if (position < message.size() && message[position] == ':')
                  {
                    ++position;
                    while (position < message.size() &&
                           std::isdigit(static_cast<unsigned char>(message[position])))
                      ++position;
                    if (position < message.size() && message[position] == ':')
                      ++position;
                    while (position < message.size() && message[position] == ' ')
                      ++position;
                  }
                message = message.substr(position);
              }
            fail(result.line, the_case + " (base " + base_as_written + ", overrides " +
                                  result.overrides_text + "): " + message);
          }
      }

      // Each group's plots need cases of its kind.
      void check_groups_fit(const std::string &the_case, const StudyCase &result) const
      {
        const auto &test = result.resolved.test;
        const auto &model = result.resolved.material.model;
        for (const auto &group : result.groups)
          {
            std::string needed;
            if (group == "tensile" && test != io::TestKind::tensile)
              needed = "test: tensile";
            else if (group != "tensile" && test != io::TestKind::indentation)
              needed = "test: indentation";
            else if (group == "mesh_j2" && model != io::ModelKind::j2)
              needed = "material.model: j2";
            else if ((group == "mesh_crystal" || group == "orientation") &&
                     model != io::ModelKind::crystal)
              needed = "material.model: crystal";
            if (!needed.empty())
              fail(result.line, the_case + ": group " + group + " needs " + needed +
                                    "; this case has test: " + io::to_string(test) +
                                    ", material.model: " + io::to_string(model));
          }
      }

      void check_across_cases(const Study &study) const
      {
        std::map<std::string, const StudyCase *> by_name, by_key;
        for (const auto &c : study.cases)
          {
            if (const auto other = by_name.find(c.name); other != by_name.end())
              fail(c.line, "case name '" + c.name + "' given twice (first on line " +
                               std::to_string(other->second->line + 1) + "); names are unique");
            by_name[c.name] = &c;
            if (const auto other = by_key.find(c.key); other != by_key.end())
              fail(c.line, "case '" + c.name + "' resolves to the same case as '" +
                               other->second->name + "' (line " +
                               std::to_string(other->second->line + 1) + ", key " + c.key +
                               "); give it once, with both groups (group: [a, b])");
            by_key[c.key] = &c;
          }
        for (const auto &group : mesh_groups)
          {
            std::map<unsigned int, std::string> by_mesh;
            for (const auto &c : study.cases)
              if (contains(c.groups, group))
                {
                  const unsigned int n = c.resolved.specimen.contact_elements;
                  if (const auto other = by_mesh.find(n); other != by_mesh.end())
                    fail(c.line, "cases '" + other->second + "' and '" + c.name + "' of group " +
                                     group + " both have contact_elements " + std::to_string(n) +
                                     "; a mesh-convergence group has one case per mesh");
                  by_mesh[n] = c.name;
                }
          }
      }
    };
  } // namespace

  YAML::Node merge_overrides(const YAML::Node &base, const YAML::Node &overrides)
  {
    return io::merge_overrides(base, overrides);
  }

  std::string canonical_case_text(const io::Case &resolved_case)
  {
    return io::canonical_case_text(resolved_case);
  }

  std::uint64_t fnv1a_64(const std::string &text)
  {
    return io::fnv1a_64(text);
  }

  std::string case_key(const io::Case &resolved_case)
  {
    const std::uint64_t hash = io::case_fingerprint(resolved_case);
    static const char  *digits = "0123456789abcdef";
    std::string         key(16, '0');
    for (int i = 15; i >= 0; --i)
      key[static_cast<std::size_t>(15 - i)] = digits[(hash >> (4 * i)) & 0xf];
    return key;
  }

  Study parse_study_yaml(const std::string &yaml_text, const std::string &source_name,
                         const std::string &output_override)
  {
    YAML::Node root;
    try
      {
        root = load_one_document(yaml_text, source_name, "");
      }
    catch (const YAML::ParserException &e)
      {
        throw StudyFileError(
            source_name +
            (e.mark.is_null() ? std::string() : ":" + std::to_string(e.mark.line + 1)) +
            ": YAML syntax error: " + e.msg);
      }
    try
      {
        return StudyReader(source_name, output_override).read(root);
      }
    catch (const YAML::Exception &e)
      {
        throw StudyFileError(
            source_name +
            (e.mark.is_null() ? std::string() : ":" + std::to_string(e.mark.line + 1)) + ": " +
            e.msg);
      }
  }

  Study read_study_file(const std::string &path, const std::string &output_override)
  {
    std::error_code error;
    if (!fs::exists(path, error))
      throw StudyFileError("study file '" + path + "' does not exist");
    if (fs::is_directory(path, error))
      throw StudyFileError("study file '" + path + "' is a directory, expected a YAML file");
    std::ifstream input(path);
    if (!input)
      throw StudyFileError("study file '" + path + "' cannot be opened for reading");
    std::ostringstream text;
    text << input.rdbuf();
    return parse_study_yaml(text.str(), path, output_override);
  }
} // namespace indentsim::study

// The case-file reference, generated from the schema (see CaseReference.h).
#include "case/CaseReference.h"
#include "case/Schema.h"

#include <algorithm>
#include <sstream>

namespace indentsim::io
{
  namespace
  {
    struct Section
    {
      const char *name; // "" for the top level
      const char *title;
      const char *about;
    };

    const Section sections[] = {
        {"", "Top level", "The kind of test."},
        {"material", "material", "The constitutive model and its parameters."},
        {"indenter", "indenter",
         "The rigid indenter. Every key is read and range-checked for every shape but used only by "
         "the shapes named in its description (`indenter.file` is opened only for "
         "`profile_table`)."},
        {"specimen", "specimen",
         "The block under the indenter (indentation) or the cube (tensile), and its mesh."},
        {"loading", "loading", "The loading programme."},
        {"contact", "contact", "Augmented-Lagrangian contact with Coulomb friction."},
        {"solver", "solver", "Newton's method and the linear solver."},
        {"output", "output", "Where the results go and what is written."},
    };

    std::string type_name(const ValueType type)
    {
      switch (type)
        {
        case ValueType::number:
          return "number";
        case ValueType::whole_number:
          return "whole number";
        case ValueType::boolean:
          return "true/false";
        case ValueType::choice:
          return "word";
        case ValueType::text:
          return "text";
        case ValueType::triple:
          return "3 numbers";
        case ValueType::list:
          return "list of numbers";
        case ValueType::words:
          return "list of words";
        case ValueType::matrix:
          return "list of lists of numbers";
        case ValueType::family_blocks:
          return "map of numbers";
        case ValueType::layers:
          return "list of maps";
        }
      return {};
    }

    std::string default_of(const Key &key)
    {
      if (key.required)
        return "**required**";
      if (!key.default_text.empty())
        return key.default_text;
      const std::string value = key.value_text(Case());
      return key.type == ValueType::text ? "\"" + value + "\"" : value;
    }

    std::string allowed_of(const Key &key)
    {
      if (!key.allowed_text.empty())
        return key.allowed_text;
      if (key.type == ValueType::choice)
        {
          std::string words;
          for (const auto &word : key.choice.words(true))
            words += (words.empty() ? "`" : " | `") + word + "`";
          const std::vector<std::string> implemented = key.choice.words(true);
          std::string                    planned;
          for (const auto &word : key.choice.words(false))
            if (std::find(implemented.begin(), implemented.end(), word) == implemented.end())
              planned += (planned.empty() ? "`" : ", `") + word + "`";
          return planned.empty() ? words : words + " (" + planned + ": not yet implemented)";
        }
      if (key.type == ValueType::boolean)
        return "`true` | `false`";
      if (key.non_empty)
        return "non-empty";
      if (key.has_range)
        {
          if (key.type == ValueType::triple)
            return "3 numbers " + key.range.text();
          if (key.type == ValueType::list)
            return "numbers " + key.range.text();
          if (key.zero_word != nullptr)
            return key.range.text() + ", or `" + key.zero_word + "`";
          return key.range.text();
        }
      if (key.type == ValueType::whole_number)
        return "≥ 0";
      return key.type == ValueType::text ? "a path, or \"\"" : "any";
    }

    // A table cell: '|' would end the cell.
    std::string cell(const std::string &text)
    {
      std::string escaped;
      for (const char c : text)
        escaped += c == '|' ? std::string("\\|") : std::string(1, c);
      return escaped.empty() ? "–" : escaped;
    }

    bool in_section(const Key &key, const std::string &section)
    {
      const std::string parent = key.parent();
      if (section.empty())
        return parent.empty();
      return !parent.empty() && parent.substr(0, parent.find('.')) == section;
    }

    const char *notes =
        "## Notes\n"
        "\n"
        "The crystal keys are read and checked for every model but used only by `crystal` (the "
        "resolved case always lists them); the J2 keys also serve `compare_j2`. Indentation and "
        "tensile keys may share one file: each test ignores the other's.\n"
        "\n"
        "**Crystal orientation convention** (`materials/Orientation.h`): Bunge, passive. The "
        "rotation g = R_z(φ2) R_x(Φ) R_z(φ1), R_z(a) = [[cos a, sin a, 0], [−sin a, cos a, 0], "
        "[0, 0, 1]], maps sample components to crystal components, v_crystal = g v_sample: its "
        "rows are the crystal axes [100], [010], [001] in the sample frame. Euler angles "
        "(0, 0, 0) put the crystal axes along the sample axes, so the (001) plane is indented. "
        "`surface_normal: [h, k, l]` is the crystal direction along sample z and "
        "`reference_direction: [u, v, w]` the crystal direction along sample x (e.g. [1, 1, 1] "
        "with [1, −1, 0]); neither needs to be normalised. The resolved case writes the form "
        "that was given.\n"
        "\n"
        "Boundary conditions: bottom face fixed (all components), lateral faces traction-free, "
        "top face free except for contact; `quarter` adds u_x = 0 on x = 0 and u_y = 0 on "
        "y = 0. Mesh: the refined region holds N×N cells across its top face (edge h = "
        "refined_x/N) and about cubic coarse cells 2^L h, coarsened by p4est's 2:1 balance and "
        "geometric grading (ratio 1.6) outside; its depth is honoured in whole coarse layers.\n"
        "\n"
        "Bad input never reaches the solver: every problem stops the program with one message "
        "that names the file, the line, the key, the value and what is allowed (with a \"did you "
        "mean\" for a misspelt key or word). Every run writes `resolved_case.yaml`, the case with "
        "every default filled in, next to its results.\n";
  } // namespace

  std::string case_file_reference_markdown()
  {
    std::ostringstream out;
    out << "# Case file reference\n"
        << "\n"
        << "A case file is YAML. Units: lengths µm (written `um`), forces mN, stresses and "
           "moduli GPa (1 GPa·µm² = 1 mN), angles degrees, times s. Only `test` and "
           "`material.model` are required; every other key has the default below.\n"
        << "\n"
        << "This file is generated from the case schema (`src/case/Schema.cc`) by\n"
        << "`" << case_reference_command << "`;\n"
        << "edit the schema, not this file (a unit test fails when the two differ).\n";
    for (const auto &section : sections)
      {
        out << "\n## " << section.title << "\n\n"
            << section.about << "\n\n"
            << "| key | type | unit | default | allowed | description |\n"
            << "|---|---|---|---|---|---|\n";
        for (const auto &key : case_keys())
          if (in_section(key, section.name))
            out << "| `" << key.path << "` | " << type_name(key.type) << " | " << cell(key.unit)
                << " | " << cell(default_of(key)) << " | " << cell(allowed_of(key)) << " | "
                << cell(key.description) << " |\n";
      }
    out << "\n" << notes;
    return out.str();
  }
} // namespace indentsim::io

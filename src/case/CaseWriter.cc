// The resolved case (resolved_case.yaml): every key of the schema with its value, in the
// order of the schema, with the schema's comment; read_case_file() of the text gives back an
// identical Case.
#include "case/CaseFile.h"
#include "case/Schema.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <iomanip>
#include <sstream>

namespace indentsim::io
{
  namespace
  {
    // Strings that the user chose freely are quoted by yaml-cpp; words of a choice are plain.
    std::string quoted(const std::string &text)
    {
      YAML::Emitter emitter;
      emitter << YAML::DoubleQuoted << text;
      return std::string(emitter.c_str());
    }

    // One "key: value   # comment" line, comments aligned.
    void write_line(std::ostream &out, const std::string &indent_key_value,
                    const std::string &comment)
    {
      constexpr std::size_t comment_column = 36;
      out << indent_key_value;
      if (!comment.empty())
        {
          const std::size_t width = indent_key_value.size();
          out << std::string(width < comment_column ? comment_column - width : 1, ' ') << "# "
              << comment;
        }
      out << '\n';
    }

    std::string indentation(const std::string &path)
    {
      return std::string(2 * static_cast<std::size_t>(std::count(path.begin(), path.end(), '.')),
                         ' ');
    }

    const Group *group_at(const std::string &path)
    {
      for (const auto &group : case_groups())
        if (group.path == path)
          return &group;
      return nullptr;
    }

    // The automatic mesh's design as comments (it is derived, never read back): the refined
    // region is written only for explicit meshes, since contact_elements: auto designs it.
    void write_mesh_design(std::ostream &out, const SpecimenParameters &s)
    {
      const MeshGrading &g = s.grading;
      std::ostringstream text;
      text << std::setprecision(4)
           << "  # designed (user guide, \"Automatic meshes\"): contact radius a_d = "
           << g.contact_radius << " um; element edge max(h_min, rho/n), h_min = " << g.min_element
           << " um, n = " << g.elements_per_radius << " for rho <= " << g.graded_radius
           << " um, rho/" << g.far_elements_per_radius << " beyond, halved " << g.surface_halvings
           << " more time(s) on the top face for rho <= " << g.surface_radius << " um;\n";
      if (g.layer_element > 0)
        text << "  # at most " << g.layer_element << " um across the layers (to the depth "
             << g.layered_depth << " um) for rho <= " << g.graded_radius << " um;\n";
      text << "  # contact nodes and guards on refined_region = [" << s.refined_region[0] << ", "
           << s.refined_region[1] << ", " << s.refined_region[2] << "] um\n";
      out << text.str();
    }
  } // namespace

  std::string resolved_case_yaml(const Case &resolved_case)
  {
    const Case        &c = resolved_case;
    std::ostringstream out;
    out << "# indentsim resolved case: every key with its default filled in.\n"
        << "# Units: lengths um, forces mN, stresses and moduli GPa (1 GPa*um^2 = 1 mN).\n";
    if (!c.source_file.empty())
      out << "# Read from: " << c.source_file << '\n';

    std::string open_section, open_group; // the maps whose header line is written
    for (const auto &key : case_keys())
      {
        if (key.written != nullptr && !key.written(c))
          continue;
        const std::string parent = key.parent();
        const std::string section = parent.substr(0, parent.find('.'));
        if (!section.empty() && section != open_section)
          {
            out << section << ":\n";
            open_section = section;
          }
        // Every map between the section and the key whose header line is not written yet.
        for (std::size_t dot = parent.find('.'); parent != section && dot != std::string::npos;
             dot = parent.find('.', dot + 1))
          {
            const std::size_t end = parent.find('.', dot + 1);
            const std::string map = parent.substr(0, end);
            if (open_group == map || open_group.rfind(map + ".", 0) == 0)
              continue;
            const Group *group = group_at(map);
            write_line(out, indentation(map) + map.substr(map.rfind('.') + 1) + ":",
                       group != nullptr ? group->comment : "");
            open_group = map;
          }
        if (parent != section)
          open_group = parent;
        if (key.type == ValueType::family_blocks)
          {
            // One line per family, named by the family in place of the key's placeholder.
            for (const FamilyHardening &block : key.family_blocks(const_cast<Case &>(c)))
              write_line(out,
                         indentation(key.path) + quoted(block.family) + ": " +
                             format_family_block(block),
                         key.comment);
            continue;
          }
        const std::string value =
            key.type == ValueType::text ? quoted(key.value_text(c)) : key.value_text(c);
        write_line(out, indentation(key.path) + key.name() + ": " + value, key.comment);
        if (key.path == "specimen.contact_elements" && c.specimen.automatic_mesh())
          write_mesh_design(out, c.specimen);
      }
    return out.str();
  }
} // namespace indentsim::io

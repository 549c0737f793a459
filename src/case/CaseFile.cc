// YAML case files: parse -> fill defaults -> validate, and the resolved case written next to
// every run's results. See CaseFile.h for the rules (required keys, defaults, messages).
#include <indenter/IndenterFactory.h>
#include <indenter/ProfileTable.h>
#include <case/CaseFile.h>

#include "analysis/OliverPharr.h"
#include <materials/MaterialFactory.h>
#include <materials/Orientation.h>

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <system_error>
#include <vector>

namespace indentsim::io
{
  namespace
  {
    namespace fs = std::filesystem;

    // ------------------------------------------------------------------------------------------
    // The schema: allowed keys per section and allowed values of the enumerations.

    const std::vector<std::string> top_level_keys = {"test",     "compare_j2", "material",
                                                     "indenter", "specimen",   "loading",
                                                     "contact",  "solver",     "output"};

    // Sections and the maps nested in them ("material.elastic"), each with its allowed keys.
    const std::map<std::string, std::vector<std::string>> section_keys = {
      {"material",
       {"model", "young_modulus", "poisson_ratio", "yield_stress", "hardening_modulus",
        "yield_stress_measure", "lattice", "elastic", "hardening", "yield_exponent_n",
        "orientation"}},
      {"material.elastic", {"C11", "C12", "C44"}},
      {"material.hardening", {"tau0", "tau1", "theta0", "theta1", "q"}},
      {"material.orientation", {"euler_bunge_deg", "surface_normal", "reference_direction"}},
      {"indenter",
       {"shape", "a", "delta", "radius", "half_angle_deg", "tip_radius", "rotation_deg",
        "edge_radius", "file"}},
      {"specimen",
       {"size", "refined_region", "contact_elements", "symmetry", "f_bar", "elements_per_side",
        "grains", "seed"}},
      {"loading",
       {"control", "max_depth", "max_force", "steps", "unload", "unload_steps", "unload_points",
        "hold_steps",
        "cycles", "max_cutbacks", "max_strain"}},
      {"contact",
       {"friction_coefficient", "penalty", "penetration_tolerance", "max_augmentations"}},
      {"solver",
       {"residual_tolerance", "absolute_tolerance", "max_newton_iterations", "linear_solver",
        "threads"}},
      {"output", {"directory", "vtu_every", "experimental_curve", "checkpoint_interval_s"}}};

    const std::vector<std::string> allowed_tests = {"indentation", "tensile"};
    const std::vector<std::string> allowed_models = {"neo_hookean", "j2", "crystal"};
    const std::vector<std::string> allowed_lattices = {"fcc"};
    const std::vector<std::string> planned_lattices = {"bcc", "hcp"}; // recognised, not yet
    const std::vector<std::string> allowed_grains = {"single", "per_element"};
    const std::vector<std::string> allowed_linear_solvers = {"auto", "direct", "iterative"};
    const std::vector<std::string> allowed_orientation_kinds = {"euler_bunge_deg",
                                                                "surface_normal"};
    const std::vector<std::string> allowed_shapes = {"rounded_cone", "sphere",     "cone",
                                                     "vickers",      "berkovich",  "flat_punch",
                                                     "profile_table"};
    const std::vector<std::string> allowed_symmetries = {"full", "quarter"};
    const std::vector<std::string> allowed_controls = {"depth", "force"};
    const std::vector<std::string> allowed_yield_measures = {"cauchy", "kirchhoff"};

    // Successive halvings of a load increment beyond this leave increments of 1e-9 of the
    // original: more would only hide a model problem.
    constexpr unsigned int max_allowed_cutbacks = 30;

    // n <= 50 keeps (tau / tau_c)^(2n) of eq. 14 finite for every ratio tau / tau_c < 1000 that a
    // trial state may reach ((10^3)^100 = 10^300 < 1.8e308); the paper uses n = 10.
    constexpr double max_yield_exponent = 50;

    // The tensile cube has elements_per_side^3 cells; beyond this it would not fit in memory
    // (and n^3 would overflow the orientation count).
    constexpr unsigned int max_elements_per_side = 200;

    // ------------------------------------------------------------------------------------------
    // Formatting helpers.

    // Shortest text that reads back to the identical double, independent of the locale.
    std::string format_number(const double value)
    {
      std::array<char, 64> buffer{};
      const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
      return std::string(buffer.data(), result.ptr);
    }

    std::string format_triple(const std::array<double, 3> &values)
    {
      return "[" + format_number(values[0]) + ", " + format_number(values[1]) + ", " +
             format_number(values[2]) + "]";
    }

    std::string format_bool(const bool value) { return value ? "true" : "false"; }


    // Levenshtein distance, for "did you mean" suggestions.
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
                previous[j - 1] +
                (std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                     std::tolower(static_cast<unsigned char>(b[j - 1])) ?
                   0 :
                   1);
              current[j] = std::min({previous[j] + 1, current[j - 1] + 1, substitution});
            }
          std::swap(previous, current);
        }
      return previous[b.size()];
    }

    // The closest candidate if it is plausibly a typo of `word`, else "".
    std::string closest_match(const std::string &word, const std::vector<std::string> &candidates)
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

    std::string key_path(const std::string &section, const std::string &key)
    {
      return section.empty() ? key : section + "." + key;
    }

    // ------------------------------------------------------------------------------------------
    // Where each value came from, so that value checks after parsing can name the line.
    struct ValueOrigin
    {
      int         line = -1; // 0-based, as yaml-cpp counts
      std::string text;      // the value as written
    };
    using OriginMap = std::map<std::string, ValueOrigin>;

    [[noreturn]] void fail(const std::string &source, const int line, const std::string &message)
    {
      std::string location = source.empty() ? std::string("case file") : source;
      if (line >= 0)
        location += ":" + std::to_string(line + 1);
      throw CaseFileError(location + ": " + message);
    }

    // ------------------------------------------------------------------------------------------
    // Reads YAML nodes into a Case: structure (unknown, duplicate, missing keys) and types.
    // Value ranges are checked afterwards by validate(), which also serves validate_case().
    class CaseReader
    {
    public:
      explicit CaseReader(std::string source_name)
        : source(std::move(source_name))
      {}

      Case read(const YAML::Node &root)
      {
        Case result;
        result.source_file = source;

        if (root.IsDefined() && !root.IsNull() && !root.IsMap())
          fail(line_of(root),
               "the case file must be a mapping of keys (test, material, indenter, ...), got '" +
                 node_text(root) + "'");
        check_keys(root, "", top_level_keys);

        if (!read_string(root, "", "test", "the kind of test", result.test))
          fail(-1,
               "missing required key 'test' (allowed: " + join(allowed_tests, ", ") + ")");
        read_bool(root, "", "compare_j2", result.compare_j2);

        {
          const YAML::Node map = section(root, "material");
          auto &material = result.material;
          if (!read_string(map, "material", "model", "the material model", material.model))
            fail(line_of(map),
                 "missing required key 'material.model' (allowed: " + join(allowed_models) + ")");
          read_double(map, "material", "young_modulus", "E in GPa", material.young_modulus);
          read_double(map, "material", "poisson_ratio", "nu", material.poisson_ratio);
          read_double(map, "material", "yield_stress", "sigma_y0 in GPa", material.yield_stress);
          read_double(map, "material", "hardening_modulus", "H in GPa",
                      material.hardening_modulus);
          read_string(map, "material", "yield_stress_measure", "a stress measure",
                      material.yield_stress_measure);

          // Crystal plasticity (model: crystal); read for every model, used by crystal only.
          read_string(map, "material", "lattice", "a lattice", material.lattice);
          const YAML::Node elastic = subsection(map, "material", "elastic");
          read_double(elastic, "material.elastic", "C11", "C11 in GPa", material.C11);
          read_double(elastic, "material.elastic", "C12", "C12 in GPa", material.C12);
          read_double(elastic, "material.elastic", "C44", "C44 in GPa", material.C44);
          const YAML::Node hardening = subsection(map, "material", "hardening");
          read_double(hardening, "material.hardening", "tau0", "tau0 in GPa", material.tau0);
          read_double(hardening, "material.hardening", "tau1", "tau1 in GPa", material.tau1);
          read_double(hardening, "material.hardening", "theta0", "theta0 in GPa",
                      material.theta0);
          read_double(hardening, "material.hardening", "theta1", "theta1 in GPa",
                      material.theta1);
          read_double(hardening, "material.hardening", "q", "the latent hardening ratio q",
                      material.q);
          read_double(map, "material", "yield_exponent_n", "the exponent n of eq. 14",
                      material.yield_exponent_n);
          read_orientation(map, material.orientation);
        }
        {
          const YAML::Node map = section(root, "indenter");
          auto &indenter = result.indenter;
          read_string(map, "indenter", "shape", "an indenter shape", indenter.shape);
          read_double(map, "indenter", "a", "the slope parameter a", indenter.a);
          read_double(map, "indenter", "delta", "the tip rounding delta in um", indenter.delta);
          read_double(map, "indenter", "radius", "the radius in um", indenter.radius);
          read_double(map, "indenter", "half_angle_deg", "the cone half-angle in degrees",
                      indenter.half_angle_deg);
          read_double(map, "indenter", "tip_radius", "the tip radius in um", indenter.tip_radius);
          read_double(map, "indenter", "rotation_deg", "an angle in degrees",
                      indenter.rotation_deg);
          read_double(map, "indenter", "edge_radius", "the edge radius in um",
                      indenter.edge_radius);
          if (read_string(map, "indenter", "file", "the path of a CSV profile table",
                          indenter.file))
            indenter.file = relative_to_case_file(indenter.file);
        }
        {
          const YAML::Node map = section(root, "specimen");
          auto &specimen = result.specimen;
          read_triple(map, "specimen", "size", specimen.size);
          read_triple(map, "specimen", "refined_region", specimen.refined_region);
          read_unsigned(map, "specimen", "contact_elements", specimen.contact_elements);
          read_string(map, "specimen", "symmetry", "a symmetry", specimen.symmetry);
          // F-bar by default for plasticity (isochoric flow locks plain hexahedra), plain
          // displacement element by default for hyperelasticity.
          if (!read_bool(map, "specimen", "f_bar", specimen.f_bar))
            specimen.f_bar =
              (result.material.model == "j2" || result.material.model == "crystal");
          read_unsigned(map, "specimen", "elements_per_side", specimen.elements_per_side);
          read_string(map, "specimen", "grains", "a grain layout", specimen.grains);
          read_unsigned(map, "specimen", "seed", specimen.seed);
        }
        {
          const YAML::Node map = section(root, "loading");
          auto &loading = result.loading;
          read_string(map, "loading", "control", "a loading control", loading.control);
          read_double(map, "loading", "max_depth", "a depth in um", loading.max_depth);
          read_double(map, "loading", "max_force", "a force in mN", loading.max_force);
          read_unsigned(map, "loading", "steps", loading.steps);
          read_bool(map, "loading", "unload", loading.unload);
          read_unsigned(map, "loading", "unload_steps", loading.unload_steps);
          read_unsigned(map, "loading", "unload_points", loading.unload_points);
          read_unsigned(map, "loading", "hold_steps", loading.hold_steps);
          read_unsigned(map, "loading", "cycles", loading.cycles);
          read_unsigned(map, "loading", "max_cutbacks", loading.max_cutbacks);
          read_double(map, "loading", "max_strain", "a logarithmic strain", loading.max_strain);
        }
        {
          const YAML::Node map = section(root, "contact");
          auto &contact = result.contact;
          read_double(map, "contact", "friction_coefficient", "the Coulomb coefficient mu",
                      contact.friction_coefficient);
          read_double(map, "contact", "penalty", "a penalty in GPa/um", contact.penalty);
          read_double(map, "contact", "penetration_tolerance", "a length in um",
                      contact.penetration_tolerance);
          read_unsigned(map, "contact", "max_augmentations", contact.max_augmentations);
        }
        {
          const YAML::Node map = section(root, "solver");
          auto &solver = result.solver;
          read_double(map, "solver", "residual_tolerance", "a relative tolerance",
                      solver.residual_tolerance);
          read_double(map, "solver", "absolute_tolerance", "a force in mN",
                      solver.absolute_tolerance);
          read_unsigned(map, "solver", "max_newton_iterations", solver.max_newton_iterations);
          read_string(map, "solver", "linear_solver", "a linear solver", solver.linear_solver);
          read_unsigned(map, "solver", "threads", solver.threads);
        }
        {
          const YAML::Node map = section(root, "output");
          auto &output = result.output;
          read_string(map, "output", "directory", "a directory path", output.directory);
          read_unsigned(map, "output", "vtu_every", output.vtu_every);
          if (read_string(map, "output", "experimental_curve",
                          "the path of a CSV with depth and force columns",
                          output.experimental_curve))
            output.experimental_curve = relative_to_case_file(output.experimental_curve);
          read_double(map, "output", "checkpoint_interval_s", "a wall time in s",
                      output.checkpoint_interval_s);
        }
        return result;
      }

      const OriginMap &origins() const { return value_origins; }

    private:
      std::string source;
      OriginMap   value_origins;

      static int line_of(const YAML::Node &node)
      {
        if (!node.IsDefined())
          return -1;
        const YAML::Mark mark = node.Mark();
        return mark.is_null() ? -1 : mark.line;
      }

      [[noreturn]] void fail(const int line, const std::string &message) const
      {
        io::fail(source, line, message);
      }

      // Unknown and duplicate keys at one level; `section_name` is "" for the top level.
      void check_keys(const YAML::Node                &map,
                      const std::string               &section_name,
                      const std::vector<std::string>  &allowed) const
      {
        if (!map.IsDefined() || !map.IsMap())
          return;
        std::map<std::string, int> seen;
        for (const auto &entry : map)
          {
            const int line = line_of(entry.first);
            if (!entry.first.IsScalar())
              fail(line,
                   "key '" + node_text(entry.first) + "'" +
                     (section_name.empty() ? "" : " in '" + section_name + "'") +
                     " is not a plain name; allowed keys: " + join(allowed));
            const std::string key = entry.first.Scalar();
            const std::string path = key_path(section_name, key);
            if (const auto previous = seen.find(key); previous != seen.end())
              fail(line,
                   "duplicate key '" + path + "' (first given on line " +
                     std::to_string(previous->second + 1) + "); give each key once");
            seen.emplace(key, line);

            if (std::find(allowed.begin(), allowed.end(), key) != allowed.end())
              continue;

            std::string hint;
            // A known key placed in the wrong section is the likeliest mistake.
            for (const auto &[other_section, other_keys] : section_keys)
              if (other_section != section_name &&
                  std::find(other_keys.begin(), other_keys.end(), key) != other_keys.end())
                {
                  hint = "; did you mean '" + other_section + "." + key + "' (under '" +
                         other_section + ":')?";
                  break;
                }
            if (hint.empty())
              if (const std::string guess = closest_match(key, allowed); !guess.empty())
                hint = "; did you mean '" + key_path(section_name, guess) + "'?";
            fail(line,
                 "unknown key '" + path + "'" + (hint.empty() ? std::string(".") : hint) +
                   " Allowed keys " +
                   (section_name.empty() ? std::string("at the top level") :
                                           "in '" + section_name + "'") +
                   ": " + join(allowed) + ".");
          }
      }

      // A section map; an absent or empty (null) section gives an undefined node: all defaults.
      YAML::Node section(const YAML::Node &root, const std::string &name) const
      {
        if (!root.IsDefined() || !root.IsMap())
          return YAML::Node(YAML::NodeType::Undefined);
        const YAML::Node node = root[name];
        if (!node.IsDefined() || node.IsNull())
          return YAML::Node(YAML::NodeType::Undefined);
        if (!node.IsMap())
          fail(line_of(node),
               "'" + name + "' = " + node_text(node) +
                 ": expected a mapping of keys (allowed: " + join(section_keys.at(name)) + ")");
        check_keys(node, name, section_keys.at(name));
        return node;
      }

      // A map nested in a section (e.g. material.elastic), read like a section.
      YAML::Node subsection(const YAML::Node  &parent,
                            const std::string &parent_name,
                            const std::string &key)
      {
        const YAML::Node node = value_node(parent, parent_name, key);
        const std::string path = key_path(parent_name, key);
        if (!node.IsDefined() || node.IsNull())
          return YAML::Node(YAML::NodeType::Undefined);
        if (!node.IsMap())
          fail(line_of(node),
               path + " = " + node_text(node) + ": expected a mapping of keys (allowed: " +
                 join(section_keys.at(path)) + ")");
        check_keys(node, path, section_keys.at(path));
        return node;
      }

      // material.orientation: exactly one of euler_bunge_deg or surface_normal (which needs
      // reference_direction: the in-plane direction is never guessed). Absent: the default
      // Euler angles (0, 0, 0).
      void read_orientation(const YAML::Node &material_map, OrientationParameters &orientation)
      {
        const std::string path = "material.orientation";
        const YAML::Node  node = subsection(material_map, "material", "orientation");
        if (!node.IsDefined())
          return;
        const bool has_euler = node["euler_bunge_deg"].IsDefined();
        const bool has_normal = node["surface_normal"].IsDefined();
        const bool has_reference = node["reference_direction"].IsDefined();
        const std::string shown = path + " = " + node_text(node) + ": ";
        const std::string either =
          "give exactly one of euler_bunge_deg: [phi1, Phi, phi2] (degrees) or "
          "surface_normal: [h, k, l] together with reference_direction: [u, v, w]";
        if (has_euler && (has_normal || has_reference))
          fail(line_of(node), shown + "both Euler angles and a surface normal given; " + either);
        if (!has_euler && !has_normal && !has_reference)
          fail(line_of(node), shown + "no orientation given; " + either);
        if (has_normal && !has_reference)
          fail(line_of(node),
               shown + "surface_normal needs reference_direction, the crystal direction [u, v, "
                       "w] along the sample x axis (perpendicular to the normal, e.g. [1, -1, "
                       "0] for [1, 1, 1]); it is not guessed");
        if (has_reference && !has_normal)
          fail(line_of(node),
               shown + "reference_direction is only used with surface_normal; " + either);

        if (has_euler)
          {
            orientation.kind = "euler_bunge_deg";
            read_triple(node, path, "euler_bunge_deg", orientation.euler_bunge_deg,
                        "[phi1, Phi, phi2] in degrees", "degrees");
          }
        else
          {
            orientation.kind = "surface_normal";
            read_triple(node, path, "surface_normal", orientation.surface_normal,
                        "[h, k, l], a crystal direction", "a Miller index");
            read_triple(node, path, "reference_direction", orientation.reference_direction,
                        "[u, v, w], a crystal direction", "a Miller index");
          }
      }

      // A path given relative to the case file's directory, made absolute (the resolved case
      // is written elsewhere and must still find the file).
      std::string relative_to_case_file(const std::string &path) const
      {
        if (path.empty())
          return path;
        fs::path resolved(path);
        if (resolved.is_relative())
          resolved = fs::path(source).parent_path() / resolved;
        std::error_code error;
        const fs::path absolute = fs::absolute(resolved, error);
        return (error ? resolved : absolute).lexically_normal().string();
      }

      // The value node of `key`, or an undefined node if the key is absent.
      YAML::Node value_node(const YAML::Node  &map,
                            const std::string &section_name,
                            const std::string &key)
      {
        if (!map.IsDefined() || !map.IsMap())
          return YAML::Node(YAML::NodeType::Undefined);
        const YAML::Node node = map[key];
        if (node.IsDefined())
          value_origins[key_path(section_name, key)] = {line_of(node), node_text(node)};
        return node;
      }

      bool read_double(const YAML::Node  &map,
                       const std::string &section_name,
                       const std::string &key,
                       const std::string &meaning,
                       double            &value)
      {
        const YAML::Node node = value_node(map, section_name, key);
        if (!node.IsDefined())
          return false;
        value = parse_double(node, key_path(section_name, key), meaning);
        return true;
      }

      double parse_double(const YAML::Node  &node,
                          const std::string &path,
                          const std::string &meaning) const
      {
        const std::string expected = "expected a number (" + meaning + ")";
        if (node.IsNull())
          fail(line_of(node), path + " has no value; " + expected);
        if (!node.IsScalar())
          fail(line_of(node), path + " = " + node_text(node) + ": " + expected);
        std::string text = node.Scalar();
        const std::size_t start = (!text.empty() && text[0] == '+') ? 1 : 0;
        double            value = 0.;
        const auto        result =
          std::from_chars(text.data() + start, text.data() + text.size(), value);
        if (result.ec != std::errc() || result.ptr != text.data() + text.size() ||
            !std::isfinite(value))
          fail(line_of(node), path + " = \"" + text + "\": " + expected);
        return value;
      }

      bool read_unsigned(const YAML::Node  &map,
                         const std::string &section_name,
                         const std::string &key,
                         unsigned int      &value)
      {
        const YAML::Node node = value_node(map, section_name, key);
        if (!node.IsDefined())
          return false;
        const std::string path = key_path(section_name, key);
        const std::string expected = "expected a non-negative whole number";
        if (node.IsNull())
          fail(line_of(node), path + " has no value; " + expected);
        if (!node.IsScalar())
          fail(line_of(node), path + " = " + node_text(node) + ": " + expected);
        const std::string text = node.Scalar();
        if (!text.empty() && text[0] == '-')
          fail(line_of(node), path + " = " + text + ": negative; " + expected);
        const std::size_t  start = (!text.empty() && text[0] == '+') ? 1 : 0;
        unsigned long long parsed = 0;
        const auto         result =
          std::from_chars(text.data() + start, text.data() + text.size(), parsed);
        if (result.ec == std::errc::result_out_of_range ||
            (result.ec == std::errc() && parsed > std::numeric_limits<unsigned int>::max()))
          fail(line_of(node), path + " = " + text + ": too large; " + expected);
        if (result.ec != std::errc() || result.ptr != text.data() + text.size() ||
            start == text.size())
          fail(line_of(node), path + " = \"" + text + "\": " + expected);
        value = static_cast<unsigned int>(parsed);
        return true;
      }

      bool read_bool(const YAML::Node  &map,
                     const std::string &section_name,
                     const std::string &key,
                     bool              &value)
      {
        const YAML::Node node = value_node(map, section_name, key);
        if (!node.IsDefined())
          return false;
        const std::string path = key_path(section_name, key);
        const std::string expected = "expected true or false";
        if (node.IsNull())
          fail(line_of(node), path + " has no value; " + expected);
        if (!node.IsScalar())
          fail(line_of(node), path + " = " + node_text(node) + ": " + expected);
        try
          {
            value = node.as<bool>();
          }
        catch (const YAML::Exception &)
          {
            fail(line_of(node), path + " = \"" + node.Scalar() + "\": " + expected);
          }
        return true;
      }

      bool read_string(const YAML::Node  &map,
                       const std::string &section_name,
                       const std::string &key,
                       const std::string &meaning,
                       std::string       &value)
      {
        const YAML::Node node = value_node(map, section_name, key);
        if (!node.IsDefined())
          return false;
        const std::string path = key_path(section_name, key);
        if (node.IsNull())
          fail(line_of(node), path + " has no value; expected " + meaning);
        if (!node.IsScalar())
          fail(line_of(node),
               path + " = " + node_text(node) + ": expected " + meaning + " (a single word)");
        value = node.Scalar();
        return true;
      }

      void read_triple(const YAML::Node       &map,
                       const std::string      &section_name,
                       const std::string      &key,
                       std::array<double, 3>  &values,
                       const std::string      &description = "[x, y, z] in um",
                       const std::string      &unit = "um")
      {
        const YAML::Node node = value_node(map, section_name, key);
        if (!node.IsDefined())
          return;
        const std::string path = key_path(section_name, key);
        const std::string expected = "expected a list of 3 numbers " + description;
        if (!node.IsSequence())
          fail(line_of(node), path + " = " + node_text(node) + ": " + expected);
        if (node.size() != 3)
          fail(line_of(node),
               path + " = " + node_text(node) + ": " + expected + ", got " +
                 std::to_string(node.size()) + " entries");
        for (std::size_t i = 0; i < 3; ++i)
          values[i] = parse_double(node[i], path + "[" + std::to_string(i) + "]", unit);
      }
    };

    // ------------------------------------------------------------------------------------------
    // Value checks, shared by read_case_file (with line numbers) and validate_case.
    class CaseValidator
    {
    public:
      // `origins` is null for a case that was not read from a file.
      CaseValidator(const Case &checked_case, const OriginMap *origins)
        : checked(checked_case)
        , value_origins(origins)
      {}

      void validate() const
      {
        const auto &m = checked.material;
        const auto &s = checked.specimen;
        const auto &l = checked.loading;
        const auto &c = checked.contact;
        const auto &sol = checked.solver;
        const auto &o = checked.output;

        check_choice("test", checked.test, allowed_tests);
        const bool tensile = (checked.test == "tensile");
        if (checked.compare_j2 && !tensile)
          reject("compare_j2", format_bool(checked.compare_j2),
                 "only the tensile test can repeat the run with J2 (test: tensile); the "
                 "indentation test compares models through separate case files");

        check_choice("material.model", m.model, allowed_models);
        if (!(m.young_modulus > 0.))
          reject("material.young_modulus", format_number(m.young_modulus),
                 "Young's modulus E must be > 0 GPa");
        if (!(m.poisson_ratio > -1. && m.poisson_ratio < 0.5))
          reject("material.poisson_ratio", format_number(m.poisson_ratio),
                 "Poisson's ratio must satisfy -1 < nu < 0.5 (0.5 is incompressible, which a "
                 "displacement formulation cannot represent)");
        if (!(m.yield_stress > 0.))
          reject("material.yield_stress", format_number(m.yield_stress),
                 "the initial yield stress sigma_y0 must be > 0 GPa");
        if (!(m.hardening_modulus >= 0.))
          reject("material.hardening_modulus", format_number(m.hardening_modulus),
                 "the hardening modulus H must be >= 0 GPa (0: perfect plasticity)");
        check_choice("material.yield_stress_measure", m.yield_stress_measure,
                     allowed_yield_measures);
        validate_crystal_parameters();

        const std::unique_ptr<indenter::IndenterSurface> surface = validate_indenter();

        static const char *axis_names[3] = {"x", "y", "z"};
        for (unsigned int d = 0; d < 3; ++d)
          if (!(s.size[d] > 0.))
            reject("specimen.size", format_triple(s.size),
                   std::string("every edge length must be > 0 um; the ") + axis_names[d] +
                     " entry is not");
        for (unsigned int d = 0; d < 3; ++d)
          if (!(s.refined_region[d] > 0.))
            reject("specimen.refined_region", format_triple(s.refined_region),
                   std::string("every edge length must be > 0 um; the ") + axis_names[d] +
                     " entry is not");
        for (unsigned int d = 0; d < 3; ++d)
          if (s.refined_region[d] > s.size[d])
            reject("specimen.refined_region", format_triple(s.refined_region),
                   std::string("the refined region must fit inside the specimen: its ") +
                     axis_names[d] + " extent " + format_number(s.refined_region[d]) +
                     " um exceeds specimen.size = " + format_triple(s.size));
        if (s.contact_elements < 4 || s.contact_elements % 4 != 0)
          reject("specimen.contact_elements", std::to_string(s.contact_elements),
                 "N must be a positive multiple of 4 (4, 8, 12, 16, ...) so that the mesh can be "
                 "built: the 2:1 coarsening around the refined region needs N/2 even, and with "
                 "symmetry: quarter the modelled N/2 x N/2 faces must be even as well; a "
                 "multiple of 4 satisfies both");
        check_choice("specimen.symmetry", s.symmetry, allowed_symmetries);
        if (!tensile && s.symmetry == "quarter" && !surface->mirror_symmetric_about_xz_and_yz())
          reject_quarter_symmetry_of_the_indenter();
        if (m.model == "crystal" && !tensile && s.symmetry == "quarter")
          check_quarter_symmetry_of_the_lattice();
        if (s.elements_per_side < 1 || s.elements_per_side > max_elements_per_side)
          reject("specimen.elements_per_side", std::to_string(s.elements_per_side),
                 "the tensile cube has n x n x n elements of 1 um; n must satisfy 1 <= n <= " +
                   std::to_string(max_elements_per_side));
        check_choice("specimen.grains", s.grains, allowed_grains);
        if (s.grains == "per_element" && !tensile)
          reject("specimen.grains", s.grains,
                 "a random orientation per element is only implemented for test: tensile; the "
                 "indentation test models a single crystal (use grains: single)");

        if (!(l.max_depth > 0.))
          reject("loading.max_depth", format_number(l.max_depth), "must be > 0 um");
        if (!(l.max_depth < s.refined_region[2]))
          reject("loading.max_depth", format_number(l.max_depth),
                 "must be smaller than the depth of the refined region, specimen.refined_region"
                 "[2] = " +
                   format_number(s.refined_region[2]) + " um");
        check_choice("loading.control", l.control, allowed_controls);
        if (l.control == "force")
          {
            if (tensile)
              reject("loading.control", l.control,
                     "force control is implemented for the indentation test only");
            if (!(l.max_force > 0.))
              reject("loading.max_force", format_number(l.max_force),
                     "force control needs the maximum indenter force, > 0 mN");
          }
        else if (l.max_force != 0.)
          reject("loading.max_force", format_number(l.max_force),
                 "is the target of force control; with loading.control: depth the maximum is "
                 "loading.max_depth (remove max_force or set control: force)");
        if (l.steps == 0)
          reject("loading.steps", "0", "must be >= 1");
        if (l.cycles == 0 || l.cycles > 1000)
          reject("loading.cycles", std::to_string(l.cycles), "must satisfy 1 <= cycles <= 1000");
        if (l.cycles > 1 && !l.unload)
          reject("loading.cycles", std::to_string(l.cycles),
                 "several load-unload cycles need loading.unload: true");
        if (l.unload_points > 10000)
          reject("loading.unload_points", std::to_string(l.unload_points),
                 "must satisfy 0 <= unload_points <= 10000 (0: uniform depth steps)");
        if (l.max_cutbacks > max_allowed_cutbacks)
          reject("loading.max_cutbacks", std::to_string(l.max_cutbacks),
                 "must be <= " + std::to_string(max_allowed_cutbacks));
        if (!(l.max_strain > 0. && l.max_strain <= 1.))
          reject("loading.max_strain", format_number(l.max_strain),
                 "the final logarithmic strain of the tensile test must satisfy 0 < strain <= 1");

        // Measured indenter-metal coefficients lie below 0.5; 2 leaves room for studies without
        // admitting a typo (e.g. 10 for 0.10).
        if (!(c.friction_coefficient >= 0. && c.friction_coefficient <= 2.))
          reject("contact.friction_coefficient", format_number(c.friction_coefficient),
                 "the Coulomb coefficient mu must satisfy 0 <= mu <= 2 (0: frictionless)");
        if (!(c.penalty >= 0.))
          reject("contact.penalty", format_number(c.penalty),
                 "must be >= 0 GPa/um (0: chosen automatically)");
        if (!(c.penetration_tolerance > 0.))
          reject("contact.penetration_tolerance", format_number(c.penetration_tolerance),
                 "must be > 0 um");
        if (c.max_augmentations == 0)
          reject("contact.max_augmentations", "0", "must be >= 1");

        if (!(sol.residual_tolerance > 0. && sol.residual_tolerance < 1.))
          reject("solver.residual_tolerance", format_number(sol.residual_tolerance),
                 "must satisfy 0 < tolerance < 1 (relative to the first residual)");
        if (!(sol.absolute_tolerance > 0.))
          reject("solver.absolute_tolerance", format_number(sol.absolute_tolerance),
                 "must be > 0 mN");
        if (sol.max_newton_iterations == 0)
          reject("solver.max_newton_iterations", "0", "must be >= 1");
        check_choice("solver.linear_solver", sol.linear_solver, allowed_linear_solvers);
        if (sol.threads > 1024)
          reject("solver.threads", std::to_string(sol.threads),
                 "must be between 0 (automatic) and 1024");

        if (o.directory.empty())
          reject("output.directory", "\"\"", "must be a non-empty directory path");
        if (!o.experimental_curve.empty())
          {
            if (checked.test != "indentation")
              reject("output.experimental_curve", "\"" + o.experimental_curve + "\"",
                     "a measured load-penetration curve belongs to test: indentation");
            try
              {
                const analysis::LoadCurve curve =
                  analysis::read_load_curve_csv(o.experimental_curve);
                if (curve.depth.size() < 2)
                  throw std::invalid_argument("it has fewer than 2 data rows");
              }
            catch (const std::invalid_argument &error)
              {
                reject("output.experimental_curve", "\"" + o.experimental_curve + "\"",
                       std::string(error.what()) +
                         " (a CSV with a header; depth and force columns with their units in "
                         "the names, e.g. depth_nm,load_uN)");
              }
          }
        if (!(o.checkpoint_interval_s >= 0) || !std::isfinite(o.checkpoint_interval_s))
          reject("output.checkpoint_interval_s", format_number(o.checkpoint_interval_s),
                 "must be a wall time >= 0 s (0: checkpoint only when stopped)");
      }

    private:
      const Case      &checked;
      const OriginMap *value_origins;

      // The first of `paths` that the case file gave explicitly, else the first: a check on a
      // pair of values then points at the line the user wrote.
      std::string given_or_first(std::initializer_list<std::string> paths) const
      {
        if (value_origins != nullptr)
          for (const auto &path : paths)
            if (value_origins->count(path) > 0)
              return path;
        return *paths.begin();
      }

      // Keys of the indenter. Like the crystal keys, every key is checked for every shape (the
      // resolved case always holds them) but used only by its shapes; the profile table file is
      // read only for shape: profile_table. Returns the indenter, built as the run will build it.
      std::unique_ptr<indenter::IndenterSurface> validate_indenter() const
      {
        const auto &ind = checked.indenter;
        check_choice("indenter.shape", ind.shape, allowed_shapes);
        if (!(ind.a > 0.))
          reject("indenter.a", format_number(ind.a),
                 "the slope parameter a (tan of the cone half-angle) must be > 0");
        if (!(ind.delta >= 0.))
          reject("indenter.delta", format_number(ind.delta),
                 "the tip rounding delta must be >= 0 um (0: sharp cone)");
        if (!(ind.radius > 0.) || !std::isfinite(ind.radius))
          reject("indenter.radius", format_number(ind.radius),
                 "the radius of the sphere or of the flat punch must be > 0 um");
        if (!(ind.half_angle_deg > 0. && ind.half_angle_deg < 90.))
          reject("indenter.half_angle_deg", format_number(ind.half_angle_deg),
                 "the cone half-angle (between flank and axis) must satisfy 0 < alpha < 90 deg "
                 "(70.3: the area function 24.5 h^2 of the Vickers and Berkovich pyramids)");
        if (!(ind.tip_radius >= 0.) || !std::isfinite(ind.tip_radius))
          reject("indenter.tip_radius", format_number(ind.tip_radius),
                 "the tip radius of the cone or pyramid must be >= 0 um (0: sharp)");
        if (!std::isfinite(ind.rotation_deg))
          reject("indenter.rotation_deg", format_number(ind.rotation_deg),
                 "the rotation about the indentation axis must be a finite angle in degrees");
        if (!(ind.edge_radius >= 0. && ind.edge_radius <= ind.radius))
          reject(given_or_first({"indenter.edge_radius", "indenter.radius"}),
                 "edge_radius = " + format_number(ind.edge_radius) +
                   ", radius = " + format_number(ind.radius),
                 "the rim rounding of the flat punch must satisfy 0 <= edge_radius <= radius "
                 "(um; 0: a sharp rim)");
        if (ind.shape == "profile_table" && ind.file.empty())
          reject("indenter.file", "\"\"",
                 "shape: profile_table needs the table: file: a CSV path (relative to the case "
                 "file's directory) with the header r_um,z_um (profile) or depth_um,area_um2 "
                 "(area function)");
        try
          {
            return indenter::create_indenter(ind);
          }
        catch (const indenter::ProfileTableError &error)
          {
            reject("indenter.file", "\"" + ind.file + "\"", error.what());
          }
        catch (const std::invalid_argument &error)
          {
            reject("indenter.shape", ind.shape, error.what());
          }
      }

      // The quarter model imposes u_x = 0 on x = 0 and u_y = 0 on y = 0, exact only if both are
      // mirror planes of the indenter (IndenterSurface::mirror_symmetric_about_xz_and_yz).
      [[noreturn]] void reject_quarter_symmetry_of_the_indenter() const
      {
        const auto &ind = checked.indenter;
        std::string shape = "indenter.shape = " + ind.shape;
        std::string advice = "use symmetry: full";
        if (ind.shape == "vickers")
          {
            shape += " with rotation_deg = " + format_number(ind.rotation_deg);
            advice = "a Vickers pyramid has them when rotation_deg is a multiple of 45; use "
                     "rotation_deg: 0 (faces towards +-x, +-y) or 45 (edges along x and y), or "
                     "symmetry: full";
          }
        else if (ind.shape == "berkovich")
          advice = "a three-sided pyramid never has two perpendicular mirror planes; use "
                   "symmetry: full";
        reject("specimen.symmetry", checked.specimen.symmetry,
               "the quarter model (u_x = 0 on x = 0, u_y = 0 on y = 0) needs the planes x = 0 "
               "and y = 0 to be mirror planes of the indenter, and " + shape +
                 " is not mirror-symmetric about both; " + advice);
      }

      // Keys of the crystal model. They are checked for every model (the resolved case always
      // holds them), but only model: crystal uses them.
      void validate_crystal_parameters() const
      {
        const auto &m = checked.material;
        if (std::find(planned_lattices.begin(), planned_lattices.end(), m.lattice) !=
            planned_lattices.end())
          reject("material.lattice", "'" + m.lattice + "'",
                 "only fcc ({111}<110>, 12 slip systems) is implemented; bcc and hcp are not "
                 "yet");
        check_choice("material.lattice", m.lattice, allowed_lattices);

        // Cubic stiffness positive definite: eigenvalues C11 + 2 C12 (dilatation), C11 - C12
        // (tetragonal shear) and C44 (shear).
        const std::string constants = "(C11 = " + format_number(m.C11) +
                                      ", C12 = " + format_number(m.C12) +
                                      ", C44 = " + format_number(m.C44) + " GPa)";
        if (!(m.C44 > 0.))
          reject("material.elastic.C44", format_number(m.C44),
                 "the cubic stiffness must be positive definite: C44 > 0 GPa " + constants);
        if (!(m.C11 - m.C12 > 0.))
          {
            const std::string path =
              given_or_first({"material.elastic.C12", "material.elastic.C11"});
            reject(path, format_number(path == "material.elastic.C11" ? m.C11 : m.C12),
                   "the cubic stiffness must be positive definite: C11 - C12 > 0 " + constants);
          }
        if (!(m.C11 + 2. * m.C12 > 0.))
          {
            const std::string path =
              given_or_first({"material.elastic.C12", "material.elastic.C11"});
            reject(path, format_number(path == "material.elastic.C11" ? m.C11 : m.C12),
                   "the cubic stiffness must be positive definite: C11 + 2 C12 > 0 (a positive "
                   "bulk modulus) " + constants);
          }

        if (!(m.tau0 > 0.))
          reject("material.hardening.tau0", format_number(m.tau0),
                 "the initial critical resolved shear stress tau0 must be > 0 GPa");
        if (!(m.tau1 >= 0.))
          reject("material.hardening.tau1", format_number(m.tau1), "must be >= 0 GPa");
        if (!(m.theta0 >= 0.))
          reject("material.hardening.theta0", format_number(m.theta0), "must be >= 0 GPa");
        if (!(m.theta1 >= 0.))
          reject("material.hardening.theta1", format_number(m.theta1), "must be >= 0 GPa");
        if (m.theta0 > 0. && !(m.tau1 > 0.))
          reject(given_or_first({"material.hardening.tau1", "material.hardening.theta0"}),
                 "tau1 = " + format_number(m.tau1) + ", theta0 = " + format_number(m.theta0),
                 "tau1 must be > 0 when theta0 > 0: the Voce law tau_c = tau0 + (tau1 + theta1 "
                 "Gamma)(1 - exp(-theta0 Gamma / tau1)) divides by tau1 (for linear hardening "
                 "set theta0 = 0 and use theta1)");
        if (!(m.q >= 0.))
          reject("material.hardening.q", format_number(m.q),
                 "the latent hardening ratio q must be >= 0 (1: isotropic hardening)");
        if (!(m.yield_exponent_n >= 1. && m.yield_exponent_n <= max_yield_exponent))
          reject("material.yield_exponent_n", format_number(m.yield_exponent_n),
                 "n (exponent 2n in eq. 14) must satisfy 1 <= n <= " +
                   format_number(max_yield_exponent) +
                   " (a real number; larger n makes (tau/tau_c)^(2n) overflow)");

        const auto &o = m.orientation;
        check_choice("material.orientation.kind", o.kind, allowed_orientation_kinds);
        try
          {
            materials::create_orientation(o);
          }
        catch (const std::invalid_argument &error)
          {
            const std::string what = error.what();
            if (o.kind == "euler_bunge_deg")
              reject("material.orientation.euler_bunge_deg", format_triple(o.euler_bunge_deg),
                     what);
            else if (what.rfind("reference_direction", 0) == 0)
              reject("material.orientation.reference_direction",
                     format_triple(o.reference_direction), what);
            else
              reject("material.orientation.surface_normal", format_triple(o.surface_normal),
                     what);
          }
      }

      // The quarter model imposes u_x = 0 on x = 0 and u_y = 0 on y = 0; for a crystal that is
      // exact only if both planes are mirror planes of the lattice (m-3m point group).
      void check_quarter_symmetry_of_the_lattice() const
      {
        const auto &o = checked.material.orientation;
        const dealii::Tensor<2, 3> g = materials::create_orientation(o);
        const dealii::Tensor<1, 3> e_x({1., 0., 0.}), e_y({0., 1., 0.});
        const bool x_mirror = materials::is_cubic_mirror_plane(g, e_x);
        const bool y_mirror = materials::is_cubic_mirror_plane(g, e_y);
        if (x_mirror && y_mirror)
          return;
        const std::string orientation =
          o.kind == "surface_normal" ?
            "material.orientation: surface_normal " + format_triple(o.surface_normal) +
              ", reference_direction " + format_triple(o.reference_direction) :
            "material.orientation: euler_bunge_deg " + format_triple(o.euler_bunge_deg);
        reject("specimen.symmetry", checked.specimen.symmetry,
               "the quarter model needs the sample planes x = 0 and y = 0 to be mirror planes "
               "of the cubic lattice, but for " + orientation + " the plane " +
                 (x_mirror ? "y = 0" : (y_mirror ? "x = 0" : "x = 0 (and y = 0)")) +
                 " is not one (e.g. a (111) surface has no two perpendicular mirror planes); "
                 "use symmetry: full");
      }

      [[noreturn]] void reject(const std::string &path,
                               const std::string &value,
                               const std::string &what) const
      {
        int         line = -1;
        std::string shown = value;
        if (value_origins != nullptr)
          {
            if (const auto origin = value_origins->find(path); origin != value_origins->end())
              line = origin->second.line;
            else
              shown += " (default)";
          }
        fail(checked.source_file, line, path + " = " + shown + ": " + what);
      }

      void check_choice(const std::string              &path,
                        const std::string              &value,
                        const std::vector<std::string> &allowed) const
      {
        if (std::find(allowed.begin(), allowed.end(), value) != allowed.end())
          return;
        std::string message = "unknown value; allowed: " + join(allowed, " | ");
        if (const std::string guess = closest_match(value, allowed); !guess.empty())
          message += " (did you mean '" + guess + "'?)";
        reject(path, "'" + value + "'", message);
      }
    };

    // The output-directory entries that belong to an earlier run.
    bool is_known_output_file(const fs::path &path)
    {
      const std::string name = path.filename().string();
      for (const char *known : output_files::known_names)
        if (name == known)
          return true;
      if (name.rfind(output_files::paraview_basename, 0) == 0)
        for (const char *extension : output_files::paraview_extensions)
          if (path.extension() == extension)
            return true;
      return false;
    }

    std::vector<fs::path> earlier_results(const fs::path &directory)
    {
      std::vector<fs::path> found;
      std::error_code       error;
      for (const auto &entry : fs::directory_iterator(directory, error))
        if ((entry.is_regular_file(error) && is_known_output_file(entry.path())) ||
            (entry.is_directory(error) &&
             entry.path().filename() == output_files::checkpoint_directory))
          found.push_back(entry.path());
      std::sort(found.begin(), found.end());
      return found;
    }
  } // namespace

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

  // --------------------------------------------------------------------------------------------

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

    CaseReader reader(source_name);
    Case       result;
    try
      {
        result = reader.read(root);
      }
    catch (const YAML::Exception &error)
      {
        // yaml-cpp reports structural problems (e.g. an invalid node) as exceptions.
        fail(source_name, error.mark.is_null() ? -1 : error.mark.line, error.msg);
      }
    CaseValidator(result, &reader.origins()).validate();
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
    CaseValidator(resolved_case, nullptr).validate();
  }

  std::string resolved_case_yaml(const Case &resolved_case)
  {
    // Strings that the user chose freely are quoted by yaml-cpp; enumerations are plain words.
    const auto quoted = [](const std::string &text) {
      YAML::Emitter emitter;
      emitter << YAML::DoubleQuoted << text;
      return std::string(emitter.c_str());
    };

    std::ostringstream out;
    // One "key: value   # comment" line, comments aligned.
    const auto line = [&out](const std::string &indent_key_value, const std::string &comment) {
      constexpr std::size_t comment_column = 36;
      out << indent_key_value;
      if (!comment.empty())
        {
          const std::size_t width = indent_key_value.size();
          out << std::string(width < comment_column ? comment_column - width : 1, ' ') << "# "
              << comment;
        }
      out << '\n';
    };

    const Case &c = resolved_case;
    out << "# indentsim resolved case: every key with its default filled in.\n"
        << "# Units: lengths um, forces mN, stresses and moduli GPa (1 GPa*um^2 = 1 mN).\n";
    if (!c.source_file.empty())
      out << "# Read from: " << c.source_file << '\n';
    line("test: " + c.test, "indentation | tensile");
    line("compare_j2: " + format_bool(c.compare_j2),
         "tensile: also run J2 (young_modulus...) on the same mesh");

    out << "material:\n";
    line("  model: " + c.material.model, "neo_hookean | j2 | crystal");
    line("  young_modulus: " + format_number(c.material.young_modulus), "E [GPa]");
    line("  poisson_ratio: " + format_number(c.material.poisson_ratio), "nu [-], -1 < nu < 0.5");
    line("  yield_stress: " + format_number(c.material.yield_stress), "sigma_y0 [GPa] (j2)");
    line("  hardening_modulus: " + format_number(c.material.hardening_modulus),
         "H [GPa], linear isotropic hardening (j2)");
    line("  yield_stress_measure: " + c.material.yield_stress_measure,
         "cauchy | kirchhoff: stress in the Mises yield function (j2)");
    line("  lattice: " + c.material.lattice, "fcc: {111}<110> slip (crystal)");
    line("  elastic:", "cubic constants, lattice frame (crystal)");
    line("    C11: " + format_number(c.material.C11), "[GPa]");
    line("    C12: " + format_number(c.material.C12), "[GPa]");
    line("    C44: " + format_number(c.material.C44), "[GPa]");
    line("  hardening:", "extended Voce law (crystal)");
    line("    tau0: " + format_number(c.material.tau0), "initial critical shear [GPa]");
    line("    tau1: " + format_number(c.material.tau1), "[GPa]");
    line("    theta0: " + format_number(c.material.theta0), "initial hardening rate [GPa]");
    line("    theta1: " + format_number(c.material.theta1), "asymptotic hardening rate [GPa]");
    line("    q: " + format_number(c.material.q), "latent hardening ratio [-]");
    line("  yield_exponent_n: " + format_number(c.material.yield_exponent_n),
         "n, exponent 2n of eq. 14 (crystal)");
    line("  orientation:", "Bunge, passive: v_crystal = g v_sample (crystal)");
    const auto &orientation = c.material.orientation;
    if (orientation.kind == "surface_normal")
      {
        line("    surface_normal: " + format_triple(orientation.surface_normal),
             "crystal direction [hkl] along sample z");
        line("    reference_direction: " + format_triple(orientation.reference_direction),
             "crystal direction [uvw] along sample x");
      }
    else
      line("    euler_bunge_deg: " + format_triple(orientation.euler_bunge_deg),
           "(phi1, Phi, phi2) [deg]");

    out << "indenter:\n";
    line("  shape: " + c.indenter.shape,
         "rounded_cone | sphere | cone | vickers | berkovich | flat_punch | profile_table");
    line("  a: " + format_number(c.indenter.a),
         "rounded_cone (eq. 16): slope [-], half-angle atan(a)");
    line("  delta: " + format_number(c.indenter.delta), "tip rounding [um], tip radius a^2*delta");
    line("  radius: " + format_number(c.indenter.radius), "sphere, flat_punch: radius [um]");
    line("  half_angle_deg: " + format_number(c.indenter.half_angle_deg),
         "cone: half-angle flank-axis [deg]");
    line("  tip_radius: " + format_number(c.indenter.tip_radius),
         "cone, vickers, berkovich: tip and edge radius [um], 0: sharp");
    line("  rotation_deg: " + format_number(c.indenter.rotation_deg),
         "vickers, berkovich: about +z, ccw from above [deg]; 0: a face towards +x");
    line("  edge_radius: " + format_number(c.indenter.edge_radius),
         "flat_punch: rim rounding [um], 0: sharp");
    line("  file: " + quoted(c.indenter.file),
         "profile_table: CSV r_um,z_um or depth_um,area_um2");

    out << "specimen:\n";
    line("  size: " + format_triple(c.specimen.size), "full block edge lengths [um]");
    line("  refined_region: " + format_triple(c.specimen.refined_region),
         "refined block under the tip [um]");
    line("  contact_elements: " + std::to_string(c.specimen.contact_elements),
         "N: N x N faces across the refined top face");
    line("  symmetry: " + c.specimen.symmetry, "full | quarter (x >= 0, y >= 0)");
    line("  f_bar: " + format_bool(c.specimen.f_bar), "F-bar element");
    line("  elements_per_side: " + std::to_string(c.specimen.elements_per_side),
         "tensile: cube of n^3 elements of 1 um");
    line("  grains: " + c.specimen.grains, "single | per_element (tensile)");
    line("  seed: " + std::to_string(c.specimen.seed), "random orientations (per_element)");

    out << "loading:\n";
    line("  control: " + c.loading.control, "depth | force");
    line("  max_depth: " + format_number(c.loading.max_depth),
         "[um] (force control: the largest admissible depth)");
    line("  max_force: " + format_number(c.loading.max_force), "[mN] (force control)");
    line("  steps: " + std::to_string(c.loading.steps),
         "increments to the maximum (tensile: max_strain)");
    line("  unload: " + format_bool(c.loading.unload),
         "then back until the force vanishes (force control: to 1 % of max_force)");
    line("  unload_steps: " + std::to_string(c.loading.unload_steps),
         "0: same increment size as loading");
    line("  unload_points: " + std::to_string(c.loading.unload_points),
         "depth control: force drop per unloading step <= max force / unload_points; 0: off");
    line("  hold_steps: " + std::to_string(c.loading.hold_steps), "increments holding the maximum");
    line("  cycles: " + std::to_string(c.loading.cycles), "load-hold-unload cycles");
    line("  max_cutbacks: " + std::to_string(c.loading.max_cutbacks),
         "successive halvings of an increment");
    line("  max_strain: " + format_number(c.loading.max_strain),
         "tensile: final logarithmic strain along z [-]");

    out << "contact:\n";
    line("  friction_coefficient: " + format_number(c.contact.friction_coefficient),
         "Coulomb mu [-], 0: frictionless");
    line("  penalty: " + format_number(c.contact.penalty), "[GPa/um], 0: automatic");
    line("  penetration_tolerance: " + format_number(c.contact.penetration_tolerance), "[um]");
    line("  max_augmentations: " + std::to_string(c.contact.max_augmentations), "");

    out << "solver:\n";
    line("  residual_tolerance: " + format_number(c.solver.residual_tolerance),
         "relative to the first residual of an increment");
    line("  absolute_tolerance: " + format_number(c.solver.absolute_tolerance), "[mN]");
    line("  max_newton_iterations: " + std::to_string(c.solver.max_newton_iterations), "");
    line("  linear_solver: " + c.solver.linear_solver,
         "auto | direct (MUMPS) | iterative (AMG-preconditioned CG/GMRES)");
    line("  threads: " + std::to_string(c.solver.threads),
         "assembly threads per MPI rank, 0: cores / ranks");

    out << "output:\n";
    line("  directory: " + quoted(c.output.directory),
         "relative paths: relative to the working directory");
    line("  vtu_every: " + std::to_string(c.output.vtu_every),
         "VTU every k-th step (0: at max depth and end)");
    line("  experimental_curve: " + quoted(c.output.experimental_curve),
         "measured curve (CSV) to overlay and compare; \"\": none");
    line("  checkpoint_interval_s: " + format_number(c.output.checkpoint_interval_s),
         "[s] wall time between checkpoints (0: only when stopped)");
    return out.str();
  }

  std::string closest_name(const std::string &word, const std::vector<std::string> &candidates)
  {
    return closest_match(word, candidates);
  }

  void write_resolved_case(const Case &resolved_case, const std::string &path)
  {
    std::ofstream output(path);
    if (!output)
      throw CaseFileError("cannot write the resolved case to '" + path + "'");
    output << resolved_case_yaml(resolved_case);
    output.close();
    if (!output)
      throw CaseFileError("writing the resolved case to '" + path + "' failed");
  }

  void prepare_output_directory(const std::string &directory, bool overwrite)
  {
    if (directory.empty())
      throw CaseFileError("output directory: the path is empty");
    const fs::path  dir(directory);
    std::error_code error;

    if (fs::exists(dir, error) && !fs::is_directory(dir, error))
      throw CaseFileError("output directory '" + directory +
                          "' exists but is not a directory; choose another one with --output DIR");
    fs::create_directories(dir, error);
    if (error || !fs::is_directory(dir))
      throw CaseFileError("output directory '" + directory + "' cannot be created" +
                          (error ? ": " + error.message() : std::string()));

    const std::vector<fs::path> earlier = earlier_results(dir);
    if (!earlier.empty())
      {
        if (!overwrite)
          throw CaseFileError("output directory '" + directory +
                              "' already contains results of an earlier run (" +
                              earlier.front().filename().string() +
                              (earlier.size() > 1 ?
                                 " and " + std::to_string(earlier.size() - 1) + " more" :
                                 std::string()) +
                              "); pass --overwrite to replace them, or choose another directory "
                              "(--output DIR or output.directory)");
        for (const auto &file : earlier)
          {
            if (fs::is_directory(file, error)) // only the checkpoint folder
              fs::remove_all(file, error);
            else
              fs::remove(file, error);
            if (error)
              throw CaseFileError("output directory '" + directory + "': cannot remove '" +
                                  file.string() + "': " + error.message());
          }
      }

    // Permission bits do not tell the whole story (read-only mounts, ACLs, root): try it.
    const fs::path probe = dir / ".indentsim_write_probe";
    {
      std::ofstream probe_stream(probe);
      probe_stream << "probe\n";
      probe_stream.close();
      if (!probe_stream)
        {
          fs::remove(probe, error);
          throw CaseFileError("output directory '" + directory +
                              "' is not writable; choose another one with --output DIR");
        }
    }
    fs::remove(probe, error);
  }
} // namespace indentsim::io

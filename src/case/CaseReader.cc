// Reads a YAML tree into a Case, key by key from the schema: unknown and duplicate keys (with
// "did you mean"), required keys and the type of every value. The value checks follow in
// CaseValidator.cc. Every message names the file, the line, the key path and the value.
#include "case/CaseReading.h"
#include "case/Schema.h"
#include "io/DamageProfileCsv.h"
#include "io/HardeningTableCsv.h"
#include "io/TextNumber.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <system_error>
#include <type_traits>

namespace indentsim::io
{
  namespace
  {
    namespace fs = std::filesystem;

    const std::string orientation_path = "material.orientation";
    // The map whose keys may also be slip families, each with its own block.
    const std::string              family_blocks_path = "material.hardening";
    const std::vector<std::string> family_block_keys = {
        "tau0", "tau1", "theta0", "theta1", "tau_irr", "softening_slip", "barrier_strength"};

    // The keys of one form of a law (a J2 hardening law, a damage law): those it needs and those
    // it may take (CaseReader::check_form_keys).
    template <typename Form>
    struct FormKeys
    {
      Form                     form;
      std::vector<std::string> required, optional;
    };

    class CaseReader
    {
    public:
      CaseReader(std::string source_name, OriginMap &origins)
        : source(std::move(source_name))
        , value_origins(origins)
      {
      }

      Case read(const YAML::Node &root)
      {
        Case result;
        result.source_file = source;

        if (root.IsDefined() && !root.IsNull() && !root.IsMap())
          fail(line_of(root),
               "the case file must be a mapping of keys (test, material, indenter, ...), got '" +
                   node_text(root) + "'");
        check_keys(root, "", allowed_names(""));
        maps.emplace("", root);

        for (const auto &key : case_keys())
          {
            if (key.parent() == orientation_path)
              {
                if (key.name() == allowed_names(orientation_path).front())
                  read_orientation(map_at("material"), result.material.orientation);
                continue;
              }
            const YAML::Node &map = map_at(key.parent());
            if (key.type == ValueType::family_blocks)
              {
                read_family_blocks(map, key, result);
                continue;
              }
            if (!read_value(map, key, result) && key.required)
              fail(key.parent().empty() ? -1 : line_of(map),
                   "missing required key '" + key.path +
                       "' (allowed: " + join(key.choice.words(true)) + ")");
          }

        read_hardening_law(result.material);
        read_damage_profile(result.material);
        given_once("material.hardening.q", "material.latent_hardening.q");

        // F-bar by default for plasticity (isochoric flow locks plain hexahedra) and for nearly
        // incompressible hyperelasticity (nu > 0.45: the volumetric stiffness locks them as
        // well, e.g. H = 242 GPa instead of a few GPa at nu = 0.4999); the plain displacement
        // element otherwise, which is exact for the compressible elastic patch tests.
        if (value_origins.count("specimen.f_bar") == 0)
          result.specimen.f_bar =
              result.material.model == ModelKind::j2 ||
              result.material.model == ModelKind::crystal ||
              (result.material.model == ModelKind::neo_hookean &&
               result.material.poisson_ratio > nearly_incompressible_poisson_ratio);
        return result;
      }

    private:
      std::string                       source;
      OriginMap                        &value_origins;
      std::map<std::string, YAML::Node> maps; // the maps read so far, by path

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

      // The map at `path`, read (and its keys checked) when first needed: a section of the top
      // level, or a map nested in one.
      const YAML::Node &map_at(const std::string &path)
      {
        if (const auto found = maps.find(path); found != maps.end())
          return found->second;
        const std::size_t dot = path.rfind('.');
        YAML::Node        node = dot == std::string::npos
                                     ? section(maps.at(""), path)
                                     : subsection(map_at(path.substr(0, dot)), path.substr(0, dot),
                                                  path.substr(dot + 1));
        return maps.emplace(path, node).first->second;
      }

      // Unknown and duplicate keys at one level; `section_name` is "" for the top level.
      void check_keys(const YAML::Node &map, const std::string &section_name,
                      const std::vector<std::string> &allowed) const
      {
        if (!map.IsDefined() || !map.IsMap())
          return;
        std::map<std::string, int> seen;
        for (const auto &entry : map)
          {
            const int line = line_of(entry.first);
            if (!entry.first.IsScalar())
              fail(line, "key '" + node_text(entry.first) + "'" +
                             (section_name.empty() ? "" : " in '" + section_name + "'") +
                             " is not a plain name; allowed keys: " + join(allowed));
            const std::string key = entry.first.Scalar();
            const std::string path = key_path(section_name, key);
            if (const auto previous = seen.find(key); previous != seen.end())
              fail(line, "duplicate key '" + path + "' (first given on line " +
                             std::to_string(previous->second + 1) + "); give each key once");
            seen.emplace(key, line);

            if (std::find(allowed.begin(), allowed.end(), key) != allowed.end())
              continue;
            // A slip family's block (read by read_family_blocks, its name checked against
            // material.slip_families by the validator).
            if (section_name == family_blocks_path && entry.second.IsMap())
              continue;
            fail(line, "unknown key '" + path + "'" + unknown_key_hint(section_name, key, allowed) +
                           " Allowed keys " +
                           (section_name.empty() ? std::string("at the top level")
                                                 : "in '" + section_name + "'") +
                           ": " + join(allowed) + ".");
          }
      }

      // "; did you mean ...?" for an unknown key, or ".".
      static std::string unknown_key_hint(const std::string &section_name, const std::string &key,
                                          const std::vector<std::string> &allowed)
      {
        // A known key placed in the wrong section is the likeliest mistake.
        for (const auto &[other_section, other_keys] : maps_with_names())
          if (other_section != section_name &&
              std::find(other_keys.begin(), other_keys.end(), key) != other_keys.end())
            return "; did you mean '" + other_section + "." + key + "' (under '" + other_section +
                   ":')?";
        if (const std::string guess = closest_name(key, allowed); !guess.empty())
          return "; did you mean '" + key_path(section_name, guess) + "'?";
        return ".";
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
                   ": expected a mapping of keys (allowed: " + join(allowed_names(name)) + ")");
        check_keys(node, name, allowed_names(name));
        return node;
      }

      // A map nested in a section (e.g. material.elastic), read like a section.
      YAML::Node subsection(const YAML::Node &parent, const std::string &parent_name,
                            const std::string &key)
      {
        const YAML::Node  node = value_node(parent, parent_name, key);
        const std::string path = key_path(parent_name, key);
        if (!node.IsDefined() || node.IsNull())
          return YAML::Node(YAML::NodeType::Undefined);
        if (!node.IsMap())
          fail(line_of(node),
               path + " = " + node_text(node) +
                   ": expected a mapping of keys (allowed: " + join(allowed_names(path)) + ")");
        check_keys(node, path, allowed_names(path));
        return node;
      }

      // One key into its place in `result`; false if the key is absent.
      bool read_value(const YAML::Node &map, const Key &key, Case &result)
      {
        const YAML::Node node = value_node(map, key.parent(), key.name());
        if (!node.IsDefined())
          return false;
        switch (key.type)
          {
          case ValueType::number:
            key.number(result) = parse_double(node, key.path, key.expected);
            break;
          case ValueType::whole_number:
            key.whole_number(result) = parse_whole_number_or_word(node, key);
            break;
          case ValueType::boolean:
            key.boolean(result) = parse_bool(node, key.path);
            break;
          case ValueType::choice:
            key.choice.assign(result, parse_word(node, key.path, key.expected));
            break;
          case ValueType::text:
            key.text(result) = parse_word(node, key.path, key.expected);
            if (key.relative_to_case_file)
              key.text(result) = relative_to_case_file(key.text(result));
            break;
          case ValueType::triple:
            key.triple(result) = parse_triple(node, key);
            break;
          case ValueType::list:
            key.list(result) = parse_list(node, key);
            break;
          case ValueType::words:
            key.words(result) = parse_words(node, key);
            break;
          case ValueType::matrix:
            key.matrix(result) = parse_matrix(node, key);
            break;
          case ValueType::family_blocks: // read by read_family_blocks
            break;
          case ValueType::layers:
            key.layers(result) = parse_layers(node, key);
            break;
          }
        return true;
      }

      // material.layers: a list of maps, each with its thickness; the other keys are kept as
      // canonical flow YAML (numbers in shortest round-trip form) and checked as a material
      // block by the validator (check_layers).
      std::vector<MaterialLayer> parse_layers(const YAML::Node &node, const Key &key) const
      {
        const std::string expected =
            "expected a list of layers from the surface down, each a map with `thickness` (um) "
            "and the material keys it changes, e.g. [{thickness: 1.5, yield_stress: 0.6}]";
        if (!node.IsSequence() || node.size() == 0)
          fail(line_of(node), key.path + " = " + node_text(node) + ": " + expected);
        std::vector<MaterialLayer> layers(node.size());
        for (std::size_t i = 0; i < node.size(); ++i)
          {
            const std::string path = key.path + "[" + std::to_string(i) + "]";
            const YAML::Node &entry = node[i];
            if (!entry.IsMap())
              fail(line_of(entry), path + " = " + node_text(entry) + ": " + expected);
            if (!entry["thickness"].IsDefined())
              fail(line_of(entry), path + " = " + node_text(entry) +
                                       ": missing key 'thickness' (the layer's thickness in um)");
            layers[i].thickness = parse_double(entry["thickness"], path + ".thickness",
                                               "the layer's thickness in um");
            YAML::Node overrides(YAML::NodeType::Map);
            for (const auto &item : entry)
              if (item.first.Scalar() != "thickness")
                overrides[item.first.Scalar()] = item.second;
            layers[i].overrides = canonical_text(overrides);
          }
        return layers;
      }

      // A word as it is, anything else (a slip family "{112}<111>", a path) in double quotes.
      static std::string plain_or_quoted(const std::string &text)
      {
        const bool plain = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
          return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
        });
        if (plain)
          return text;
        YAML::Emitter emitter;
        emitter << YAML::DoubleQuoted << text;
        return emitter.c_str();
      }

      // Flow YAML with numbers in shortest round-trip form, so that 0.60 and 0.6 give one
      // resolved case and one fingerprint.
      static std::string canonical_text(const YAML::Node &node)
      {
        if (node.IsScalar())
          {
            const std::optional<double> value = io::parse_yaml_number(node.Scalar());
            return value ? format_number(*value) : plain_or_quoted(node.Scalar());
          }
        std::string text;
        if (node.IsSequence())
          {
            for (std::size_t i = 0; i < node.size(); ++i)
              text += (i == 0 ? "" : ", ") + canonical_text(node[i]);
            return "[" + text + "]";
          }
        if (node.IsMap())
          {
            for (const auto &item : node)
              text += (text.empty() ? "" : ", ") + plain_or_quoted(item.first.Scalar()) + ": " +
                      canonical_text(item.second);
            return "{" + text + "}";
          }
        return node_text(node);
      }

      // The maps under material.hardening named by slip families, in file order: each key a
      // block leaves out takes the common value read before (material.hardening.tau0, ...).
      void read_family_blocks(const YAML::Node &map, const Key &key, Case &result)
      {
        if (!map.IsDefined() || !map.IsMap())
          return;
        const MaterialParameters &m = result.material;
        for (const auto &entry : map)
          {
            if (!entry.second.IsMap())
              continue; // a key of the schema
            const std::string family = entry.first.Scalar();
            const std::string path = key.parent() + "." + family;
            value_origins[path] = {line_of(entry.second), node_text(entry.second)};
            check_keys(entry.second, path, family_block_keys);
            FamilyHardening block{family,   m.tau0,    m.tau1,           m.theta0,
                                  m.theta1, m.tau_irr, m.softening_slip, m.barrier_strength};
            double         *values[] = {
                        &block.tau0,    &block.tau1,           &block.theta0,          &block.theta1,
                        &block.tau_irr, &block.softening_slip, &block.barrier_strength};
            for (std::size_t i = 0; i < family_block_keys.size(); ++i)
              {
                const YAML::Node node = value_node(entry.second, path, family_block_keys[i]);
                if (node.IsDefined())
                  *values[i] = parse_double(node, path + "." + family_block_keys[i],
                                            family_block_keys[i] + " for the family " + family);
              }
            key.family_blocks(result).push_back(block);
          }
      }

      // Two spellings of one value (material.hardening.q and material.latent_hardening.q): at
      // most one.
      void given_once(const std::string &first, const std::string &second) const
      {
        if (value_origins.count(first) > 0 && value_origins.count(second) > 0)
          fail(value_origins.at(second).line,
               second + " = " + value_origins.at(second).text + ": the same value as " + first +
                   " (given on line " + std::to_string(value_origins.at(first).line + 1) +
                   "); give it once");
      }

      // material.orientation: exactly one of euler_bunge_deg or surface_normal (which needs
      // reference_direction: the in-plane direction is never guessed). Absent: the default
      // Euler angles (0, 0, 0).
      void read_orientation(const YAML::Node &material_map, OrientationParameters &orientation)
      {
        const std::string &path = orientation_path;
        const YAML::Node   node = subsection(material_map, "material", "orientation");
        if (!node.IsDefined())
          return;
        const bool        has_euler = node["euler_bunge_deg"].IsDefined();
        const bool        has_normal = node["surface_normal"].IsDefined();
        const bool        has_reference = node["reference_direction"].IsDefined();
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

        const auto read_form = [&](const char *name, auto &values) {
          const Key &key = find_key(path + "." + name);
          if constexpr (std::is_same_v<std::remove_cvref_t<decltype(values)>,
                                       std::array<double, 3>>)
            values = parse_triple(value_node(node, path, name), key);
          else
            values = parse_list(value_node(node, path, name), key);
        };
        if (has_euler)
          {
            orientation.kind = OrientationKind::euler_bunge_deg;
            read_form("euler_bunge_deg", orientation.euler_bunge_deg);
          }
        else
          {
            orientation.kind = OrientationKind::surface_normal;
            read_form("surface_normal", orientation.surface_normal);
            read_form("reference_direction", orientation.reference_direction);
          }
      }

      // material.hardening.law of J2 and its keys: each law takes its own keys, all required
      // except the Voce law's linear term (default 0); H is given once (hardening_modulus, or
      // the law's modulus); a table is inline or a file, which is read here into the lists. The
      // values are checked in CaseValidator.cc.
      void read_hardening_law(MaterialParameters &material)
      {
        const std::string prefix = "material.hardening.";
        const auto        given = [&](const std::string &name) {
          return value_origins.count(prefix + name) > 0;
        };
        const auto line = [&](const std::string &path) {
          const auto origin = value_origins.find(path);
          return origin == value_origins.end() ? -1 : origin->second.line;
        };
        const auto shown = [&](const std::string &name) {
          return prefix + name + " = " + value_origins.at(prefix + name).text;
        };
        const std::vector<std::string> parameters = {
            "modulus", "exponent", "saturation", "rate", "plastic_strain", "stress", "file"};
        const std::string laws = join(choice_words<HardeningLaw>(true), " | ");
        if (!given("law"))
          {
            for (const auto &name : parameters)
              if (given(name))
                fail(line(prefix + name),
                     shown(name) +
                         ": a parameter of a J2 hardening law, given without "
                         "material.hardening.law; give law: " +
                         laws + " with its keys (linear hardening alone: hardening_modulus)");
            return;
          }
        if (value_origins.count("material.hardening_modulus") > 0)
          fail(line("material.hardening_modulus"),
               "material.hardening_modulus = " +
                   value_origins.at("material.hardening_modulus").text +
                   ": give the hardening once, either hardening_modulus (linear) or "
                   "hardening: {law: ...} (here law: " +
                   material.hardening_law.word() + "; for linear: {law: linear, modulus: H})");
        if (!material.hardening_law.known())
          return; // named by the validator, with the allowed words

        const std::vector<FormKeys<HardeningLaw>> law_keys = {
            {HardeningLaw::linear, {"modulus"}, {}},
            {HardeningLaw::power, {"exponent"}, {}},
            {HardeningLaw::voce, {"saturation", "rate"}, {"modulus"}},
            {HardeningLaw::table, {}, {"plastic_strain", "stress", "file"}},
        };
        for (const auto &keys : law_keys)
          if (material.hardening_law == keys.form)
            check_form_keys("material.hardening", "law", parameters, keys.required, keys.optional);
        if (material.hardening_law == HardeningLaw::voce && !given("modulus"))
          material.hardening_modulus = 0.0;
        if (material.hardening_law == HardeningLaw::table)
          read_hardening_table(material, given("plastic_strain"), given("stress"), given("file"),
                               line(prefix + "law"));
      }

      // law: table: the two lists, or the file read into them.
      void read_hardening_table(MaterialParameters &material, const bool has_strain,
                                const bool has_stress, const bool has_file, const int law_line)
      {
        const std::string prefix = "material.hardening.";
        const std::string either =
            "give plastic_strain: [...] together with stress: [...] (GPa), or file: a CSV with "
            "the header plastic_strain,true_stress_GPa";
        if (has_file && (has_strain || has_stress))
          fail(value_origins.at(prefix + "file").line,
               prefix + "file = " + value_origins.at(prefix + "file").text +
                   ": the table is given twice (file and lists); " + either);
        if (has_file)
          {
            try
              {
                const HardeningTable table = read_hardening_table_csv(material.hardening_file);
                material.hardening_plastic_strain = table.plastic_strain;
                material.hardening_stress = table.stress;
              }
            catch (const std::invalid_argument &error)
              {
                fail(value_origins.at(prefix + "file").line,
                     prefix + "file = \"" + material.hardening_file + "\": " + error.what());
              }
            return;
          }
        if (!has_strain || !has_stress)
          fail(law_line, std::string("material.hardening: law: table needs ") +
                             (has_strain   ? "stress"
                              : has_stress ? "plastic_strain"
                                           : "the table") +
                             "; " + either);
      }

      // material.damage_profile: the profile inline (depth with dpa) or a file read here into
      // the two lists, and its law's form with the form's own keys, all required except the
      // saturation exponent (default 1). The values are checked in CaseValidator.cc.
      void read_damage_profile(MaterialParameters &material)
      {
        const std::string prefix = "material.damage_profile.";
        const auto        given = [&](const std::string &name) {
          return value_origins.count(prefix + name) > 0;
        };
        const auto line = [&](const std::string &name) {
          const auto origin = value_origins.find(prefix + name);
          return origin == value_origins.end() ? -1 : origin->second.line;
        };
        const auto shown = [&](const std::string &name) {
          return prefix + name + " = " + value_origins.at(prefix + name).text;
        };
        const std::string either =
            "give file: a CSV with the header depth_nm,dpa (or depth_um), or depth: [...] (um) "
            "together with dpa: [...]";
        DamageProfileParameters &profile = material.damage_profile;
        if (!given("file") && !given("depth") && !given("dpa"))
          {
            for (const auto &[path, origin] : value_origins)
              if (path.rfind(prefix, 0) == 0)
                fail(origin.line, path + " = " + origin.text +
                                      ": a key of a damage profile, given without the profile; " +
                                      either);
            return;
          }
        if (given("file") && (given("depth") || given("dpa")))
          fail(line("file"),
               shown("file") + ": the profile is given twice (file and lists); " + either);
        if (!given("file") && !(given("depth") && given("dpa")))
          fail(line(given("depth") ? "depth" : "dpa"), shown(given("depth") ? "depth" : "dpa") +
                                                           ": the profile needs both lists; " +
                                                           either);
        if (given("file"))
          {
            try
              {
                DamageProfileTable table = read_damage_profile_csv(profile.file);
                profile.depth = std::move(table.depth);
                profile.dpa = std::move(table.dpa);
              }
            catch (const std::invalid_argument &error)
              {
                fail(line("file"), prefix + "file = \"" + profile.file + "\": " + error.what());
              }
          }

        const std::vector<std::string> parameters = {
            "saturation_increment", "saturation_dose", "exponent",       "dpa",
            "delta_yield_stress",   "shear_modulus",   "burgers_vector", "defect_size",
            "saturation_density"};
        const std::string forms = join(choice_words<DamageLaw>(true), " | ");
        if (!given("law.form"))
          fail(line("law") >= 0 ? line("law") : line(given("file") ? "file" : "depth"),
               "material.damage_profile needs law: {form: " + forms +
                   ", ...} (the dose-to-strength law; user guide, \"Damage profiles\")");
        if (!profile.law.known())
          return; // named by the validator, with the allowed words
        const std::vector<FormKeys<DamageLaw>> form_keys = {
            {DamageLaw::saturation, {"saturation_increment", "saturation_dose"}, {"exponent"}},
            {DamageLaw::table, {"dpa", "delta_yield_stress"}, {}},
            {DamageLaw::dispersed_barrier,
             {"shear_modulus", "burgers_vector", "defect_size", "saturation_density",
              "saturation_dose"},
             {}},
        };
        for (const auto &keys : form_keys)
          if (profile.law == keys.form)
            check_form_keys("material.damage_profile.law", "form", parameters, keys.required,
                            keys.optional);
      }

      // The keys of the map `map` for the form its key `kind` names (a J2 hardening law, a
      // damage law): none of the other forms' `parameters`, every one of its `required`.
      void check_form_keys(const std::string &map, const std::string &kind,
                           const std::vector<std::string> &parameters,
                           const std::vector<std::string> &required,
                           const std::vector<std::string> &optional) const
      {
        const auto origin = [&](const std::string &name) {
          const auto found = value_origins.find(map + "." + name);
          return found == value_origins.end() ? nullptr : &found->second;
        };
        const std::string        form = kind + ": " + origin(kind)->text;
        std::vector<std::string> own = required;
        own.insert(own.end(), optional.begin(), optional.end());
        for (const auto &name : parameters)
          if (origin(name) && std::find(own.begin(), own.end(), name) == own.end())
            fail(origin(name)->line, map + "." + name + " = " + origin(name)->text +
                                         ": not a parameter of " + form +
                                         " (its keys: " + join(own) + ")");
        for (const auto &name : required)
          if (!origin(name))
            fail(origin(kind)->line, map + ": " + form + " needs " + map + "." + name +
                                         " (its keys: " + join(own) + ")");
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
        const fs::path  absolute = fs::absolute(resolved, error);
        return (error ? resolved : absolute).lexically_normal().string();
      }

      // The value node of `key`, or an undefined node if the key is absent.
      YAML::Node value_node(const YAML::Node &map, const std::string &section_name,
                            const std::string &key)
      {
        if (!map.IsDefined() || !map.IsMap())
          return YAML::Node(YAML::NodeType::Undefined);
        const YAML::Node node = map[key];
        if (node.IsDefined())
          value_origins[key_path(section_name, key)] = {line_of(node), node_text(node)};
        return node;
      }

      double parse_double(const YAML::Node &node, const std::string &path,
                          const std::string &meaning) const
      {
        const std::string expected = "expected a number (" + meaning + ")";
        if (node.IsNull())
          fail(line_of(node), path + " has no value; " + expected);
        if (!node.IsScalar())
          fail(line_of(node), path + " = " + node_text(node) + ": " + expected);
        const std::optional<double> value = io::parse_yaml_number(node.Scalar());
        if (!value)
          fail(line_of(node), path + " = \"" + node.Scalar() + "\": " + expected);
        return *value;
      }

      // A whole number, or the key's word for 0 (specimen.contact_elements: auto); a literal 0
      // is then refused, since it would read as the word.
      unsigned int parse_whole_number_or_word(const YAML::Node &node, const Key &key) const
      {
        if (key.zero_word == nullptr)
          return parse_unsigned(node, key.path);
        if (node.IsScalar() && node.Scalar() == key.zero_word)
          return 0;
        const std::string either = std::string("; allowed: ") + key.zero_word + ", or " +
                                   (key.has_range ? key.range_message : "a whole number > 0");
        if (node.IsScalar() && !node.Scalar().empty() &&
            !std::isdigit(static_cast<unsigned char>(node.Scalar()[0])) &&
            node.Scalar()[0] != '+' && node.Scalar()[0] != '-')
          fail(line_of(node), key.path + " = " + node.Scalar() + ": unknown word" + either);
        const unsigned int value = parse_unsigned(node, key.path);
        if (value == 0)
          fail(line_of(node), key.path + " = 0: not allowed" + either);
        return value;
      }

      unsigned int parse_unsigned(const YAML::Node &node, const std::string &path) const
      {
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
        const auto result = std::from_chars(text.data() + start, text.data() + text.size(), parsed);
        if (result.ec == std::errc::result_out_of_range ||
            (result.ec == std::errc() && parsed > std::numeric_limits<unsigned int>::max()))
          {
            // A count key states its own range; others are bounded by the unsigned type.
            const Key &key = find_key(path);
            const bool bounded = key.has_range && std::isfinite(key.range.upper);
            fail(line_of(node),
                 path + " = " + text + ": too large; " +
                     (bounded ? key.range_message
                              : expected + " <= " +
                                    std::to_string(std::numeric_limits<unsigned int>::max())));
          }
        if (result.ec != std::errc() || result.ptr != text.data() + text.size() ||
            start == text.size())
          fail(line_of(node), path + " = \"" + text + "\": " + expected);
        return static_cast<unsigned int>(parsed);
      }

      bool parse_bool(const YAML::Node &node, const std::string &path) const
      {
        const std::string expected = "expected true or false";
        if (node.IsNull())
          fail(line_of(node), path + " has no value; " + expected);
        if (!node.IsScalar())
          fail(line_of(node), path + " = " + node_text(node) + ": " + expected);
        try
          {
            return node.as<bool>();
          }
        catch (const YAML::Exception &)
          {
            fail(line_of(node), path + " = \"" + node.Scalar() + "\": " + expected);
          }
      }

      std::string parse_word(const YAML::Node &node, const std::string &path,
                             const std::string &meaning) const
      {
        if (node.IsNull())
          fail(line_of(node), path + " has no value; expected " + meaning);
        if (!node.IsScalar())
          fail(line_of(node),
               path + " = " + node_text(node) + ": expected " + meaning + " (a single word)");
        return node.Scalar();
      }

      std::vector<double> parse_list(const YAML::Node &node, const Key &key) const
      {
        const std::string expected = "expected a list of numbers (" + key.expected + ")";
        if (!node.IsSequence() || node.size() == 0)
          fail(line_of(node), key.path + " = " + node_text(node) + ": " + expected);
        std::vector<double> values(node.size());
        for (std::size_t i = 0; i < node.size(); ++i)
          values[i] =
              parse_double(node[i], key.path + "[" + std::to_string(i) + "]", key.entry_unit);
        return values;
      }

      std::vector<std::string> parse_words(const YAML::Node &node, const Key &key) const
      {
        const std::string expected = "expected a list of words (" + key.expected + ")";
        if (!node.IsSequence() || node.size() == 0)
          fail(line_of(node), key.path + " = " + node_text(node) + ": " + expected);
        std::vector<std::string> values(node.size());
        for (std::size_t i = 0; i < node.size(); ++i)
          values[i] = parse_word(node[i], key.path + "[" + std::to_string(i) + "]", key.entry_unit);
        return values;
      }

      std::vector<std::vector<double>> parse_matrix(const YAML::Node &node, const Key &key) const
      {
        const std::string expected =
            "expected a list of rows, each a list of numbers, e.g. [[1, 1.4], [1.4, 1]]";
        if (!node.IsSequence() || node.size() == 0)
          fail(line_of(node), key.path + " = " + node_text(node) + ": " + expected);
        std::vector<std::vector<double>> rows(node.size());
        for (std::size_t i = 0; i < node.size(); ++i)
          {
            const std::string row = key.path + "[" + std::to_string(i) + "]";
            if (!node[i].IsSequence() || node[i].size() == 0)
              fail(line_of(node[i]), row + " = " + node_text(node[i]) + ": " + expected);
            for (std::size_t j = 0; j < node[i].size(); ++j)
              rows[i].push_back(
                  parse_double(node[i][j], row + "[" + std::to_string(j) + "]", "a ratio"));
          }
        return rows;
      }

      std::array<double, 3> parse_triple(const YAML::Node &node, const Key &key) const
      {
        const std::string &path = key.path;
        const std::string  expected = "expected a list of 3 numbers " + key.expected;
        if (!node.IsSequence())
          fail(line_of(node), path + " = " + node_text(node) + ": " + expected);
        if (node.size() != 3)
          fail(line_of(node), path + " = " + node_text(node) + ": " + expected + ", got " +
                                  std::to_string(node.size()) + " entries");
        std::array<double, 3> values{};
        for (std::size_t i = 0; i < 3; ++i)
          values[i] = parse_double(node[i], path + "[" + std::to_string(i) + "]", key.entry_unit);
        return values;
      }
    };
  } // namespace

  Case read_case_tree(const YAML::Node &root, const std::string &source, OriginMap &origins)
  {
    return CaseReader(source, origins).read(root);
  }
} // namespace indentsim::io

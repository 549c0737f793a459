// Parameter keys of calibration files (see ParameterKey.h). Units: those of the keys.
#include "calibration/ParameterKey.h"

#include "case/Schema.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <stdexcept>

namespace indentsim::calibration
{
  namespace
  {
    // The keys of a slip family's own hardening block (case-file reference,
    // material.hardening.<family>).
    const std::vector<std::string> family_keys = {
        "tau0", "tau1", "theta0", "theta1", "tau_irr", "softening_slip", "barrier_strength"};

    bool is_family_key(const std::string &name)
    {
      return std::find(family_keys.begin(), family_keys.end(), name) != family_keys.end();
    }

    std::string joined(const std::vector<std::string> &names, const std::size_t from)
    {
      std::string text;
      for (std::size_t n = from; n < names.size(); ++n)
        text += (text.empty() ? "" : ".") + names[n];
      return text;
    }

    // material.hardening.<family>.<key> -> material.hardening.<key>, for the schema's unit.
    std::string schema_path_of(std::vector<std::string> material_path)
    {
      if (material_path.size() == 3 && material_path[0] == "hardening" &&
          !is_family_key(material_path[1]) && is_family_key(material_path[2]))
        material_path.erase(material_path.begin() + 1);
      return "material." + joined(material_path, 0);
    }

    // The node at `path` below `node`, created as maps where missing.
    YAML::Node map_at(YAML::Node node, const std::vector<std::string> &path)
    {
      for (const std::string &name : path)
        {
          if (!node[name].IsMap())
            node[name] = YAML::Node(YAML::NodeType::Map);
          node.reset(node[name]);
        }
      return node;
    }
  } // namespace

  ParameterKey parse_parameter_key(const std::string &text)
  {
    ParameterKey key;
    key.text = text;
    for (std::size_t start = 0;;)
      {
        const std::size_t dot = text.find('.', start);
        std::string       name = text.substr(start, dot - start);
        if (const std::size_t open = name.find('['); open != std::string::npos)
          {
            const std::string index = name.substr(open + 1, name.size() - open - 2);
            if (key.names != std::vector<std::string>{"material"} ||
                name.substr(0, open) != "layers" || name.back() != ']' || index.empty() ||
                !std::all_of(index.begin(), index.end(),
                             [](const char c) { return c >= '0' && c <= '9'; }) ||
                index.size() > 4)
              throw std::invalid_argument(
                  "an index is allowed only as material.layers[i] with i a whole number from 0 "
                  "(e.g. material.layers[0].yield_stress)");
            key.layer = std::stoul(index);
            name = "layers";
          }
        if (name.empty())
          throw std::invalid_argument("an empty name between dots");
        key.names.push_back(name);
        if (dot == std::string::npos)
          break;
        start = dot + 1;
      }
    if (key.layer)
      {
        if (key.names.size() < 3)
          throw std::invalid_argument("a layer's key follows the index: material.layers[" +
                                      std::to_string(*key.layer) +
                                      "].yield_stress, .thickness, .hardening.exponent, ...");
        const std::vector<std::string> rest(key.names.begin() + 2, key.names.end());
        key.schema_path = rest == std::vector<std::string>{"thickness"} ? "" : schema_path_of(rest);
      }
    else if (key.names.size() > 1 && key.names[0] == "material")
      key.schema_path =
          schema_path_of(std::vector<std::string>(key.names.begin() + 1, key.names.end()));
    else
      key.schema_path = text;
    if (key.names.size() > 2 && key.names[0] == "material" &&
        (key.names[1] == "layers" || key.names[1] == "damage_profile"))
      key.optional_block = key.names[1];
    return key;
  }

  bool ParameterKey::enters(const YAML::Node &base) const
  {
    if (optional_block.empty())
      return true;
    if (!base.IsMap() || !base["material"].IsMap())
      return false;
    const YAML::Node block = base["material"][optional_block];
    return block.IsDefined() && !block.IsNull();
  }

  void write_parameter(const ParameterKey &key, const double value, const YAML::Node &base,
                       YAML::Node &overrides)
  {
    if (!key.enters(base))
      return;
    const std::string number = io::format_number(value);
    if (!key.layer)
      {
        const std::vector<std::string> outer(key.names.begin(), key.names.end() - 1);
        map_at(overrides, outer)[key.names.back()] = number;
        return;
      }
    const YAML::Node base_layers = base["material"]["layers"];
    if (!base_layers.IsSequence() || *key.layer >= base_layers.size())
      throw std::invalid_argument(
          key.text + ": the case has " +
          (base_layers.IsSequence() ? std::to_string(base_layers.size()) : "no list of") +
          " layer(s) in material.layers; the index counts from 0 at the surface");
    YAML::Node material = map_at(overrides, {"material"});
    if (!material["layers"].IsDefined())
      material["layers"] = YAML::Clone(base_layers);
    YAML::Node                     layer = material["layers"][*key.layer];
    const std::vector<std::string> inner(key.names.begin() + 2, key.names.end() - 1);
    map_at(layer, inner)[key.names.back()] = number;
  }
} // namespace indentsim::calibration

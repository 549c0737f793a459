// The materials of a depth-graded specimen (see MaterialLayers.h).
#include "case/MaterialLayers.h"

#include "case/CaseFile.h"
#include "case/Schema.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>

namespace indentsim::io
{
  namespace
  {
    void merge_into(YAML::Node target, const YAML::Node &source, const std::string &path)
    {
      for (const auto &entry : source)
        {
          if (!entry.first.IsScalar())
            {
              // Not a plain name: kept as given, for the case reader to reject with its message.
              target[entry.first] = YAML::Clone(entry.second);
              continue;
            }
          const std::string key = entry.first.Scalar();
          const std::string child_path = path.empty() ? key : path + "." + key;
          if (entry.second.IsNull())
            {
              target.remove(key);
              continue;
            }
          const YAML::Node &read_only = target;
          const YAML::Node  existing = read_only[key];
          if (existing.IsDefined() && existing.IsMap() && entry.second.IsMap() &&
              child_path != "material.orientation")
            merge_into(target[key], entry.second, child_path);
          else
            target[key] = YAML::Clone(entry.second);
        }
    }

    // The first structural key among a layer's keys ("" if none), as a path below material.
    std::string structural_key(const YAML::Node &overrides)
    {
      for (const std::string &path : structural_layer_keys())
        {
          const std::size_t dot = path.find('.');
          const YAML::Node  outer = overrides[path.substr(0, dot)];
          if (!outer.IsDefined())
            continue;
          if (dot == std::string::npos ||
              (outer.IsMap() && outer[path.substr(dot + 1)].IsDefined()))
            return path;
        }
      return "";
    }
  } // namespace

  YAML::Node merge_overrides(const YAML::Node &base, const YAML::Node &overrides)
  {
    if (!overrides.IsDefined() || overrides.IsNull())
      return YAML::Clone(base);
    if (!base.IsDefined() || !base.IsMap() || !overrides.IsMap())
      return YAML::Clone(overrides);
    YAML::Node result = YAML::Clone(base);
    merge_into(result, overrides, "");
    return result;
  }

  const std::vector<std::string> &structural_layer_keys()
  {
    static const std::vector<std::string> keys = {
        "model", "lattice", "slip_families", "c_over_a", "orientation", "hardening.law", "layers",
        "damage_profile"};
    return keys;
  }

  std::vector<MaterialParameters> layer_materials(const MaterialParameters &material,
                                                  const std::string        &source)
  {
    std::vector<MaterialParameters> result;
    if (material.layers.empty())
      return result;
    // The substrate's material block as resolved, in a case of otherwise default keys (the
    // material's own checks do not depend on them).
    Case substrate;
    substrate.material = material;
    substrate.material.layers.clear();
    const YAML::Node resolved = YAML::Load(resolved_case_yaml(substrate));
    for (std::size_t i = 0; i < material.layers.size(); ++i)
      {
        const MaterialLayer &layer = material.layers[i];
        const std::string    listed = format_layers({layer}); // "[{thickness: ...}]"
        const std::string    where =
            "material.layers[" + std::to_string(i) + "] = " + listed.substr(1, listed.size() - 2);
        const YAML::Node overrides = YAML::Load(layer.overrides);
        if (const std::string key = structural_key(overrides); !key.empty())
          throw CaseFileError(source + ": " + where + ": a layer may not give material." + key +
                              " (every layer shares the substrate's " +
                              join(structural_layer_keys()) +
                              "); give only the parameters that change with depth");
        YAML::Node wrapped;
        wrapped["material"] = overrides;
        try
          {
            result.push_back(
                parse_case_yaml(YAML::Dump(merge_overrides(resolved, wrapped)), "layer").material);
          }
        catch (const CaseFileError &error)
          {
            // "layer:LINE: message": the line is that of the merged text, not of the case file.
            std::string message = error.what();
            message = message.substr(std::min(message.find(": "), message.size() - 2) + 2);
            throw CaseFileError(source + ": " + where + ": in this layer, " + message);
          }
      }
    return result;
  }
} // namespace indentsim::io

// The key of a fitted parameter (calibration files' `parameters`): a dotted path of the case
// file, as in the case-file reference, with two forms that reach inside a block:
//   material.yield_stress                      a key of the reference
//   material.hardening.{110}<111>.tau0         a key of one slip family's hardening block
//   material.layers[0].yield_stress            a key of one layer of a depth-graded specimen
//   material.layers[1].thickness               (um) a layer's thickness
//   material.layers[0].hardening.basal.tau0    both
// The schema key behind each (material.hardening.tau0 for the family form, material.<rest>
// for a layer) gives the type and the unit; the case reader checks the value like any other.
// A key inside a block that only some cases have (material.layers, material.damage_profile)
// enters only those cases: a tensile test of the substrate, or the pristine specimen's
// indentation, does not see it.
// Units: those of the keys (um, GPa).
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace YAML
{
  class Node;
}

namespace indentsim::calibration
{
  struct ParameterKey
  {
    std::string                text;        // as written
    std::vector<std::string>   names;       // the path without the index: material, layers, ...
    std::optional<std::size_t> layer;       // i of material.layers[i]
    std::string                schema_path; // the case-file reference's key ("" for thickness)
    // "layers" or "damage_profile" for a key inside that optional material block, else "".
    std::string optional_block;

    // Whether the case file's YAML `base` has the optional block (true without one).
    bool enters(const YAML::Node &base) const;
  };

  // Parses `text`. Throws std::invalid_argument with what is wrong and what is allowed.
  ParameterKey parse_parameter_key(const std::string &text);

  // Writes `value` (its shortest exact text) at the key into `overrides` (merged onto the case
  // `base` by the study machinery, which replaces lists whole): a layer's key goes into a copy
  // of the base case's material.layers, kept in `overrides` for the next layer key. A case
  // without the key's optional block is left alone; a case with too few layers throws
  // std::invalid_argument.
  void write_parameter(const ParameterKey &key, double value, const YAML::Node &base,
                       YAML::Node &overrides);
} // namespace indentsim::calibration

// Depth-graded specimens (material.layers): the material of each layer, and the merge of YAML
// maps that builds it (shared with the study files' overrides). Units: um, GPa.
//
// A layer's material is the material block as resolved (every key written out, as in
// resolved_case.yaml) with the keys the layer gives replaced, nested maps key by key
// (hardening: {tau0: 0.2} replaces tau0 only). It is read and checked like any material block,
// so a layer accepts what the block accepts, except the keys that fix the kind of material and
// the layout of its state (structural_layer_keys): every layer shares the substrate's model,
// lattice and slip systems, and its orientation. A slip family with its own hardening block
// keeps that block's values unless the layer names them (hardening: {basal: {tau0: 0.4}}).
#pragma once

#include "case/MaterialParameters.h"

#include <string>
#include <vector>

namespace YAML
{
  class Node;
}

namespace indentsim::io
{
  // `overrides` merged onto a copy of `base`: maps key by key, anything else (numbers, lists,
  // words) replaced whole, a null value removes the key; material.orientation is replaced whole
  // (its two forms exclude each other). Neither argument is modified.
  YAML::Node merge_overrides(const YAML::Node &base, const YAML::Node &overrides);

  // The material keys a layer may not give (paths below `material`).
  const std::vector<std::string> &structural_layer_keys();

  // The material of each of material.layers, in order (empty for a homogeneous material). Throws
  // CaseFileError naming `source`, the layer and the key when a layer's material is not
  // admissible.
  std::vector<MaterialParameters> layer_materials(const MaterialParameters &material,
                                                  const std::string        &source);
} // namespace indentsim::io

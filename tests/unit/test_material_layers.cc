// Depth-graded materials (material.layers): the case-file spelling and its resolved form, each
// layer's material, the errors that name the layer, and LayeredMaterial's choice of the layer and
// its hand-over to the layer's model. Units: um, GPa.
#include "case/CaseFile.h"
#include "case/Fingerprint.h"
#include "case/MaterialLayers.h"
#include "materials/J2Plasticity.h"
#include "materials/LayeredMaterial.h"
#include "materials/MaterialFactory.h"

#include "../case_file_errors.h"
#include "material_test_utilities.h"

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

namespace
{
  using namespace indentsim;
  using namespace indentsim::io;
  using test_case_files::expect_rejected;

  using test_case_files::j2_material;

  std::string with_layers(const std::string &layers)
  {
    return j2_material + "  layers: " + layers + "\n";
  }
} // namespace

// The spelling, its resolved form (numbers canonical, read back identically) and each
// layer's material: the block with the layer's keys replaced.
TEST(MaterialLayers, LayersAreReadResolvedAndMerged)
{
  const Case c =
      parse_case_yaml(with_layers("[{thickness: 1.5, yield_stress: 0.60}, {thickness: 0.5, "
                                  "hardening_modulus: 2}]"),
                      "layers.yaml");
  ASSERT_EQ(c.material.layers.size(), 2u);
  EXPECT_EQ(c.material.layers[0].thickness, 1.5);
  EXPECT_EQ(c.material.layers[0].overrides, "{yield_stress: 0.6}");
  EXPECT_EQ(c.material.layers[1].overrides, "{hardening_modulus: 2}");
  const std::string resolved = resolved_case_yaml(c);
  EXPECT_NE(resolved.find("layers: [{thickness: 1.5, yield_stress: 0.6}, {thickness: 0.5, "
                          "hardening_modulus: 2}]"),
            std::string::npos)
      << resolved;
  EXPECT_EQ(parse_case_yaml(resolved, "resolved.yaml").material, c.material);
  EXPECT_NE(case_fingerprint(c), case_fingerprint(parse_case_yaml(j2_material, "plain.yaml")));

  const std::vector<MaterialParameters> layers = layer_materials(c.material, "layers.yaml");
  ASSERT_EQ(layers.size(), 2u);
  EXPECT_EQ(layers[0].yield_stress, 0.6);
  EXPECT_EQ(layers[0].hardening_modulus, 0.5);
  EXPECT_EQ(layers[0].young_modulus, 69.0);
  EXPECT_TRUE(layers[0].layers.empty());
  EXPECT_EQ(layers[1].yield_stress, 0.305);
  EXPECT_EQ(layers[1].hardening_modulus, 2.0);
}

// Crystals: a layer replaces the common Voce keys and, named, a family block's keys; the family
// without a block follows the common value.
TEST(MaterialLayers, CrystalLayerReplacesFamilyBlocksByName)
{
  const Case c = parse_case_yaml(
      "test: indentation\n"
      "material:\n"
      "  model: crystal\n"
      "  lattice: bcc\n"
      "  slip_families: [\"{110}<111>\", \"{112}<111>\"]\n"
      "  elastic: {C11: 231.4, C12: 134.7, C44: 116.4}\n"
      "  hardening: {tau0: 0.1, \"{112}<111>\": {tau0: 0.12}}\n"
      "  layers: [{thickness: 1, hardening: {tau0: 0.3, \"{112}<111>\": {tau0: 0.35}}}, "
      "{thickness: 1, hardening: {tau0: 0.2}}]\n",
      "bcc.yaml");
  const std::vector<MaterialParameters> layers = layer_materials(c.material, "bcc.yaml");
  ASSERT_EQ(layers.size(), 2u);
  EXPECT_EQ(layers[0].tau0, 0.3);
  ASSERT_EQ(layers[0].family_hardening.size(), 1u);
  EXPECT_EQ(layers[0].family_hardening[0].tau0, 0.35);
  EXPECT_EQ(layers[1].tau0, 0.2);
  EXPECT_EQ(layers[1].family_hardening[0].tau0, 0.12); // its block keeps its own value
  EXPECT_EQ(parse_case_yaml(resolved_case_yaml(c), "resolved.yaml").material, c.material);
}

TEST(MaterialLayers, BadLayersAreNamed)
{
  expect_rejected(with_layers("{thickness: 1}"), {"material.layers", "expected a list of layers"});
  expect_rejected(with_layers("[]"), {"material.layers", "expected a list of layers"});
  expect_rejected(with_layers("[0.5]"), {"material.layers[0] = 0.5", "expected a list"});
  expect_rejected(with_layers("[{yield_stress: 0.6}]"),
                  {"material.layers[0]", "missing key 'thickness'"});
  expect_rejected(with_layers("[{thickness: thin}]"),
                  {"material.layers[0].thickness", "thin", "expected a number"});
  expect_rejected(with_layers("[{thickness: -1, yield_stress: 0.6}]"),
                  {"material.layers", "thickness of layer 0 (-1)", ">= 0 um"});
  expect_rejected(with_layers("[{thickness: 1, yeild_stress: 0.6}]"),
                  {"bad.yaml:8", "material.layers[0]", "in this layer", "yeild_stress",
                   "did you mean 'material.yield_stress'"});
  expect_rejected(with_layers("[{thickness: 1}, {thickness: 1, yield_stress: -0.6}]"),
                  {"material.layers[1]", "material.yield_stress = -0.6"});
  expect_rejected(with_layers("[{thickness: 1, model: neo_hookean}]"),
                  {"material.layers[0]", "may not give material.model"});
  expect_rejected(with_layers("[{thickness: 1, hardening: {law: power, exponent: 0.2}}]"),
                  {"material.layers[0]", "may not give material.hardening.law"});
  expect_rejected("test: tensile\n"
                  "material: {model: j2, layers: [{thickness: 1, yield_stress: 0.6}]}\n",
                  {"material.layers", "test: indentation"});
}

// The layer of a depth: a point on a boundary belongs to the deeper layer, a layer of zero
// thickness holds no point, below the layers lies the substrate; the state carries the layer and
// the update is the layer's model's.
TEST(MaterialLayers, LayeredMaterialPassesEachPointToItsLayer)
{
  using namespace materials;
  const auto j2 = [](const double yield_stress) {
    MaterialParameters p;
    p.yield_stress = yield_stress;
    return create_material(p);
  };
  std::vector<std::unique_ptr<MaterialModel>> layers;
  layers.push_back(j2(0.6));
  layers.push_back(j2(0.9));
  layers.push_back(j2(1.2));
  const LayeredMaterial layered(std::move(layers), {1.0, 0.0, 0.5}, j2(0.305));
  EXPECT_EQ(layered.layer_at_depth(-0.1), 0u);
  EXPECT_EQ(layered.layer_at_depth(0.0), 0u);
  EXPECT_EQ(layered.layer_at_depth(0.999), 0u);
  EXPECT_EQ(layered.layer_at_depth(1.0), 2u); // the empty layer 1 is skipped
  EXPECT_EQ(layered.layer_at_depth(1.49), 2u);
  EXPECT_EQ(layered.layer_at_depth(1.5), 3u);
  EXPECT_EQ(layered.layer_at_depth(1e9), 3u);

  const auto         substrate = j2(0.305), third = j2(1.2);
  const Tensor<2, 3> g = indentsim::testing::identity();
  const unsigned int n = layered.n_state_variables();
  ASSERT_EQ(n, 1 + substrate->n_state_variables());
  std::vector<double> old_state(n), new_state(n);
  std::vector<double> plain_old(n - 1), plain_new(n - 1);
  // A stretch that yields the 0.305 and 1.2 GPa materials differently.
  const Tensor<2, 3>    F = indentsim::testing::diagonal(1.03, 0.99, 0.99);
  MaterialPointResponse layered_response, plain_response;
  for (const auto &[depth, model] : std::vector<std::pair<double, const MaterialModel *>>{
           {1.2, third.get()}, {7.0, substrate.get()}})
    {
      layered.initial_state_at_depth(old_state, g, depth);
      model->oriented_initial_state(plain_old, g);
      ASSERT_EQ(layered.update(F, old_state, layered_response, new_state), UpdateStatus::success);
      ASSERT_EQ(model->update(F, plain_old, plain_response, plain_new), UpdateStatus::success);
      EXPECT_EQ(layered.layer_of(new_state), layered.layer_at_depth(depth));
      EXPECT_EQ(layered_response.P, plain_response.P) << "depth " << depth;
      EXPECT_EQ(layered_response.dP_dF, plain_response.dP_dF) << "depth " << depth;
      EXPECT_EQ(layered.equivalent_plastic_strain(new_state),
                model->equivalent_plastic_strain(plain_new));
    }
  EXPECT_GT(layered.equivalent_plastic_strain(new_state), 0.); // the substrate yielded
}

// Case files, the resolved case, output-directory protection and the command line.
#include "case/CaseFile.h"
#include "case/CaseReference.h"
#include "case/Fingerprint.h"
#include "case/Schema.h"
#include "io/CommandLine.h"
#include "io/Version.h"

#include "../case_file_errors.h"
#include "../test_files.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace
{
  namespace fs = std::filesystem;
  using namespace indentsim::io;
  using namespace std::string_literals;

  // A fresh, empty scratch directory for one test.
  fs::path scratch_directory(const std::string &test_name)
  {
    return indentsim::test_files::scratch_directory("case_file", test_name);
  }

  fs::path write_text(const fs::path &path, const std::string &text)
  {
    std::ofstream out(path);
    out << text;
    return path;
  }

  std::string read_text_file(const std::string &path)
  {
    return indentsim::test_files::read_text(path);
  }

  const std::string minimal_case = "test: indentation\nmaterial:\n  model: j2\n";

  using indentsim::test_case_files::error_of;
  using indentsim::test_case_files::expect_rejected;

  // Asserts that validate_case rejects `c` with a message containing every part.
  void expect_rejected_case(const Case &c, std::initializer_list<std::string> parts)
  {
    std::string message;
    try
      {
        validate_case(c);
      }
    catch (const CaseFileError &error)
      {
        message = error.what();
      }
    SCOPED_TRACE("message: " + message);
    ASSERT_FALSE(message.empty()) << "no CaseFileError thrown";
    for (const auto &part : parts)
      EXPECT_NE(message.find(part), std::string::npos) << "missing '" << part << "'";
  }

  // minimal_case plus one more section.
  std::string with(const std::string &extra)
  {
    return minimal_case + extra;
  }
} // namespace

// The paper's J2 example parses into exactly the paper's parameters (Table 1, eq. 16).
TEST(CaseFile, PaperExampleHasThePaperValues)
{
  const Case c = read_case_file(std::string(INDENTSIM_SOURCE_DIR) + "/examples/paper_j2_n12.yaml");
  EXPECT_EQ(c.test, "indentation");
  EXPECT_EQ(c.material.model, "j2");
  EXPECT_DOUBLE_EQ(c.material.young_modulus, 69.0);
  EXPECT_DOUBLE_EQ(c.material.poisson_ratio, 0.26);
  EXPECT_DOUBLE_EQ(c.material.yield_stress, 0.305);
  EXPECT_DOUBLE_EQ(c.material.hardening_modulus, 0.5);
  EXPECT_EQ(c.indenter.shape, "rounded_cone");
  EXPECT_DOUBLE_EQ(c.indenter.a, 2.48);
  EXPECT_DOUBLE_EQ(c.indenter.delta, 0.005);
  EXPECT_EQ(c.specimen.size, (std::array<double, 3>{{360., 360., 180.}}));
  EXPECT_EQ(c.specimen.refined_region, (std::array<double, 3>{{120., 120., 30.}}));
  EXPECT_EQ(c.specimen.contact_elements, 12u);
  EXPECT_EQ(c.specimen.symmetry, "quarter");
  EXPECT_TRUE(c.specimen.f_bar);
  EXPECT_DOUBLE_EQ(c.loading.max_depth, 6.0);
  EXPECT_EQ(c.loading.steps, 64u);
  EXPECT_TRUE(c.loading.unload);
  EXPECT_DOUBLE_EQ(c.contact.friction_coefficient, 0.0);
  EXPECT_EQ(c.output.directory, "results/paper_j2_n12");
  EXPECT_NE(c.source_file.find("paper_j2_n12.yaml"), std::string::npos);
}

// The elastic Hertz example is a valid case with the advertised depth and mesh.
TEST(CaseFile, ElasticHertzExampleIsValid)
{
  const Case c = read_case_file(std::string(INDENTSIM_SOURCE_DIR) + "/examples/elastic_hertz.yaml");
  EXPECT_EQ(c.material.model, "neo_hookean");
  EXPECT_FALSE(c.specimen.f_bar);
  EXPECT_DOUBLE_EQ(c.loading.max_depth / c.indenter.delta, 0.1);
  EXPECT_EQ(c.loading.steps, 4u);
  EXPECT_FALSE(c.loading.unload);
  EXPECT_EQ(c.specimen.contact_elements, 16u);
  EXPECT_EQ(c.specimen.symmetry, "quarter");
  EXPECT_EQ(c.output.directory, "results/elastic_hertz");
}

// Only `test` and `material.model` are required; every other key takes the Case.h default.
TEST(CaseFile, MinimalCaseGetsAllDefaults)
{
  Case expected;
  expected.source_file = "minimal.yaml";
  const Case c = parse_case_yaml(minimal_case, "minimal.yaml");
  EXPECT_TRUE(c == expected);
}

// The F-bar default follows the material: on for j2 and crystal, off for neo_hookean, and an
// explicit value wins.
TEST(CaseFile, FBarDefaultDependsOnModel)
{
  EXPECT_TRUE(parse_case_yaml(minimal_case, "a.yaml").specimen.f_bar);
  EXPECT_FALSE(parse_case_yaml("test: indentation\nmaterial:\n  model: neo_hookean\n", "a.yaml")
                   .specimen.f_bar);
  EXPECT_FALSE(parse_case_yaml(with("specimen:\n  f_bar: false\n"), "a.yaml").specimen.f_bar);
  EXPECT_TRUE(parse_case_yaml("test: indentation\nmaterial:\n  model: neo_hookean\n"
                              "specimen:\n  f_bar: true\n",
                              "a.yaml")
                  .specimen.f_bar);
  EXPECT_TRUE(
      parse_case_yaml("test: indentation\nmaterial:\n  model: crystal\n", "a.yaml").specimen.f_bar);
}

// Writing the resolved case and reading it back gives an identical case for every key.
TEST(CaseFile, ResolvedCaseRoundTrips)
{
  // Every value differs from its default, so a key the writer forgot cannot go unnoticed.
  Case c;
  c.test = "indentation";
  c.material.model = "neo_hookean";
  c.material.young_modulus = 70.5;
  c.material.poisson_ratio = 0.3;
  c.material.yield_stress = 0.25;
  c.material.hardening_modulus = 0.75;
  c.material.yield_stress_measure = "kirchhoff";
  c.indenter = {"rounded_cone", 1.9, 0.0123};
  c.indenter.radius = 7.5;
  c.indenter.half_angle_deg = 65.5;
  c.indenter.tip_radius = 0.04;
  c.indenter.rotation_deg = -22.5;
  c.indenter.edge_radius = 0.3;
  c.indenter.file = "/data/tips/my tip #2.csv"; // read only for shape: profile_table
  c.specimen = {{{300., 310., 150.}}, {{100., 90., 25.}}, 16, 0, "quarter", false};
  c.loading = {"depth", 5.5, 0.0, 33, false, 7, 11, 2, 1, 5};
  c.contact = {0.0, 12.5, 3e-7, 17};
  c.solver = {1e-9, 2.5e-11, 31};
  c.output = {"out dir: #1/\"quoted\"", 3};
  c.source_file = "whatever.yaml";
  // The crystal and tensile keys (a tensile case, so that compare_j2 and per_element are valid).
  c.test = "tensile";
  c.compare_j2 = true;
  c.material.lattice = "fcc";
  c.material.C11 = 108.2;
  c.material.C12 = 61.3;
  c.material.C44 = 28.5;
  c.material.tau0 = 0.13;
  c.material.tau1 = 0.03;
  c.material.theta0 = 0.2;
  c.material.theta1 = 0.007;
  c.material.q = 1.2;
  c.material.yield_exponent_n = 12.5;
  c.material.orientation.euler_bunge_deg = {{10., 20.5, 30.}};
  c.specimen.elements_per_side = 4;
  c.specimen.grains = "per_element";
  c.specimen.seed = 42;
  c.loading.max_strain = 0.15;
  validate_case(c);
  ASSERT_FALSE(c.material == Case().material);

  const fs::path    dir = scratch_directory("round_trip");
  const std::string path = (dir / "resolved_case.yaml").string();
  write_resolved_case(c, path);
  Case back = read_case_file(path);
  EXPECT_EQ(back.source_file, path);
  back.source_file = c.source_file;
  EXPECT_TRUE(back == c) << resolved_case_yaml(c) << "\nread back as\n" << resolved_case_yaml(back);
  EXPECT_EQ(resolved_case_yaml(back), resolved_case_yaml(c));

  // Numbers that have no short decimal form survive as well.
  Case awkward;
  awkward.material.young_modulus = 1. / 3.;
  awkward.loading.max_depth = 0.1 + 0.2;
  Case awkward_back = parse_case_yaml(resolved_case_yaml(awkward), "");
  awkward_back.source_file = awkward.source_file;
  EXPECT_TRUE(awkward_back == awkward);

  // An orientation given as surface normal and reference direction is written in that form.
  Case normal;
  normal.material.model = "crystal";
  normal.material.orientation.kind = "surface_normal";
  normal.material.orientation.surface_normal = {1., 1., 1.};
  normal.material.orientation.reference_direction = {1., -1., 0.};
  validate_case(normal);
  const std::string text = resolved_case_yaml(normal);
  EXPECT_NE(text.find("surface_normal: [1, 1, 1]"), std::string::npos) << text;
  EXPECT_NE(text.find("reference_direction: [1, -1, 0]"), std::string::npos) << text;
  EXPECT_EQ(text.find("euler_bunge_deg"), std::string::npos) << text;
  Case normal_back = parse_case_yaml(text, "");
  normal_back.source_file = normal.source_file;
  EXPECT_TRUE(normal_back == normal) << text << "\nread back as\n"
                                     << resolved_case_yaml(normal_back);
}

// Every crystal-plasticity and tensile-test key of the case file reaches the Case.
TEST(CaseFile, CrystalAndTensileKeysAreParsed)
{
  const Case c = parse_case_yaml("test: tensile\n"
                                 "compare_j2: true\n"
                                 "material:\n"
                                 "  model: crystal\n"
                                 "  lattice: fcc\n"
                                 "  elastic: {C11: 107.5, C12: 61.5, C44: 29.5}\n"
                                 "  hardening: {tau0: 0.11, tau1: 0.025, theta0: 0.15, "
                                 "theta1: 0.004, q: 1.1}\n"
                                 "  yield_exponent_n: 7.5\n"
                                 "  orientation: {euler_bunge_deg: [15, 35.5, 45]}\n"
                                 "specimen:\n"
                                 "  elements_per_side: 5\n"
                                 "  grains: per_element\n"
                                 "  seed: 7\n"
                                 "loading:\n"
                                 "  max_strain: 0.25\n"
                                 "  steps: 50\n",
                                 "tensile.yaml");
  EXPECT_EQ(c.test, "tensile");
  EXPECT_TRUE(c.compare_j2);
  EXPECT_EQ(c.material.model, "crystal");
  EXPECT_EQ(c.material.lattice, "fcc");
  EXPECT_DOUBLE_EQ(c.material.C11, 107.5);
  EXPECT_DOUBLE_EQ(c.material.C12, 61.5);
  EXPECT_DOUBLE_EQ(c.material.C44, 29.5);
  EXPECT_DOUBLE_EQ(c.material.tau0, 0.11);
  EXPECT_DOUBLE_EQ(c.material.tau1, 0.025);
  EXPECT_DOUBLE_EQ(c.material.theta0, 0.15);
  EXPECT_DOUBLE_EQ(c.material.theta1, 0.004);
  EXPECT_DOUBLE_EQ(c.material.q, 1.1);
  EXPECT_DOUBLE_EQ(c.material.yield_exponent_n, 7.5);
  EXPECT_EQ(c.material.orientation.kind, "euler_bunge_deg");
  EXPECT_EQ(c.material.orientation.euler_bunge_deg, (std::array<double, 3>{{15., 35.5, 45.}}));
  EXPECT_EQ(c.specimen.elements_per_side, 5u);
  EXPECT_EQ(c.specimen.grains, "per_element");
  EXPECT_EQ(c.specimen.seed, 7u);
  EXPECT_DOUBLE_EQ(c.loading.max_strain, 0.25);
  EXPECT_EQ(c.loading.steps, 50u);
  EXPECT_TRUE(c.specimen.f_bar) << "F-bar is the default for crystal plasticity";

  const Case n = parse_case_yaml("test: indentation\nmaterial:\n  model: crystal\n"
                                 "  orientation:\n    surface_normal: [1, 1, 0]\n"
                                 "    reference_direction: [0, 0, 1]\n",
                                 "normal.yaml");
  EXPECT_EQ(n.material.orientation.kind, "surface_normal");
  EXPECT_EQ(n.material.orientation.surface_normal, (std::vector<double>{1., 1., 0.}));
  EXPECT_EQ(n.material.orientation.reference_direction, (std::vector<double>{0., 0., 1.}));

  // Without any crystal key the crystal model takes the paper's Table 2 and the (001) plane.
  const Case d = parse_case_yaml("test: tensile\nmaterial:\n  model: crystal\n", "d.yaml");
  EXPECT_DOUBLE_EQ(d.material.C11, 106.7);
  EXPECT_DOUBLE_EQ(d.material.C12, 60.4);
  EXPECT_DOUBLE_EQ(d.material.C44, 28.3);
  EXPECT_DOUBLE_EQ(d.material.tau0, 0.12);
  EXPECT_DOUBLE_EQ(d.material.tau1, 0.02);
  EXPECT_DOUBLE_EQ(d.material.theta0, 0.1);
  EXPECT_DOUBLE_EQ(d.material.theta1, 0.006);
  EXPECT_DOUBLE_EQ(d.material.q, 1.4);
  EXPECT_DOUBLE_EQ(d.material.yield_exponent_n, 10.);
  EXPECT_EQ(d.material.orientation.kind, "euler_bunge_deg");
  EXPECT_EQ(d.material.orientation.euler_bunge_deg, (std::array<double, 3>{{0., 0., 0.}}));
  EXPECT_EQ(d.specimen.grains, "single");
  EXPECT_FALSE(d.compare_j2);
}

// BCC and HCP: the families are read, defaulted and written back; c/a, C13 and C33 belong to hcp
// alone and hcp needs them; unknown or repeated families are named with the allowed ones.
TEST(CaseFile, LatticesAndSlipFamilies)
{
  const std::string crystal = "test: indentation\nmaterial:\n  model: crystal\n";
  const auto        crystal_with = [&](const std::string &extra) { return crystal + extra; };
  const Case        bcc = parse_case_yaml(
             crystal_with("  lattice: bcc\n  slip_families: [\"{110}<111>\", \"{112}<111>\"]\n"),
             "bcc.yaml");
  EXPECT_EQ(bcc.material.slip_families, (std::vector<std::string>{"{110}<111>", "{112}<111>"}));
  const Case hcp = parse_case_yaml(
      crystal_with("  lattice: hcp\n  c_over_a: 1.587\n  elastic: {C11: 160, C12: 90, C13: 66, "
                   "C33: 181.7, C44: 46.5}\n"),
      "hcp.yaml");
  EXPECT_EQ(hcp.material.slip_families,
            (std::vector<std::string>{"basal", "prismatic", "pyramidal_ca"}));
  for (const Case &c : {bcc, hcp})
    {
      const Case again = parse_case_yaml(resolved_case_yaml(c), "resolved.yaml");
      EXPECT_EQ(again.material, c.material);
    }
  expect_rejected(crystal_with("  lattice: bcc\n  slip_families: [basal]\n"),
                  {"material.slip_families", "\"basal\" is not a slip family of bcc",
                   "allowed: {110}<111>, {112}<111>, {123}<111>"});
  expect_rejected(crystal_with("  lattice: hcp\n  c_over_a: 1.6\n  slip_families: [basal, "
                               "basal]\n  elastic: {C13: 66, C33: 181.7}\n"),
                  {"\"basal\" is listed twice"});
  expect_rejected(crystal_with("  lattice: bcc\n  c_over_a: 1.6\n"),
                  {"material.c_over_a = 1.6", "only the hexagonal lattice", ":5:"});
  expect_rejected(crystal_with("  elastic: {C33: 181.7}\n"),
                  {"material.elastic.C33 = 181.7", "only the hexagonal lattice"});
  expect_rejected(crystal_with("  lattice: hcp\n  elastic: {C13: 66, C33: 181.7}\n"),
                  {"material.c_over_a = 0", "needs c/a, C13 and C33"});
  expect_rejected(crystal_with("  lattice: hcp\n  c_over_a: 1.6\n  elastic: {C13: 200, C33: "
                               "100}\n"),
                  {"material.elastic.C13", "hexagonal stiffness not positive definite"});
}

// Per-family Voce blocks (the keys a block leaves out take the common values), the latent
// ratio's two spellings and the latent matrix; the resolved case reads back to the same case.
TEST(CaseFile, FamilyHardeningAndLatentMatrix)
{
  const std::string bcc = "test: indentation\nmaterial:\n  model: crystal\n  lattice: bcc\n"
                          "  slip_families: [\"{110}<111>\", \"{112}<111>\"]\n";
  const Case        c = parse_case_yaml(bcc + "  hardening:\n    tau0: 0.3\n    theta1: 0.02\n"
                                                     "    \"{112}<111>\": {tau0: 0.42, theta0: 1.5}\n"
                                                     "  latent_hardening: {matrix: [[1, 1.4], [1.3, 1]]}\n",
                                        "bcc.yaml");
  ASSERT_EQ(c.material.family_hardening.size(), 1u);
  EXPECT_EQ(c.material.family_hardening[0],
            (FamilyHardening{"{112}<111>", 0.42, Case().material.tau1, 1.5, 0.02, 0.0,
                             Case().material.softening_slip, 0.0}));
  EXPECT_EQ(c.material.tau0, 0.3);
  EXPECT_EQ(c.material.latent_matrix, (std::vector<std::vector<double>>{{1, 1.4}, {1.3, 1}}));
  const Case again = parse_case_yaml(resolved_case_yaml(c), "resolved.yaml");
  EXPECT_EQ(again.material, c.material);
  EXPECT_EQ(parse_case_yaml(bcc + "  latent_hardening: {q: 1.2}\n", "q.yaml").material.q, 1.2);

  expect_rejected(bcc + "  hardening: {q: 1.3}\n  latent_hardening: {q: 1.2}\n",
                  {"material.latent_hardening.q = 1.2", "material.hardening.q", "give it once"});
  expect_rejected(bcc + "  hardening: {\"{123}<111>\": {tau0: 0.4}}\n",
                  {"material.hardening.{123}<111> = {tau0: 0.4",
                   "not a slip family of this crystal", "[\"{110}<111>\", \"{112}<111>\"]"});
  expect_rejected(
      bcc + "  hardening: {\"{112}<111>\": {tau2: 0.4}}\n",
      {"unknown key 'material.hardening.{112}<111>.tau2'", "tau0, tau1, theta0, theta1"});
  expect_rejected(bcc + "  hardening: {\"{112}<111>\": {tau0: 0}}\n",
                  {"material.hardening.{112}<111>.tau0 = 0", "> 0 GPa"});
  expect_rejected(bcc + "  hardening: {\"{112}<111>\": {tau1: 0, theta0: 1}}\n",
                  {"material.hardening.{112}<111>.tau1 = 0", "theta0 = 1", "divides by tau1"});
  expect_rejected(bcc + "  hardening: {\"{112}<111>\": {tau0: fast}}\n",
                  {"material.hardening.{112}<111>.tau0", "fast", "expected a number"});
  expect_rejected(bcc + "  latent_hardening: {matrix: [[1.4]]}\n",
                  {"material.latent_hardening.matrix = [[1.4]]", "needs 2 rows of 2",
                   "order of material.slip_families"});
  expect_rejected(bcc + "  latent_hardening: {matrix: [[1, 1.4], [-1, 1]]}\n",
                  {"material.latent_hardening.matrix", ">= 0", "row 1, column 0 (-1)"});
  expect_rejected(bcc + "  latent_hardening: {matrix: [1, 1.4]}\n",
                  {"material.latent_hardening.matrix[0] = 1", "expected a list of rows"});
  expect_rejected("test: indentation\nmaterial:\n  model: j2\n  hardening: {\"{110}<111>\": "
                  "{tau0: 0.4}}\n",
                  {"material.hardening.{110}<111>", "for model: crystal (here model: j2)"});
}

// Miller-Bravais orientations of hcp and the messages for indices that name nothing.
TEST(CaseFile, MillerBravaisOrientationIsChecked)
{
  const std::string hcp = "test: indentation\nmaterial:\n  model: crystal\n  lattice: hcp\n"
                          "  c_over_a: 1.587\n  elastic: {C11: 160, C12: 90, C13: 66, C33: 181.7, "
                          "C44: 46.5}\n";
  const Case        c = parse_case_yaml(
             hcp + "  orientation: {surface_normal: [1, 0, -1, 0], reference_direction: [-1, 2, -1, 0]}\n",
             "hcp.yaml");
  EXPECT_EQ(c.material.orientation.surface_normal, (std::vector<double>{1, 0, -1, 0}));
  EXPECT_EQ(parse_case_yaml(resolved_case_yaml(c), "resolved.yaml").material, c.material);
  expect_rejected(hcp + "  orientation: {surface_normal: [1, 0, 0, 0], reference_direction: "
                        "[-1, 2, -1, 0]}\n",
                  {"material.orientation.surface_normal = [1, 0, 0, 0]", "i = -(h + k) = -1"});
  expect_rejected(hcp + "  orientation: {surface_normal: [0, 0, 0, 1], reference_direction: "
                        "[0, 0, 0, 1]}\n",
                  {"material.orientation.reference_direction = [0, 0, 0, 1]",
                   "does not lie in the plane surface_normal [0, 0, 0, 1]"});
  expect_rejected(hcp + "  orientation: {surface_normal: [0, 0, 1, 1, 0], reference_direction: "
                        "[1, 0, 0]}\n",
                  {"material.orientation.surface_normal", "expected 3 indices [h, k, l] or 4"});
  expect_rejected("test: indentation\nmaterial:\n  model: crystal\n  orientation: "
                  "{surface_normal: [0, 0, 0, 1], reference_direction: [1, 0, 0]}\n",
                  {"material.orientation.surface_normal = [0, 0, 0, 1]", "for hcp only"});
}

// Crystal parameters outside their admissible range are rejected with key path, value and rule.
TEST(CaseFile, CrystalRangesAreChecked)
{
  const std::string crystal = "test: indentation\nmaterial:\n  model: crystal\n";
  const auto        crystal_with = [&](const std::string &extra) { return crystal + extra; };
  expect_rejected(crystal_with("  lattice: fc\n"),
                  {"material.lattice = 'fc'", "allowed: fcc | bcc | hcp", "did you mean 'fcc'"});
  expect_rejected(crystal_with("  elastic: {C44: 0}\n"),
                  {"material.elastic.C44 = 0", "positive definite", "C44 > 0"});
  expect_rejected(crystal_with("  elastic: {C12: 110}\n"),
                  {"material.elastic.C12 = 110", "C11 - C12 > 0", "C11 = 106.7"});
  expect_rejected(crystal_with("  elastic: {C11: 50}\n"),
                  {"material.elastic.C11 = 50", "C11 - C12 > 0", "C12 = 60.4"});
  expect_rejected(crystal_with("  elastic: {C11: 10, C12: -6}\n"),
                  {"material.elastic.C12 = -6", "C11 + 2 C12 > 0"});
  expect_rejected(crystal_with("  hardening: {tau0: 0}\n"),
                  {"material.hardening.tau0 = 0", "> 0 GPa"});
  expect_rejected(crystal_with("  hardening: {tau1: -0.01}\n"),
                  {"material.hardening.tau1 = -0.01", ">= 0"});
  expect_rejected(crystal_with("  hardening: {theta0: -1}\n"),
                  {"material.hardening.theta0 = -1", ">= 0"});
  expect_rejected(crystal_with("  hardening: {theta1: -1}\n"),
                  {"material.hardening.theta1 = -1", ">= 0"});
  expect_rejected(crystal_with("  hardening: {q: -0.5}\n"),
                  {"material.hardening.q = -0.5", ">= 0"});
  expect_rejected(crystal_with("  hardening: {tau1: 0}\n"),
                  {"material.hardening.tau1 = 0: ", "(here theta0 = 0.1 GPa)", "divides by tau1"});
  EXPECT_EQ(error_of(crystal_with("  hardening: {tau1: 0, theta0: 0}\n")), "")
      << "no hardening (theta0 = 0) needs no tau1";
  expect_rejected(crystal_with("  yield_exponent_n: 0.5\n"),
                  {"material.yield_exponent_n = 0.5", "1 <= n <= 50"});
  expect_rejected(crystal_with("  yield_exponent_n: 60\n"),
                  {"material.yield_exponent_n = 60", "1 <= n <= 50", "overflow"});
  EXPECT_EQ(error_of(crystal_with("  yield_exponent_n: 2.5\n")), "") << "n may be real";
  expect_rejected(crystal_with("  elastic: {C11: stiff}\n"),
                  {"material.elastic.C11", "stiff", "expected a number"});
  expect_rejected(crystal_with("  elastic: 106.7\n"),
                  {"material.elastic = 106.7", "expected a mapping", "C11, C12, C44"});
  expect_rejected(crystal_with("  elastic: {C31: 50}\n"),
                  {"unknown key 'material.elastic.C31'", "did you mean 'material.elastic."});
  expect_rejected(crystal_with("  tau0: 0.1\n"),
                  {"unknown key 'material.tau0'", "did you mean 'material.hardening.tau0'"});
}

// The orientation takes exactly one form, validated like every other key.
TEST(CaseFile, OrientationIsChecked)
{
  const std::string crystal = "test: indentation\nmaterial:\n  model: crystal\n";
  const auto        crystal_with = [&](const std::string &extra) { return crystal + extra; };
  expect_rejected(
      crystal_with("  orientation: {surface_normal: [1, 1, 1]}\n"),
      {"material.orientation", "[1, 1, 1]", "needs reference_direction", "not guessed", ":4:"});
  expect_rejected(crystal_with("  orientation: {reference_direction: [1, 0, 0]}\n"),
                  {"material.orientation", "[1, 0, 0]", "only used with surface_normal"});
  expect_rejected(crystal_with("  orientation: {euler_bunge_deg: [0, 0, 0], "
                               "surface_normal: [0, 0, 1], reference_direction: [1, 0, 0]}\n"),
                  {"material.orientation", "both", "exactly one"});
  expect_rejected(crystal_with("  orientation: {}\n"),
                  {"material.orientation", "no orientation given", "euler_bunge_deg"});
  expect_rejected(
      crystal_with("  orientation: {surface_normal: [1, 1, 1], "
                   "reference_direction: [1, 0, 0]}\n"),
      {"material.orientation.reference_direction = [1, 0, 0]", "not perpendicular", ":4:"});
  expect_rejected(crystal_with("  orientation: {surface_normal: [0, 0, 0], "
                               "reference_direction: [1, 0, 0]}\n"),
                  {"material.orientation.surface_normal = [0, 0, 0]", "non-zero"});
  expect_rejected(crystal_with("  orientation: {surface_normal: [0, 0, 1], "
                               "reference_direction: [0, 0, 0]}\n"),
                  {"material.orientation.reference_direction = [0, 0, 0]", "non-zero"});
  expect_rejected(crystal_with("  orientation: {euler_bunge_deg: [0, 90]}\n"),
                  {"material.orientation.euler_bunge_deg", "[0, 90]", "3 numbers", "degrees"});
  expect_rejected(crystal_with("  orientation: {euler_bunge_deg: [0, ninety, 0]}\n"),
                  {"material.orientation.euler_bunge_deg[1]", "ninety", "expected a number"});
  expect_rejected(crystal_with("  orientation: {miller: [1, 1, 1]}\n"),
                  {"unknown key 'material.orientation.miller'", "surface_normal"});
  expect_rejected(crystal_with("  orientation: [0, 0, 0]\n"),
                  {"material.orientation = [0, 0, 0]", "expected a mapping"});

  Case c;
  c.material.orientation.kind = "miller";
  expect_rejected_case(c, {"material.orientation.kind = 'miller'", "euler_bunge_deg"});
}

// The quarter model of a crystal is exact only if x = 0 and y = 0 are lattice mirror planes.
TEST(CaseFile, QuarterSymmetryNeedsCubicMirrorPlanes)
{
  const std::string quarter_crystal = "test: indentation\nspecimen:\n  symmetry: quarter\n"
                                      "material:\n  model: crystal\n";
  expect_rejected(quarter_crystal + "  orientation: {surface_normal: [1, 1, 1], "
                                    "reference_direction: [1, -1, 0]}\n",
                  {"specimen.symmetry = quarter", "mirror planes", "[1, 1, 1]", "y = 0", "(111)",
                   "use symmetry: full"});
  expect_rejected(quarter_crystal + "  orientation: {euler_bunge_deg: [10, 0, 0]}\n",
                  {"specimen.symmetry = quarter", "euler_bunge_deg [10, 0, 0]", "symmetry: full"});
  EXPECT_EQ(error_of(quarter_crystal + "  orientation: {euler_bunge_deg: [0, 0, 0]}\n"), "")
      << "(001) with <100> along x: x = 0 and y = 0 are {100} mirror planes";
  EXPECT_EQ(error_of(quarter_crystal + "  orientation: {euler_bunge_deg: [45, 0, 0]}\n"), "")
      << "(001) with <110> along x: {110} mirror planes";
  EXPECT_EQ(error_of(quarter_crystal + "  orientation: {surface_normal: [0, 1, 1], "
                                       "reference_direction: [1, 0, 0]}\n"),
            "")
      << "(011) with [100] along x: (100) and (01-1) are mirror planes";
  EXPECT_EQ(error_of(quarter_crystal + "  orientation: {surface_normal: [0, 0, 1], "
                                       "reference_direction: [1, 0, 0]}\n"),
            "");
  // The full model and isotropic models accept any orientation.
  EXPECT_EQ(error_of("test: indentation\nmaterial:\n  model: crystal\n  orientation: "
                     "{surface_normal: [1, 1, 1], reference_direction: [1, -1, 0]}\n"),
            "");
  EXPECT_EQ(error_of("test: indentation\nspecimen:\n  symmetry: quarter\nmaterial:\n"
                     "  model: j2\n  orientation: {surface_normal: [1, 1, 1], "
                     "reference_direction: [1, -1, 0]}\n"),
            "");
}

// Every indenter key of the library reaches the Case; the keys of other shapes keep their
// defaults and are checked but not used (as the crystal keys under j2).
TEST(CaseFile, IndenterKeysAreParsed)
{
  const Case c = parse_case_yaml(with("indenter:\n"
                                      "  shape: vickers\n"
                                      "  tip_radius: 0.05\n"
                                      "  rotation_deg: 45\n"
                                      "  radius: 12.5\n"
                                      "  half_angle_deg: 60\n"
                                      "  edge_radius: 0.5\n"),
                                 "v.yaml");
  EXPECT_EQ(c.indenter.shape, "vickers");
  EXPECT_DOUBLE_EQ(c.indenter.tip_radius, 0.05);
  EXPECT_DOUBLE_EQ(c.indenter.rotation_deg, 45.);
  EXPECT_DOUBLE_EQ(c.indenter.radius, 12.5);
  EXPECT_DOUBLE_EQ(c.indenter.half_angle_deg, 60.);
  EXPECT_DOUBLE_EQ(c.indenter.edge_radius, 0.5);
  EXPECT_EQ(c.indenter.file, "");
  EXPECT_DOUBLE_EQ(c.indenter.a, 2.48) << "rounded_cone keys keep their defaults";

  // Defaults of the new keys (Case.h, README).
  const Case d = parse_case_yaml(minimal_case, "d.yaml");
  EXPECT_DOUBLE_EQ(d.indenter.radius, 10.);
  EXPECT_DOUBLE_EQ(d.indenter.half_angle_deg, 70.3);
  EXPECT_DOUBLE_EQ(d.indenter.tip_radius, 0.);
  EXPECT_DOUBLE_EQ(d.indenter.rotation_deg, 0.);
  EXPECT_DOUBLE_EQ(d.indenter.edge_radius, 0.);
  EXPECT_EQ(d.indenter.file, "");

  for (const std::string shape : {"sphere", "cone", "berkovich", "flat_punch"})
    EXPECT_EQ(parse_case_yaml(with("indenter:\n  shape: " + shape + "\n"), "s.yaml").indenter.shape,
              shape);
  // A file given for another shape is not read (but kept in the resolved case).
  EXPECT_EQ(error_of(with("indenter:\n  shape: sphere\n  file: no_such_table.csv\n")), "");
}

// Indenter values outside their range are rejected with the file, key, value and rule.
TEST(CaseFile, IndenterRangesAreChecked)
{
  expect_rejected(with("indenter:\n  radius: 0\n"), {"indenter.radius = 0", "> 0 um", ":5:"});
  expect_rejected(with("indenter:\n  shape: sphere\n  radius: -2\n"),
                  {"indenter.radius = -2", "> 0 um", ":6:"});
  expect_rejected(with("indenter:\n  half_angle_deg: 90\n"),
                  {"indenter.half_angle_deg = 90", "0 < alpha < 90 deg"});
  expect_rejected(with("indenter:\n  shape: cone\n  half_angle_deg: 0\n"),
                  {"indenter.half_angle_deg = 0", "0 < alpha < 90 deg"});
  expect_rejected(with("indenter:\n  tip_radius: -0.1\n"),
                  {"indenter.tip_radius = -0.1", ">= 0 um", "0: sharp"});
  expect_rejected(
      with("indenter:\n  shape: flat_punch\n  edge_radius: -0.1\n"),
      {"indenter.edge_radius = -0.1: ", "here radius = 10 um", "0 <= edge_radius <= radius"});
  expect_rejected(with("indenter:\n  shape: flat_punch\n  radius: 2\n  edge_radius: 3\n"),
                  {"indenter.edge_radius = 3: ", "here radius = 2 um", ":7:"});
  expect_rejected(with("indenter:\n  rotation_deg: ninety\n"),
                  {"indenter.rotation_deg", "ninety", "expected a number", "degrees"});
  expect_rejected(with("indenter:\n  tip_radius: [0.1]\n"),
                  {"indenter.tip_radius", "expected a number"});
  expect_rejected(with("indenter:\n  tipradius: 0.1\n"),
                  {"unknown key 'indenter.tipradius'", "did you mean 'indenter.tip_radius'"});
  expect_rejected(with("indenter:\n  shape: profile_table\n"),
                  {"indenter.file = \"\" (default)", "profile_table needs the table", "r_um,z_um",
                   "depth_um,area_um2"});
  expect_rejected(with("indenter:\n  shape: profile_table\n  file: [a.csv]\n"),
                  {"indenter.file", "expected the path of a CSV profile table"});
  EXPECT_EQ(error_of(with("indenter:\n  shape: berkovich\n  rotation_deg: -725.5\n")), "")
      << "any finite rotation";
  EXPECT_EQ(error_of(with("indenter:\n  shape: flat_punch\n  radius: 2\n  edge_radius: 2\n")), "")
      << "edge_radius = radius: a hemispherical end";

  Case c;
  c.indenter.half_angle_deg = 95.;
  expect_rejected_case(c, {"indenter.half_angle_deg = 95"});
  c = Case();
  c.indenter.rotation_deg = std::numeric_limits<double>::infinity();
  expect_rejected_case(c, {"indenter.rotation_deg = inf", "finite"});
}

// A sharp pyramid cannot be computed (docs/user-guide.md, "Pyramids need a rounded tip"): a case
// read for a run or a check refuses tip_radius 0 for vickers and berkovich, with the line, the
// value and what is allowed; read for its description (the indenter of an analysis) it is valid,
// and a sharp cone or a rounded pyramid runs.
TEST(CaseFile, RunsRefuseASharpPyramid)
{
  const fs::path dir = scratch_directory("sharp_pyramid");
  const auto     for_run = [&](const std::string &indenter) {
    const fs::path path = write_text(dir / "case.yaml", with("indenter:\n" + indenter));
    try
      {
        read_case_for_run(path.string(), [](Case &) { return std::vector<std::string>(); });
      }
    catch (const CaseFileError &error)
      {
        return std::string(error.what());
      }
    return std::string();
  };
  for (const std::string shape : {"vickers", "berkovich"})
    {
      const std::string message = for_run("  shape: " + shape + "\n  tip_radius: 0\n");
      for (const std::string part : {std::string("case.yaml:6: indenter.tip_radius = 0: "),
                                     std::string("tip_radius > 0 um"), std::string("0.01 um")})
        EXPECT_NE(message.find(part), std::string::npos) << shape << ": " << message;
      EXPECT_NE(for_run("  shape: " + shape + "\n").find("(default)"), std::string::npos)
          << "the default tip_radius 0 is named as the default";
      EXPECT_EQ(error_of(with("indenter:\n  shape: " + shape + "\n  tip_radius: 0\n")), "")
          << shape << ": read for its description";
      EXPECT_EQ(for_run("  shape: " + shape + "\n  tip_radius: 0.01\n"), "") << shape;
    }
  EXPECT_EQ(for_run("  shape: cone\n  tip_radius: 0\n"), "") << "a sharp cone runs";
}

// profile_table: the file is relative to the case file's directory, stored as an absolute path
// (so that the resolved case, written elsewhere, finds it), and a bad table is reported with
// the case file's line of indenter.file, the table's file and line, and what is allowed.
TEST(CaseFile, ProfileTableFileIsResolvedAndChecked)
{
  const fs::path dir = scratch_directory("profile_table");
  fs::create_directories(dir / "cases" / "tables");
  write_text(dir / "cases" / "tables" / "tip.csv", "r_um,z_um\n0,0\n1,0.1\n3,1\n");
  const std::string case_text = with("indenter:\n  shape: profile_table\n"
                                     "  file: tables/../tables/tip.csv\n");
  const fs::path    case_path = write_text(dir / "cases" / "case.yaml", case_text);
  const Case        c = read_case_file(case_path.string());
  const fs::path expected = fs::absolute(dir / "cases" / "tables" / "tip.csv").lexically_normal();
  EXPECT_EQ(c.indenter.file, expected.string());

  // The resolved case, written into another directory, reads back identically.
  fs::create_directories(dir / "results");
  const std::string resolved = (dir / "results" / "resolved_case.yaml").string();
  write_resolved_case(c, resolved);
  Case back = read_case_file(resolved);
  back.source_file = c.source_file;
  EXPECT_TRUE(back == c) << read_text_file(resolved);

  // Missing and malformed tables.
  expect_rejected(
      with("indenter:\n  shape: profile_table\n  file: /no/such/dir/tip.csv\n"),
      {"bad.yaml:6:", "indenter.file = \"/no/such/dir/tip.csv\"", "does not exist", "r_um,z_um"});
  write_text(dir / "cases" / "tables" / "bad.csv", "r_um,z_um\n0,0\n1,0.5\n0.5,0.7\n");
  const fs::path bad_case =
      write_text(dir / "cases" / "bad_case.yaml",
                 with("indenter:\n  shape: profile_table\n  file: tables/bad.csv\n"));
  try
    {
      read_case_file(bad_case.string());
      ADD_FAILURE() << "a non-monotone table was accepted";
    }
  catch (const CaseFileError &error)
    {
      const std::string message = error.what();
      const std::string table = (fs::absolute(dir / "cases" / "tables" / "bad.csv")).string();
      for (const std::string &part : {bad_case.string() + ":6:", std::string("indenter.file"),
                                      table + ":4:", std::string("r_um = 0.5 does not increase"),
                                      std::string("strictly increasing")})
        EXPECT_NE(message.find(part), std::string::npos) << "missing '" << part << "' in\n"
                                                         << message;
    }
}

// The quarter model needs x = 0 and y = 0 to be mirror planes of the indenter: never for
// Berkovich, for Vickers only at multiples of 45 deg; axisymmetric shapes always.
TEST(CaseFile, QuarterSymmetryNeedsAMirrorSymmetricIndenter)
{
  const std::string quarter = with("specimen:\n  symmetry: quarter\n");
  expect_rejected(quarter + "indenter:\n  shape: berkovich\n",
                  {"specimen.symmetry = quarter", ":5:", "indenter.shape = berkovich",
                   "mirror planes", "never", "use symmetry: full"});
  expect_rejected(quarter + "indenter:\n  shape: vickers\n  rotation_deg: 30\n",
                  {"specimen.symmetry = quarter", "vickers with rotation_deg = 30",
                   "multiple of 45", "symmetry: full"});
  for (const std::string ok :
       {"vickers\n", "vickers\n  rotation_deg: 45\n", "vickers\n  rotation_deg: -90\n", "sphere\n",
        "cone\n", "flat_punch\n", "rounded_cone\n"})
    EXPECT_EQ(error_of(quarter + "indenter:\n  shape: " + ok), "") << ok;
  EXPECT_EQ(error_of(with("specimen:\n  symmetry: full\nindenter:\n  shape: berkovich\n")), "");
  EXPECT_EQ(error_of("test: tensile\nmaterial:\n  model: j2\nspecimen:\n  symmetry: quarter\n"
                     "indenter:\n  shape: berkovich\n"),
            "")
      << "the tensile test ignores the indenter's symmetry";
  Case c;
  c.indenter.shape = "berkovich";
  c.specimen.symmetry = "quarter";
  expect_rejected_case(c, {"specimen.symmetry = quarter", "berkovich"});
}

// The axisymmetric model is exact only for isotropic materials under axisymmetric tips.
TEST(CaseFile, AxisymmetricModelNeedsIsotropyAndAnAxisymmetricTip)
{
  const std::string axisymmetric = with("specimen:\n  symmetry: axisymmetric\n");
  expect_rejected(
      axisymmetric + "indenter:\n  shape: berkovich\n",
      {"specimen.symmetry = axisymmetric", "axisymmetric indenters", "berkovich", "70.3 deg"});
  expect_rejected(axisymmetric + "indenter:\n  shape: vickers\n",
                  {"specimen.symmetry = axisymmetric", "vickers"});
  const std::string axisymmetric_of = "test: indentation\nspecimen:\n  symmetry: axisymmetric\n";
  expect_rejected(axisymmetric_of + "material:\n  model: crystal\n",
                  {"specimen.symmetry = axisymmetric", "isotropic", "crystal"});
  expect_rejected("test: tensile\nmaterial:\n  model: j2\nspecimen:\n  symmetry: axisymmetric\n",
                  {"specimen.symmetry = axisymmetric", "tensile", "symmetry: full"});
  for (const std::string ok : {"sphere\n", "cone\n", "flat_punch\n", "rounded_cone\n"})
    EXPECT_EQ(error_of(axisymmetric + "indenter:\n  shape: " + ok), "") << ok;
  EXPECT_EQ(error_of(axisymmetric_of + "material:\n  model: neo_hookean\n"), "");
}

// The Vickers and Berkovich examples are valid cases with the advertised indenters and meshes.
TEST(CaseFile, PyramidExamplesAreValid)
{
  const Case v =
      read_case_file(std::string(INDENTSIM_SOURCE_DIR) + "/examples/vickers_j2_n12.yaml");
  EXPECT_EQ(v.indenter.shape, "vickers");
  EXPECT_EQ(v.material.model, "j2");
  EXPECT_EQ(v.specimen.contact_elements, 12u);
  EXPECT_EQ(v.specimen.symmetry, "quarter");
  EXPECT_EQ(v.output.directory, "results/vickers_j2_n12");
  const Case b =
      read_case_file(std::string(INDENTSIM_SOURCE_DIR) + "/examples/berkovich_j2_n12.yaml");
  EXPECT_EQ(b.indenter.shape, "berkovich");
  EXPECT_EQ(b.material.model, "j2");
  EXPECT_EQ(b.specimen.contact_elements, 12u);
  EXPECT_EQ(b.specimen.symmetry, "full");
  EXPECT_EQ(b.output.directory, "results/berkovich_j2_n12");
  EXPECT_DOUBLE_EQ(v.indenter.tip_radius, b.indenter.tip_radius);
}

// The friction and force-control examples are valid cases with the advertised programme.
TEST(CaseFile, FrictionAndForceControlExamplesAreValid)
{
  const Case f =
      read_case_file(std::string(INDENTSIM_SOURCE_DIR) + "/examples/friction_j2_n12.yaml");
  EXPECT_DOUBLE_EQ(f.contact.friction_coefficient, 0.1);
  EXPECT_EQ(f.loading.control, "depth");
  const Case c =
      read_case_file(std::string(INDENTSIM_SOURCE_DIR) + "/examples/force_control_j2_n12.yaml");
  EXPECT_EQ(c.loading.control, "force");
  EXPECT_DOUBLE_EQ(c.loading.max_force, 500.0);
  EXPECT_EQ(c.loading.cycles, 2u);
  EXPECT_EQ(c.loading.hold_steps, 2u);
  EXPECT_TRUE(c.loading.unload);
}

// Tensile-test keys outside their range, or given for the indentation test, are rejected.
TEST(CaseFile, TensileRangesAreChecked)
{
  const std::string tensile = "test: tensile\nmaterial:\n  model: crystal\n";
  EXPECT_EQ(error_of(tensile), "");
  expect_rejected(tensile + "specimen:\n  elements_per_side: 0\n",
                  {"specimen.elements_per_side = 0", "1 <= n"});
  expect_rejected(tensile + "specimen:\n  elements_per_side: 201\n",
                  {"specimen.elements_per_side = 201", "n <= 200"});
  expect_rejected(tensile + "specimen:\n  grains: random\n",
                  {"specimen.grains = 'random'", "single | per_element"});
  expect_rejected(tensile + "specimen:\n  seed: -1\n", {"specimen.seed", "-1", "negative"});
  expect_rejected(tensile + "loading:\n  spacing: geometric\n",
                  {"loading.spacing = geometric", "tensile test takes"});
  expect_rejected(tensile + "loading:\n  max_strain: 0\n",
                  {"loading.max_strain = 0", "0 < strain <= 1"});
  expect_rejected(tensile + "loading:\n  max_strain: 1.5\n",
                  {"loading.max_strain = 1.5", "0 < strain <= 1"});
  expect_rejected(tensile + "compare_j2: yes please\n",
                  {"compare_j2", "yes please", "true or false"});
  expect_rejected(with("compare_j2: true\n"), {"compare_j2 = true", "only the tensile test"});
  expect_rejected(with("specimen:\n  grains: per_element\n"),
                  {"specimen.grains = per_element", "only implemented for test: tensile"});
  expect_rejected(with("elements_per_side: 3\n"),
                  {"unknown key 'elements_per_side'", "did you mean 'specimen.elements_per_side'"});
  // The tensile cube ignores specimen.symmetry, so the mirror-plane check does not apply.
  EXPECT_EQ(error_of(tensile + "  orientation: {surface_normal: [1, 1, 1], "
                               "reference_direction: [1, -1, 0]}\n"
                               "specimen:\n  symmetry: quarter\n  grains: per_element\n"),
            "");
}

// The tensile example is a valid case with the paper's Table 2 and 27 grains.
TEST(CaseFile, TensileExampleIsValid)
{
  const Case c =
      read_case_file(std::string(INDENTSIM_SOURCE_DIR) + "/examples/tensile_27_grains.yaml");
  EXPECT_EQ(c.test, "tensile");
  EXPECT_TRUE(c.compare_j2);
  EXPECT_EQ(c.material.model, "crystal");
  EXPECT_DOUBLE_EQ(c.material.C11, 106.7);
  EXPECT_DOUBLE_EQ(c.material.tau0, 0.12);
  EXPECT_DOUBLE_EQ(c.material.q, 1.4);
  EXPECT_DOUBLE_EQ(c.material.yield_exponent_n, 10.);
  EXPECT_EQ(c.specimen.elements_per_side, 3u);
  EXPECT_EQ(c.specimen.grains, "per_element");
  EXPECT_EQ(c.specimen.seed, 1u);
  EXPECT_DOUBLE_EQ(c.loading.max_strain, 0.2);
  EXPECT_EQ(c.loading.steps, 100u);
  EXPECT_EQ(c.output.directory, "results/tensile_27_grains");
}

// The resolved case documents units next to the values it writes.
TEST(CaseFile, ResolvedCaseCarriesUnitComments)
{
  const std::string text = resolved_case_yaml(Case());
  for (const std::string fragment :
       {"young_modulus: 69", "# E [GPa]", "max_depth: 6", "delta: 0.005", "[um]", "[mN]",
        "radius: 10", "half_angle_deg: 70.3", "tip_radius: 0", "rotation_deg: 0", "edge_radius: 0",
        "file: \"\"", "[deg]", "size: [360, 360, 180]", "f_bar: true",
        "directory: \"results/run\""})
    EXPECT_NE(text.find(fragment), std::string::npos) << fragment << "\n" << text;
}

// A misspelt or misplaced key at any level is an error that suggests the intended key.
TEST(CaseFile, UnknownKeysAreRejectedWithSuggestion)
{
  expect_rejected("tset: indentation\nmaterial:\n  model: j2\n",
                  {"unknown key 'tset'", "did you mean 'test'"});
  expect_rejected(with("  youngs_modulus: 70\n"), {"unknown key 'material.youngs_modulus'",
                                                   "did you mean 'material.young_modulus'", ":4:"});
  expect_rejected(with("loading:\n  max_depht: 5\n"),
                  {"loading.max_depht", "did you mean 'loading.max_depth'"});
  expect_rejected(with("max_depth: 5\n"),
                  {"unknown key 'max_depth'", "did you mean 'loading.max_depth'"});
  expect_rejected(
      with("specimen:\n  elephant: 1\n"),
      {"unknown key 'specimen.elephant'", "Allowed keys in 'specimen'", "contact_elements"});
  expect_rejected(with("output:\n  directory: a\n  directory: b\n"),
                  {"duplicate key 'output.directory'"});
}

// A case without `test` or `material.model` is rejected, naming the missing key.
TEST(CaseFile, MissingRequiredKeys)
{
  expect_rejected("material:\n  model: j2\n", {"missing required key 'test'", "indentation"});
  expect_rejected("test: indentation\n", {"missing required key 'material.model'", "j2"});
  expect_rejected("test: indentation\nmaterial:\n  young_modulus: 69\n",
                  {"material.model", "neo_hookean"});
  expect_rejected("", {"missing required key 'test'"});
}

// Values of the wrong type name the key, the value and the expected type.
TEST(CaseFile, WrongTypesAreRejected)
{
  expect_rejected(with("  young_modulus: abc\n"),
                  {"material.young_modulus", "abc", "expected a number"});
  expect_rejected(with("  young_modulus:\n"), {"material.young_modulus", "no value"});
  expect_rejected(with("loading:\n  steps: -3\n"), {"loading.steps", "-3", "negative"});
  expect_rejected(with("specimen:\n  contact_elements: 12.5\n"),
                  {"specimen.contact_elements", "12.5", "whole number"});
  expect_rejected(with("specimen:\n  size: [360, 360]\n"),
                  {"specimen.size", "[360, 360]", "3 numbers", "got 2"});
  expect_rejected(with("specimen:\n  refined_region: 120\n"),
                  {"specimen.refined_region", "120", "list of 3"});
  expect_rejected(with("specimen:\n  size: [360, wide, 180]\n"),
                  {"specimen.size[1]", "wide", "expected a number"});
  expect_rejected(with("loading:\n  unload: maybe\n"),
                  {"loading.unload", "maybe", "true or false"});
  expect_rejected(with("indenter:\n  shape: [rounded_cone]\n"), {"indenter.shape", "rounded_cone"});
  expect_rejected(with("contact: 0.0\n"), {"'contact' = 0.0", "mapping"});
  expect_rejected(with("solver:\n  max_newton_iterations: 1e99\n"),
                  {"solver.max_newton_iterations", "1e99"});
}

// A YAML syntax error is reported with the file and the line.
TEST(CaseFile, SyntaxErrorNamesTheLine)
{
  expect_rejected("test: indentation\nmaterial:\n  model: [j2\n  young_modulus: 69\n",
                  {"YAML syntax error"});
  const std::string message = error_of("test: indentation\nmaterial: {model: j2\n");
  EXPECT_NE(message.find("bad.yaml:"), std::string::npos) << message;
  EXPECT_NE(message.find("YAML syntax error"), std::string::npos) << message;

  const fs::path    dir = scratch_directory("syntax");
  const std::string path = write_text(dir / "broken.yaml", "test: indentation\nmaterial:\n"
                                                           "  model: j2\n  a: b: c\n")
                               .string();
  try
    {
      read_case_file(path);
      FAIL() << "no error for broken YAML";
    }
  catch (const CaseFileError &error)
    {
      const std::string text = error.what();
      EXPECT_NE(text.find(path + ":4:"), std::string::npos) << text;
      EXPECT_NE(text.find("YAML syntax error"), std::string::npos) << text;
    }
}

// A case file that does not exist gives an error naming the path.
TEST(CaseFile, MissingFileIsReported)
{
  const std::string path = (scratch_directory("missing_file") / "no_such_case.yaml").string();
  try
    {
      read_case_file(path);
      FAIL() << "no error for a missing file";
    }
  catch (const CaseFileError &error)
    {
      EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("does not exist"), std::string::npos);
    }
}

// Material parameters outside their physical range are rejected with key, value and range.
TEST(CaseFile, MaterialRangesAreChecked)
{
  expect_rejected(with("  young_modulus: 0\n"), {"material.young_modulus = 0", "> 0", ":4:"});
  expect_rejected(with("  young_modulus: -69\n"), {"material.young_modulus = -69"});
  expect_rejected(with("  poisson_ratio: 0.5\n"),
                  {"material.poisson_ratio = 0.5", "-1 < nu < 0.5"});
  expect_rejected(with("  poisson_ratio: -1\n"), {"material.poisson_ratio = -1"});
  expect_rejected(with("  yield_stress: 0\n"), {"material.yield_stress = 0", "> 0"});
  expect_rejected(with("  hardening_modulus: -0.1\n"),
                  {"material.hardening_modulus = -0.1", ">= 0"});
  EXPECT_EQ(error_of(with("  hardening_modulus: 0\n  poisson_ratio: 0.499\n")), "");
}

// Indenter and specimen geometry that cannot be meshed or makes no sense is rejected.
TEST(CaseFile, GeometryRangesAreChecked)
{
  expect_rejected(with("indenter:\n  a: 0\n"), {"indenter.a = 0", "> 0"});
  expect_rejected(with("indenter:\n  delta: -0.001\n"), {"indenter.delta = -0.001", ">= 0"});
  EXPECT_EQ(error_of(with("indenter:\n  delta: 0\n")), "") << "a sharp cone is allowed";
  expect_rejected(with("specimen:\n  size: [360, 0, 180]\n"),
                  {"specimen.size = [360, 0, 180]", "> 0", "y entry"});
  expect_rejected(with("specimen:\n  refined_region: [120, 120, -30]\n"),
                  {"specimen.refined_region = [120, 120, -30]", "z entry"});
  expect_rejected(with("specimen:\n  refined_region: [400, 120, 30]\n"),
                  {"specimen.refined_region = [400, 120, 30]", "x extent", "[360, 360, 180]"});
  expect_rejected(with("specimen:\n  size: [360, 360, 20]\n"),
                  {"specimen.refined_region = [120, 120, 30] (default)", "z extent",
                   "specimen.size = [360, 360, 20]"});
  expect_rejected(with("specimen:\n  contact_elements: 10\n"),
                  {"specimen.contact_elements = 10", "multiple of 4", "quarter"});
  expect_rejected(with("specimen:\n  contact_elements: 0\n"),
                  {"specimen.contact_elements = 0", "multiple of 4"});
  EXPECT_EQ(error_of(with("specimen:\n  contact_elements: 8\n  symmetry: quarter\n")), "");
}

// Loading, contact, solver and output settings outside their admissible range are rejected.
TEST(CaseFile, LoadingContactSolverRangesAreChecked)
{
  expect_rejected(with("loading:\n  steps: 0\n"), {"loading.steps = 0", "1 <= steps <= 100000"});
  expect_rejected(with("loading:\n  max_depth: 0\n"), {"loading.max_depth = 0", "> 0"});
  expect_rejected(with("loading:\n  max_depth: -2\n"), {"loading.max_depth = -2"});
  expect_rejected(with("loading:\n  max_depth: 30\n"),
                  {"loading.max_depth = 30", "refined_region[2] = 30"});
  expect_rejected(with("contact:\n  friction_coefficient: -0.1\n"),
                  {"contact.friction_coefficient = -0.1", "0 <= mu <= 2"});
  expect_rejected(with("contact:\n  friction_coefficient: 10\n"),
                  {"contact.friction_coefficient = 10", "0 <= mu <= 2"});
  EXPECT_EQ(error_of(with("contact:\n  friction_coefficient: 0.2\n")), "");
  expect_rejected(with("loading:\n  control: load\n"),
                  {"loading.control = 'load'", "depth | force"});
  expect_rejected(with("loading:\n  control: force\n"),
                  {"loading.max_force = 0", "force control needs the maximum indenter force"});
  expect_rejected(with("loading:\n  max_force: 100\n"),
                  {"loading.max_force = 100", "with loading.control: depth"});
  EXPECT_EQ(error_of(with("loading:\n  control: force\n  max_force: 100\n")), "");
  expect_rejected(with("loading:\n  cycles: 0\n"), {"loading.cycles = 0", "1 <= cycles"});
  expect_rejected(with("loading:\n  cycles: 2\n  unload: false\n"),
                  {"loading.cycles = 2", "need loading.unload: true"});
  EXPECT_EQ(error_of(with("loading:\n  cycles: 3\n  hold_steps: 4\n")), "");
  // Partial unloads: by depth, within the loading, in one cycle.
  EXPECT_EQ(error_of(with("loading:\n  partial_unloads: {every: 0.5, fraction: 0.1}\n")), "");
  expect_rejected(with("loading:\n  partial_unloads: {every: 6}\n"),
                  {"loading.partial_unloads.every = 6", "smaller than loading.max_depth = 6"});
  expect_rejected(with("loading:\n  partial_unloads: {every: -1}\n"),
                  {"loading.partial_unloads.every = -1", ">= 0 um"});
  expect_rejected(with("loading:\n  partial_unloads: {every: 0.5, fraction: 0.6}\n"),
                  {"loading.partial_unloads.fraction = 0.6", "0 < fraction <= 0.5"});
  expect_rejected(with("loading:\n  partial_unloads: {every: 0.5, points: 2}\n"),
                  {"loading.partial_unloads.points = 2", "3 <= points <= 100"});
  expect_rejected(with("loading:\n  control: force\n  max_force: 100\n  partial_unloads: "
                       "{every: 0.5}\n"),
                  {"loading.partial_unloads.every = 0.5", "loading.control: depth"});
  expect_rejected(with("loading:\n  cycles: 2\n  partial_unloads: {every: 0.5}\n"),
                  {"loading.partial_unloads.every = 0.5", "loading.cycles: 1"});
  expect_rejected(with("loading:\n  partial_unloads: {every: 0.001}\n"),
                  {"loading.partial_unloads.every = 0.001", "more than 1000"});
  expect_rejected(with("loading:\n  partial_unloads: {evry: 0.5}\n"),
                  {"loading.partial_unloads.evry"});
  expect_rejected(with("loading:\n  spacing: logarithmic\n"),
                  {"loading.spacing", "logarithmic", "uniform", "geometric"});
  expect_rejected(with("loading:\n  spacing: geometric\n  steps: 1\n"),
                  {"loading.steps = 1", "at least 2 steps"});
  expect_rejected(with("loading:\n  spacing: geometric\n  first_fraction: 0\n"),
                  {"loading.first_fraction = 0", "0 < first_fraction <= 0.5"});
  expect_rejected(with("loading:\n  first_fraction: 0.01\n"),
                  {"loading.first_fraction = 0.01", "spacing: uniform"});
  EXPECT_EQ(error_of(with("loading:\n  spacing: geometric\n  first_fraction: 0.01\n")), "");
  expect_rejected(with("contact:\n  penalty: -1\n"), {"contact.penalty = -1"});
  expect_rejected(with("contact:\n  penetration_tolerance: 0\n"),
                  {"contact.penetration_tolerance = 0"});
  expect_rejected(with("solver:\n  residual_tolerance: 1.5\n"),
                  {"solver.residual_tolerance = 1.5"});
  expect_rejected(with("solver:\n  max_newton_iterations: 0\n"),
                  {"solver.max_newton_iterations = 0"});
  expect_rejected(with("solver:\n  linear_solver: amg\n"),
                  {"solver.linear_solver", "amg", "auto", "direct", "iterative"});
  expect_rejected(with("solver:\n  threads: 5000\n"), {"solver.threads = 5000", "1024"});
  expect_rejected(with("solver:\n  threads: -1\n"), {"solver.threads", "-1"});
  expect_rejected(with("output:\n  directory: \"\"\n"), {"output.directory"});
}

// Unknown enumeration values list the allowed values.
TEST(CaseFile, UnknownChoicesListAllowedValues)
{
  expect_rejected("test: indentation\nmaterial:\n  model: elastic\n",
                  {"material.model = 'elastic'", "neo_hookean | j2"});
  expect_rejected("test: indentation\nmaterial:\n  model: J2\n",
                  {"material.model = 'J2'", "did you mean 'j2'"});
  expect_rejected(with("indenter:\n  shape: sphre\n"),
                  {"indenter.shape = 'sphre'",
                   "rounded_cone | sphere | cone | vickers | berkovich | flat_punch | "
                   "profile_table",
                   "did you mean 'sphere'"});
  expect_rejected(with("specimen:\n  symmetry: half\n"),
                  {"specimen.symmetry = 'half'", "full | quarter"});
  expect_rejected("test: compression\nmaterial:\n  model: j2\n",
                  {"test = 'compression'", "indentation | tensile"});
  expect_rejected(with("  yield_stress_measure: mises\n"),
                  {"material.yield_stress_measure = 'mises'", "cauchy | kirchhoff"});
  expect_rejected(
      "test: indentation\nmaterial:\n  model: cristal\n",
      {"material.model = 'cristal'", "neo_hookean | j2 | crystal", "did you mean 'crystal'"});
  EXPECT_EQ(error_of("test: tensile\nmaterial:\n  model: j2\n"), "");
}

// validate_case applies the same checks to a case changed in code (e.g. by --output).
TEST(CaseFile, ValidateCaseChecksProgrammaticCases)
{
  Case c;
  EXPECT_NO_THROW(validate_case(c));
  c.output.directory = "";
  EXPECT_THROW(validate_case(c), CaseFileError);
  c = Case();
  c.material.poisson_ratio = 0.6;
  try
    {
      validate_case(c);
      FAIL() << "nu = 0.6 accepted";
    }
  catch (const CaseFileError &error)
    {
      EXPECT_NE(std::string(error.what()).find("material.poisson_ratio = 0.6"), std::string::npos)
          << error.what();
    }
}

// A new output directory is created, with its parents, and is usable.
TEST(OutputDirectory, IsCreated)
{
  const fs::path dir = scratch_directory("create") / "a" / "b";
  prepare_output_directory(dir.string(), false);
  EXPECT_TRUE(fs::is_directory(dir));
  EXPECT_TRUE(fs::is_empty(dir)) << "the write probe was left behind";
  // Unrelated files do not count as an earlier run.
  write_text(dir / "notes.txt", "mine");
  EXPECT_NO_THROW(prepare_output_directory(dir.string(), false));
}

// An earlier run's results are never overwritten without --overwrite.
TEST(OutputDirectory, RefusesEarlierResultsWithoutOverwrite)
{
  const fs::path dir = scratch_directory("refuse");
  write_text(dir / "load_penetration.csv", "step,depth_um,force_mN\n");
  try
    {
      prepare_output_directory(dir.string(), false);
      FAIL() << "earlier results accepted without --overwrite";
    }
  catch (const CaseFileError &error)
    {
      const std::string message = error.what();
      EXPECT_NE(message.find(dir.string()), std::string::npos) << message;
      EXPECT_NE(message.find("--overwrite"), std::string::npos) << message;
      EXPECT_NE(message.find("load_penetration.csv"), std::string::npos) << message;
    }
  EXPECT_TRUE(fs::exists(dir / "load_penetration.csv"));

  const fs::path other = scratch_directory("refuse_resolved");
  write_text(other / "resolved_case.yaml", "test: indentation\n");
  EXPECT_THROW(prepare_output_directory(other.string(), false), CaseFileError);
  const fs::path tensile = scratch_directory("refuse_tensile");
  write_text(tensile / "stress_strain_j2.csv", "step,log_strain\n");
  EXPECT_THROW(prepare_output_directory(tensile.string(), false), CaseFileError);
  const fs::path paraview = scratch_directory("refuse_paraview");
  write_text(paraview / "specimen.pvd", "<VTKFile/>");
  EXPECT_THROW(prepare_output_directory(paraview.string(), false), CaseFileError);
}

// --overwrite removes only indentsim's own output files and keeps everything else.
TEST(OutputDirectory, OverwriteRemovesOnlyOwnFiles)
{
  const fs::path dir = scratch_directory("overwrite");
  for (const char *name : {"load_penetration.csv", "load_penetration.png", "resolved_case.yaml",
                           "run.log", "specimen.pvd", "specimen_0003.pvtu", "specimen_0003.0.vtu",
                           "stress_strain.csv", "stress_strain_j2.csv", "stress_strain.png"})
    write_text(dir / name, "old");
  for (const char *name : {"notes.txt", "my_mesh.vtu", "load_penetration_paper.csv"})
    write_text(dir / name, "keep");
  fs::create_directories(dir / "my_analysis");
  write_text(dir / "my_analysis" / "resolved_case.yaml", "keep");

  prepare_output_directory(dir.string(), true);
  for (const char *name : {"load_penetration.csv", "load_penetration.png", "resolved_case.yaml",
                           "run.log", "specimen.pvd", "specimen_0003.pvtu", "specimen_0003.0.vtu",
                           "stress_strain.csv", "stress_strain_j2.csv", "stress_strain.png"})
    EXPECT_FALSE(fs::exists(dir / name)) << name;
  for (const char *name : {"notes.txt", "my_mesh.vtu", "load_penetration_paper.csv"})
    EXPECT_TRUE(fs::exists(dir / name)) << name;
  EXPECT_TRUE(fs::exists(dir / "my_analysis" / "resolved_case.yaml"));
  // The emptied directory now counts as fresh.
  EXPECT_NO_THROW(prepare_output_directory(dir.string(), false));
}

// A directory that cannot be created or written gives an error naming it.
TEST(OutputDirectory, UnusableDirectoryIsReported)
{
  const fs::path root = scratch_directory("unusable");
  write_text(root / "a_file", "x");
  const std::string below_file = (root / "a_file" / "out").string();
  try
    {
      prepare_output_directory(below_file, false);
      FAIL() << "a directory below a regular file was accepted";
    }
  catch (const CaseFileError &error)
    {
      EXPECT_NE(std::string(error.what()).find(below_file), std::string::npos) << error.what();
    }
  EXPECT_THROW(prepare_output_directory((root / "a_file").string(), false), CaseFileError);
}

// An existing directory that cannot take a file is detected by the write probe. /proc is such
// a directory for every user, root included (permission bits do not bind root, so a directory
// made read-only with them is checked only when the test does not run as root).
TEST(OutputDirectory, ReadOnlyDirectoryIsReported)
{
  const auto expect_not_writable = [](const fs::path &dir) {
    try
      {
        prepare_output_directory(dir.string(), false);
        ADD_FAILURE() << "the read-only directory " << dir << " was accepted";
      }
    catch (const CaseFileError &error)
      {
        EXPECT_NE(std::string(error.what()).find("not writable"), std::string::npos)
            << error.what();
      }
  };
  ASSERT_TRUE(fs::is_directory("/proc"));
  expect_not_writable("/proc");
  if (::geteuid() != 0)
    {
      const fs::path dir = scratch_directory("read_only");
      fs::permissions(dir, fs::perms::owner_read | fs::perms::owner_exec);
      expect_not_writable(dir);
      fs::permissions(dir, fs::perms::owner_all);
    }
}

// The documented command forms parse into the right command and options.
TEST(CommandLine, ParsesTheDocumentedForms)
{
  auto options = parse_command_line({"run", "case.yaml"});
  EXPECT_EQ(options.command, Command::run);
  EXPECT_EQ(options.case_file, "case.yaml");
  EXPECT_FALSE(options.output_directory.has_value());
  EXPECT_FALSE(options.overwrite);

  options = parse_command_line({"run", "case.yaml", "--output", "out", "--overwrite"});
  EXPECT_EQ(options.command, Command::run);
  EXPECT_EQ(options.output_directory.value_or(""), "out");
  EXPECT_TRUE(options.overwrite);

  options = parse_command_line({"run", "--overwrite", "--output=o2", "c.yaml"});
  EXPECT_EQ(options.case_file, "c.yaml");
  EXPECT_EQ(options.output_directory.value_or(""), "o2");

  options = parse_command_line({"check", "case.yaml"});
  EXPECT_EQ(options.command, Command::check);
  EXPECT_EQ(options.case_file, "case.yaml");

  options = parse_command_line({"run", "tensile.yaml", "--compare-j2"});
  EXPECT_TRUE(options.compare_j2);
  EXPECT_FALSE(parse_command_line({"run", "tensile.yaml"}).compare_j2);
  EXPECT_TRUE(parse_command_line({"check", "--compare-j2", "tensile.yaml"}).compare_j2);

  const char *argv[] = {"indentsim", "--version"};
  EXPECT_EQ(parse_command_line(2, argv).command, Command::version);
  EXPECT_EQ(parse_command_line({"--help"}).command, Command::help);
  EXPECT_EQ(parse_command_line({"-h"}).command, Command::help);
}

// Bad usage raises an error that carries the usage text.
TEST(CommandLine, BadUsageShowsUsage)
{
  for (const std::vector<std::string> &arguments :
       std::vector<std::vector<std::string>>{{},
                                             {"case.yaml"},
                                             {"simulate", "case.yaml"},
                                             {"run"},
                                             {"run", "a.yaml", "b.yaml"},
                                             {"run", "a.yaml", "--output"},
                                             {"run", "a.yaml", "--frobnicate"},
                                             {"check", "a.yaml", "--overwrite"},
                                             {"--version", "extra"}})
    {
      std::string joined;
      for (const auto &argument : arguments)
        joined += argument + " ";
      try
        {
          parse_command_line(arguments);
          ADD_FAILURE() << "accepted: indentsim " << joined;
        }
      catch (const CommandLineError &error)
        {
          EXPECT_NE(std::string(error.what()).find("Usage:"), std::string::npos) << joined;
        }
    }
}

// The help text lists the commands and options and states the units.
TEST(CommandLine, HelpListsCommandsOptionsAndUnits)
{
  const std::string help = help_text();
  for (const std::string fragment :
       {"run CASE.yaml", "check CASE.yaml", "--output DIR", "--overwrite", "--compare-j2", "--help",
        "--version", "um", "mN", "GPa", "stress_strain.csv"})
    EXPECT_NE(help.find(fragment), std::string::npos) << fragment;
  EXPECT_NE(version_text().find("indentsim"), std::string::npos);
}

// The version names the project version and the commit the build came from: compared with what
// git itself says of the source tree (the build refreshes the generated file before every build,
// so a stale version fails here).
TEST(CommandLine, VersionNamesTheGitCommit)
{
  const std::string version = indentsim::version();
  const std::string project = std::string(INDENTSIM_PROJECT_VERSION) + " (";
  ASSERT_EQ(version.rfind(project, 0), 0u) << version;
  ASSERT_EQ(version.back(), ')') << version;
  EXPECT_EQ(version_text(), "indentsim " + version + "\n");

  const std::string source = INDENTSIM_SOURCE_DIR;
  if (!std::filesystem::exists(source + "/.git") ||
      std::system("git --version > /dev/null 2>&1") != 0)
    {
      EXPECT_EQ(version, project + "no git checkout)");
      return;
    }
  std::string head;
  {
    FILE *pipe = popen(("git -C '" + source + "' rev-parse HEAD 2>/dev/null").c_str(), "r");
    ASSERT_NE(pipe, nullptr);
    char buffer[128];
    while (std::fgets(buffer, sizeof buffer, pipe) != nullptr)
      head += buffer;
    pclose(pipe);
  }
  if (head.size() < 40) // git refuses the tree (e.g. another owner): so does the build
    {
      EXPECT_EQ(version, project + "no git checkout)");
      return;
    }
  const std::string expected = project + "git " + head.substr(0, 12);
  EXPECT_EQ(version.rfind(expected, 0), 0u) << version << " does not start with " << expected;
}

// output.experimental_curve: relative to the case file's directory, stored absolute, read and
// checked before any computation; a missing file or a column without a known unit is rejected
// naming the key, the file and what is allowed.
TEST(CaseFile, ExperimentalCurveIsResolvedAndChecked)
{
  const fs::path dir = scratch_directory("experimental_curve");
  fs::create_directories(dir / "cases" / "data");
  write_text(dir / "cases" / "data" / "measured.csv", "depth_nm,load_uN\n0,0\n500,1000\n");
  const fs::path case_path =
      write_text(dir / "cases" / "case.yaml",
                 with("output:\n  directory: out\n  experimental_curve: data/measured.csv\n"));
  const Case c = read_case_file(case_path.string());
  EXPECT_EQ(c.output.experimental_curve,
            fs::absolute(dir / "cases" / "data" / "measured.csv").lexically_normal().string());
  Case missing = c;
  missing.output.experimental_curve = "/no/such/measured.csv";
  expect_rejected_case(missing, {"output.experimental_curve = \"/no/such/measured.csv\"",
                                 "cannot open", "depth_nm,load_uN"});
  write_text(dir / "cases" / "data" / "unitless.csv", "depth,force\n0,0\n1,2\n");
  Case unitless = c;
  unitless.output.experimental_curve = (dir / "cases" / "data" / "unitless.csv").string();
  expect_rejected_case(unitless, {"output.experimental_curve", "depth unit '' is not known"});
}

// docs/case-file-reference.md is generated from the schema; it must be the generator's text.
TEST(CaseFile, ReferenceDocumentIsUpToDate)
{
  const std::string path = std::string(INDENTSIM_SOURCE_DIR) + "/docs/case-file-reference.md";
  std::string       committed;
  if (fs::exists(path))
    committed = read_text_file(path);
  EXPECT_TRUE(committed == case_file_reference_markdown())
      << path << " is out of date with the case schema (src/case/Schema.cc); regenerate it from "
      << "the repository root with: " << case_reference_command;
}

// Every schema key appears in the reference and in the resolved case.
TEST(CaseFile, EveryKeyIsDocumentedAndWritten)
{
  const std::string reference = case_file_reference_markdown();
  Case              by_normal;
  by_normal.material.orientation.kind = OrientationKind::surface_normal;
  std::string written = resolved_case_yaml(Case()) + resolved_case_yaml(by_normal);
  // The J2 hardening laws other than linear write their own keys.
  for (const auto law : {HardeningLaw::power, HardeningLaw::voce, HardeningLaw::table})
    {
      Case c;
      c.material.hardening_law = law;
      written += resolved_case_yaml(c);
      c.material.hardening_file = "curve.csv";
      written += resolved_case_yaml(c);
    }
  Case geometric; // writes loading.first_fraction
  geometric.loading.spacing = Spacing::geometric;
  written += resolved_case_yaml(geometric);
  Case hexagonal; // writes material.slip_families, c_over_a, elastic.C13 and C33
  hexagonal.material.lattice = Lattice::hcp;
  written += resolved_case_yaml(hexagonal);
  Case automatic; // writes specimen.elements_per_radius
  automatic.specimen.contact_elements = automatic_contact_elements;
  written += resolved_case_yaml(automatic);
  Case families; // writes a family's block (named by the family) and the latent matrix
  families.material.family_hardening = {{"{111}<110>", 0.1, 0.02, 0.1, 0.006}};
  families.material.latent_matrix = {{1.4}};
  written += resolved_case_yaml(families);
  Case layered; // writes material.layers
  layered.material.layers = {{1.5, "{yield_stress: 0.6}"}};
  written += resolved_case_yaml(layered);
  layered.specimen.contact_elements = automatic_contact_elements; // elements_across_layers
  written += resolved_case_yaml(layered);
  Case irradiated; // writes the crystal's irradiation keys
  irradiated.material.model = ModelKind::crystal;
  irradiated.material.tau_irr = 0.1;
  written += resolved_case_yaml(irradiated);
  for (const auto law : {DamageLaw::saturation, DamageLaw::table, DamageLaw::dispersed_barrier})
    {
      Case damaged; // writes the damage profile inline, then by its file, with each law's keys
      damaged.material.damage_profile.depth = {0, 1};
      damaged.material.damage_profile.dpa = {1, 0};
      damaged.material.damage_profile.law = law;
      written += resolved_case_yaml(damaged);
      damaged.material.damage_profile.file = "dpa.csv";
      written += resolved_case_yaml(damaged);
    }
  for (const auto &key : case_keys())
    {
      EXPECT_NE(reference.find("| `" + key.path + "` |"), std::string::npos) << key.path;
      const std::string name = key.type == ValueType::family_blocks ? "\"{111}<110>\"" : key.name();
      EXPECT_NE(written.find(name + ": "), std::string::npos) << key.path;
      EXPECT_FALSE(key.description.empty()) << key.path;
    }
}

// One fingerprint for checkpoint and study: keys that only say where and when results are
// written (or how many threads share the work) leave it unchanged; a physical key changes it.
TEST(CaseFile, FingerprintIgnoresOnlyKeysThatDoNotDetermineResults)
{
  const Case          base = parse_case_yaml(minimal_case, "a.yaml");
  const std::uint64_t fingerprint = case_fingerprint(base);

  Case moved = base;
  moved.source_file = "elsewhere/b.yaml";
  moved.output.directory = "results/other";
  moved.output.checkpoint_interval_s = 17;
  moved.solver.threads = 3;
  EXPECT_EQ(case_fingerprint(moved), fingerprint);
  EXPECT_EQ(canonical_case_text(moved), canonical_case_text(base));

  const auto changed = [&](const auto &change) {
    Case c = base;
    change(c);
    return case_fingerprint(c) != fingerprint;
  };
  EXPECT_TRUE(changed([](Case &c) { c.material.young_modulus = 70; }));
  EXPECT_TRUE(changed([](Case &c) { c.loading.max_depth = 5; }));
  EXPECT_TRUE(changed([](Case &c) { c.indenter.shape = IndenterShape::sphere; }));
  EXPECT_TRUE(changed([](Case &c) { c.contact.friction_coefficient = 0.1; }));
  EXPECT_TRUE(changed([](Case &c) { c.solver.residual_tolerance = 1e-8; }));
  EXPECT_TRUE(changed([](Case &c) { c.output.vtu_every = 2; }));
  EXPECT_TRUE(
      changed([](Case &c) { c.material.orientation.kind = OrientationKind::surface_normal; }));
  for (const auto &key : case_keys())
    EXPECT_EQ(canonical_case_text(base).find(key.path + ": ") != std::string::npos,
              key.determines_results && (key.written == nullptr || key.written(base)))
        << key.path;
}

// A word that names no enumerator is kept (for the validator's message) and compares unequal
// to every enumerator.
TEST(CaseFile, ChoiceKeepsAnUnknownWord)
{
  Choice<Control> control = "forse";
  EXPECT_FALSE(control.known());
  EXPECT_EQ(to_string(control), "forse");
  EXPECT_FALSE(control == Control::force);
  EXPECT_FALSE(control == Control::depth);
  control = "force";
  EXPECT_TRUE(control.known());
  EXPECT_TRUE(control == Control::force);
  EXPECT_EQ(choice_words<Lattice>(true), (std::vector<std::string>{"fcc", "bcc", "hcp"}));
}

// A second YAML document in a case file (after a second '---') would be ignored: it is refused
// with the file and the line of its '---'. A leading '---' and an empty trailing document are
// one document.
TEST(CaseFile, SecondYamlDocumentIsRefused)
{
  expect_rejected(minimal_case + "---\nloading:\n  max_depth: 1\n",
                  {"bad.yaml:4: ", "a second YAML document", "holds one document"});
  expect_rejected("---\n" + minimal_case + "--- {loading: {max_depth: 1}}\n",
                  {"bad.yaml:5: ", "a second YAML document"});
  EXPECT_EQ(error_of("---\n" + minimal_case), "");
  EXPECT_EQ(error_of(minimal_case + "---\n"), "");
  EXPECT_EQ(error_of(minimal_case + "...\n"), "");
}

// Tab indentation and binary content (a NUL byte, bytes that are not UTF-8) are named with
// their line, instead of the YAML parser's generic message; a tab inside a value or a comment
// is not indentation, and UTF-8 text (a byte-order mark, a µ) is accepted.
TEST(CaseFile, TabsAndBinaryContentAreNamed)
{
  expect_rejected("test: indentation\nmaterial:\n\tmodel: j2\n",
                  {"bad.yaml:3: ", "a tab in the indentation (column 1)", "spaces"});
  expect_rejected("test: indentation\nmaterial:\n  \tmodel: j2\n",
                  {"bad.yaml:3: ", "a tab in the indentation (column 3)"});
  expect_rejected(minimal_case + "loading:\n  max_depth: 1\0\n"s,
                  {"bad.yaml:5: ", "binary content (a NUL byte at column 15)"});
  expect_rejected(minimal_case + "# \xFF\xFE\n", {"bad.yaml:4: ", "byte 0xFF", "not UTF-8"});
  expect_rejected("\x89PNG\r\n\x1A\n", {"bad.yaml:1: ", "binary content (byte 0x89"});
  EXPECT_EQ(error_of(minimal_case + "# \ttab in a comment, \xC2\xB5m in UTF-8\n"), "");
  EXPECT_EQ(error_of("\xEF\xBB\xBF" + minimal_case), "");
}

// Plain trilinear hexahedra lock when nearly incompressible (nu = 0.4999 gave H = 242 GPa):
// neo-Hookean with nu > 0.45 gets F-bar unless specimen.f_bar is given; nu = 0.45 and below
// keep the plain element, and an explicit f_bar: false is honoured.
TEST(CaseFile, NearlyIncompressibleNeoHookeanGetsFBar)
{
  const auto neo_hookean = [](const std::string &nu, const std::string &extra = "") {
    return parse_case_yaml(
        "test: indentation\nmaterial:\n  model: neo_hookean\n  poisson_ratio: " + nu + "\n" + extra,
        "a.yaml");
  };
  EXPECT_TRUE(neo_hookean("0.4999").specimen.f_bar);
  EXPECT_TRUE(neo_hookean("0.46").specimen.f_bar);
  EXPECT_FALSE(neo_hookean("0.45").specimen.f_bar);
  EXPECT_FALSE(neo_hookean("0.3").specimen.f_bar);
  EXPECT_FALSE(neo_hookean("0.4999", "specimen:\n  f_bar: false\n").specimen.f_bar);
  EXPECT_DOUBLE_EQ(nearly_incompressible_poisson_ratio, 0.45);
}

// A rule on two keys names the key with its value once and the other key's value in the rule:
// never a doubled label such as "material.hardening.tau1 = tau1 = 0".
TEST(CaseFile, TwoKeyRulesNameEachLabelOnce)
{
  const std::regex         doubled(R"(([A-Za-z_0-9]+) = \1 = )");
  std::vector<std::string> messages = {
      error_of("test: indentation\nmaterial:\n  model: crystal\n  hardening: {tau1: 0}\n"),
      error_of("test: indentation\nmaterial:\n  model: crystal\n  hardening: {tau1: 0, theta0: "
               "0.2}\n"),
      error_of(with("indenter:\n  shape: flat_punch\n  radius: 2\n  edge_radius: 3\n"))};
  Case c;
  c.material.tau1 = 0;
  c.material.theta0 = 0.1;
  try
    {
      validate_case(c);
    }
  catch (const CaseFileError &error)
    {
      messages.push_back(error.what());
    }
  ASSERT_EQ(messages.size(), 4u);
  for (const std::string &message : messages)
    {
      ASSERT_FALSE(message.empty());
      EXPECT_FALSE(std::regex_search(message, doubled)) << message;
    }
  EXPECT_NE(messages[1].find("material.hardening.tau1 = 0: tau1 must be > 0 when theta0 > 0 "
                             "(here theta0 = 0.2 GPa)"),
            std::string::npos)
      << messages[1];
  EXPECT_NE(messages[3].find("material.hardening.tau1 = 0: "), std::string::npos) << messages[3];
}

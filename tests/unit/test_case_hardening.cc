// The J2 hardening law in case files (material.hardening.law and its keys): the spellings of
// the user guide, the resolved case, the CSV table, study overrides, and every bad input named
// with file, key, value and what is allowed.
#include "case/CaseFile.h"
#include "case/Fingerprint.h"
#include "materials/J2Plasticity.h"
#include "materials/MaterialFactory.h"
#include "study/StudyFile.h"

#include "../case_file_errors.h"
#include "../test_files.h"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>

namespace
{
  namespace fs = std::filesystem;
  using namespace indentsim;
  using namespace indentsim::io;

  const std::string power_case =
      "test: indentation\n"
      "material: {model: j2, young_modulus: 50, poisson_ratio: 0.3, yield_stress: 0.2, "
      "hardening: {law: power, exponent: 0.3}}\n";
  const std::string linear_case =
      "test: indentation\n"
      "material: {model: j2, young_modulus: 69, poisson_ratio: 0.26, yield_stress: 0.305, "
      "hardening: {law: linear, modulus: 0.5}}\n";
  const std::string table_case =
      "test: indentation\n"
      "material: {model: j2, young_modulus: 69, poisson_ratio: 0.33, yield_stress: 0.276, "
      "hardening: {law: table, plastic_strain: [0, 0.05, 0.2], stress: [0.276, 0.31, 0.33]}}\n";

  // test: indentation with a j2 material whose block is `material` (flow-style entries).
  std::string j2_with(const std::string &material)
  {
    return "test: indentation\nmaterial: {model: j2, " + material + "}\n";
  }

  using indentsim::test_case_files::error_of;
  using indentsim::test_case_files::expect_rejected;

  const materials::IsotropicHardening &law_of(const Case                                &c,
                                              std::unique_ptr<materials::MaterialModel> &model)
  {
    model = materials::create_material(c.material);
    return dynamic_cast<const materials::J2Plasticity &>(*model).hardening_law();
  }

  fs::path write_text(const fs::path &path, const std::string &text)
  {
    std::ofstream out(path);
    out << text;
    return path;
  }
} // namespace

// The three spellings of the user guide are read into the law they name, and the material
// built from them has that law's flow stress (power: sigma_y0 (1 + E eps/sigma_y0)^n).
TEST(CaseHardening, DocumentedSpellingsAreRead)
{
  std::unique_ptr<materials::MaterialModel> model;

  const Case power = parse_case_yaml(power_case, "power.yaml");
  EXPECT_EQ(power.material.hardening_law, HardeningLaw::power);
  EXPECT_DOUBLE_EQ(power.material.hardening_exponent, 0.3);
  const auto &power_law = law_of(power, model);
  EXPECT_EQ(power_law.law(), materials::IsotropicHardening::Law::power);
  EXPECT_NEAR(power_law.flow_stress(0.01), 0.2 * std::pow(1 + 50 * 0.01 / 0.2, 0.3), 1e-15);

  const Case linear = parse_case_yaml(linear_case, "linear.yaml");
  EXPECT_EQ(linear.material.hardening_law, HardeningLaw::linear);
  EXPECT_DOUBLE_EQ(linear.material.hardening_modulus, 0.5);
  EXPECT_NEAR(law_of(linear, model).flow_stress(0.1), 0.305 + 0.05, 1e-15);

  const Case table = parse_case_yaml(table_case, "table.yaml");
  EXPECT_EQ(table.material.hardening_law, HardeningLaw::table);
  EXPECT_EQ(table.material.hardening_plastic_strain, (std::vector<double>{0, 0.05, 0.2}));
  EXPECT_EQ(table.material.hardening_stress, (std::vector<double>{0.276, 0.31, 0.33}));
  EXPECT_NEAR(law_of(table, model).flow_stress(0.125), 0.32, 1e-15);

  const Case voce =
      parse_case_yaml(j2_with("hardening: {law: voce, saturation: 0.1, rate: 20}"), "voce.yaml");
  EXPECT_DOUBLE_EQ(voce.material.hardening_modulus, 0.0) << "the Voce linear term defaults to 0";
  EXPECT_NEAR(law_of(voce, model).flow_stress(1.0), 0.305 + 0.1 * (1 - std::exp(-20.0)), 1e-15);
  const Case voce_h = parse_case_yaml(
      j2_with("hardening: {law: voce, saturation: 0.1, rate: 20, modulus: 0.2}"), "voce.yaml");
  EXPECT_DOUBLE_EQ(voce_h.material.hardening_modulus, 0.2);
}

// Without `law` the resolved case is the linear one of hardening_modulus, unchanged (no law
// keys written, the default key frozen in StudyKey.HashIsFnv1aAndStable), and
// {law: linear, modulus: H} is the same case as hardening_modulus: H (one resolved form).
TEST(CaseHardening, LinearLawResolvesToHardeningModulus)
{
  const Case        plain = parse_case_yaml(j2_with("hardening_modulus: 0.5"), "a.yaml");
  const Case        spelled = parse_case_yaml(linear_case, "b.yaml");
  const std::string text = resolved_case_yaml(plain);
  EXPECT_EQ(text.find("law:"), std::string::npos) << text;
  EXPECT_NE(text.find("hardening_modulus: 0.5"), std::string::npos) << text;
  EXPECT_EQ(canonical_case_text(plain), canonical_case_text(spelled));
  EXPECT_EQ(case_fingerprint(plain), case_fingerprint(spelled));
}

// Every law's resolved case writes its own keys (and no hardening_modulus unless it is used)
// and reads back as the identical case.
TEST(CaseHardening, ResolvedCaseRoundTrips)
{
  const fs::path dir = test_files::scratch_directory("case_hardening", "round_trip");
  write_text(dir / "curve.csv", "plastic_strain,true_stress_MPa\n0,276\n0.05,310\n0.2,330\n");
  write_text(dir / "table_file.yaml",
             j2_with("yield_stress: 0.276, hardening: {law: table, file: curve.csv}"));
  const std::vector<std::pair<Case, std::vector<std::string>>> cases = {
      {parse_case_yaml(power_case, "p.yaml"), {"law: power", "exponent: 0.3"}},
      {parse_case_yaml(j2_with("hardening: {law: voce, saturation: 0.1, rate: 20, modulus: 0.2}"),
                       "v.yaml"),
       {"law: voce", "saturation: 0.1", "rate: 20", "modulus: 0.2"}},
      {parse_case_yaml(table_case, "t.yaml"),
       {"law: table", "plastic_strain: [0, 0.05, 0.2]", "stress: [0.276, 0.31, 0.33]"}},
      {read_case_file((dir / "table_file.yaml").string()), {"law: table", "file: \""}},
  };
  for (const auto &[c, lines] : cases)
    {
      const std::string text = resolved_case_yaml(c);
      SCOPED_TRACE(text);
      for (const auto &line : lines)
        EXPECT_NE(text.find(line), std::string::npos) << line;
      EXPECT_EQ(text.find("hardening_modulus:"), std::string::npos);
      const fs::path path = dir / "resolved_case.yaml";
      write_text(path, text);
      Case back = read_case_file(path.string());
      back.source_file = c.source_file;
      EXPECT_TRUE(back == c) << "read back as\n" << resolved_case_yaml(back);
    }
}

// A table file (relative to the case file's folder) is read with the unit of its stress
// column (MPa here); a file without a unit in the stress column's name, with a wrong header
// or a bad row is refused naming the key, the file and the line.
TEST(CaseHardening, TableFromCsvFile)
{
  const fs::path dir = test_files::scratch_directory("case_hardening", "csv");
  write_text(dir / "curve.csv", "# tensile test, 6061-T6\nplastic_strain,true_stress_MPa\n"
                                "0,276\n0.05,310\n0.2,330\n");
  write_text(dir / "case.yaml",
             j2_with("yield_stress: 0.276, hardening: {law: table, file: curve.csv}"));
  const Case c = read_case_file((dir / "case.yaml").string());
  EXPECT_EQ(c.material.hardening_file, (dir / "curve.csv").lexically_normal().string());
  EXPECT_EQ(c.material.hardening_plastic_strain, (std::vector<double>{0, 0.05, 0.2}));
  ASSERT_EQ(c.material.hardening_stress.size(), 3u);
  EXPECT_NEAR(c.material.hardening_stress[1], 0.31, 1e-15);

  const auto error_with = [&](const std::string &csv) {
    write_text(dir / "bad.csv", csv);
    write_text(dir / "bad.yaml",
               j2_with("yield_stress: 0.276, hardening: {law: table, file: bad.csv}"));
    try
      {
        read_case_file((dir / "bad.yaml").string());
      }
    catch (const CaseFileError &error)
      {
        return std::string(error.what());
      }
    return std::string();
  };
  const auto expect_error = [&](const std::string &csv, std::initializer_list<std::string> parts) {
    const std::string message = error_with(csv);
    SCOPED_TRACE(message);
    ASSERT_FALSE(message.empty());
    EXPECT_NE(message.find("material.hardening.file"), std::string::npos);
    EXPECT_NE(message.find("bad.csv"), std::string::npos);
    for (const auto &part : parts)
      EXPECT_NE(message.find(part), std::string::npos) << part;
  };
  expect_error("plastic_strain,true_stress\n0,0.276\n0.1,0.3\n", {"no unit", "GPa or MPa"});
  expect_error("strain,stress_GPa\n0,0.276\n", {"line 1", "plastic_strain,true_stress_GPa"});
  expect_error("plastic_strain,stress_GPa\n0,0.276\n0.1,abc\n", {"line 3", "0.1,abc"});
  expect_error("plastic_strain,stress_GPa\n0,0.276\n", {"1 points", "at least 2"});
  expect_error("plastic_strain,stress_GPa\n0,0.276\n0.1,0.25\n", {"stress[1] = 0.25"});
  expect_error("plastic_strain,stress_GPa\n0,0.3\n0.1,0.35\n",
               {"first stress", "0.3 GPa", "yield_stress = 0.276"});
  std::filesystem::remove(dir / "bad.csv");
  write_text(dir / "bad.yaml",
             j2_with("yield_stress: 0.276, hardening: {law: table, file: bad.csv}"));
  EXPECT_THROW(read_case_file((dir / "bad.yaml").string()), CaseFileError);
}

// Every bad hardening input is refused with the file, the key, the value and what is allowed.
TEST(CaseHardening, BadInputIsNamed)
{
  // Unknown law: the allowed ones listed.
  expect_rejected(j2_with("hardening: {law: exponential, exponent: 0.2}"),
                  {"material.hardening.law = 'exponential'", "linear | power | voce | table"});
  // Missing keys of each law, and keys of another law or unknown keys.
  expect_rejected(j2_with("hardening: {law: power}"),
                  {"law: power needs material.hardening.exponent"});
  expect_rejected(j2_with("hardening: {law: linear}"),
                  {"law: linear needs material.hardening.modulus"});
  expect_rejected(j2_with("hardening: {law: voce, saturation: 0.1}"),
                  {"law: voce needs material.hardening.rate", "saturation, rate, modulus"});
  expect_rejected(j2_with("hardening: {law: table}"), {"law: table needs the table"});
  expect_rejected(j2_with("hardening: {law: table, plastic_strain: [0, 0.1]}"),
                  {"law: table needs stress"});
  expect_rejected(j2_with("hardening: {law: power, exponent: 0.2, saturation: 0.1}"),
                  {"material.hardening.saturation = 0.1", "not a parameter of law: power",
                   "its keys: exponent"});
  expect_rejected(j2_with("hardening: {law: power, n: 0.2}"),
                  {"unknown key 'material.hardening.n'", "exponent"});
  expect_rejected(j2_with("hardening: {exponent: 0.2}"),
                  {"material.hardening.exponent = 0.2", "without material.hardening.law"});
  expect_rejected(j2_with("yield_stress: 0.276, hardening: {law: table, file: c.csv, "
                          "plastic_strain: [0, 0.1], stress: [0.276, 0.3]}"),
                  {"material.hardening.file", "given twice"});
  // H given twice.
  expect_rejected(j2_with("hardening_modulus: 0.5, hardening: {law: linear, modulus: 0.5}"),
                  {"material.hardening_modulus = 0.5", "give the hardening once"});
  expect_rejected(j2_with("hardening_modulus: 0.5, hardening: {law: power, exponent: 0.1}"),
                  {"material.hardening_modulus = 0.5", "law: power"});
  // A J2 law on another model.
  expect_rejected("test: indentation\nmaterial: {model: crystal, hardening: {law: power, "
                  "exponent: 0.2}}\n",
                  {"material.hardening.law = power", "model: j2", "tau0"});
  expect_rejected("test: indentation\nmaterial: {model: neo_hookean, hardening: {law: voce, "
                  "saturation: 0.1, rate: 3}}\n",
                  {"material.hardening.law = voce", "no plasticity"});
  // Values out of range.
  expect_rejected(j2_with("hardening: {law: power, exponent: 1}"),
                  {"material.hardening.exponent = 1", "0 <= n < 1"});
  expect_rejected(j2_with("hardening: {law: power, exponent: -0.1}"),
                  {"material.hardening.exponent = -0.1"});
  expect_rejected(j2_with("hardening: {law: voce, saturation: -0.1, rate: 2}"),
                  {"material.hardening.saturation = -0.1", ">= 0"});
  expect_rejected(j2_with("hardening: {law: voce, saturation: 0.1, rate: 0}"),
                  {"material.hardening.rate = 0", "> 0"});
  expect_rejected(j2_with("hardening: {law: voce, saturation: 0.1, rate: 2, modulus: -1}"),
                  {"material.hardening.modulus = -1", ">= 0"});
  expect_rejected(j2_with("hardening: {law: linear, modulus: -1}"),
                  {"material.hardening.modulus = -1", ">= 0"});
  // Tables.
  expect_rejected(j2_with("hardening: {law: table, plastic_strain: [0.01, 0.1], "
                          "stress: [0.305, 0.4]}"),
                  {"material.hardening.plastic_strain = [0.01, 0.1]", "start at plastic strain 0"});
  expect_rejected(j2_with("hardening: {law: table, plastic_strain: [0, 0.1, 0.1], "
                          "stress: [0.305, 0.4, 0.5]}"),
                  {"material.hardening.plastic_strain = [0, 0.1, 0.1]", "increase strictly"});
  expect_rejected(j2_with("hardening: {law: table, plastic_strain: [0, -0.1], "
                          "stress: [0.305, 0.4]}"),
                  {"material.hardening.plastic_strain = [0, -0.1]", ">= 0"});
  expect_rejected(j2_with("hardening: {law: table, plastic_strain: [0, 0.1, 0.2], "
                          "stress: [0.305, 0.4, 0.35]}"),
                  {"material.hardening.stress = [0.305, 0.4, 0.35]", "must not decrease"});
  expect_rejected(j2_with("hardening: {law: table, plastic_strain: [0, 0.1, 0.2], "
                          "stress: [0.305, 0.4]}"),
                  {"material.hardening.stress", "one stress per plastic strain"});
  expect_rejected(j2_with("hardening: {law: table, plastic_strain: [0], stress: [0.305]}"),
                  {"material.hardening.plastic_strain = [0]", "at least 2"});
  expect_rejected(j2_with("hardening: {law: table, plastic_strain: [0, 0.1], stress: [0, 0.4]}"),
                  {"material.hardening.stress = [0, 0.4]", "> 0"});
  expect_rejected(j2_with("hardening: {law: table, plastic_strain: 0.1, stress: [0.305]}"),
                  {"material.hardening.plastic_strain = 0.1", "list of numbers"});
  // The first stress against yield_stress: both values named.
  expect_rejected(j2_with("yield_stress: 0.3, hardening: {law: table, plastic_strain: [0, 0.1], "
                          "stress: [0.276, 0.4]}"),
                  {"material.yield_stress = 0.3", "0.276 GPa", "must equal"});
  expect_rejected(j2_with("hardening: {law: table, plastic_strain: [0, 0.1], "
                          "stress: [0.276, 0.4]}"),
                  {"material.hardening.stress", "0.276 GPa", "yield_stress = 0.305",
                   "give "
                   "yield_stress: 0.276"});
}

// A study sweeps the power-law exponent: an override of material.hardening.exponent alone
// keeps the base's law and gives another case key for each value.
TEST(CaseHardening, StudyOverridesSweepTheExponent)
{
  const YAML::Node         base = YAML::Load(power_case);
  std::vector<std::string> keys;
  for (const double n : {0.0, 0.1, 0.3})
    {
      const YAML::Node overrides =
          YAML::Load("material: {hardening: {exponent: " + std::to_string(n) + "}}");
      const Case c = parse_case_yaml(YAML::Dump(study::merge_overrides(base, overrides)), "s.yaml");
      EXPECT_EQ(c.material.hardening_law, HardeningLaw::power);
      EXPECT_DOUBLE_EQ(c.material.hardening_exponent, n);
      EXPECT_DOUBLE_EQ(c.material.yield_stress, 0.2);
      keys.push_back(study::case_key(c));
    }
  EXPECT_NE(keys[0], keys[1]);
  EXPECT_NE(keys[1], keys[2]);
  EXPECT_EQ(keys[2], study::case_key(parse_case_yaml(power_case, "p.yaml")));
}

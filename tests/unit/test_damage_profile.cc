// Damage profiles (material.damage_profile): the CSV reader (units, rows, errors naming the line),
// the case-file spelling and its errors, the dose-to-strength laws against their closed forms
// computed here by hand, the sampling slabs a quadrature point takes its strength from, and the
// mesh's refinement across the damage peak. Units: um, dpa, GPa, 1/um^3.
#include "case/CaseFile.h"
#include "case/DamageProfile.h"
#include "case/Fingerprint.h"
#include "io/DamageProfileCsv.h"
#include "materials/LayeredMaterial.h"
#include "materials/MaterialFactory.h"

#include "../case_file_errors.h"
#include "../test_files.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace
{
  using namespace indentsim;
  using namespace indentsim::io;
  using test_case_files::expect_rejected;
  namespace fs = std::filesystem;

  void write_text(const fs::path &path, const std::string &text)
  {
    std::ofstream(path) << text;
  }

  using test_case_files::j2_material;

  // A triangular profile: 0 at the surface, 1 dpa at 1 um, 0 at 2 um.
  const std::string triangle = "{depth: [0, 1, 2], dpa: [0, 1, 0], law: {form: saturation, "
                               "saturation_increment: 0.3, saturation_dose: 0.2}}";

  std::string with_profile(const std::string &profile)
  {
    return j2_material + "  damage_profile: " + profile + "\n";
  }

  const std::string tungsten =
      "test: indentation\n"
      "material:\n"
      "  model: crystal\n"
      "  lattice: bcc\n"
      "  slip_families: [\"{110}<111>\", \"{112}<111>\"]\n"
      "  elastic: {C11: 522.4, C12: 204.4, C44: 160.6}\n"
      "  hardening: {tau0: 0.4, tau1: 0.1, theta0: 1.0, theta1: 0.01, "
      "barrier_strength: 0.3, softening_slip: 0.02,\n"
      "              \"{112}<111>\": {tau0: 0.42, barrier_strength: 0.2}}\n"
      "  damage_profile: {depth: [0, 1, 2], dpa: [0.5, 0.5, 0], law: "
      "{form: dispersed_barrier, shear_modulus: 161, burgers_vector: "
      "2.74e-4, defect_size: 2e-3, saturation_density: 1e5, "
      "saturation_dose: 0.1}}\n";
} // namespace

// The reader: the depth's unit from its column name (nm converted), further columns ignored,
// comments skipped; every error names the line, the column or the header and what is allowed.
TEST(DamageProfile, CsvReaderConvertsUnitsAndNamesBadRows)
{
  const fs::path dir = test_files::scratch_directory("damage_profile", "csv");
  write_text(dir / "srim.csv", "# SRIM-2013, 20 MeV W on W\nDepth (nm),vacancies,dpa\n"
                               "0,1,0.1\n500,2,0.4\n1000,3,0.2\n");
  const DamageProfileTable table = read_damage_profile_csv((dir / "srim.csv").string());
  EXPECT_EQ(table.depth, (std::vector<double>{0, 0.5, 1.0}));
  EXPECT_EQ(table.dpa, (std::vector<double>{0.1, 0.4, 0.2}));

  const auto error_of = [&](const std::string &text) {
    write_text(dir / "bad.csv", text);
    try
      {
        read_damage_profile_csv((dir / "bad.csv").string());
      }
    catch (const std::invalid_argument &error)
      {
        return std::string(error.what());
      }
    return std::string();
  };
  const auto expect_error = [&](const std::string &text, std::initializer_list<std::string> parts) {
    const std::string message = error_of(text);
    SCOPED_TRACE(message);
    ASSERT_FALSE(message.empty());
    for (const auto &part : parts)
      EXPECT_NE(message.find(part), std::string::npos) << part;
  };
  expect_error("depth,dpa\n0,1\n1,2\n", {"line 1", "no unit", "depth_nm,dpa"});
  expect_error("depth_ft,dpa\n0,1\n1,2\n", {"the unit 'ft'", "um, nm, mm"});
  expect_error("depth_um,vacancies\n0,1\n1,2\n", {"no dpa column"});
  expect_error("depth_um,dpa\n0,1\n0.5,x\n", {"line 3", "column 'dpa'", "'x'"});
  expect_error("depth_um,dpa\n0,1\n0.5\n", {"line 3", "1 fields"});
  expect_error("depth_um,dpa\n0,1\n", {"1 points", "at least 2"});
  expect_error("", {"no header"});
}

// The spelling with a file (relative to the case file), its resolved form read back
// as the same material, and a fingerprint that differs from the homogeneous case.
TEST(DamageProfile, ProfileIsReadFromFileAndResolved)
{
  const fs::path dir = test_files::scratch_directory("damage_profile", "case");
  write_text(dir / "srim_dpa.csv", "depth_nm,dpa\n0,0.2\n1000,1.0\n1500,0\n");
  write_text(dir / "case.yaml",
             with_profile("{file: srim_dpa.csv, law: {form: saturation, saturation_increment: "
                          "0.4, saturation_dose: 0.5, exponent: 0.5}}"));
  const Case                     c = read_case_file((dir / "case.yaml").string());
  const DamageProfileParameters &p = c.material.damage_profile;
  EXPECT_EQ(p.file, (dir / "srim_dpa.csv").lexically_normal().string());
  EXPECT_EQ(p.depth, (std::vector<double>{0, 1.0, 1.5}));
  EXPECT_EQ(p.dpa, (std::vector<double>{0.2, 1.0, 0}));
  EXPECT_EQ(p.law, DamageLaw::saturation);
  EXPECT_EQ(p.exponent, 0.5);
  const std::string resolved = resolved_case_yaml(c);
  EXPECT_NE(resolved.find("  damage_profile:"), std::string::npos) << resolved;
  EXPECT_NE(resolved.find("    law:"), std::string::npos) << resolved;
  EXPECT_NE(resolved.find("      form: saturation"), std::string::npos) << resolved;
  EXPECT_EQ(parse_case_yaml(resolved, "resolved.yaml").material, c.material);

  // The fingerprint takes the profile's content, not the file's path: a copy elsewhere keeps
  // it, a changed dose changes it.
  fs::create_directories(dir / "moved");
  write_text(dir / "moved" / "profile.csv", "depth_nm,dpa\n0,0.2\n1000,1.0\n1500,0\n");
  write_text(dir / "moved" / "case.yaml",
             with_profile("{file: profile.csv, law: {form: saturation, saturation_increment: "
                          "0.4, saturation_dose: 0.5, exponent: 0.5}}"));
  EXPECT_EQ(case_fingerprint(read_case_file((dir / "moved" / "case.yaml").string())),
            case_fingerprint(c));
  write_text(dir / "moved" / "profile.csv", "depth_nm,dpa\n0,0.2\n1000,1.1\n1500,0\n");
  EXPECT_NE(case_fingerprint(read_case_file((dir / "moved" / "case.yaml").string())),
            case_fingerprint(c));

  const Case inline_case = parse_case_yaml(with_profile(triangle), "inline.yaml");
  EXPECT_EQ(parse_case_yaml(resolved_case_yaml(inline_case), "r.yaml").material,
            inline_case.material);
  EXPECT_NE(case_fingerprint(inline_case),
            case_fingerprint(parse_case_yaml(j2_material, "j.yaml")));
}

// Every error names the key, the value and what is allowed.
TEST(DamageProfile, BadProfilesAreRejectedWithTheirKey)
{
  const std::string law =
      "law: {form: saturation, saturation_increment: 0.3, saturation_dose: 0.2}";
  expect_rejected(with_profile("{depth: [0, 1], dpa: [1, 0]}"), {"needs law: {form:"});
  expect_rejected(with_profile("{depth: [0, 1], " + law + "}"), {"needs both lists"});
  expect_rejected(with_profile("{depth: [0, 1, 1], dpa: [1, 1, 0], " + law + "}"),
                  {"material.damage_profile.depth", "point 3", "strictly increasing"});
  expect_rejected(with_profile("{depth: [0, 1], dpa: [1, -1], " + law + "}"),
                  {"material.damage_profile.dpa", ">= 0"});
  expect_rejected(with_profile("{depth: [0, 1], dpa: [0, 0], " + law + "}"), {"every dose is 0"});
  expect_rejected(with_profile("{depth: [0, 1], dpa: [1, 0], law: {form: saturation, "
                               "saturation_increment: 0.3}}"),
                  {"form: saturation needs", "saturation_dose"});
  expect_rejected(with_profile("{depth: [0, 1], dpa: [1, 0], law: {form: saturation, "
                               "saturation_increment: 0.3, saturation_dose: 0.2, dpa: [0, 1]}}"),
                  {"law.dpa", "not a parameter of form: saturation"});
  expect_rejected(with_profile("{depth: [0, 1], dpa: [1, 0], law: {form: dispersed_barrier, "
                               "shear_modulus: 161, burgers_vector: 2.7e-4, defect_size: 2e-3, "
                               "saturation_density: 1e5, saturation_dose: 0.1}}"),
                  {"law.form", "model: j2 takes form: saturation or table"});
  expect_rejected(with_profile("{depth: [0, 1], dpa: [1, 0], law: {form: table, dpa: [0.1, 1], "
                               "delta_yield_stress: [0, 0.2]}}"),
                  {"law.dpa", "the first 0"});
  expect_rejected(with_profile("{depth: [0, 1], dpa: [1, 0], law: {form: table, dpa: [0, 1], "
                               "delta_yield_stress: [0.1, 0.2]}}"),
                  {"law.delta_yield_stress", "(at 0 dpa) must be 0"});
  expect_rejected(with_profile("{depth: [0, 1], dpa: [1, 0], law: {form: linear}}"),
                  {"law.form", "saturation"});
  expect_rejected(j2_material + "  layers: [{thickness: 0.5, yield_stress: 0.6}]\n" +
                      "  damage_profile: " + triangle + "\n",
                  {"material.damage_profile.depth", "not both"});
  expect_rejected(with_profile("{depth: [0, 1000], dpa: [1, 0], resolution: 0.001, " + law + "}"),
                  {"material.damage_profile.resolution", "slabs"});
  std::string crystal_without_alpha = tungsten;
  crystal_without_alpha.replace(crystal_without_alpha.find("barrier_strength: 0.3"), 21,
                                "barrier_strength: 0");
  crystal_without_alpha.replace(crystal_without_alpha.find("barrier_strength: 0.2"), 21,
                                "barrier_strength: 0");
  expect_rejected(crystal_without_alpha, {"barrier_strength", "harden nothing"});
}

// The laws against their closed forms: linear interpolation of the dose (the first point's dose
// above it, 0 below the last), Delta sigma_sat (1 - exp(-d/d0))^p, the table, and
// alpha mu b sqrt(N_sat (1 - exp(-d/d0)) D); the width at half maximum of a triangle (1 um) and
// of a finely sampled Gaussian (2 sqrt(2 ln 2) s).
TEST(DamageProfile, LawsMatchTheirClosedForms)
{
  DamageProfileParameters p;
  p.depth = {0.1, 1.0, 2.0};
  p.dpa = {0.3, 1.0, 0.0};
  p.saturation_increment = 0.4;
  p.saturation_dose = 0.5;
  p.exponent = 0.5;
  EXPECT_DOUBLE_EQ(dose_at(p, 0.0), 0.3);
  EXPECT_DOUBLE_EQ(dose_at(p, 0.55), 0.65);
  EXPECT_DOUBLE_EQ(dose_at(p, 1.5), 0.5);
  EXPECT_DOUBLE_EQ(dose_at(p, 2.5), 0.0);
  EXPECT_NEAR(yield_stress_increment(p, 0.5), 0.4 * std::sqrt(1 - std::exp(-1.0)), 1e-15);
  EXPECT_EQ(yield_stress_increment(p, 0.0), 0.0);

  p.law = DamageLaw::table;
  p.table_dpa = {0, 0.1, 1.0};
  p.table_delta_yield_stress = {0, 0.2, 0.3};
  EXPECT_NEAR(yield_stress_increment(p, 0.05), 0.1, 1e-15);
  EXPECT_NEAR(yield_stress_increment(p, 0.55), 0.25, 1e-15);
  EXPECT_NEAR(yield_stress_increment(p, 3.0), 0.3, 1e-15);

  p.law = DamageLaw::dispersed_barrier;
  p.shear_modulus = 161;
  p.burgers_vector = 2.74e-4;
  p.defect_size = 2e-3;
  p.saturation_density = 1e5;
  p.saturation_dose = 0.1;
  // 0.3 * 161 * 2.74e-4 * sqrt(1e5 * (1 - e^-2) * 2e-3) = 0.013234 * 13.150 = 0.17403 GPa
  const double expected = 0.3 * 161 * 2.74e-4 * std::sqrt(1e5 * (1 - std::exp(-2.0)) * 2e-3);
  EXPECT_NEAR(barrier_shear(p, 0.3, 0.2), expected, 1e-15);
  EXPECT_NEAR(expected, 0.17403, 1e-5);

  DamageProfileParameters tri;
  tri.depth = {0, 1, 2};
  tri.dpa = {0, 1, 0};
  EXPECT_NEAR(peak_width(tri), 1.0, 1e-15);
  DamageProfileParameters gauss;
  for (int i = 0; i <= 400; ++i)
    {
      gauss.depth.push_back(0.01 * i);
      gauss.dpa.push_back(std::exp(-std::pow(0.01 * i - 1.5, 2) / (2 * 0.3 * 0.3)));
    }
  EXPECT_NEAR(peak_width(gauss) / (2 * std::sqrt(2 * std::log(2.0)) * 0.3), 1.0, 1e-3);
}

// The slabs: they cover the profile to its last depth; a point takes the strength of its
// slab's centre, within resolution / 2 of its own depth (checked through the material the run
// builds: its layer and that layer's yield stress); equal neighbours are merged; below the
// profile the material block holds.
TEST(DamageProfile, SlabsSampleTheProfileAtTheirCentres)
{
  // 0 at the surface, 1 dpa at 1 um, 0.5 dpa at 2 um: no two slabs alike.
  const Case c =
      parse_case_yaml(with_profile("{depth: [0, 1, 2], dpa: [0, 1, 0.5], law: {form: saturation, "
                                   "saturation_increment: 0.3, saturation_dose: 0.2}}"),
                      "t.yaml");
  const auto dose_of = [](const double z) { return z < 1 ? z : 1 - 0.5 * (z - 1); };
  const std::vector<DepthSlab> slabs = depth_slabs(c.material, "t.yaml");
  ASSERT_EQ(slabs.size(), 400u); // 2 um / 0.005 um
  double top = 0;
  for (const DepthSlab &slab : slabs)
    {
      const double centre = top + 0.5 * slab.thickness;
      const double dose = dose_of(centre);
      EXPECT_NEAR(slab.material.yield_stress, 0.305 + 0.3 * (1 - std::exp(-dose / 0.2)), 1e-12)
          << "slab centred at " << centre;
      EXPECT_FALSE(slab.material.damage_profile.given());
      top += slab.thickness;
    }
  EXPECT_NEAR(top, 2.0, 1e-12);
  EXPECT_EQ(graded_depth(c.material), 2.0);
  EXPECT_NEAR(graded_feature(c.material), 1.5, 1e-15); // dose >= 0.5 from 0.5 um to the end

  const auto  material = materials::create_material(c.material);
  const auto &layered = dynamic_cast<const materials::LayeredMaterial &>(*material);
  for (const double depth : {0.0, 0.0123, 0.999, 1.5, 1.9999})
    {
      const unsigned int layer = layered.layer_at_depth(depth);
      ASSERT_LT(layer, slabs.size());
      const double dose = dose_of(depth);
      // The slab's strength differs from the point's own by at most the change over 2.5 nm.
      EXPECT_NEAR(slabs[layer].material.yield_stress, 0.305 + 0.3 * (1 - std::exp(-dose / 0.2)),
                  0.3 / 0.2 * 0.0025 + 1e-12)
          << "depth " << depth;
    }
  EXPECT_EQ(layered.layer_at_depth(2.01), slabs.size()); // the substrate

  // A plateau of constant dose is one slab.
  const Case plateau = parse_case_yaml(
      with_profile("{depth: [0, 1, 1.0001], dpa: [2, 2, 0], law: {form: saturation, "
                   "saturation_increment: 0.3, saturation_dose: 0.2}}"),
      "p.yaml");
  EXPECT_EQ(depth_slabs(plateau.material, "p.yaml").front().thickness, 1.0);
}

// Crystals: each family's tau_irr from its own barrier strength, the families' other keys kept.
TEST(DamageProfile, CrystalSlabsTakeEachFamilysBarrierStrength)
{
  const Case                   c = parse_case_yaml(tungsten, "w.yaml");
  const std::vector<DepthSlab> slabs = depth_slabs(c.material, "w.yaml");
  ASSERT_FALSE(slabs.empty());
  const MaterialParameters &top = slabs.front().material;
  const double              root = std::sqrt(1e5 * (1 - std::exp(-5.0)) * 2e-3);
  EXPECT_NEAR(top.tau_irr, 0.3 * 161 * 2.74e-4 * root, 1e-12);
  ASSERT_EQ(top.family_hardening.size(), 1u);
  EXPECT_NEAR(top.family_hardening[0].tau_irr, 0.2 * 161 * 2.74e-4 * root, 1e-12);
  EXPECT_EQ(top.family_hardening[0].tau0, 0.42);
  EXPECT_EQ(top.family_hardening[0].softening_slip, 0.02);
  EXPECT_EQ(parse_case_yaml(resolved_case_yaml(c), "r.yaml").material, c.material);
}

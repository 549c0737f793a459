// Calibration: the file's checks (every bad configuration refused before any run, naming the
// key), the statistics at the optimum against the closed forms of linear regression, the
// resampling of measured curves, and the launcher template. The closed loops that run the
// program are in tests/system/calibration/. Units: um, mN, GPa.
#include "../test_files.h"
#include "calibration/CalibrationFile.h"
#include "calibration/CurveData.h"
#include "calibration/FitStatistics.h"
#include "calibration/ForwardRuns.h"
#include "calibration/IndentationFeatures.h"
#include "calibration/LeastSquaresFit.h"
#include "study/StudyRunner.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <string>

namespace
{
  using namespace indentsim;
  using namespace indentsim::calibration;
  namespace fs = std::filesystem;

  // A scratch folder with the forward case and a measured curve P = 30 h^2 over 0..1 um and back.
  fs::path calibration_folder()
  {
    const fs::path dir = test_files::scratch_directory("calibration", "files");
    fs::copy_file(fs::path(INDENTSIM_TEST_DATA_DIR) / "system/calibration/cone_j2.yaml",
                  dir / "cone_j2.yaml");
    std::ofstream curve(dir / "curve.csv");
    curve << "depth_nm,force_mN\n";
    for (int i = 0; i <= 20; ++i)
      curve << 50 * i << "," << 30. * (0.05 * i) * (0.05 * i) << "\n";
    for (int i = 1; i <= 5; ++i)
      curve << 1000 - 20 * i << "," << 30. * (1. - 0.2 * i) << "\n";
    std::ofstream deep(dir / "deep.csv");
    deep << "depth_um,force_mN\n2,10\n2.5,20\n3,30\n";
    // Two tests' features in other units than the program's, at depths around the case's 1 um.
    std::ofstream features(dir / "features.csv");
    features << "# two tests\nTest,C_MPa,S (uN/nm),plastic_work_ratio,h_max_nm\n"
             << "1,30000,110,0.50,1000\n2,32000,100,0.54,950\n";
    std::ofstream(dir / "shallow.csv") << "C (GPa),Wp/Wt,hm (um)\n30,0.5,0.8\n"; // 20 % short
    std::ofstream(dir / "ratio.csv") << "Wp/Wt\n1.2\n";
    // A continuous-stiffness profile in nm and MPa, H = 2 + h GPa, from 100 to 1000 nm.
    std::ofstream csm(dir / "csm.csv");
    csm << "Displacement (nm),Hardness (MPa)\n";
    for (int i = 1; i <= 10; ++i)
      csm << 100 * i << "," << 1000. * (2. + 0.1 * i) << "\n";
    // The forward case with a partial unload every 0.25 um.
    std::string       with_partial_unloads = test_files::read_text(dir / "cone_j2.yaml");
    const std::string loading = "unload: true}";
    with_partial_unloads.replace(with_partial_unloads.find(loading), loading.size(),
                                 "unload: true, partial_unloads: {every: 0.25}}");
    std::ofstream(dir / "cone_csm.yaml") << with_partial_unloads;
    return dir;
  }

  const std::string good_parameters =
      "parameters:\n"
      "  material.yield_stress: {start: 0.25, min: 0.05, max: 1.0}\n"
      "  material.hardening_modulus: {start: 1.0, min: 0.0, max: 5.0, step: 0.05}\n";

  std::string error_of(const std::string &yaml, const fs::path &dir)
  {
    try
      {
        parse_calibration_yaml(yaml, (dir / "calibrate.yaml").string());
      }
    catch (const CalibrationFileError &error)
      {
        return error.what();
      }
    return "";
  }

  void expect_refused(const std::string &yaml, std::initializer_list<std::string> parts)
  {
    const fs::path    dir = calibration_folder();
    const std::string message = error_of(yaml, dir);
    SCOPED_TRACE("calibration file:\n" + yaml + "\nmessage: " + message);
    ASSERT_FALSE(message.empty()) << "not refused";
    EXPECT_NE(message.find("calibrate.yaml"), std::string::npos) << "the file is not named";
    for (const auto &part : parts)
      EXPECT_NE(message.find(part), std::string::npos) << "missing '" << part << "'";
    EXPECT_FALSE(fs::exists(dir / "results")) << "something was written";
  }
} // namespace

TEST(CalibrationFile, AGoodFileResolvesItsPathsAndComparisonPoints)
{
  const fs::path    dir = calibration_folder();
  const Calibration c = parse_calibration_yaml(
      "base_case: cone_j2.yaml\noutput: " + (dir / "out").string() + "\n" + good_parameters +
          "data:\n  - {kind: load_penetration, file: curve.csv, points: 10}\n"
          "  - {kind: load_penetration, file: curve.csv, branch: unloading, weight: 0.5}\n",
      (dir / "calibrate.yaml").string());
  ASSERT_EQ(c.parameters.size(), 2u);
  EXPECT_EQ(c.parameters[0].key, "material.yield_stress");
  EXPECT_EQ(c.parameters[0].unit, "GPa");
  EXPECT_EQ(c.parameters[0].step, 0.); // relative to the value (solver.finite_difference_step)
  EXPECT_EQ(c.parameters[1].step, 0.05);
  EXPECT_EQ(c.base_case_file, (dir / "cone_j2.yaml").string());
  ASSERT_EQ(c.data.size(), 2u);
  // Loading: the 20 measured points above 0 (nm read as such) in 10 pairs, each pair's means.
  ASSERT_EQ(c.data[0].x.size(), 10u);
  EXPECT_NEAR(c.data[0].x.front(), 0.075, 1e-12);
  EXPECT_NEAR(c.data[0].measured.front(), 30. * (0.05 * 0.05 + 0.1 * 0.1) / 2., 1e-12);
  EXPECT_NEAR(c.data[0].x.back(), 0.975, 1e-12);
  EXPECT_NEAR(c.data[0].scale, 30. * (0.95 * 0.95 + 1.) / 2., 1e-9);
  // Unloading: its 6 points (fewer than 40: each its own), from 0.9 um (0 mN) to 1 um.
  ASSERT_EQ(c.data[1].x.size(), 6u);
  EXPECT_NEAR(c.data[1].x.front(), 0.9, 1e-12);
  EXPECT_NEAR(c.data[1].measured.front(), 0., 1e-9);
  EXPECT_NEAR(c.data[1].x.back(), 1.0, 1e-12);
  EXPECT_EQ(c.data[1].weight, 0.5);
  EXPECT_EQ(c.forward_cases().size(), 1u);
  EXPECT_FALSE(fs::exists(dir / "out")) << "reading a calibration file writes nothing";

  // A range keeps the measured points inside it, both ends included: 0.3 to 0.7 um.
  const Calibration narrow = parse_calibration_yaml(
      "base_case: cone_j2.yaml\n" + good_parameters +
          "data:\n  - {kind: load_penetration, file: curve.csv, range: [0.3, 0.7]}\n",
      (dir / "calibrate.yaml").string());
  ASSERT_EQ(narrow.data[0].x.size(), 9u);
  EXPECT_NEAR(narrow.data[0].x.front(), 0.3, 1e-12);
  EXPECT_NEAR(narrow.data[0].x.back(), 0.7, 1e-12);
}

// A layer's key, a damage law's key and a slip family's key reach inside their blocks; a case
// without the block (the substrate's tensile test) does not see the key and is shared by the
// points that differ only in it.
TEST(CalibrationFile, KeysInsideLayersDamageProfilesAndSlipFamilies)
{
  const fs::path    dir = calibration_folder();
  const fs::path    data = fs::path(INDENTSIM_TEST_DATA_DIR) / "system/calibration";
  std::string       layered = test_files::read_text(dir / "cone_j2.yaml");
  const std::string plastic = "hardening_modulus: 2.0}";
  layered.replace(layered.find(plastic), plastic.size(),
                  "hardening_modulus: 2.0, layers: [{thickness: 0.4, yield_stress: 0.9}, "
                  "{thickness: 0.2, hardening_modulus: 1.0}]}");
  std::ofstream(dir / "cone_layer.yaml") << layered;
  fs::copy_file(data / "tensile_j2.yaml", dir / "tensile_j2.yaml");
  std::ofstream(dir / "tensile.csv")
      << "log_strain,true_stress_GPa\n0.01,0.31\n0.02,0.33\n0.03,0.35\n"
         "0.04,0.37\n";

  const std::string layer_keys =
      "parameters:\n"
      "  material.yield_stress: {start: 0.3, min: 0.1, max: 1}\n"
      "  material.layers[0].yield_stress: {start: 0.75, min: 0.1, max: 3}\n"
      "  material.layers[1].thickness: {start: 0.25, min: 0.05, max: 1}\n";
  const Calibration c =
      parse_calibration_yaml("base_case: cone_layer.yaml\n" + layer_keys +
                                 "data:\n  - {kind: load_penetration, file: curve.csv}\n"
                                 "  - {kind: tensile, file: tensile.csv, case: tensile_j2.yaml}\n",
                             (dir / "calibrate.yaml").string());
  EXPECT_EQ(c.parameters[1].unit, "GPa");
  EXPECT_EQ(c.parameters[2].unit, "um");
  const io::Case indentation = forward_case(c, {0.35, 0.8, 0.3}, 0);
  ASSERT_EQ(indentation.material.layers.size(), 2u);
  EXPECT_EQ(indentation.material.yield_stress, 0.35);
  EXPECT_EQ(indentation.material.layers[0].thickness, 0.4);
  EXPECT_NE(indentation.material.layers[0].overrides.find("yield_stress: 0.8"), std::string::npos)
      << indentation.material.layers[0].overrides;
  EXPECT_EQ(indentation.material.layers[1].thickness, 0.3);
  EXPECT_NE(indentation.material.layers[1].overrides.find("hardening_modulus: 1"),
            std::string::npos)
      << indentation.material.layers[1].overrides;
  const io::Case tensile = forward_case(c, {0.35, 0.8, 0.3}, 1);
  EXPECT_TRUE(tensile.material.layers.empty());
  EXPECT_EQ(tensile.material.yield_stress, 0.35);

  // Three points: the second differs from the first in a layer's key only, the third in the
  // substrate's. Five cases, the first two points sharing their tensile test.
  const ForwardBatch batch =
      forward_study(c, {{0.35, 0.8, 0.3}, {0.35, 0.9, 0.3}, {0.4, 0.8, 0.3}});
  EXPECT_EQ(batch.study.cases.size(), 5u);
  EXPECT_EQ(batch.index[0][1], batch.index[1][1]);
  EXPECT_NE(batch.index[0][0], batch.index[1][0]);
  EXPECT_NE(batch.index[0][1], batch.index[2][1]);

  // A damage law's key enters the irradiated case only, not the substrate's tensile test.
  std::string       damaged = test_files::read_text(dir / "cone_j2.yaml");
  const std::string plain = "hardening_modulus: 2.0}";
  damaged.replace(damaged.find(plain), plain.size(),
                  "hardening_modulus: 2.0, damage_profile: {depth: [0, 0.5], dpa: [1, 0], "
                  "law: {form: saturation, saturation_increment: 0.3, saturation_dose: 0.5}}}");
  std::ofstream(dir / "cone_damage.yaml") << damaged;
  const Calibration dose = parse_calibration_yaml(
      "base_case: cone_damage.yaml\nparameters:\n"
      "  material.damage_profile.law.saturation_increment: {start: 0.4, min: 0, max: 2}\n"
      "data:\n  - {kind: load_penetration, file: curve.csv}\n"
      "  - {kind: tensile, file: tensile.csv, case: tensile_j2.yaml}\n",
      (dir / "calibrate.yaml").string());
  EXPECT_EQ(forward_case(dose, {0.45}, 0).material.damage_profile.saturation_increment, 0.45);
  EXPECT_TRUE(forward_case(dose, {0.45}, 1).material.damage_profile.depth.empty());
  EXPECT_EQ(forward_study(dose, {{0.45}, {0.5}}).study.cases.size(), 3u);

  // A slip family's own block: the key lands in it, the other families keep the common value.
  fs::copy_file(data / "cone_crystal.yaml", dir / "cone_crystal.yaml");
  const Calibration crystal = parse_calibration_yaml(
      "base_case: cone_crystal.yaml\nparameters:\n"
      "  material.hardening.{111}<110>.tau0: {start: 0.15, min: 0.05, max: 0.5}\n"
      "data:\n  - {kind: load_penetration, file: curve.csv}\n",
      (dir / "calibrate.yaml").string());
  EXPECT_EQ(crystal.parameters[0].unit, "GPa");
  const io::Case family = forward_case(crystal, {0.2}, 0);
  ASSERT_EQ(family.material.family_hardening.size(), 1u);
  EXPECT_EQ(family.material.family_hardening[0].family, "{111}<110>");
  EXPECT_EQ(family.material.family_hardening[0].tau0, 0.2);
  EXPECT_EQ(family.material.family_hardening[0].theta0, 0.1);

  // Keys that name no layer or no number are refused before any run, named.
  const std::string data_set = "data:\n  - {kind: load_penetration, file: curve.csv}\n";
  for (const auto &[key, part] : std::vector<std::pair<std::string, std::string>>{
           {"material.layers[2].yield_stress", "has 2 layer(s)"},
           {"material.layers[0].thickness", "has no material.layers"},
           {"material.damage_profile.law.saturation_increment", "has no material.damage_profile"},
           {"material.layers[0]", "a layer's key follows the index"},
           {"material.layers[a].yield_stress", "material.layers[i] with i a whole number"},
           {"material.hardening[0].tau0", "an index is allowed only as material.layers[i]"},
           {"material.layers[0].yield_stres", "did you mean 'material.yield_stress'"},
           {"material.hardening.basal.tau00", "not a key of a case file"}})
    {
      const fs::path folder = calibration_folder();
      std::ofstream(folder / "cone_layer.yaml") << layered;
      const bool without_block = key.ends_with("thickness") || key.find("damage") != key.npos;
      const std::string base = without_block ? "cone_j2.yaml" : "cone_layer.yaml";
      const std::string yaml = "base_case: " + base + "\nparameters:\n  " + key +
                               ": {start: 0.5, min: 0.1, max: 1}\n" + data_set;
      const std::string message = error_of(yaml, folder);
      SCOPED_TRACE(key + ": " + message);
      EXPECT_NE(message.find("parameters." + key), std::string::npos);
      EXPECT_NE(message.find(part), std::string::npos);
    }
}

// Every calibration the repository ships passes the checks a run makes before its first
// forward run (keys, bounds, every case at the start and the bounds, data files and their
// overlap with the simulated range).
TEST(CalibrationFile, ShippedCalibrationsPassTheirChecks)
{
  const fs::path shipped = fs::path(INDENTSIM_SOURCE_DIR) / "calibrations";
  unsigned int   files = 0;
  for (const auto &folder : fs::directory_iterator(shipped))
    if (fs::exists(folder.path() / "calibrate.yaml"))
      {
        SCOPED_TRACE(folder.path().string());
        const Calibration c = read_calibration_file((folder.path() / "calibrate.yaml").string());
        EXPECT_FALSE(c.parameters.empty());
        EXPECT_FALSE(c.data.empty());
        ++files;
      }
  EXPECT_GE(files, 3u);
}

TEST(CalibrationFile, BadConfigurationsAreRefusedBeforeAnyRunNamingTheKey)
{
  const std::string base = "base_case: cone_j2.yaml\n";
  const std::string data = "data:\n  - {kind: load_penetration, file: curve.csv}\n";
  expect_refused(base + good_parameters + data + "tolerance: 1\n",
                 {"unknown key 'tolerance'", "base_case, output, parameters, data, solver"});
  expect_refused(base + "parameters:\n  material.yield_stres: {start: 0.3, min: 0.1, max: 1}\n" +
                     data,
                 {"parameters.material.yield_stres", "did you mean 'material.yield_stress'"});
  expect_refused(base + "parameters:\n  loading.steps: {start: 10, min: 5, max: 20}\n" + data,
                 {"parameters.loading.steps", "not a number that changes the result"});
  expect_refused(base + "parameters:\n  material.yield_stress: {start: 0.3, min: 1.0, max: 0.1}\n" +
                     data,
                 {"parameters.material.yield_stress", "min = 1", "max = 0.1", "min < max"});
  expect_refused(base + "parameters:\n  material.yield_stress: {start: 2, min: 0.1, max: 1}\n" +
                     data,
                 {"parameters.material.yield_stress.start = 2", "outside the bounds [0.1, 1]"});
  expect_refused(base + "parameters:\n  material.yield_stress: {start: 0.3, min: -0.1, max: 1}\n" +
                     data,
                 {"parameters.material.yield_stress.min = -0.1", "is refused by a case",
                  "material.yield_stress"});
  expect_refused(base +
                     "parameters:\n  material.yield_stress: {start: 0.3, min: 0.1, max: 1, "
                     "step: 0.5}\n" +
                     data,
                 {"parameters.material.yield_stress.step = 0.5", "at most half the bounds' width, "
                                                                 "0.45"});
  expect_refused(base + "parameters:\n  material.yield_stress: {start: 0.3, max: 1}\n" + data,
                 {"missing key 'min'"});
  expect_refused(base + good_parameters + "data:\n  - {kind: load_penetration, file: nope.csv}\n",
                 {"data[0].file = nope.csv", "no file", "nope.csv"});
  expect_refused(base + good_parameters + "data:\n  - {kind: load_penetration, file: deep.csv}\n",
                 {"data[0]", "deep.csv", "0 measured point(s) within the range",
                  "0 to 1 um (loading.max_depth)", "spans 2 to 3"});
  expect_refused(base + good_parameters + "data:\n  - {kind: hardness, file: curve.csv}\n",
                 {"data[0].kind = hardness", "allowed: load_penetration, tensile, pileup_profile, "
                                             "indentation_features, hardness_depth"});
  expect_refused(base + good_parameters + "data:\n  - {kind: hardness_depth, file: csm.csv}\n",
                 {"data[0]", "kind: hardness_depth needs partial unloads", "cone_j2.yaml",
                  "loading.partial_unloads.every: 0"});
  expect_refused(base + good_parameters +
                     "data:\n  - {kind: load_penetration, file: curve.csv, azimuth_deg: 10}\n",
                 {"data[0].azimuth_deg", "only for kind: pileup_profile"});
  expect_refused(base + good_parameters + "data:\n  - {kind: tensile, file: curve.csv}\n",
                 {"data[0]", "needs its own case"});
  expect_refused(base + good_parameters +
                     "data:\n  - {kind: load_penetration, file: curve.csv, weight: 0}\n",
                 {"data[0].weight = 0", "must be > 0"});
  expect_refused(base + good_parameters +
                     "data:\n  - {kind: load_penetration, file: curve.csv, branch: up}\n",
                 {"data[0].branch = up", "loading, unloading"});
  expect_refused("base_case: missing.yaml\n" + good_parameters + data,
                 {"base_case = missing.yaml", "no file"});
  expect_refused(base + good_parameters +
                     "data:\n  - {kind: load_penetration, file: curve.csv, range: [0.7, 0.3]}\n",
                 {"data[0].range = [0.7, 0.3]", "lo < hi"});
  expect_refused(base + good_parameters +
                     "data:\n  - {kind: load_penetration, file: curve.csv, range: [2, 3]}\n",
                 {"data[0]", "0 measured point(s)", "within range [2, 3]"});
  const std::string features = "data:\n  - {kind: indentation_features, file: ";
  expect_refused(base + good_parameters + features + "curve.csv}\n",
                 {"data[0]", "curve.csv", "no feature column", "C (GPa), dP/dh (N/m) or Wp/Wt"});
  expect_refused(base + good_parameters + features + "features.csv, features: [C, H]}\n",
                 {"data[0].features: H", "allowed: C (loading_curvature)"});
  expect_refused(base + good_parameters + features + "features.csv, points: 5}\n",
                 {"data[0].points", "not for kind: indentation_features"});
  expect_refused(base + good_parameters + features + "features.csv, stiffness_scale: -1}\n",
                 {"data[0].stiffness_scale = -1", "must be > 0"});
  expect_refused(base + good_parameters +
                     "data:\n  - {kind: load_penetration, file: curve.csv, features: [C]}\n",
                 {"data[0].features", "only for kind: indentation_features"});
  expect_refused(base + good_parameters + data + "solver: {max_iterations: 0}\n",
                 {"solver.max_iterations = 0", "between 1 and 1000"});
}

// The features of a curve with a closed form: loading P = 30 h^2 to 1 um (C = 30 GPa, W_t = 10
// mN um), unloading P = 30 ((h - 0.6) / 0.4)^1.5 (S = 30 * 1.5 / 0.4 = 112.5 mN/um, W_e =
// 30 * 0.4 / 2.5 = 4.8 mN um, W_p/W_t = 0.52); a partial unload on the way is left out.
TEST(IndentationFeatures, OfACurveAgainstTheirClosedForms)
{
  io::LoadCurve curve;
  curve.source = "closed form";
  const auto add = [&](const double h, const double P, const char *segment) {
    curve.depth.push_back(h), curve.force.push_back(P), curve.segment.push_back(segment);
  };
  for (int i = 0; i <= 400; ++i)
    {
      const double h = 0.0025 * i;
      add(h, 30. * h * h, "load");
      if (i == 200) // a partial unload to 80 % of the force at 0.5 um, and the reload
        {
          add(0.49, 0.8 * 7.5, "partial_unload");
          add(0.5, 7.5, "reload");
        }
    }
  for (int i = 1; i <= 400; ++i)
    {
      const double h = 1. - 0.001 * i;
      add(h, 30. * std::pow((h - 0.6) / 0.4, 1.5), "unload");
    }
  const CurveFeatures f = curve_features(curve);
  EXPECT_NEAR(f.max_depth, 1., 1e-12);
  EXPECT_NEAR(f.value[0], 30., 1e-9);
  EXPECT_NEAR(f.value[1], 112.5, 112.5 * 1e-6);
  EXPECT_NEAR(f.value[2], 0.52, 1e-4); // trapezoid rule on steps of 2.5 and 1 nm
}

// A table in MPa, uN/nm and nm: converted, S brought to the case's depth (1 um) and scaled.
TEST(IndentationFeatures, MeasuredTableInItsUnitsScaledToTheSimulatedDepth)
{
  const fs::path    dir = calibration_folder();
  const Calibration c = parse_calibration_yaml(
      "base_case: cone_j2.yaml\n" + good_parameters +
          "data:\n  - {kind: indentation_features, file: features.csv, stiffness_scale: 0.5}\n",
      (dir / "calibrate.yaml").string());
  const DataSet &d = c.data.at(0);
  ASSERT_EQ(d.features.size(), 3u);
  EXPECT_EQ(d.features[1], Feature::unloading_stiffness);
  ASSERT_EQ(d.measured.size(), 6u);
  const std::vector<double> expected = {30., 110. * 0.5, 0.50, 32., 100. * 0.5 / 0.95, 0.54};
  for (std::size_t i = 0; i < 6; ++i)
    {
      EXPECT_EQ(d.x[i], double(i % 3));
      EXPECT_NEAR(d.measured[i], expected[i], 1e-9) << i;
      EXPECT_NEAR(d.scale_at(i), (expected[i % 3] + expected[i % 3 + 3]) / 2., 1e-9) << i;
    }

  // A chosen subset; a test 20 % shallower than the case is refused.
  const Calibration subset = parse_calibration_yaml(
      "base_case: cone_j2.yaml\n" + good_parameters +
          "data:\n  - {kind: indentation_features, file: features.csv, features: [Wp/Wt, C]}\n",
      (dir / "calibrate.yaml").string());
  EXPECT_EQ(subset.data[0].features,
            (std::vector<Feature>{Feature::loading_curvature, Feature::plastic_work_ratio}));
  EXPECT_EQ(subset.data[0].measured.size(), 4u);
  expect_refused("base_case: cone_j2.yaml\n" + good_parameters +
                     "data:\n  - {kind: indentation_features, file: shallow.csv}\n",
                 {"data[0]", "shallow.csv", "line 2", "depth 0.8 um", "within 10 %",
                  "loading.max_depth 1 um"});
  expect_refused("base_case: cone_j2.yaml\n" + good_parameters +
                     "data:\n  - {kind: indentation_features, file: ratio.csv}\n",
                 {"ratio.csv", "column 'Wp/Wt'", "1.2", "not a ratio between 0 and 1"});
}

// A measured hardness profile against the partial unloads at 0.25, 0.5 and 0.75 um: the
// measured points from 0.25 to 0.75 um, and a run's profile interpolated at them.
TEST(CurveData, HardnessProfilesBetweenThePartialUnloads)
{
  const fs::path    dir = calibration_folder();
  const Calibration c =
      parse_calibration_yaml("base_case: cone_csm.yaml\n" + good_parameters +
                                 "data:\n  - {kind: hardness_depth, file: csm.csv}\n",
                             (dir / "calibrate.yaml").string());
  const DataSet &d = c.data.at(0);
  EXPECT_EQ(d.x_name(), "depth_um");
  ASSERT_EQ(d.x.size(), 5u);
  for (std::size_t i = 0; i < 5; ++i)
    EXPECT_NEAR(d.x[i], 0.3 + 0.1 * double(i), 1e-12) << i;
  EXPECT_NEAR(d.measured.front(), 2.3, 1e-12);
  EXPECT_NEAR(d.measured.back(), 2.7, 1e-12);
  const fs::path run = dir / "run";
  fs::create_directories(run);
  std::ofstream(run / "hardness_depth.csv")
      << "depth_um,force_mN,hardness_GPa\n0.25,1,3.0\n0.5,4,2.0\n0.75,9,2.5\n";
  const std::vector<double> simulated = simulated_values(d, run.string());
  const std::vector<double> expected = {2.8, 2.4, 2.0, 2.2, 2.4};
  ASSERT_EQ(simulated.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i)
    EXPECT_NEAR(simulated[i], expected[i], 1e-12) << i;
}

// The difference Jacobian of r(x) = (x0^2 + x1, 3 x0 - x1^3) at x = (1, 2), with the forward
// runs failing wherever x0 > 1: the first column falls back to its backward difference, whose
// closed forms are (1 - 0.99^2) / 0.01 = 1.99 and 3; the second keeps its forward difference,
// 1 and -(2.01^3 - 8) / 0.01 = -12.0601. The failed column's retry is a batch of its own point
// only (x is not run again); a column out of candidates, or a failed x, gives nothing.
namespace
{
  // Stand-in forward runs of the residuals r(x): runs fail wherever x0 > 1; batch_sizes gets
  // the number of points of each batch.
  SampleResiduals failing_above_one(const std::function<std::vector<double>(const Point &)> &r,
                                    std::vector<std::size_t> &batch_sizes)
  {
    return [r, &batch_sizes](const std::vector<Point> &points) {
      batch_sizes.push_back(points.size());
      std::vector<std::optional<std::vector<double>>> result;
      for (const Point &x : points)
        if (x[0] > 1.)
          result.emplace_back(std::nullopt);
        else
          result.emplace_back(r(x));
      return result;
    };
  }
} // namespace

TEST(LeastSquaresFit, ADifferenceAroundAFailedRunTakesTheOtherSide)
{
  std::vector<std::size_t> batch_sizes;
  const SampleResiduals    sample = failing_above_one(
      [](const Point &x) {
        return std::vector<double>{x[0] * x[0] + x[1], 3. * x[0] - x[1] * x[1] * x[1]};
      },
      batch_sizes);
  const Point x = {1., 2.};
  const auto  both =
      difference_jacobian(sample, x, {{{1., 1.01}, {0.99, 1.}}, {{2., 2.01}, {1.99, 2.}}});
  ASSERT_TRUE(both.has_value());
  EXPECT_EQ(batch_sizes, (std::vector<std::size_t>{3, 1}));
  const std::vector<double> &r = both->first, &jacobian = both->second;
  EXPECT_DOUBLE_EQ(r[0], 3.);
  EXPECT_DOUBLE_EQ(r[1], -5.);
  EXPECT_NEAR(jacobian[0], 1.99, 1e-12);     // d r0 / d x0, backward
  EXPECT_NEAR(jacobian[1], 1., 1e-12);       // d r0 / d x1, forward
  EXPECT_NEAR(jacobian[2], 3., 1e-12);       // d r1 / d x0, backward
  EXPECT_NEAR(jacobian[3], -12.0601, 1e-10); // d r1 / d x1, forward

  EXPECT_FALSE(difference_jacobian(sample, x, {{{1., 1.01}}, {{2., 2.01}}}).has_value());
  EXPECT_FALSE(difference_jacobian(sample, {1.5, 2.}, {{{1.4, 1.5}}, {{2., 2.01}}}).has_value());
}

// A central difference whose upper run fails falls back to the backward difference from x: both
// of its points have run already, so the fallback must not start an empty batch of runs (a
// forward batch without cases is an error, which once stopped a calibration's statistics).
TEST(LeastSquaresFit, AFallbackThatNeedsNoNewRunStartsNone)
{
  std::vector<std::size_t> batch_sizes;
  const SampleResiduals    sample = failing_above_one(
      [](const Point &x) { return std::vector<double>{x[0] * x[0]}; }, batch_sizes);
  const auto jacobian = difference_jacobian(sample, {1.}, {{{0.99, 1.01}, {0.99, 1.}}});
  ASSERT_TRUE(jacobian.has_value());
  EXPECT_EQ(batch_sizes, (std::vector<std::size_t>{3}));
  EXPECT_NEAR(jacobian->second[0], 1.99, 1e-12); // (1 - 0.99^2) / 0.01, the backward difference
}

// The statistics of y = a + b t fitted to 8 points: the residuals r_i = a + b t_i - y_i have
// the Jacobian [1, t_i]; the textbook formulas of simple linear regression are the oracle.
TEST(FitStatistics, StandardErrorsAndCorrelationOfALinearRegression)
{
  const std::vector<double> t = {0., 1., 2., 3., 4., 5., 6., 7.};
  const std::vector<double> y = {1.1, 2.9, 5.2, 6.8, 9.1, 11.2, 12.8, 15.1};
  const double              n = double(t.size());
  double                    t_mean = 0., y_mean = 0.;
  for (std::size_t i = 0; i < t.size(); ++i)
    t_mean += t[i] / n, y_mean += y[i] / n;
  double stt = 0., sty = 0.;
  for (std::size_t i = 0; i < t.size(); ++i)
    stt += (t[i] - t_mean) * (t[i] - t_mean), sty += (t[i] - t_mean) * (y[i] - y_mean);
  const double        b = sty / stt, a = y_mean - b * t_mean;
  std::vector<double> residuals, jacobian;
  double              ssr = 0.;
  for (std::size_t i = 0; i < t.size(); ++i)
    {
      residuals.push_back(a + b * t[i] - y[i]);
      ssr += residuals.back() * residuals.back();
      jacobian.insert(jacobian.end(), {1., t[i]});
    }
  const double s = std::sqrt(ssr / (n - 2.));
  const double se_b = s / std::sqrt(stt), se_a = s * std::sqrt(1. / n + t_mean * t_mean / stt);
  double       sum_t2 = 0.;
  for (const double ti : t)
    sum_t2 += ti * ti;
  const double correlation = -t_mean / std::sqrt(sum_t2 / n);

  const FitStatistics fit =
      fit_statistics({a, b}, residuals, jacobian, {"a", "b"}, {{{-100., 100.}}, {{-100., 100.}}});
  EXPECT_EQ(fit.degrees_of_freedom, 6u);
  EXPECT_NEAR(fit.standard_error[0], se_a, 1e-12 * se_a + 1e-14);
  EXPECT_NEAR(fit.standard_error[1], se_b, 1e-12 * se_b + 1e-14);
  EXPECT_NEAR(fit.correlation[0][1], correlation, 1e-12);
  // Student's t for 6 degrees of freedom at 97.5 %: 2.446912 (tables).
  EXPECT_NEAR(fit.t_quantile, 2.446912, 1e-6);
  EXPECT_NEAR(fit.ci95[1][1] - fit.ci95[1][0], 2. * 2.446912 * se_b, 1e-5 * se_b);
  EXPECT_TRUE(fit.identifiable);
  EXPECT_TRUE(fit.warnings.empty());
}

TEST(FitStatistics, ParametersTheDataCannotSeparateAreNamed)
{
  // Two parameters that enter only through their sum: identical columns.
  std::vector<double> residuals, jacobian;
  for (int i = 0; i < 6; ++i)
    {
      residuals.push_back(0.01 * ((i % 2) - 0.5));
      jacobian.insert(jacobian.end(), {1. + i, 1. + i});
    }
  const FitStatistics same =
      fit_statistics({1., 2.}, residuals, jacobian, {"p", "q"}, {{{0., 5.}}, {{0., 5.}}});
  EXPECT_FALSE(same.identifiable);
  ASSERT_FALSE(same.warnings.empty());
  EXPECT_NE(same.warnings.front().find("near-singular"), std::string::npos);
  EXPECT_NE(same.warnings.front().find("p, q"), std::string::npos);

  // Nearly parallel columns: correlated above 0.95, named.
  jacobian.clear();
  for (int i = 0; i < 6; ++i)
    jacobian.insert(jacobian.end(), {1. + i, 1. + i + 0.3 * (i % 2)});
  const FitStatistics close =
      fit_statistics({1., 2.}, residuals, jacobian, {"p", "q"}, {{{0., 5.}}, {{0., 5.}}});
  EXPECT_FALSE(close.identifiable);
  bool named = false;
  for (const auto &w : close.warnings)
    named = named || (w.find("p and q correlate") != std::string::npos);
  EXPECT_TRUE(named);

  // A parameter the data do not depend on.
  jacobian.clear();
  for (int i = 0; i < 6; ++i)
    jacobian.insert(jacobian.end(), {1. + i, 0.});
  const FitStatistics none =
      fit_statistics({1., 2.}, residuals, jacobian, {"p", "q"}, {{{0., 5.}}, {{0., 5.}}});
  EXPECT_FALSE(none.identifiable);
  EXPECT_NE(none.warnings.front().find("do not change with q"), std::string::npos);

  // An interval wider than the bounds.
  jacobian.clear();
  for (int i = 0; i < 6; ++i)
    jacobian.insert(jacobian.end(), {1e-3 * (1. + i), 1e-3 * (i % 3)});
  const FitStatistics wide =
      fit_statistics({1., 2.}, residuals, jacobian, {"p", "q"}, {{{0.9, 1.1}}, {{1.9, 2.1}}});
  EXPECT_FALSE(wide.identifiable);
  bool wider = false;
  for (const auto &w : wide.warnings)
    wider = wider || (w.find("wider than its bounds") != std::string::npos);
  EXPECT_TRUE(wider);
}

TEST(CurveData, SortsAveragesAndInterpolates)
{
  const SampledCurve curve = sorted_curve({2., 0., 1., 1.}, {4., 0., 1., 3.});
  ASSERT_EQ(curve.x.size(), 3u);
  EXPECT_EQ(curve.y[1], 2.); // the two points at x = 1 averaged
  EXPECT_DOUBLE_EQ(curve.at(0.5), 1.);
  EXPECT_DOUBLE_EQ(curve.at(1.5), 3.);
  EXPECT_DOUBLE_EQ(curve.at(5.), 4.); // the end value beyond the range
}

// A measured line across the imprint in nm (negative positions folded onto the radius) against
// a run's pileup_profiles.csv: the unloaded stage along the azimuth nearest to the one asked.
TEST(CurveData, HeightProfilesAreFoldedAndReadAlongTheNearestAzimuth)
{
  const fs::path dir = calibration_folder();
  {
    std::ofstream line(dir / "afm.csv");
    line << "# AFM line\nx_nm,height_nm\n-2000,10\n-1000,-400\n0,-900\n1000,-420\n2000,12\n"
            "3000,5\n";
  }
  Calibration c = parse_calibration_yaml(
      "base_case: cone_j2.yaml\n" + good_parameters +
          "data:\n  - {kind: pileup_profile, file: afm.csv, azimuth_deg: 40}\n",
      (dir / "calibrate.yaml").string());
  const DataSet &d = c.data.at(0);
  EXPECT_EQ(d.kind_name(), "pileup_profile");
  EXPECT_EQ(d.x_name(), "r_um");
  // Radii 0, 1, 2, 3 um; the two sides averaged at 1 and 2 um; heights in um.
  ASSERT_EQ(d.x.size(), 4u);
  EXPECT_DOUBLE_EQ(d.x[1], 1.);
  EXPECT_NEAR(d.measured[0], -0.9, 1e-12);
  EXPECT_NEAR(d.measured[1], -0.41, 1e-12);
  EXPECT_NEAR(d.measured[2], 0.011, 1e-12);
  EXPECT_NEAR(d.scale, 0.9, 1e-12);

  const fs::path run = dir / "run";
  fs::create_directories(run);
  {
    std::ofstream profiles(run / "pileup_profiles.csv");
    profiles << "stage,azimuth_deg,r_um,height_um\n";
    for (const double azimuth : {0., 45., 90.})
      for (const char *stage : {"max_depth", "unloaded"})
        for (int i = 0; i <= 2; ++i)
          profiles << stage << "," << azimuth << "," << 1.5 * i << ","
                   << (std::string(stage) == "unloaded" ? azimuth / 1000. : -1.) - 0.1 * i << "\n";
  }
  const std::vector<double> simulated = simulated_values(d, run.string());
  ASSERT_EQ(simulated.size(), 4u);
  EXPECT_NEAR(simulated[0], 0.045, 1e-12);             // azimuth 45, r = 0
  EXPECT_NEAR(simulated[1], 0.045 - 0.1 / 1.5, 1e-12); // linear between r = 0 and 1.5
  EXPECT_NEAR(simulated[3], 0.045 - 0.2, 1e-12);       // beyond the profile: its last height
}

TEST(StudyLauncher, TheTemplateWrapsTheCommand)
{
  EXPECT_EQ(
      study::launch_command("srun -n {ranks} --label=r{ranks} {command}",
                            {"indentsim", "run", "case.yaml"}, 4),
      (std::vector<std::string>{"srun", "-n", "4", "--label=r4", "indentsim", "run", "case.yaml"}));
  EXPECT_THROW(study::launch_command("srun -n {ranks}", {"indentsim"}, 2), study::StudyFileError);
}

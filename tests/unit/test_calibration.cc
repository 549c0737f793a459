// Calibration: the file's checks (every bad configuration refused before any run, naming the
// key), the statistics at the optimum against the closed forms of linear regression, the
// resampling of measured curves, and the launcher template. The closed loops that run the
// program are in tests/system/calibration/. Units: um, mN, GPa.
#include "../test_files.h"
#include "calibration/CalibrationFile.h"
#include "calibration/CurveData.h"
#include "calibration/FitStatistics.h"
#include "study/StudyRunner.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
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
    return dir;
  }

  const std::string good_parameters =
      "parameters:\n"
      "  material.yield_stress: {start: 0.25, min: 0.05, max: 1.0}\n"
      "  material.hardening_modulus: {start: 1.0, min: 0.0, max: 5.0}\n";

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
  expect_refused(base + "parameters:\n  material.yield_stress: {start: 0.3, max: 1}\n" + data,
                 {"missing key 'min'"});
  expect_refused(base + good_parameters + "data:\n  - {kind: load_penetration, file: nope.csv}\n",
                 {"data[0].file = nope.csv", "no file", "nope.csv"});
  expect_refused(base + good_parameters + "data:\n  - {kind: load_penetration, file: deep.csv}\n",
                 {"data[0]", "deep.csv", "0 measured point(s) within the range",
                  "0 to 1 um (loading.max_depth)", "spans 2 to 3"});
  expect_refused(base + good_parameters + "data:\n  - {kind: hardness_depth, file: curve.csv}\n",
                 {"data[0].kind = hardness_depth", "not available yet",
                  "load_penetration, tensile, pileup_profile"});
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
  expect_refused(base + good_parameters + data + "solver: {max_iterations: 0}\n",
                 {"solver.max_iterations = 0", "between 1 and 1000"});
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

// The hardness-depth analysis of partial unloads and the Nix-Gao fit (analysis/HardnessDepth.h)
// on synthetic curves with known answers. Units: um, mN, GPa (1 GPa*um^2 = 1 mN).
#include "analysis/AnalyzeCommand.h"
#include "analysis/HardnessDepth.h"

#include "../test_files.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

using namespace indentsim;
using analysis::LoadCurve;
namespace fs = std::filesystem;

namespace
{
  void add(LoadCurve &curve, const double h, const double p, const std::string &segment)
  {
    curve.depth.push_back(h);
    curve.force.push_back(p);
    curve.segment.push_back(segment);
  }
} // namespace

// Sneddon's elastic cone, P = (2/pi) E_r tan(theta) h^2, loaded with 10 % partial unloads at
// 1, 2 and 3 um (unloading and reloading on the same curve): each gives S = 2 P / h, and with
// the cone's epsilon the exact contact depth 2h/pi and E_r (to the fit's convergence, 1e-5:
// five points over 10 % of the force); rows of the full curve that
// belong to no partial unload are ignored, and the full unload is left to Oliver-Pharr.
TEST(HardnessDepth, ElasticConePartialUnloadsGiveSneddonExactly)
{
  const double reduced_modulus = 74.0, tan_theta = std::tan(70.3 * M_PI / 180.);
  const double c = 2. / M_PI * reduced_modulus * tan_theta;
  LoadCurve    curve;
  add(curve, 0, 0, "start");
  for (int k = 1; k <= 3; ++k)
    {
      for (int i = 1; i <= 10; ++i)
        {
          const double h = k - 1 + 0.1 * i;
          add(curve, h, c * h * h, "load");
        }
      const double p_k = c * k * k;
      for (int i = 1; i <= 4; ++i)
        {
          const double p = p_k * (1 - 0.025 * i);
          add(curve, std::sqrt(p / c), p, "partial_unload");
        }
      add(curve, k, p_k, "reload");
    }
  add(curve, 2.5, c * 6.25, "unload");
  analysis::OliverPharrSettings settings;
  settings.epsilon = analysis::default_epsilon("cone");
  const auto area = [&](const double h_c) { return M_PI * tan_theta * tan_theta * h_c * h_c; };
  std::vector<std::string> skipped;
  const auto points = analysis::analyze_partial_unloads(curve, area, settings, skipped);
  EXPECT_TRUE(skipped.empty());
  ASSERT_EQ(points.size(), 3u);
  for (int k = 1; k <= 3; ++k)
    {
      const analysis::HardnessPoint &p = points[k - 1];
      EXPECT_DOUBLE_EQ(p.depth, k);
      EXPECT_NEAR(p.stiffness, 2 * c * k, 1e-5 * c * k);
      EXPECT_NEAR(p.estimate.contact_depth, 2 * k / M_PI, 1e-5 * k);
      EXPECT_NEAR(p.estimate.reduced_modulus, reduced_modulus, 1e-5 * reduced_modulus);
      EXPECT_NEAR(p.unloaded_fraction, 0.1, 1e-12);
      EXPECT_EQ(p.fit.n_points, 5u);
    }
  // The CSV has the columns the user guide names, one row per partial unload.
  const std::string csv = analysis::to_csv(points);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "depth_um,force_mN,stiffness_mN_per_um,contact_depth_um,contact_area_um2,hardness_GPa,"
            "reduced_modulus_GPa,true_contact_area_um2,true_hardness_GPa,unloaded_fraction,"
            "fit_points,fit_exponent");
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);
  // Oliver-Pharr of the whole curve sees the loading and the full unload only.
  const LoadCurve kept = analysis::without_partial_unloads(curve);
  EXPECT_EQ(kept.depth.size(), 32u);
}

// A partial unload whose points give no positive stiffness (a force that rises while the depth
// falls) is left out, and the message names its depth and row.
TEST(HardnessDepth, UnanalysablePartialUnloadIsNamedAndLeftOut)
{
  LoadCurve curve;
  curve.source = "synthetic";
  add(curve, 0, 0, "start");
  add(curve, 1.0, 10.0, "load");
  for (int i = 1; i <= 4; ++i)
    add(curve, 1.0 - 0.01 * i, 10.0 + i, "partial_unload");
  std::vector<std::string> skipped;
  const auto               points = analysis::analyze_partial_unloads(
                    curve, [](const double h) { return 24.5 * h * h; }, analysis::OliverPharrSettings{}, skipped);
  EXPECT_TRUE(points.empty());
  ASSERT_EQ(skipped.size(), 1u);
  EXPECT_NE(skipped.front().find("at 1 um (point 2)"), std::string::npos) << skipped.front();
}

// Nix-Gao: H^2 = H_0^2 (1 + h*/h) over the shallow points and another straight line in 1/h
// beyond a knee at h = 1.3 um, continuous there: the bilinear fit recovers the knee to its
// search grid (a twentieth of the interval between the points at 1.2 and 1.4 um), H_0 and h*
// closely, with a residual far below that of one straight line.
TEST(HardnessDepth, NixGaoBilinearFitRecoversKneeAndLayerHardness)
{
  const double        h0 = 3.0, h_star = 0.2, knee = 1.3;
  const auto          layer = [&](const double x) { return h0 * h0 * (1 + h_star * x); };
  const double        deep_slope = -4.0;
  std::vector<double> depth, hardness;
  for (double h = 0.2; h < 3.05; h += 0.2)
    {
      const double x = 1 / h;
      const double y = x >= 1 / knee ? layer(x) : layer(1 / knee) + deep_slope * (x - 1 / knee);
      depth.push_back(h);
      hardness.push_back(std::sqrt(y));
    }
  const auto fit = analysis::fit_nix_gao(depth, hardness);
  ASSERT_TRUE(fit.has_value());
  EXPECT_NEAR(1 / fit->knee_depth, 1 / knee, 0.05 * (1 / 1.2 - 1 / 1.4));
  EXPECT_NEAR(fit->layer_hardness, h0, 1e-3 * h0);
  EXPECT_NEAR(fit->layer_characteristic, h_star, 2e-3);
  EXPECT_NEAR(fit->deep_slope, deep_slope, 0.05);
  EXPECT_DOUBLE_EQ(fit->layer_range[0], 0.2);
  EXPECT_NEAR(fit->layer_range[1], 1.2, 1e-12);
  EXPECT_NEAR(fit->deep_range[0], 1.4, 1e-12);
  EXPECT_LT(fit->rms, 0.01);
  EXPECT_GT(fit->single_line_rms, 10 * fit->rms);
  EXPECT_TRUE(fit->knee_significant());
  // Points on one line with a little scatter: the knee is not significant.
  std::vector<double> scattered;
  for (std::size_t i = 0; i < depth.size(); ++i)
    scattered.push_back(std::sqrt(layer(1 / depth[i]) * (1 + (i % 2 ? 1e-3 : -1e-3))));
  const auto flat = analysis::fit_nix_gao(depth, scattered);
  ASSERT_TRUE(flat.has_value());
  EXPECT_FALSE(flat->knee_significant()) << "F = " << flat->f_statistic;
  // Too few points for two branches of three: no fit.
  EXPECT_FALSE(analysis::fit_nix_gao({1, 2, 3, 4, 5}, {1, 1, 1, 1, 1}).has_value());
}

// `indentsim analyze` of a curve with partial unloads (a run's CSV with its `segment` column):
// the full unloading goes to Oliver-Pharr as before, and the partial unloads give
// hardness_depth.csv and .json next to oliver_pharr.json, each S = 2 P / h of Sneddon's cone.
TEST(HardnessDepth, AnalyzeCommandWritesTheProfileOfARunsCurve)
{
  const double   reduced_modulus = 74.0, tan_theta = std::tan(70.3 * M_PI / 180.);
  const double   c = 2. / M_PI * reduced_modulus * tan_theta;
  const fs::path dir = test_files::scratch_directory("hardness_depth", "analyze");
  std::ofstream  csv(dir / "load_penetration.csv");
  csv << std::setprecision(15) << "depth_um,force_mN,segment\n0,0,start\n";
  for (int k = 1; k <= 3; ++k)
    {
      for (int i = 1; i <= 10; ++i)
        {
          const double h = k - 1 + 0.1 * i;
          csv << h << ',' << c * h * h << ",load\n";
        }
      for (int i = 1; i <= 4; ++i)
        {
          const double p = c * k * k * (1 - 0.025 * i);
          csv << std::sqrt(p / c) << ',' << p << ",partial_unload\n";
        }
      csv << k << ',' << c * k * k << ",reload\n";
    }
  for (int i = 1; i <= 20; ++i)
    {
      const double h = 3.0 - 0.05 * i;
      csv << h << ',' << c * h * h << ",unload\n";
    }
  csv.close();
  io::AnalyzeOptions options;
  options.target = (dir / "load_penetration.csv").string();
  options.indenter_shape = "cone";
  analysis::analyze_command(options, dir.string());
  ASSERT_TRUE(fs::exists(dir / "oliver_pharr.json"));
  ASSERT_TRUE(fs::exists(dir / "hardness_depth.json"));
  std::ifstream            profile(dir / "hardness_depth.csv");
  std::string              line;
  std::vector<std::string> rows;
  while (std::getline(profile, line))
    rows.push_back(line);
  ASSERT_EQ(rows.size(), 4u); // the header and one row per partial unload
  for (int k = 1; k <= 3; ++k)
    {
      std::istringstream fields(rows[k]);
      double             depth = 0, force = 0, stiffness = 0;
      char               comma = 0;
      fields >> depth >> comma >> force >> comma >> stiffness;
      EXPECT_NEAR(depth, k, 1e-9);
      EXPECT_NEAR(stiffness, 2 * c * k, 1e-5 * c * k);
    }
}

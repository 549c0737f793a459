// Oliver-Pharr analysis (analysis/OliverPharr.h) against closed forms: synthetic power laws,
// Sneddon's elastic cone, Hertz's paraboloid, the work integrals of known curves, and an
// elastic indentation computed by the solver. Units: um, mN, GPa (1 GPa*um^2 = 1 mN).
#include "../test_cases.h"
#include "../test_files.h"
#include "analysis/CurveComparison.h"
#include "analysis/OliverPharr.h"
#include "indenter/IndenterFactory.h"
#include "problems/IndentationProblem.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

using namespace indentsim;
using analysis::LoadCurve;

namespace
{
  // Loading P = load(h) from 0 to h_max in n_load steps, then unloading P = unload(h) from
  // h_max down to h_end in n_unload steps.
  template <typename Load, typename Unload>
  LoadCurve make_curve(const Load &load, const Unload &unload, const double h_max,
                       const double h_end, const unsigned int n_load, const unsigned int n_unload)
  {
    LoadCurve curve;
    curve.source = "synthetic";
    for (unsigned int i = 0; i <= n_load; ++i)
      {
        const double h = h_max * i / n_load;
        curve.depth.push_back(h);
        curve.force.push_back(load(h));
      }
    for (unsigned int i = 1; i <= n_unload; ++i)
      {
        const double h = h_max + (h_end - h_max) * i / n_unload;
        curve.depth.push_back(h);
        curve.force.push_back(unload(h));
      }
    return curve;
  }
} // namespace

// The fit recovers the parameters of an exact power law P = alpha (h - h_f)^m to round-off,
// for exponents on both sides of the usual range.
TEST(OliverPharr, PowerLawFitRecoversExactParameters)
{
  for (const double m : {1.2, 1.5, 2.0, 2.7})
    {
      const double        alpha = 37.1, h_f = 1.234;
      std::vector<double> depth, force;
      for (int i = 0; i < 12; ++i)
        {
          const double h = 1.9 + 0.05 * i;
          depth.push_back(h);
          force.push_back(alpha * std::pow(h - h_f, m));
        }
      const analysis::PowerLawFit fit = analysis::fit_power_law(depth, force);
      EXPECT_NEAR(fit.m, m, 1e-7 * m) << "m = " << m;
      EXPECT_NEAR(fit.h_f, h_f, 1e-7) << "m = " << m;
      EXPECT_NEAR(fit.alpha, alpha, 1e-6 * alpha) << "m = " << m;
      EXPECT_LT(fit.rms_error, 1e-9 * force.back());
    }
}

// Sneddon's elastic cone: P = (2/pi) E_r tan(theta) h^2 on loading and unloading, contact depth
// h_c = 2h/pi, area pi tan^2(theta) h_c^2. With epsilon = 2(pi - 2)/pi and beta = 1 the method
// is exact: E_r, H, h_c to 1e-6; an elastic curve leaves no residual depth and no plastic work.
TEST(OliverPharr, ElasticConeGivesSneddonModulusExactly)
{
  const double reduced_modulus = 74.0, tan_theta = std::tan(70.3 * M_PI / 180.);
  const auto   sneddon = [&](const double h) {
    return 2. / M_PI * reduced_modulus * tan_theta * h * h;
  };
  const LoadCurve               curve = make_curve(sneddon, sneddon, 2.0, 0.0, 400, 400);
  analysis::OliverPharrSettings settings;
  settings.epsilon = analysis::default_epsilon("cone");
  const auto area = [&](const double h_c) { return M_PI * tan_theta * tan_theta * h_c * h_c; };
  const auto result = analysis::analyze(curve, area, settings);
  EXPECT_NEAR(result.reduced_modulus, reduced_modulus, 1e-6 * reduced_modulus);
  EXPECT_NEAR(result.contact_depth, 2.0 * 2.0 / M_PI, 1e-6);
  EXPECT_NEAR(result.hardness, sneddon(2.0) / area(4.0 / M_PI), 1e-6 * result.hardness);
  EXPECT_NEAR(result.fit.m, 2.0, 1e-6);
  EXPECT_NEAR(result.residual_depth, 0.0, 1e-9);
  EXPECT_EQ(result.residual_depth_source, "curve");
  EXPECT_NEAR(result.plastic_work_ratio, 0.0, 1e-4); // trapezoid rule on 400 steps
  // The rounded cone's own factor: the cone is the tool's default for it.
  EXPECT_NEAR(analysis::default_epsilon("rounded_cone"), 0.7268, 1e-4);
}

// Hertz's paraboloid (sphere of radius R at small depth): P = 4/3 E_r sqrt(R) h^1.5, h_c = h/2,
// A = 2 pi R h_c. epsilon = 0.75 makes the method exact; the sample modulus follows from nu
// and a rigid indenter, and from a diamond indenter's compliance.
TEST(OliverPharr, ElasticParaboloidGivesHertzModulusAndSampleModulus)
{
  const double reduced_modulus = 74.0, radius = 10.0;
  const auto   hertz = [&](const double h) {
    return 4. / 3. * reduced_modulus * std::sqrt(radius) * std::pow(h, 1.5);
  };
  const LoadCurve               curve = make_curve(hertz, hertz, 0.5, 0.0, 200, 200);
  analysis::OliverPharrSettings settings;
  settings.epsilon = 0.75;
  settings.sample_poisson_ratio = 0.3;
  const auto area = [&](const double h_c) { return 2. * M_PI * radius * h_c; };
  auto       result = analysis::analyze(curve, area, settings);
  EXPECT_NEAR(result.contact_depth, 0.25, 1e-7);
  EXPECT_NEAR(result.reduced_modulus, reduced_modulus, 1e-6 * reduced_modulus);
  EXPECT_NEAR(*result.sample_modulus, reduced_modulus * (1 - 0.09), 1e-5);
  settings.indenter_modulus = 1141.;
  result = analysis::analyze(curve, area, settings);
  const double expected = (1 - 0.09) / (1 / reduced_modulus - (1 - 0.07 * 0.07) / 1141.);
  EXPECT_NEAR(*result.sample_modulus, expected, 1e-6 * expected);
}

// Work split of an elasto-plastic synthetic curve: loading P = C h^2 (W_t = C h_max^3 / 3),
// unloading P = alpha (h - h_f)^m (W_e = alpha (h_max - h_f)^(m+1) / (m+1)). With the data
// ending at 30 % of P_max the fitted law closes the elastic work; the residual depth is then
// the fit's h_f. The stiffness is the exact slope.
TEST(OliverPharr, WorkSplitMatchesClosedFormIntegrals)
{
  const double    C = 30., h_max = 2.0, h_f = 1.6, m = 1.4;
  const double    p_max = C * h_max * h_max, alpha = p_max / std::pow(h_max - h_f, m);
  const auto      load = [&](const double h) { return C * h * h; };
  const auto      unload = [&](const double h) { return alpha * std::pow(h - h_f, m); };
  const double    total = C * std::pow(h_max, 3) / 3;
  const double    elastic = alpha * std::pow(h_max - h_f, m + 1) / (m + 1);
  const double    h_end = h_f + (h_max - h_f) * std::pow(0.3, 1 / m); // P = 0.3 P_max
  const LoadCurve curve = make_curve(load, unload, h_max, h_end, 2000, 400);
  analysis::OliverPharrSettings settings;
  const auto                    area = [](const double h_c) { return 24.5 * h_c * h_c; };
  const auto                    result = analysis::analyze(curve, area, settings);
  EXPECT_NEAR(result.total_work, total, 1e-5 * total);
  EXPECT_NEAR(result.elastic_work, elastic, 1e-4 * elastic);
  EXPECT_NEAR(result.plastic_work_ratio, 1 - elastic / total, 1e-5);
  EXPECT_EQ(result.residual_depth_source, "fit h_f");
  EXPECT_NEAR(result.residual_depth, h_f, 1e-6);
  EXPECT_NEAR(result.stiffness, alpha * m * std::pow(h_max - h_f, m - 1), 1e-6 * result.stiffness);
  EXPECT_EQ(result.max_force, p_max);
}

// A hold at the maximum and a second cycle: the analysed unloading is the one that starts at
// the last point of the largest depth.
TEST(OliverPharr, UnloadingStartsAfterTheHoldAtTheLargestDepth)
{
  LoadCurve curve;
  curve.source = "cycles";
  const auto add = [&](const double h, const double p) {
    curve.depth.push_back(h);
    curve.force.push_back(p);
  };
  for (const double h : {0.0, 0.5, 1.0})
    add(h, 10 * h * h);
  for (const double h : {0.95, 0.9, 0.85})
    add(h, 10 * std::pow((h - 0.8) / 0.2, 1.5));
  for (const double h : {0.9, 1.0, 1.5, 2.0})
    add(h, 10 * h * h);
  add(2.05, 40); // the maximum, held for one more point
  add(2.05, 40);
  const double h_f = 1.7;
  for (int i = 1; i <= 10; ++i)
    {
      const double h = 2.05 - 0.03 * i;
      add(h, 40 * std::pow((h - h_f) / (2.05 - h_f), 1.5));
    }
  const auto result =
      analysis::analyze(curve, [](const double h_c) { return 24.5 * h_c * h_c; }, {});
  EXPECT_EQ(result.unloading_begin, 11u); // the second point at 2.05 um
  EXPECT_EQ(result.unloading_end, curve.depth.size());
  EXPECT_DOUBLE_EQ(result.max_depth, 2.05);
  EXPECT_NEAR(result.fit.h_f, h_f, 1e-7);
  EXPECT_NEAR(result.fit.m, 1.5, 1e-7);
}

// Too few unloading points: the error names the curve, the count and the fit range.
TEST(OliverPharr, TooFewUnloadingPointsIsANamedError)
{
  LoadCurve curve;
  curve.source = "few.csv";
  curve.depth = {0, 1, 2, 1.9, 1.5};
  curve.force = {0, 10, 40, 10, 0};
  try
    {
      analysis::analyze(curve, [](double h) { return 24.5 * h * h; }, {});
      FAIL() << "no error";
    }
  catch (const std::invalid_argument &e)
    {
      const std::string message = e.what();
      EXPECT_NE(message.find("few.csv"), std::string::npos) << message;
      EXPECT_NE(message.find("has 1 points between 50 % and 100 %"), std::string::npos) << message;
    }
}

// CSV input: columns found by name with their units (nm, uN) converted to um and mN; a
// non-number names file, line, column and value; an unknown unit names the column.
TEST(OliverPharr, CsvColumnsAndUnits)
{
  const auto        dir = test_files::scratch_directory("oliver_pharr", "csv");
  const std::string path = (dir / "measured.csv").string();
  {
    std::ofstream out(path);
    out << "# Berkovich test, sample 3\ntime_s,Depth (nm),Load_uN\n0,0,0\n1,500,1200\n2,480,600\n";
  }
  const LoadCurve curve = analysis::read_load_curve_csv(path);
  ASSERT_EQ(curve.depth.size(), 3u);
  EXPECT_DOUBLE_EQ(curve.depth[1], 0.5);
  EXPECT_DOUBLE_EQ(curve.force[1], 1.2);
  EXPECT_TRUE(curve.contact_area.empty());

  {
    std::ofstream out(path);
    out << "depth_um,force_mN\n0,0\n1,abc\n";
  }
  try
    {
      analysis::read_load_curve_csv(path);
      FAIL() << "no error";
    }
  catch (const std::invalid_argument &e)
    {
      const std::string message = e.what();
      EXPECT_NE(message.find("line 3, column 'force_mN': 'abc'"), std::string::npos) << message;
    }
  {
    std::ofstream out(path);
    out << "depth_furlong,force_mN\n0,0\n";
  }
  try
    {
      analysis::read_load_curve_csv(path);
      FAIL() << "no error";
    }
  catch (const std::invalid_argument &e)
    {
      const std::string message = e.what();
      EXPECT_NE(message.find("'depth_furlong': depth unit 'furlong' is not known"),
                std::string::npos)
          << message;
    }
  // Named columns and units given explicitly.
  {
    std::ofstream out(path);
    out << "a;b\n0;0\n2;3\n";
  }
  const LoadCurve named = analysis::read_load_curve_csv(path, "a", "b", "mm", "N");
  EXPECT_DOUBLE_EQ(named.depth[1], 2000.0);
  EXPECT_DOUBLE_EQ(named.force[1], 3000.0);
}

// The solver's elastic indentation by the rounded cone in the Hertz regime (h = 0.1 delta,
// spherical tip R = a^2 delta), loaded and unloaded with force-paced unloading: Oliver-Pharr
// recovers E_r = E/(1 - nu^2) within 4 % (measured +0.8 %; the mesh over-estimates the force
// by about 3 %, see ElasticIndentation.HertzRegimeMatchesClosedForm), leaves no residual depth
// and no plastic work beyond the trapezoid rule's on 4 loading steps (measured W_p/W_t 0.017),
// and its contact area agrees with the simulation's interpolated contact area within 8 %
// (measured +5.2 %; no pile-up in elasticity). The force-paced unloading records at least 10
// points.
TEST(OliverPharr, ElasticIndentationRecoversTheReducedModulus)
{
  io::Case c = test_cases::elastic_rounded_cone_case();
  c.specimen.refined_region = {{4., 4., 2.}};
  c.specimen.contact_elements = 24;
  c.loading.max_depth = 0.1;
  c.loading.steps = 4;
  c.loading.unload = true;
  c.loading.unload_points = 12;
  problems::IndentationProblem<3> problem(c, MPI_COMM_WORLD, false);
  problem.setup();
  problem.run("");
  LoadCurve curve;
  curve.source = "elastic run";
  unsigned int n_unload = 0;
  for (const auto &r : problem.records())
    {
      curve.depth.push_back(r.depth);
      curve.force.push_back(r.force);
      curve.contact_area.push_back(r.contact_area); // whole indent (quarter model scaled)
      n_unload += r.segment == "unload";
    }
  EXPECT_GE(n_unload, 10u);
  // The progress line's ETA counts on unload_points + 1 force-paced unloading steps (not the
  // loading's step count): the run took that many, within one.
  const unsigned int n_steps = problem.records().size() - 1; // without the initial state
  EXPECT_NEAR(double(n_steps), double(nonlinear::expected_steps(c.loading)), 1.0);
  EXPECT_EQ(nonlinear::expected_steps(c.loading), 4u + 13u);
  const auto                    indenter = indenter::create_indenter(c.indenter);
  analysis::OliverPharrSettings settings;
  settings.epsilon = 0.75; // paraboloid (the spherical tip)
  settings.sample_poisson_ratio = c.material.poisson_ratio;
  const auto result = analysis::analyze(
      curve, [&](const double h) { return indenter->projected_area(h); }, settings);
  const double reduced_modulus =
      c.material.young_modulus / (1 - c.material.poisson_ratio * c.material.poisson_ratio);
  std::cout << "[ oliver-pharr ] E_r " << result.reduced_modulus << " GPa (closed form "
            << reduced_modulus << "), m " << result.fit.m << ", h_r/h_max "
            << result.residual_depth / result.max_depth << ", W_p/W_t " << result.plastic_work_ratio
            << ", area " << result.contact_area << " um^2 (true " << *result.true_contact_area
            << ")" << std::endl;
  EXPECT_NEAR(result.reduced_modulus / reduced_modulus, 1.0, 0.04);
  EXPECT_NEAR(*result.sample_modulus / c.material.young_modulus, 1.0, 0.04);
  EXPECT_LT(result.residual_depth / result.max_depth, 0.02);
  EXPECT_LT(std::abs(result.plastic_work_ratio), 0.03);
  EXPECT_LT(std::abs(*result.area_error_percent), 8.0);
}

// Comparison with a measured curve: computed P = C h^2 (with an unloading), measured 1.1 C h^2
// on other depths and beyond the computed range. The RMS deviation over the measured loading
// points inside the computed range is 0.1 C sqrt(mean h^4) up to the linear interpolation of
// the computed curve (fine here), the deviation at the largest computed depth -1/11.
TEST(CurveComparison, ScaledMeasurementGivesClosedFormDeviation)
{
  const double C = 20.0;
  LoadCurve    computed, measured;
  computed.source = "computed";
  measured.source = "measured.csv";
  for (int i = 0; i <= 600; ++i)
    {
      computed.depth.push_back(0.01 * i);
      computed.force.push_back(C * 0.0001 * i * i);
    }
  computed.depth.push_back(5.9);
  computed.force.push_back(100.0); // unloading: ignored
  double sum = 0;
  int    n = 0;
  for (int i = 1; i <= 70; ++i)
    {
      const double h = 0.0937 * i; // up to 6.56 um, beyond the computed 6.0
      measured.depth.push_back(h);
      measured.force.push_back(1.1 * C * h * h);
      if (h <= 6.0)
        {
          sum += std::pow(0.1 * C * h * h, 2);
          ++n;
        }
    }
  const analysis::CurveDeviation d = analysis::compare_loading(computed, measured);
  EXPECT_EQ(d.n_points, static_cast<unsigned int>(n));
  EXPECT_NEAR(d.rms_mN, std::sqrt(sum / n), 1e-3 * std::sqrt(sum / n));
  EXPECT_DOUBLE_EQ(d.max_depth, 6.0);
  EXPECT_NEAR(d.computed_force, C * 36, 1e-9);
  ASSERT_TRUE(d.measured_force.has_value());
  // interpolated linearly between 5.9907 and 6.0844 um: error <= 1.1 C (0.0937)^2 / 8 = 0.024
  EXPECT_NEAR(*d.measured_force, 1.1 * C * 36, 0.024);
  EXPECT_NEAR(*d.deviation_at_max_depth_percent, -100.0 / 11, 0.005);

  // A measurement that stops short of 6.0 um has no force there; one in the wrong unit
  // (depths 1000 times too large) matches no computed depth and says so.
  measured.depth.resize(30);
  measured.force.resize(30);
  EXPECT_FALSE(analysis::compare_loading(computed, measured).measured_force.has_value());
  for (double &h : measured.depth)
    h *= 1000;
  EXPECT_THROW(analysis::compare_loading(computed, measured), std::invalid_argument);
}

// The JSON names its source file as a valid JSON string, quotes and backslashes escaped.
TEST(OliverPharr, JsonEscapesTheSourcePath)
{
  const analysis::OliverPharrResult   result;
  const analysis::OliverPharrSettings settings;
  const std::string json = analysis::to_json(result, settings, "vickers", "data/run \"A\"\\1.csv");
  EXPECT_NE(json.find("\"source\": \"data/run \\\"A\\\"\\\\1.csv\""), std::string::npos) << json;
}

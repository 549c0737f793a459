// The checks of the Oliver-Pharr analysis (analysis/OliverPharr.h) on synthetic curves: rows out
// of order, files in reverse order, too few fitted points and results outside the bounds of an
// indentation are refused with the file, the row and the values, and nothing is written; a
// measured curve saved with a byte-order mark and CRLF line endings reads as the plain file.
// Units: um, mN, GPa.
#include "../test_files.h"
#include "analysis/AnalyzeCommand.h"
#include "analysis/OliverPharr.h"
#include "indenter/IndenterFactory.h"
#include "indenter/ProfileTable.h"
#include "io/CommandLine.h"

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

namespace
{
  namespace fs = std::filesystem;

  // An elasto-plastic curve like the default example's: loading P = C h^2 to h_max in n_load
  // steps, force-paced unloading P = P_max ((h - h_f) / (h_max - h_f))^m in n_unload steps of
  // P_max / n_unload down to zero force.
  struct SyntheticCurve
  {
    double       h_max = 6.0, p_max = 770.0, h_f = 5.6, m = 1.2;
    unsigned int n_load = 64, n_unload = 20;
    double       unload_to = 0.0; // the unloading ends at this fraction of P_max

    LoadCurve curve() const
    {
      LoadCurve curve;
      curve.source = "synthetic";
      for (unsigned int i = 0; i <= n_load; ++i)
        {
          const double h = h_max * i / n_load;
          curve.depth.push_back(h);
          curve.force.push_back(p_max * h * h / (h_max * h_max));
        }
      for (unsigned int i = 1; i <= n_unload; ++i)
        {
          const double fraction = 1.0 - (1.0 - unload_to) * i / n_unload;
          curve.depth.push_back(h_f + (h_max - h_f) * std::pow(fraction, 1 / m));
          curve.force.push_back(p_max * fraction);
        }
      return curve;
    }
  };

  const auto cone_area = [](const double h_c) { return 19.3 * h_c * h_c; };

  // The curve as a CSV file (header on line 1, point k on line k + 2).
  fs::path write_csv(const fs::path &path, const LoadCurve &curve, const std::string &bom = "",
                     const std::string &newline = "\n")
  {
    std::ofstream out(path, std::ios::binary);
    out << bom << "depth_um,force_mN" << newline << std::setprecision(17);
    for (std::size_t i = 0; i < curve.depth.size(); ++i)
      out << curve.depth[i] << ',' << curve.force[i] << newline;
    return path;
  }

  // The message of the std::invalid_argument thrown by analyze(), or "" if none.
  std::string refusal(const LoadCurve &curve, const analysis::OliverPharrSettings &settings = {})
  {
    try
      {
        analysis::analyze(curve, cone_area, settings);
      }
    catch (const std::invalid_argument &error)
      {
        return error.what();
      }
    return "";
  }

  void expect_parts(const std::string &message, std::initializer_list<std::string> parts)
  {
    SCOPED_TRACE("message: " + message);
    ASSERT_FALSE(message.empty()) << "not refused";
    for (const auto &part : parts)
      EXPECT_NE(message.find(part), std::string::npos) << "missing '" << part << "'";
  }

  // `indentsim analyze CSV --indenter rounded_cone --output DIR`: the refusal's message (empty
  // if it was accepted) and whether oliver_pharr.json was written.
  std::pair<std::string, bool> analyze_file(const fs::path &csv, const fs::path &output)
  {
    io::AnalyzeOptions options;
    options.target = csv.string();
    options.indenter_shape = "rounded_cone";
    std::string message;
    try
      {
        analysis::analyze_command(options, output.string());
      }
    catch (const std::invalid_argument &error)
      {
        message = error.what();
      }
    return {message, fs::exists(output / "oliver_pharr.json")};
  }
} // namespace

// One swapped pair of unloading rows (the defect: the unloading ended at the swap and
// the fit on the 5 points before it gave m = 6) is refused with the file, the line of the rising
// row and both depths; `indentsim analyze` writes nothing. In memory the row is a point number.
TEST(OliverPharrChecks, SwappedUnloadingPairIsRefused)
{
  const SyntheticCurve synthetic;
  const LoadCurve      curve = synthetic.curve();
  const auto           result = analysis::analyze(curve, cone_area, {});
  EXPECT_NEAR(result.fit.m, synthetic.m, 1e-6); // the intact curve passes
  EXPECT_NEAR(result.residual_depth, synthetic.h_f, 1e-9);

  LoadCurve         swapped = curve;
  const std::size_t first = synthetic.n_load + 5; // unloading points 5 and 6
  std::swap(swapped.depth[first], swapped.depth[first + 1]);
  std::swap(swapped.force[first], swapped.force[first + 1]);
  std::ostringstream shallower, deeper;
  shallower << std::setprecision(10) << curve.depth[first + 1];
  deeper << std::setprecision(10) << curve.depth[first];
  expect_parts(
      refusal(swapped),
      {"synthetic, point " + std::to_string(first + 2) + ": ",
       "the depth rises to " + deeper.str() + " um (point " + std::to_string(first + 2) + ")",
       "after " + shallower.str() + " um (point " + std::to_string(first + 1) + ")",
       "rows out of order"});

  const fs::path dir = test_files::scratch_directory("oliver_pharr_checks", "swapped");
  const fs::path csv = write_csv(dir / "swapped.csv", swapped);
  const auto [message, written] = analyze_file(csv, dir / "out");
  expect_parts(message, {csv.string() + ", line " + std::to_string(first + 3) + ": ",
                         "(line " + std::to_string(first + 2) + ")", "rows out of order"});
  EXPECT_FALSE(written);
  std::cout << "[ swapped pair ] " << message << std::endl;
}

// A swapped pair of loading rows (the depth falls for one row and jumps beyond its
// predecessor at the next) is refused; a genuine unloading cycle in the loading part is not.
TEST(OliverPharrChecks, SwappedLoadingPairIsRefused)
{
  LoadCurve curve = SyntheticCurve().curve();
  std::swap(curve.depth[30], curve.depth[31]);
  std::swap(curve.force[30], curve.force[31]);
  expect_parts(refusal(curve), {"synthetic, point 32: ", "the loading's depth falls to",
                                "two rows out of order", "never re-sorted"});
}

// A file with its rows in reverse order (the defect: W_p/W_t = -11.9, H = 14.6 GPa with
// exit 0) is refused, naming its first row and the end of its "unloading", and nothing is
// written; it is not re-sorted.
TEST(OliverPharrChecks, ReversedFileIsRefused)
{
  LoadCurve curve = SyntheticCurve().curve();
  std::reverse(curve.depth.begin(), curve.depth.end());
  std::reverse(curve.force.begin(), curve.force.end());
  expect_parts(refusal(curve), {"synthetic: the curve starts at depth 5.6 um (point 1)",
                                "ends at 0 um (point 85)", "reverse order"});

  const fs::path dir = test_files::scratch_directory("oliver_pharr_checks", "reversed");
  const fs::path csv = write_csv(dir / "reversed.csv", curve);
  const auto [message, written] = analyze_file(csv, dir / "out");
  expect_parts(message, {"(line 2)", "(line 86)", "reverse order"});
  EXPECT_FALSE(written);
  // The same curve in the recorded order is analysed and written.
  const auto [accepted, written_forward] =
      analyze_file(write_csv(dir / "forward.csv", SyntheticCurve().curve()), dir / "out");
  EXPECT_EQ(accepted, "");
  EXPECT_TRUE(written_forward);
}

// The fit needs min_fit_points (5) unloading points in the fit range: 4 are refused (the
// message names the count and the minimum), 5 are accepted.
TEST(OliverPharrChecks, FewerFitPointsThanTheMinimumAreRefused)
{
  EXPECT_EQ(analysis::min_fit_points, 5u);
  SyntheticCurve synthetic;
  synthetic.n_unload = 7; // P_max (1 - i/7) >= P_max / 2 for i = 0 ... 3: 4 points
  expect_parts(refusal(synthetic.curve()),
               {"has 4 points between 50 % and 100 %", "needs at least 5"});
  synthetic.n_unload = 8; // i = 0 ... 4: 5 points
  EXPECT_EQ(refusal(synthetic.curve()), "");
}

// The unloading exponent of an elastic contact lies between 1 (flat punch) and 2 (cone):
// m = 2.4 is accepted, an exact power law with m = 3 is refused with its exponent.
TEST(OliverPharrChecks, ExponentBeyondTheElasticRangeIsRefused)
{
  EXPECT_DOUBLE_EQ(analysis::max_physical_exponent, 2.5);
  SyntheticCurve synthetic;
  synthetic.h_f = 5.0;
  synthetic.m = 2.4;
  EXPECT_EQ(refusal(synthetic.curve()), "");
  synthetic.m = 3.0;
  const std::string message = refusal(synthetic.curve());
  const std::string prefix = "synthetic: the fitted unloading exponent m = ";
  expect_parts(message, {prefix, "outside 1 <= m <= 2.5", "is not written"});
  if (const auto at = message.find(prefix); at != std::string::npos)
    {
      EXPECT_NEAR(std::stod(message.substr(at + prefix.size())), 3.0, 1e-6) << message;
    }
}

// An unloading that releases more work than the loading put in (W_p/W_t < 0: a loading far
// below the unloading) is refused with W_p/W_t, W_t and W_e.
TEST(OliverPharrChecks, PlasticWorkRatioBelowZeroIsRefused)
{
  SyntheticCurve synthetic;
  synthetic.h_f = 0.6;
  LoadCurve curve = synthetic.curve();
  for (unsigned int i = 0; i <= synthetic.n_load; ++i) // P = P_max (h / h_max)^4
    curve.force[i] = synthetic.p_max * std::pow(curve.depth[i] / synthetic.h_max, 4);
  // W_t = P_max h_max / 5 = 924, W_e = P_max (h_max - h_f) / (m + 1) = 1890 mN um
  expect_parts(refusal(curve),
               {"the plastic work ratio W_p/W_t = -1.0", "W_t = 924", "outside 0 <= W_p/W_t <= 1"});
}

// A residual depth outside 0 <= h_r <= h_max (here the fitted h_f = -0.5 um closes an unloading
// recorded down to 40 % of P_max) is refused.
TEST(OliverPharrChecks, NegativeResidualDepthIsRefused)
{
  SyntheticCurve synthetic;
  synthetic.h_max = 1.0;
  synthetic.p_max = 10.0;
  synthetic.h_f = -0.5;
  synthetic.m = 1.0;
  synthetic.unload_to = 0.4;
  analysis::OliverPharrSettings settings;
  settings.epsilon = 0.5; // h_c = 0.25 um: a contact area
  expect_parts(refusal(synthetic.curve(), settings),
               {"the residual depth h_r = -0.", "(fit h_f)", "outside 0 <= h_r <= h_max = 1 um"});
}

// A measured curve saved by a spreadsheet as "CSV UTF-8" (byte-order mark) with CRLF line
// endings reads exactly as the plain file (column names without the mark) and gives the same
// analysis; the same holds for an indenter profile table.
TEST(OliverPharrChecks, ByteOrderMarkAndCrlfAreAccepted)
{
  const fs::path  dir = test_files::scratch_directory("oliver_pharr_checks", "bom");
  const LoadCurve curve = SyntheticCurve().curve();
  const LoadCurve plain = analysis::read_load_curve_csv(write_csv(dir / "plain.csv", curve));
  const LoadCurve marked = analysis::read_load_curve_csv(
      write_csv(dir / "marked.csv", curve, "\xEF\xBB\xBF", "\r\n").string());
  ASSERT_EQ(marked.depth.size(), curve.depth.size());
  EXPECT_EQ(marked.depth, plain.depth);
  EXPECT_EQ(marked.force, plain.force);
  EXPECT_EQ(marked.line, plain.line);
  const auto a = analysis::analyze(plain, cone_area, {});
  const auto b = analysis::analyze(marked, cone_area, {});
  EXPECT_EQ(a.fit.m, b.fit.m);
  EXPECT_EQ(a.hardness, b.hardness);
  EXPECT_EQ(a.reduced_modulus, b.reduced_modulus);
  EXPECT_EQ(a.plastic_work_ratio, b.plastic_work_ratio);

  // A marked file whose first line is the header with a unit in parentheses, tab-separated.
  {
    std::ofstream out(dir / "instrument.csv", std::ios::binary);
    out << "\xEF\xBB\xBF"
        << "Depth (nm)\tLoad (uN)\r\n0\t0\r\n500\t1200\r\n";
  }
  const LoadCurve instrument = analysis::read_load_curve_csv((dir / "instrument.csv").string());
  ASSERT_EQ(instrument.depth.size(), 2u);
  EXPECT_DOUBLE_EQ(instrument.depth[1], 0.5);
  EXPECT_DOUBLE_EQ(instrument.force[1], 1.2);

  const std::string table = "r_um,z_um\n0,0\n1,0.5\n2,1.5\n";
  std::string       crlf;
  for (const char c : table)
    crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  {
    std::ofstream(dir / "plain_table.csv", std::ios::binary) << table;
    std::ofstream(dir / "marked_table.csv", std::ios::binary) << "\xEF\xBB\xBF" << crlf;
  }
  const auto plain_table = indenter::ProfileTable::read((dir / "plain_table.csv").string());
  const auto marked_table = indenter::ProfileTable::read((dir / "marked_table.csv").string());
  for (const double h : {0.1, 0.7, 1.2, 2.0})
    EXPECT_EQ(plain_table.projected_area(h), marked_table.projected_area(h)) << h;
}

// A simulated curve whose recorded contact area is below one contact element's circle (the
// contact spans less than an element) gets no true-area comparison, and says why; above it,
// the comparison is made.
TEST(OliverPharrChecks, UnresolvedTrueContactAreaIsNotCompared)
{
  LoadCurve curve = SyntheticCurve().curve();
  curve.contact_area.assign(curve.depth.size(), 0.05); // um^2
  analysis::OliverPharrSettings settings;
  settings.min_true_contact_area = 3.14159 * 1.0 * 1.0; // contact elements of 1 um
  const auto unresolved = analysis::analyze(curve, cone_area, settings);
  EXPECT_FALSE(unresolved.true_contact_area);
  EXPECT_FALSE(unresolved.true_hardness);
  EXPECT_NE(unresolved.true_area_note.find("does not resolve the contact"), std::string::npos)
      << unresolved.true_area_note;

  curve.contact_area.assign(curve.depth.size(), 500.0); // um^2: many elements across
  const auto resolved = analysis::analyze(curve, cone_area, settings);
  ASSERT_TRUE(resolved.true_contact_area);
  EXPECT_DOUBLE_EQ(*resolved.true_hardness, resolved.max_force / 500.0);
  EXPECT_TRUE(resolved.true_area_note.empty());
}

// The analysis of a run on the automatic mesh compares with the true contact area once the
// contact spans the mesh's smallest edge h_min (that mesh has no refined-region edge h_e: the
// threshold must come from its design, not from a division by the `auto` contact elements).
TEST(OliverPharrChecks, AutomaticMeshRunComparesTheTrueContactArea)
{
  io::Case the_case;
  the_case.material.model = "j2";
  the_case.specimen.contact_elements = io::automatic_contact_elements;
  the_case.specimen.grading.min_element = 0.14; // um
  the_case.output.directory = test_files::scratch_directory("oliver_pharr_checks", "auto").string();
  LoadCurve curve = SyntheticCurve().curve();
  curve.contact_area.assign(curve.depth.size(), 700.0); // um^2: 15 um, a hundred h_min
  std::ostringstream summary, warnings;
  ASSERT_TRUE(analysis::analyze_run(curve, the_case, *indenter::create_indenter(the_case.indenter),
                                    summary, warnings))
      << warnings.str();
  const std::string json =
      test_files::read_text(fs::path(the_case.output.directory) / "oliver_pharr.json");
  EXPECT_NE(json.find("\"true_contact_area_um2\": 700"), std::string::npos) << json;
  EXPECT_EQ(warnings.str().find("does not resolve"), std::string::npos) << warnings.str();
  EXPECT_EQ(summary.str().find("does not resolve"), std::string::npos) << summary.str();
}

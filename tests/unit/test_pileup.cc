// Pile-up analysis (analysis/PileUp.h) on synthetic surfaces with known symmetry: interpolation,
// angular Fourier spectrum and dominant fold, quarter mirroring, maximum pile-up, file formats.
// Units: um, deg.
#include "analysis/PileUp.h"

#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <functional>
#include <numbers>
#include <sstream>

using namespace indentsim::analysis::pileup;

namespace
{
  constexpr double pi = std::numbers::pi;

  // Height field and in-plane displacement as functions of the reference position (X, Y).
  using ScalarField = std::function<double(double, double)>;
  using InPlaneField = std::function<std::array<double, 2>(double, double)>;

  SurfaceNode node(const double X, const double Y, const ScalarField &h, const InPlaneField &u)
  {
    const auto [u_x, u_y] = u(X, Y);
    return {X, Y, u_x, u_y, h(X, Y)};
  }

  const InPlaneField no_displacement = [](double, double) {
    return std::array<double, 2>{{0., 0.}};
  };

  // Rings r_i = i dr (i = 0 ... n_rings) and n_spokes spokes; counter-clockwise quads. The quads
  // at the centre have two coincident corners (one degenerate triangle).
  std::vector<SurfaceQuad> polar_surface(const unsigned int n_rings, const double dr,
                                         const unsigned int n_spokes, const ScalarField &h)
  {
    std::vector<SurfaceQuad> surface;
    const auto               at = [&](const unsigned int i, const unsigned int j) {
      const double theta = 2 * pi * j / n_spokes;
      return node(i * dr * std::cos(theta), i * dr * std::sin(theta), h, no_displacement);
    };
    for (unsigned int i = 0; i < n_rings; ++i)
      for (unsigned int j = 0; j < n_spokes; ++j)
        surface.push_back({{at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}});
    return surface;
  }

  // n x n square quads over [x0, x1] x [y0, y1], counter-clockwise.
  std::vector<SurfaceQuad> square_surface(const double x0, const double x1, const double y0,
                                          const double y1, const unsigned int n,
                                          const ScalarField &h, const InPlaneField &u)
  {
    std::vector<SurfaceQuad> surface;
    const auto               at = [&](const unsigned int i, const unsigned int j) {
      return node(x0 + (x1 - x0) * i / n, y0 + (y1 - y0) * j / n, h, u);
    };
    for (unsigned int j = 0; j < n; ++j)
      for (unsigned int i = 0; i < n; ++i)
        surface.push_back({{at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)}});
    return surface;
  }

  // A pile-up ring of radius r0 and width w, modulated k-fold:
  // h = f(r) (B + A cos(k theta)), f(r) = exp(-((r - r0) / w)^2).
  constexpr double r0 = 6, width = 1.5, mean_height = 0.5, modulation = 0.2, contact_radius = 3;
  double           ring(const double r)
  {
    return std::exp(-std::pow((r - r0) / width, 2));
  }
  ScalarField modulated_ring(const unsigned int k, const double A = modulation)
  {
    return [k, A](const double x, const double y) {
      return ring(std::hypot(x, y)) * (mean_height + A * std::cos(k * std::atan2(y, x)));
    };
  }

  // True if `text` holds a number written as nan or inf (a word starting with them, not
  // "dominant").
  bool has_non_finite(const std::string &text)
  {
    for (const char *word : {"nan", "inf"})
      for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1))
        if (at == 0 || !std::isalpha(static_cast<unsigned char>(text[at - 1])))
          return true;
    return false;
  }

  // Analysis with a fixed grid spacing (the automatic one follows the tiny central edges of a
  // polar mesh).
  PileUpResult analyse_with_spacing(const std::vector<SurfaceQuad> &surface, const double spacing)
  {
    PileUpParameters parameters;
    parameters.depth = 1;
    parameters.contact_radius = contact_radius;
    parameters.grid_spacing = spacing;
    return analyse(surface, "unloaded", parameters);
  }
} // namespace

// Linear interpolation on the triangulated surface reproduces a field that is linear in the
// current coordinates exactly, whatever the in-plane displacement; points off the surface have
// no height.
TEST(PileUp, InterpolationIsExactForLinearField)
{
  const InPlaneField wavy = [](const double X, const double Y) {
    return std::array<double, 2>{{0.1 * std::sin(Y), 0.05 * std::cos(X)}};
  };
  const auto        linear = [](const double x, const double y) { return 0.3 - 0.2 * x + 0.7 * y; };
  const ScalarField height_of_reference = [&](const double X, const double Y) {
    const auto [u_x, u_y] = wavy(X, Y);
    return linear(X + u_x, Y + u_y);
  };
  const SurfaceInterpolator surface(square_surface(-5, 5, -5, 5, 10, height_of_reference, wavy));
  for (double x = -4.8; x <= 4.8; x += 0.37)
    for (double y = -4.8; y <= 4.8; y += 0.41)
      {
        const auto h = surface.height(x, y);
        ASSERT_TRUE(h.has_value()) << x << ", " << y;
        EXPECT_NEAR(*h, linear(x, y), 1e-12) << x << ", " << y;
      }
  EXPECT_FALSE(surface.height(6, 0).has_value());
  EXPECT_FALSE(surface.height(0, -5.5).has_value());
  EXPECT_FALSE(surface.height(100, 100).has_value());
}

// A k-fold modulated pile-up ring (k = 2, 3, 4: the (011), (111), (001) patterns of the paper's
// Fig. 7) gives dominant fold k, its cosine amplitude A f(r_c) within 1 %, no other harmonic,
// k peaks at the maxima of cos(k theta), and the largest height B + A on the ring's crest.
TEST(PileUp, ModulatedRingGivesItsFold)
{
  for (const unsigned int k : {2u, 3u, 4u})
    {
      SCOPED_TRACE("k = " + std::to_string(k));
      const PileUpResult result =
          analyse_with_spacing(polar_surface(120, 0.1, 360, modulated_ring(k)), 0.1);
      const AzimuthalSpectrum &spectrum = result.spectrum;
      EXPECT_EQ(spectrum.dominant_fold, k);
      EXPECT_NEAR(result.analysis_radius, r0, 0.05);
      const double f = ring(result.analysis_radius);
      ASSERT_EQ(spectrum.amplitudes.size(), 13u);
      EXPECT_NEAR(spectrum.amplitudes[0], mean_height * f, 0.01 * mean_height * f);
      EXPECT_NEAR(spectrum.amplitudes[k], modulation * f, 0.01 * modulation * f);
      for (unsigned int other = 1; other <= 12; ++other)
        if (other != k)
          {
            EXPECT_LT(spectrum.amplitudes[other], 1e-9) << "harmonic " << other;
          }
      ASSERT_EQ(spectrum.peak_azimuths_deg.size(), k);
      for (unsigned int p = 0; p < k; ++p)
        EXPECT_NEAR(spectrum.peak_azimuths_deg[p], p * 360. / k, 1e-9);
      EXPECT_NEAR(result.max_pileup, mean_height + modulation, 1e-3);
      EXPECT_NEAR(result.max_pileup_radius, r0, 1e-9);
      EXPECT_NEAR(std::remainder(result.max_pileup_azimuth_deg, 360. / k), 0., 1e-9);
    }
}

// An axisymmetric pile-up ring has no dominant fold (reported as 0: every harmonic k >= 2 is
// below the noise level max(1e-3 |A_0|, 1e-6 um)) and no peaks; its maximum lies on the crest.
TEST(PileUp, AxisymmetricBumpHasNoFold)
{
  const PileUpResult result =
      analyse_with_spacing(polar_surface(120, 0.1, 360, modulated_ring(0, 0.)), 0.1);
  EXPECT_EQ(result.spectrum.dominant_fold, 0u);
  for (unsigned int k = 1; k <= 12; ++k)
    EXPECT_LT(result.spectrum.amplitudes[k], 1e-12) << "harmonic " << k;
  EXPECT_TRUE(result.spectrum.peak_azimuths_deg.empty());
  EXPECT_NEAR(result.analysis_radius, r0, 0.05);
  EXPECT_NEAR(result.max_pileup, mean_height, 1e-12);
  EXPECT_NEAR(result.max_pileup_radius, r0, 1e-9);
}

// The dominant fold is sought among k >= 2: a stronger k = 1 component (an off-centre pile-up)
// does not hide a 2-fold pattern; a pure k = 1 signal has no fold.
TEST(PileUp, FirstHarmonicIsNotAFold)
{
  std::vector<double> samples(360), shifted(360);
  for (unsigned int j = 0; j < 360; ++j)
    {
      const double theta = 2 * pi * j / 360;
      samples[j] = 1.0 + 0.3 * std::cos(theta) + 0.05 * std::cos(2 * theta + 0.4);
      shifted[j] = 1.0 + 0.3 * std::cos(theta);
    }
  const AzimuthalSpectrum spectrum = spectrum_of_samples(samples, 12);
  EXPECT_NEAR(spectrum.amplitudes[1], 0.3, 1e-12);
  EXPECT_NEAR(spectrum.amplitudes[2], 0.05, 1e-12);
  EXPECT_EQ(spectrum.dominant_fold, 2u);
  EXPECT_EQ(spectrum_of_samples(shifted, 12).dominant_fold, 0u);
}

// A square mesh imprints harmonics 4 and 8 as large as a crystal's 2- or 3-fold pattern: the
// symmetry fold names the material's pattern (2 for (011), 3 for (111) with its k = 6 and the
// mixing products 1 = 4 - 3, 5, 7 of a 3-fold crystal on a 4-fold mesh), while a pattern made
// of multiples of 4 only ((001), or isotropic plus imprint) keeps fold 4, and off-mesh
// harmonics below 10 % of the largest (interpolation noise) change nothing.
TEST(PileUp, SymmetryFoldSeesThroughTheMeshImprint)
{
  const auto spectrum_of = [](const std::vector<std::pair<unsigned int, double>> &harmonics) {
    std::vector<double> samples(360);
    for (unsigned int j = 0; j < 360; ++j)
      {
        const double theta = 2 * pi * j / 360;
        samples[j] = 0.75;
        for (const auto &[k, amplitude] : harmonics)
          samples[j] += amplitude * std::cos(k * theta + 0.1 * k);
      }
    return spectrum_of_samples(samples, 12);
  };
  const AzimuthalSpectrum crystal_011 = spectrum_of({{2, 0.087}, {4, 0.092}, {8, 0.136}});
  EXPECT_EQ(crystal_011.dominant_fold, 8u);
  EXPECT_EQ(crystal_011.symmetry_fold, 2u);
  const AzimuthalSpectrum crystal_111 =
      spectrum_of({{1, 0.02}, {3, 0.117}, {4, 0.152}, {5, 0.01}, {6, 0.03}, {7, 0.01}, {8, 0.131}});
  EXPECT_EQ(crystal_111.dominant_fold, 4u);
  EXPECT_EQ(crystal_111.symmetry_fold, 3u);
  const AzimuthalSpectrum crystal_001 = spectrum_of({{4, 0.556}, {8, 0.1}, {12, 0.02}});
  EXPECT_EQ(crystal_001.dominant_fold, 4u);
  EXPECT_EQ(crystal_001.symmetry_fold, 4u);
  const AzimuthalSpectrum noisy_001 = spectrum_of({{2, 0.009}, {3, 0.009}, {4, 0.1}, {8, 0.05}});
  EXPECT_EQ(noisy_001.symmetry_fold, 4u);
  const AzimuthalSpectrum flat = spectrum_of({});
  EXPECT_EQ(flat.dominant_fold, 0u);
  EXPECT_EQ(flat.symmetry_fold, 0u);
}

// Local maxima a few degrees apart (a crest split by a shallow dip where it crosses a mesh line)
// are one peak of the pattern: a 4-fold signal with a dip at every maximum gives four peaks, on
// the mirror planes.
TEST(PileUp, SplitMaximaAreOnePeak)
{
  std::vector<double> samples(360);
  for (unsigned int j = 0; j < 360; ++j)
    {
      const double theta_deg = j, to_plane = std::remainder(theta_deg, 90.);
      samples[j] = 0.5 + 0.1 * std::cos(4 * theta_deg * pi / 180) -
                   0.01 * std::exp(-to_plane * to_plane / 4.);
    }
  const AzimuthalSpectrum spectrum = spectrum_of_samples(samples, 12);
  EXPECT_EQ(spectrum.dominant_fold, 4u);
  ASSERT_EQ(spectrum.peak_azimuths_deg.size(), 4u);
  for (unsigned int p = 0; p < 4; ++p)
    EXPECT_NEAR(spectrum.peak_azimuths_deg[p], 90. * p, 1e-9);
}

// The quarter model mirrored through x = 0 and y = 0 (in-plane displacement components flipped)
// reproduces the full surface of a field symmetric in x and y, including its in-plane motion:
// same heights on the grid and same spectrum, to round-off.
TEST(PileUp, MirroredQuarterEqualsFullSurface)
{
  const InPlaneField radial = [](const double X, const double Y) {
    const double scale = 0.15 * ring(std::hypot(X, Y));
    return std::array<double, 2>{{scale * X, scale * Y}};
  };
  const ScalarField h = modulated_ring(4);
  const auto        full = square_surface(-12, 12, -12, 12, 160, h, radial);
  const auto        quarter = square_surface(0, 12, 0, 12, 80, h, radial);
  const auto        mirrored = mirror_quarter(quarter);
  ASSERT_EQ(mirrored.size(), full.size());

  const SurfaceInterpolator full_surface(full), mirrored_surface(mirrored);
  const HeightGrid          a = resample_on_grid(full_surface, 9, 0.1);
  const HeightGrid          b = resample_on_grid(mirrored_surface, 9, 0.1);
  ASSERT_EQ(a.height.size(), b.height.size());
  double largest_difference = 0;
  for (std::size_t i = 0; i < a.height.size(); ++i)
    {
      ASSERT_TRUE(a.height[i] && b.height[i]) << "grid point " << i << " not covered";
      largest_difference = std::max(largest_difference, std::abs(*a.height[i] - *b.height[i]));
    }
  EXPECT_LT(largest_difference, 1e-12);

  const PileUpResult from_full = analyse_with_spacing(full, 0.1);
  const PileUpResult from_mirror = analyse_with_spacing(mirrored, 0.1);
  EXPECT_EQ(from_full.spectrum.dominant_fold, 4u);
  EXPECT_EQ(from_mirror.spectrum.dominant_fold, 4u);
  EXPECT_NEAR(from_full.analysis_radius, from_mirror.analysis_radius, 1e-12);
  for (unsigned int k = 0; k <= 12; ++k)
    EXPECT_NEAR(from_full.spectrum.amplitudes[k], from_mirror.spectrum.amplitudes[k], 1e-12)
        << "harmonic " << k;
  EXPECT_NEAR(from_full.max_pileup, from_mirror.max_pileup, 1e-12);

  // Forgetting the sign flip of u_x, u_y moves the mirrored surface by 2 u: detectable.
  auto wrong = mirrored;
  for (std::size_t q = quarter.size(); q < wrong.size(); ++q)
    for (unsigned int v = 0; v < 4; ++v)
      {
        const SurfaceNode &original = quarter[q % quarter.size()][v];
        wrong[q][v].u_x = original.u_x;
        wrong[q][v].u_y = original.u_y;
      }
  const HeightGrid c = resample_on_grid(SurfaceInterpolator(wrong), 9, 0.1);
  double           wrong_difference = 0;
  for (std::size_t i = 0; i < a.height.size(); ++i)
    if (a.height[i] && c.height[i])
      wrong_difference = std::max(wrong_difference, std::abs(*a.height[i] - *c.height[i]));
  EXPECT_GT(wrong_difference, 0.1);
}

// The files: grid points off the surface are empty CSV cells (never NaN), and pileup.json has
// both stages plus the top-level stage's dominant_fold and max_pileup_um.
TEST(PileUp, FilesHaveEmptyCellsAndBothStages)
{
  const auto       surface = square_surface(-2, 2, -2, 2, 8, modulated_ring(4), no_displacement);
  PileUpParameters parameters;
  parameters.depth = 0.5;
  parameters.contact_radius = 1;
  parameters.half_width = 3; // beyond the 2 um surface: empty cells
  const PileUpResult max_depth = analyse(surface, "max_depth", parameters);
  const PileUpResult unloaded = analyse(surface, "unloaded", parameters);

  std::ostringstream grid;
  write_grid_csv(grid, unloaded.grid);
  const std::string grid_text = grid.str();
  EXPECT_EQ(grid_text.rfind("x_um,y_um,height_um\n", 0), 0u);
  EXPECT_NE(grid_text.find("-3,-3,\n"), std::string::npos) << "corner must be an empty cell";
  EXPECT_FALSE(has_non_finite(grid_text));

  std::ostringstream json;
  write_json(json, {max_depth, unloaded}, unloaded);
  const std::string text = json.str();
  for (const char *key : {"\"max_depth\": {", "\"unloaded\": {", "\"dominant_fold\":",
                          "\"max_pileup_um\":", "\"fourier_amplitudes_um\":", "\"units\":",
                          "\"axis_height_um\":", "\"peak_azimuths_deg\": [0, 90, 180, 270]"})
    EXPECT_NE(text.find(key), std::string::npos) << key << " in\n" << text;
  EXPECT_FALSE(has_non_finite(text));
  // The top-level fields come before the stage objects.
  EXPECT_LT(text.find("\"max_pileup_um\":"), text.find("\"max_depth\": {"));

  std::ostringstream profiles;
  write_profiles_csv(profiles, {max_depth, unloaded});
  EXPECT_EQ(profiles.str().rfind("stage,azimuth_deg,r_um,height_um\nmax_depth,0,0,", 0), 0u);
  EXPECT_NE(profiles.str().find("unloaded,345,"), std::string::npos);
}

// An isotropic material under an axisymmetric indenter has no fold: with the square mesh's
// imprint (A_4, A_8 as large as in the default example: 0.153 and 0.074 um on A_0 = 0.41 um)
// and harmonics beyond it of noise size (below 1e-3 A_0), the fold is 0 and its source
// "axisymmetric", while the raw largest harmonic stays 4. The same samples from a crystal keep
// the 4 ("mesh_imprint_possible"); an isotropic pile-up with a harmonic beyond the imprint above
// the noise is a numerical asymmetry.
TEST(PileUp, IsotropicUnderAxisymmetricIndenterHasNoFold)
{
  const auto samples_of = [](const std::vector<std::pair<unsigned int, double>> &harmonics) {
    std::vector<double> samples(360);
    for (unsigned int j = 0; j < 360; ++j)
      {
        const double theta = 2 * pi * j / 360;
        samples[j] = 0.41;
        for (const auto &[k, amplitude] : harmonics)
          samples[j] += amplitude * std::cos(k * theta + 0.1 * k);
      }
    return samples;
  };
  const std::vector<double> imprint =
      samples_of({{2, 2e-4}, {3, 1e-4}, {4, 0.153}, {6, 2e-4}, {8, 0.074}, {12, 0.015}});
  const SymmetrySources   isotropic_cone{false, false};
  const AzimuthalSpectrum j2 = spectrum_of_samples(imprint, 12, isotropic_cone);
  EXPECT_NEAR(j2.noise_level, 4.1e-4, 1e-12);
  EXPECT_EQ(j2.dominant_fold, 4u);
  EXPECT_EQ(j2.symmetry_fold, 0u);
  EXPECT_EQ(j2.fold_source, "axisymmetric");
  const std::string text = describe_fold(j2);
  EXPECT_EQ(text.rfind("axisymmetric (no fold)", 0), 0u) << text;
  EXPECT_NE(text.find("A_4 = 0.153 um, is the mesh's imprint"), std::string::npos) << text;

  const SymmetrySources   crystal{true, false};
  const AzimuthalSpectrum crystal_001 = spectrum_of_samples(imprint, 12, crystal);
  EXPECT_EQ(crystal_001.symmetry_fold, 4u);
  EXPECT_EQ(crystal_001.fold_source, "mesh_imprint_possible");

  const AzimuthalSpectrum asymmetric =
      spectrum_of_samples(samples_of({{2, 0.01}, {4, 0.153}}), 12, isotropic_cone);
  EXPECT_EQ(asymmetric.symmetry_fold, 2u);
  EXPECT_EQ(asymmetric.fold_source, "numerical");

  // The whole analysis on a square mesh (a ring with a 4-fold imprint) and its pileup.json.
  PileUpParameters parameters;
  parameters.depth = 1;
  parameters.contact_radius = contact_radius;
  parameters.grid_spacing = 0.1;
  parameters.sources = isotropic_cone;
  const auto surface =
      square_surface(-12, 12, -12, 12, 96, modulated_ring(4, 0.05), no_displacement);
  const PileUpResult result = analyse(surface, "unloaded", parameters);
  EXPECT_EQ(result.spectrum.dominant_fold, 4u);
  EXPECT_EQ(result.spectrum.symmetry_fold, 0u);
  std::ostringstream json;
  write_json(json, {result}, result);
  EXPECT_NE(json.str().find("\"symmetry_fold\": 0,\n  \"fold_source\": \"axisymmetric\","),
            std::string::npos)
      << json.str();
}

// The crystals keep their folds and name them: (011) 2 and (111) 3 beyond a mesh imprint as
// large as in the paper's 12x12 and 24x24 cases are the crystal's; (001) 4 may be the mesh's.
// Under a Berkovich pyramid an isotropic material's 3-fold is the indenter's.
TEST(PileUp, CrystalFoldsKeepTheirSource)
{
  const auto spectrum_of = [](const std::vector<std::pair<unsigned int, double>> &harmonics,
                              const SymmetrySources                              &sources) {
    std::vector<double> samples(360);
    for (unsigned int j = 0; j < 360; ++j)
      {
        const double theta = 2 * pi * j / 360;
        samples[j] = 0.75;
        for (const auto &[k, amplitude] : harmonics)
          samples[j] += amplitude * std::cos(k * theta + 0.1 * k);
      }
    return spectrum_of_samples(samples, 12, sources);
  };
  const SymmetrySources   crystal_under_cone{true, false};
  const AzimuthalSpectrum crystal_011 =
      spectrum_of({{2, 0.087}, {4, 0.092}, {8, 0.136}}, crystal_under_cone);
  EXPECT_EQ(crystal_011.symmetry_fold, 2u);
  EXPECT_EQ(crystal_011.fold_source, "crystal");
  const AzimuthalSpectrum crystal_111 =
      spectrum_of({{1, 0.02}, {3, 0.117}, {4, 0.152}, {5, 0.01}, {6, 0.03}, {7, 0.01}, {8, 0.131}},
                  crystal_under_cone);
  EXPECT_EQ(crystal_111.symmetry_fold, 3u);
  EXPECT_EQ(crystal_111.fold_source, "crystal");
  EXPECT_EQ(describe_fold(crystal_111).rfind("3-fold (the crystal's", 0), 0u);
  const AzimuthalSpectrum crystal_001 =
      spectrum_of({{4, 0.556}, {8, 0.1}, {12, 0.02}}, crystal_under_cone);
  EXPECT_EQ(crystal_001.symmetry_fold, 4u);
  EXPECT_EQ(crystal_001.fold_source, "mesh_imprint_possible");
  const AzimuthalSpectrum berkovich = spectrum_of({{3, 0.1}, {4, 0.05}}, {false, true});
  EXPECT_EQ(berkovich.symmetry_fold, 3u);
  EXPECT_EQ(berkovich.fold_source, "indenter");
}

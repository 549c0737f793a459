// Pile-up output of a whole indentation run: the small J2 case (quarter model) loaded and
// unloaded writes pileup.json and the pile-up CSV files; its isotropic residual impression
// piles up with the symmetry of the square mesh. Units: um, mN, GPa.
#include "../test_cases.h"
#include "../test_files.h"
#include "case/Case.h"
#include "problems/IndentationProblem.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include <unistd.h>

using namespace indentsim;

namespace
{
  namespace fs = std::filesystem;

  fs::path scratch_directory(const std::string &name)
  {
    return test_files::scratch_directory("pileup", name);
  }
  using test_files::read_text;
} // namespace

// An isotropic J2 block with low hardening (E / sigma_y = 226, H = 0.5 GPa) piles up around the
// residual impression, and the files hold both stages. The problem is axisymmetric, but its
// discretization is not: the mirrored quarter of a square mesh has the square's symmetry (mirror
// planes x = 0, y = 0 and x = y), so every harmonic except k = 4, 8, 12 must vanish, and the
// largest harmonic is the mesh's 4 (or 0). The 4-fold imprint is large on this coarse mesh
// (contact radius 3.7 elements, the pile-up crest within the first element ring outside it):
// measured A_4 / A_0 = 0.31 at maximum depth and 0.20 after unloading; 0.5 is the bound. The
// reported fold is none: "axisymmetric" (an isotropic material under the rounded cone), in
// pileup.json too.
TEST(PileUpRun, IsotropicJ2PilesUpWithTheMeshSymmetry)
{
  io::Case c = test_cases::small_j2_case("quarter");
  c.loading.unload = true;
  const fs::path               directory = scratch_directory("small_j2");
  problems::IndentationProblem<3> problem(c, MPI_COMM_WORLD, false);
  problem.setup();
  problem.run(directory.string());

  for (const char *name :
       {"pileup.json", "pileup_max_depth.csv", "pileup_unloaded.csv", "pileup_profiles.csv"})
    EXPECT_TRUE(fs::exists(directory / name)) << name;
  const std::string json = read_text(directory / "pileup.json");
  for (const char *key :
       {"\"max_depth\": {", "\"unloaded\": {", "\"dominant_fold\":", "\"max_pileup_um\":",
        "\"fourier_amplitudes_um\":", "\"symmetry_fold\": 0,", "\"fold_source\": \"axisymmetric\""})
    EXPECT_NE(json.find(key), std::string::npos) << key;
  EXPECT_EQ(json.find(": nan"), std::string::npos);
  EXPECT_EQ(read_text(directory / "pileup_unloaded.csv").find("nan"), std::string::npos);

  const auto &results = problem.pileup_results();
  ASSERT_EQ(results.size(), 2u);
  EXPECT_EQ(results[0].stage, "max_depth");
  EXPECT_EQ(results[1].stage, "unloaded");
  EXPECT_NEAR(results[0].depth, c.loading.max_depth, 1e-12);
  for (const auto &r : results)
    {
      const auto &A = r.spectrum.amplitudes;
      std::cout << "[ pile-up ] " << r.stage << ": max " << r.max_pileup
                << " um at r = " << r.max_pileup_radius << " um, az " << r.max_pileup_azimuth_deg
                << " deg; a_c = " << r.contact_radius << " um, r_c = " << r.analysis_radius
                << " um, fold " << r.spectrum.dominant_fold << ", A_0..A_8 =";
      for (unsigned int k = 0; k <= 8; ++k)
        std::cout << ' ' << A[k];
      std::cout << std::endl;
      EXPECT_GT(r.analysis_radius, r.contact_radius);
      ASSERT_EQ(A.size(), 13u);
      EXPECT_GT(A[0], 0.) << r.stage << ": the pile-up ring is raised on average";
      for (unsigned int k = 1; k <= 12; ++k)
        if (k % 4 != 0)
          {
            EXPECT_LT(A[k], 1e-8) << r.stage << ", harmonic " << k;
          }
      EXPECT_LT(A[4], 0.5 * A[0]) << r.stage;
      EXPECT_TRUE(r.spectrum.dominant_fold == 4 || r.spectrum.dominant_fold == 0) << r.stage;
      EXPECT_EQ(r.spectrum.symmetry_fold, 0u) << r.stage;
      EXPECT_EQ(r.spectrum.fold_source, "axisymmetric") << r.stage;
    }
  const auto &unloaded = results[1];
  EXPECT_GT(unloaded.max_pileup, 0.);
  EXPECT_GT(unloaded.max_pileup_radius, unloaded.contact_radius);
}

// The pile-up folds of BCC single crystals under the paper's rounded cone, the lattice's
// symmetry about the indentation axis: 2-fold on (011) and 3-fold on (111), as for FCC (the
// paper's Fig. 7). The square mesh imprints only multiples of 4, so these folds are the
// crystal's. alpha-iron with {110}<111> slip (examples/ferrite_bcc_001_n12.yaml), the paper's
// 24 x 24 mesh, 3 um deep. Units: um, mN, GPa.
#include "../test_files.h"
#include "case/Case.h"
#include "case/CaseFile.h"
#include "problems/IndentationProblem.h"

#include <gtest/gtest.h>

#include <iostream>
#include <string>
#include <vector>

using namespace indentsim;

namespace
{
  io::Case ferrite_case(const std::vector<double> &normal, const std::vector<double> &reference,
                        const std::string &symmetry)
  {
    io::Case c;
    c.material =
        io::read_case_file(std::string(INDENTSIM_SOURCE_DIR) + "/examples/ferrite_bcc_001_n12.yaml")
            .material;
    c.material.orientation.kind = "surface_normal";
    c.material.orientation.surface_normal = normal;
    c.material.orientation.reference_direction = reference;
    c.specimen.contact_elements = 24;
    c.specimen.symmetry = symmetry;
    c.loading.max_depth = 3.0;
    c.loading.steps = 16;
    c.loading.unload = false;
    return c;
  }

  void expect_fold(const io::Case &c, const std::string &name, const unsigned int fold)
  {
    problems::IndentationProblem<3> problem(c, MPI_COMM_WORLD, false);
    problem.setup();
    problem.run(test_files::scratch_directory("crystal_folds", name).string());
    const auto &results = problem.pileup_results();
    ASSERT_FALSE(results.empty());
    const auto &spectrum = results.front().spectrum;
    std::cout << "[ measured ] bcc " << name << ": force at 3 um " << problem.records().back().force
              << " mN, symmetry fold " << spectrum.symmetry_fold << " (" << spectrum.fold_source
              << "), A_0..A_4 =";
    for (unsigned int k = 0; k <= 4 && k < spectrum.amplitudes.size(); ++k)
      std::cout << ' ' << spectrum.amplitudes[k];
    std::cout << " um\n";
    EXPECT_EQ(spectrum.symmetry_fold, fold) << name;
    EXPECT_EQ(spectrum.fold_source, "crystal") << name;
  }
} // namespace

TEST(CrystalFolds, BccPileUpHasTheFoldOfItsSurface)
{
  expect_fold(ferrite_case({0., 1., 1.}, {1., 0., 0.}, "quarter"), "011", 2);
  expect_fold(ferrite_case({1., 1., 1.}, {1., -1., 0.}, "full"), "111", 3);
}

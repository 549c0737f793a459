// A nearly incompressible neo-Hookean block (nu = 0.4999) indented by the paper's rounded cone,
// read through the case file so that its default element applies: F-bar (on by default for
// nu > 0.45) gives Sneddon's force, the plain hexahedra lock. Units: um, mN, GPa.
#include "case/CaseFile.h"
#include "indenter/SneddonReference.h"
#include "problems/IndentationProblem.h"

#include <gtest/gtest.h>

#include <iostream>

using namespace indentsim;

namespace
{
  // The tiny study's block (16 um refined region, 8 contact elements, rounded cone with
  // delta = 0.5 um) pressed to 1 um, elastic: the force at 1 um [mN].
  double force_at_one_micron(const std::string &specimen_extra)
  {
    const io::Case c = io::parse_case_yaml(
        "test: indentation\n"
        "material: {model: neo_hookean, young_modulus: 69.0, poisson_ratio: 0.4999}\n"
        "indenter: {shape: rounded_cone, a: 2.48, delta: 0.5}\n"
        "specimen: {size: [60, 60, 30], refined_region: [16, 16, 4], contact_elements: 8, "
        "symmetry: quarter" +
            specimen_extra +
            "}\n"
            "loading: {max_depth: 1.0, steps: 8, unload: false}\n",
        "nearly_incompressible.yaml");
    problems::IndentationProblem<3> problem(c, MPI_COMM_WORLD, false);
    problem.setup();
    problem.run("");
    EXPECT_NEAR(problem.records().back().depth, 1.0, 1e-12);
    return problem.records().back().force;
  }
} // namespace

// Requirement: a neo-Hookean case with nu > 0.45 and no specimen.f_bar is not locked. Oracle:
// Sneddon's closed form for the rounded cone, 256.3 mN at 1 um (E* = E / (1 - nu^2)); the
// default element (F-bar) is within 5 % (measured 253.4 mN, -1.1 %), the plain element that
// f_bar: false selects is locked, more than 5 times stiffer (measured 3595 mN).
TEST(NearlyIncompressible, NeoHookeanDefaultElementGivesSneddonsForce)
{
  const double sneddon = indenter::SneddonReference(
                             indenter::SneddonReference::reduced_modulus(69.0, 0.4999), 2.48, 0.5)
                             .force_at_depth(1.0);
  EXPECT_NEAR(sneddon, 256.35, 0.01);
  const double default_element = force_at_one_micron("");
  const double plain = force_at_one_micron(", f_bar: false");
  std::cout << "[ nu = 0.4999 ] force at 1 um: default element " << default_element
            << " mN, plain element " << plain << " mN, Sneddon " << sneddon << " mN" << std::endl;
  EXPECT_NEAR(default_element / sneddon, 1.0, 0.05);
  EXPECT_GT(plain / sneddon, 5.0);
}

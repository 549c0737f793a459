// Small cases shared by several tests. Units: um, mN, GPa.
#pragma once

#include "io/Case.h"

namespace indentsim::test_cases
{
  // A small J2 indentation (rounded cone with delta = 0.5 um, 16 contact elements across a
  // 16 um refined region): a few seconds per run, plastic from the first increment.
  inline io::Case small_j2_case(const std::string &symmetry = "quarter")
  {
    io::Case c;
    c.material.model = "j2";
    c.indenter.delta = 0.5;
    c.specimen.size = {60., 60., 30.};
    c.specimen.refined_region = {16., 16., 4.};
    c.specimen.contact_elements = 16;
    c.specimen.symmetry = symmetry;
    c.loading.max_depth = 1.0;
    c.loading.steps = 8;
    c.loading.unload = false;
    return c;
  }
} // namespace indentsim::test_cases

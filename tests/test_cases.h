// Small cases shared by several tests. Units: um, mN, GPa.
#pragma once

#include "case/Case.h"

namespace indentsim::test_cases
{
  // A small J2 indentation (rounded cone with delta = 0.5 um, 16 contact elements across a
  // 16 um refined region): a few seconds per run, plastic from the first increment.
  inline io::Case small_j2_case(const std::string &symmetry = "quarter")
  {
    io::Case c;
    c.material.model = "j2";
    c.indenter.delta = 0.5;
    c.specimen.size = {{60., 60., 30.}};
    c.specimen.refined_region = {{16., 16., 4.}};
    c.specimen.contact_elements = 16;
    c.specimen.symmetry = symmetry;
    c.loading.max_depth = 1.0;
    c.loading.steps = 8;
    c.loading.unload = false;
    return c;
  }

  // Elastic (neo-Hookean) half-space under a blunt rounded cone, delta = 1 um (tip radius
  // R = a^2 delta = 6.15 um), so that the Hertz regime h <= 0.1 delta is resolved by a modest
  // mesh: at h = 0.1 um the contact radius is sqrt(R h) = 0.78 um, at h = delta it is 2.8 um.
  // Frictionless and hyperelastic: the solution at a depth does not depend on the path to it.
  inline io::Case elastic_rounded_cone_case()
  {
    io::Case c;
    c.material.model = "neo_hookean";
    c.specimen.f_bar = false;
    c.indenter.a = 2.48;
    c.indenter.delta = 1.0;
    c.specimen.size = {{80., 80., 40.}};
    c.specimen.refined_region = {{6., 6., 2.5}};
    c.specimen.contact_elements = 32; // h = 0.1875 um: 4.2 elements across a_c at 0.1 delta
    c.specimen.symmetry = "quarter";
    c.loading.max_depth = 1.0;
    c.loading.steps = 10;
    c.loading.unload = false;
    return c;
  }

  // The same geometry with the crystal model of the paper's Table 2 (FCC, n = 10), Euler
  // angles (phi1, Phi, phi2) in degrees.
  inline io::Case small_crystal_case(const std::string           &symmetry = "quarter",
                                     const std::array<double, 3> &euler_bunge_deg = {{0., 0., 0.}})
  {
    io::Case c = small_j2_case(symmetry);
    c.material.model = "crystal";
    c.material.orientation.kind = "euler_bunge_deg";
    c.material.orientation.euler_bunge_deg = euler_bunge_deg;
    return c;
  }
} // namespace indentsim::test_cases

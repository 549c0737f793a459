// The resolved case: every key of the YAML case file with its default filled in.
// Units: lengths in um, forces in mN, stresses and moduli in GPa.
#pragma once

#include <array>
#include <string>

namespace indentsim::io
{
  struct MaterialParameters
  {
    std::string model = "j2";            // neo_hookean | j2
    double      young_modulus = 69.0;    // E [GPa]
    double      poisson_ratio = 0.26;    // nu [-], -1 < nu < 0.5
    double      yield_stress = 0.305;    // sigma_y0 [GPa]
    double      hardening_modulus = 0.5; // H [GPa], linear isotropic hardening
    std::string yield_stress_measure = "cauchy"; // cauchy | kirchhoff: which stress enters eq. 4

    bool operator==(const MaterialParameters &) const = default;
  };

  struct IndenterParameters
  {
    std::string shape = "rounded_cone"; // z = sqrt((x^2+y^2)/a^2 + delta^2) - delta (eq. 16)
    double      a = 2.48;               // slope parameter [-]
    double      delta = 0.005;          // tip rounding [um]

    bool operator==(const IndenterParameters &) const = default;
  };

  struct SpecimenParameters
  {
    std::array<double, 3> size = {{360., 360., 180.}};       // block edge lengths [um]
    std::array<double, 3> refined_region = {{120., 120., 30.}}; // refined block under the tip [um]
    unsigned int          contact_elements = 12; // N: N x N faces across the refined top face
    std::string           symmetry = "full";     // full | quarter
    bool                  f_bar = true;          // F-bar element (default on for plasticity)

    bool operator==(const SpecimenParameters &) const = default;
  };

  struct LoadingParameters
  {
    double       max_depth = 6.0;  // [um]
    unsigned int steps = 64;       // increments from 0 to max_depth
    bool         unload = true;    // then back until the indenter force vanishes
    unsigned int unload_steps = 0; // 0: same increment size as loading (computed)
    unsigned int max_cutbacks = 8; // successive halvings of an increment before giving up

    bool operator==(const LoadingParameters &) const = default;
  };

  struct ContactParameters
  {
    double friction_coefficient = 0.0; // Coulomb mu [-] (only 0 is supported for now)
    double penalty = 0.0;              // augmentation parameter [GPa/um]; 0: automatic
    double penetration_tolerance = 1e-6; // largest admissible penetration at convergence [um]
    unsigned int max_augmentations = 30;

    bool operator==(const ContactParameters &) const = default;
  };

  struct SolverParameters
  {
    double       residual_tolerance = 1e-8;  // relative to the first residual of the increment
    double       absolute_tolerance = 1e-10; // [mN]
    unsigned int max_newton_iterations = 25;

    bool operator==(const SolverParameters &) const = default;
  };

  struct OutputParameters
  {
    std::string  directory = "results/run";
    unsigned int vtu_every = 0; // write VTU every k-th step (0: only at max depth and end)

    bool operator==(const OutputParameters &) const = default;
  };

  struct Case
  {
    std::string        source_file; // the YAML file this case was read from
    std::string        test = "indentation";
    MaterialParameters material;
    IndenterParameters indenter;
    SpecimenParameters specimen;
    LoadingParameters  loading;
    ContactParameters  contact;
    SolverParameters   solver;
    OutputParameters   output;

    bool operator==(const Case &) const = default;
  };
} // namespace indentsim::io

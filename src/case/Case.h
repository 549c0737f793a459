// The resolved case: every key of the YAML case file with its default filled in.
// Units: lengths in um, forces in mN, stresses and moduli in GPa.
#pragma once

#include <array>
#include <string>

namespace indentsim::io
{
  // Crystal orientation (material.orientation). Bunge convention, passive: the rotation matrix
  // g = R_z(phi2) R_x(Phi) R_z(phi1) maps sample components to crystal components,
  // v_crystal = g v_sample. Alternatively the crystal direction [hkl] along the sample z axis
  // (the indented plane's normal) and the crystal direction [uvw] along the sample x axis.
  struct OrientationParameters
  {
    std::string           kind = "euler_bunge_deg";       // euler_bunge_deg | surface_normal
    std::array<double, 3> euler_bunge_deg = {{0., 0., 0.}}; // (phi1, Phi, phi2) [deg]
    std::array<double, 3> surface_normal = {{0., 0., 1.}};  // Miller indices [hkl] of the plane
    std::array<double, 3> reference_direction = {{1., 0., 0.}}; // [uvw] along sample x

    bool operator==(const OrientationParameters &) const = default;
  };

  struct MaterialParameters
  {
    std::string model = "j2";            // neo_hookean | j2 | crystal
    double      young_modulus = 69.0;    // E [GPa]
    double      poisson_ratio = 0.26;    // nu [-], -1 < nu < 0.5
    double      yield_stress = 0.305;    // sigma_y0 [GPa]
    double      hardening_modulus = 0.5; // H [GPa], linear isotropic hardening
    std::string yield_stress_measure = "cauchy"; // cauchy | kirchhoff: which stress enters eq. 4

    // Crystal plasticity (model: crystal), the paper's section 2.2 and Table 2.
    std::string lattice = "fcc";             // fcc: {111}<110>, 12 slip systems
    double      C11 = 106.7, C12 = 60.4, C44 = 28.3; // cubic elastic constants [GPa]
    double      tau0 = 0.12;   // initial critical resolved shear stress [GPa]
    double      tau1 = 0.02;   // Voce back-extrapolated increment [GPa]
    double      theta0 = 0.1;  // initial hardening rate [GPa]
    double      theta1 = 0.006; // asymptotic hardening rate [GPa]
    double      q = 1.4;       // latent hardening ratio [-]
    double      yield_exponent_n = 10; // n of the regularized Schmid law (exponent 2n), eq. 14
    OrientationParameters orientation;

    bool operator==(const MaterialParameters &) const = default;
  };

  // The rigid indenter (indenter/). Every key is read and range-checked for every shape, but
  // each shape uses only its own keys (listed after each member).
  struct IndenterParameters
  {
    // rounded_cone | sphere | cone | vickers | berkovich | flat_punch | profile_table
    std::string shape = "rounded_cone";
    double      a = 2.48;      // rounded_cone: slope parameter [-] (eq. 16), half-angle atan(a)
    double      delta = 0.005; // rounded_cone: tip rounding [um], tip radius a^2 delta
    double      radius = 10.0; // sphere, flat_punch: radius [um]
    double      half_angle_deg = 70.3; // cone: half-angle [deg] (70.3: the area function 24.5 h^2
                                       // of the Vickers and Berkovich pyramids)
    double      tip_radius = 0.0;   // cone, vickers, berkovich: tip (and edge) radius [um], 0: sharp
    double      rotation_deg = 0.0; // vickers, berkovich: about +z, counterclockwise from above;
                                    // 0: face 0's normal along +x (Pyramid.h)
    double      edge_radius = 0.0;  // flat_punch: rounding of the rim [um], 0: sharp
    // profile_table: the CSV table (ProfileTable.h). A relative path in a case file is relative
    // to the case file's directory; the reader stores the absolute path, so that the resolved
    // case works from any directory. In a Case built in code it is relative to the working
    // directory.
    std::string file = "";

    bool operator==(const IndenterParameters &) const = default;
  };

  struct SpecimenParameters
  {
    std::array<double, 3> size = {{360., 360., 180.}};       // block edge lengths [um]
    std::array<double, 3> refined_region = {{120., 120., 30.}}; // refined block under the tip [um]
    unsigned int          contact_elements = 12; // N: N x N faces across the refined top face
    std::string           symmetry = "full";     // full | quarter
    bool                  f_bar = true;          // F-bar element (default on for plasticity)
    // Tensile test (test: tensile): a cube of elements_per_side^3 elements of 1 um edge.
    unsigned int          elements_per_side = 3;
    std::string           grains = "single"; // single | per_element (random orientation each)
    unsigned int          seed = 1;          // seed of the random orientations (per_element)

    bool operator==(const SpecimenParameters &) const = default;
  };

  // The loading programme: `cycles` times (load to the maximum in `steps` increments, hold it
  // for `hold_steps` increments, unload), under depth or force control.
  struct LoadingParameters
  {
    std::string  control = "depth"; // depth | force (the indenter depth becomes an unknown)
    double       max_depth = 6.0;  // depth control: the maximum depth; force control: the
                                   // largest admissible depth (the refined region's design) [um]
    double       max_force = 0.0;  // force control: the maximum indenter force [mN]
    unsigned int steps = 64;       // increments from 0 to the maximum
    bool         unload = true;    // then back until the indenter force vanishes (force control:
                                   // down to 1 % of max_force)
    unsigned int unload_steps = 0; // 0: same increment size as loading (computed)
    unsigned int unload_points = 20; // depth control: each unloading step lowers the force by
                                     // about max force / unload_points (the Oliver-Pharr fit
                                     // needs points on the upper unloading); 0: off
    unsigned int hold_steps = 0;   // increments holding the maximum (recorded; no creep in these
                                   // rate-independent models)
    unsigned int cycles = 1;       // load-hold-unload cycles to the same maximum
    unsigned int max_cutbacks = 8; // successive halvings of an increment before giving up
    double       max_strain = 0.2; // tensile test: final logarithmic strain along z [-]

    bool operator==(const LoadingParameters &) const = default;
  };

  struct ContactParameters
  {
    double friction_coefficient = 0.0; // Coulomb mu [-], 0 <= mu <= 2 (0: frictionless)
    double penalty = 0.0;              // augmentation parameter [GPa/um]; 0: automatic
    double penetration_tolerance = 1e-6; // largest admissible penetration at convergence [um]
    unsigned int max_augmentations = 30;

    bool operator==(const ContactParameters &) const = default;
  };

  struct SolverParameters
  {
    double       residual_tolerance = 1e-7;  // relative to the first residual of the increment (indentation: or the last indenter force, if larger)
    double       absolute_tolerance = 1e-10; // [mN]
    unsigned int max_newton_iterations = 25;
    // Linear solver of the Newton iterations (solver/LinearSolver.h): auto (direct below
    // LinearSolver::iterative_threshold_dofs unknowns, else iterative) | direct (MUMPS LU) |
    // iterative (CG/GMRES with ML smoothed-aggregation AMG, rigid-body modes).
    std::string  linear_solver = "auto";
    unsigned int threads = 0; // assembly threads per MPI rank; 0: the cores divided by the ranks

    bool operator==(const SolverParameters &) const = default;
  };

  struct OutputParameters
  {
    std::string  directory = "results/run";
    unsigned int vtu_every = 0; // write VTU every k-th step (0: only at max depth and end)
    // A measured load-penetration curve (CSV, units in the column names as for indentsim
    // analyze) overlaid on the plot and compared with the loading curve; "" for none. A
    // relative path is relative to the case file's directory; the reader stores it absolute.
    std::string  experimental_curve = "";
    // Indentation: wall time between checkpoints of a run [s] (0: only when stopped by
    // SIGINT/SIGTERM); `indentsim run CASE --resume` continues from the last one.
    double checkpoint_interval_s = 300;

    bool operator==(const OutputParameters &) const = default;
  };

  struct Case
  {
    std::string        source_file; // the YAML file this case was read from
    std::string        test = "indentation"; // indentation | tensile
    bool               compare_j2 = false;  // tensile: also run the J2 model (material.young_modulus...)
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

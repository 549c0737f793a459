// The resolved case: every key of the YAML case file with its default filled in (the keys,
// their defaults and ranges are declared once, in Schema.cc). Units: lengths in um, forces in
// mN, stresses and moduli in GPa. The material and the indenter have their own headers, so
// that their factories depend on their parameters only.
#pragma once

#include "case/Choice.h"
#include "case/IndenterParameters.h"
#include "case/MaterialParameters.h"

#include <array>
#include <string>

namespace indentsim::io
{
  enum class TestKind
  {
    indentation,
    tensile
  };
  template <>
  struct ChoiceWords<TestKind>
  {
    static constexpr std::array<ChoiceWord<TestKind>, 2> words = {
        {{TestKind::indentation, "indentation"}, {TestKind::tensile, "tensile"}}};
  };

  // specimen.symmetry: the full block, the quarter x >= 0, y >= 0 with mirror planes, or the
  // axisymmetric (r, z) model of the cylinder of radius size_x / 2 and height size_z.
  enum class Symmetry
  {
    full,
    quarter,
    axisymmetric
  };
  template <>
  struct ChoiceWords<Symmetry>
  {
    static constexpr std::array<ChoiceWord<Symmetry>, 3> words = {
        {{Symmetry::full, "full"},
         {Symmetry::quarter, "quarter"},
         {Symmetry::axisymmetric, "axisymmetric"}}};
  };

  // specimen.grains: one orientation, or a random orientation per element (tensile).
  enum class Grains
  {
    single,
    per_element
  };
  template <>
  struct ChoiceWords<Grains>
  {
    static constexpr std::array<ChoiceWord<Grains>, 2> words = {
        {{Grains::single, "single"}, {Grains::per_element, "per_element"}}};
  };

  // loading.control: the indenter depth is prescribed, or the force (the depth an unknown).
  enum class Control
  {
    depth,
    force
  };
  template <>
  struct ChoiceWords<Control>
  {
    static constexpr std::array<ChoiceWord<Control>, 2> words = {
        {{Control::depth, "depth"}, {Control::force, "force"}}};
  };

  // loading.spacing: equal increments of the control value, or increments proportional to it.
  enum class Spacing
  {
    uniform,
    geometric
  };
  template <>
  struct ChoiceWords<Spacing>
  {
    static constexpr std::array<ChoiceWord<Spacing>, 2> words = {
        {{Spacing::uniform, "uniform"}, {Spacing::geometric, "geometric"}}};
  };

  // solver.linear_solver (solver/LinearSolver.h).
  enum class LinearSolverChoice
  {
    automatic,
    direct,
    iterative
  };
  template <>
  struct ChoiceWords<LinearSolverChoice>
  {
    static constexpr std::array<ChoiceWord<LinearSolverChoice>, 3> words = {
        {{LinearSolverChoice::automatic, "auto"},
         {LinearSolverChoice::direct, "direct"},
         {LinearSolverChoice::iterative, "iterative"}}};
  };

  // The graded mesh of specimen.contact_elements: auto, designed from the indenter and the
  // loading (mesh/MeshDesign.h); derived from the other keys, never read from a case file.
  // Target element edge at the distance rho from the tip: max(min_element, rho / n) with
  // n = elements_per_radius up to graded_radius and far_elements_per_radius beyond; the cells on
  // the top face within surface_radius of the axis are halved surface_halvings times more.
  // Units: um.
  struct MeshGrading
  {
    double       contact_radius = 0;          // a_d: the predicted contact radius at the maximum
    double       min_element = 0;             // h_min: resolves the contact from max_depth / 8
    double       elements_per_radius = 0;     // n: elements per distance from the tip, near field
    double       graded_radius = 0;           // rho_p: the near field (contact and plastic zone)
    double       far_elements_per_radius = 0; // beyond rho_p
    double       surface_radius = 0;          // the contact nodes' reach on the top face
    unsigned int surface_halvings = 0;        // m: top-face cells there: edge s(rho) / 2^m
    double       layered_depth = 0; // depth of the last layer's bottom (material.layers) [um]
    double       layer_element = 0; // edge across the layers in the near field; 0: none [um]

    bool operator==(const MeshGrading &) const = default;
  };

  // specimen.contact_elements: auto is stored as 0.
  inline constexpr unsigned int automatic_contact_elements = 0;

  struct SpecimenParameters
  {
    std::array<double, 3> size = {{360., 360., 180.}};          // block edge lengths [um]
    std::array<double, 3> refined_region = {{120., 120., 30.}}; // refined block under the tip [um]
    unsigned int          contact_elements = 12; // N: N x N faces across the refined top face;
                                                 // 0: auto (the graded mesh of `grading`)
    unsigned int     elements_per_radius = 0;    // n of the automatic mesh; 0: auto (by dimension)
    Choice<Symmetry> symmetry = Symmetry::full;
    bool             f_bar = true; // F-bar element (default on for plasticity)
    // Tensile test (test: tensile): a cube of elements_per_side^3 elements of 1 um edge.
    unsigned int   elements_per_side = 3;
    Choice<Grains> grains = Grains::single; // per_element: random orientation each
    unsigned int   seed = 1;                // seed of the random orientations (per_element)
    // The automatic mesh's elements across the thinnest layer or the damage peak.
    unsigned int elements_across_layers = 4;
    // 2^m: the automatic mesh's top-face cells within the contact nodes' reach are this many
    // times smaller than s(rho) (1, 2, 4 or 8); 0: auto (by dimension).
    unsigned int surface_refinement = 0;
    MeshGrading  grading; // contact_elements: auto only (designed)

    bool automatic_mesh() const { return contact_elements == automatic_contact_elements; }
    bool operator==(const SpecimenParameters &) const = default;
  };

  // Partial unloads on the way down (depth control): at every multiple of `every` below the
  // maximum depth the force is lowered by `fraction` of its value in `points` force-paced steps,
  // then the indenter returns to that depth and loading goes on. Each partial unload is
  // analysed by Oliver-Pharr (analysis/HardnessDepth.h): a hardness-depth profile in one run,
  // as continuous stiffness measurement gives in an experiment. Units: um.
  struct PartialUnloads
  {
    double       every = 0;      // depth between partial unloads [um]; 0: none
    double       fraction = 0.1; // of the force at the start of each partial unload [-]
    unsigned int points = 4;     // force-paced unloading steps of each

    bool enabled() const { return every > 0; }
    bool operator==(const PartialUnloads &) const = default;
  };

  // The loading programme: `cycles` times (load to the maximum in `steps` increments, hold it
  // for `hold_steps` increments, unload), under depth or force control; in the first cycle's
  // loading, partial unloads if asked for.
  struct LoadingParameters
  {
    Choice<Control> control = Control::depth; // force: the indenter depth becomes an unknown
    double          max_depth = 6.0; // depth control: the maximum depth; force control: the
                                     // largest admissible depth (the refined region's design) [um]
    double       max_force = 0.0;    // force control: the maximum indenter force [mN]
    unsigned int steps = 64;         // increments from 0 to the maximum
    bool         unload = true;      // then back until the indenter force vanishes (force control:
                                     // down to 1 % of max_force)
    unsigned int unload_steps = 0;   // 0: same increment size as loading (computed)
    unsigned int unload_points = 20; // depth control: each unloading step lowers the force by
                                     // about max force / unload_points (the Oliver-Pharr fit
                                     // needs points on the upper unloading); 0: off
    unsigned int hold_steps = 0;     // increments holding the maximum (recorded; no creep in these
                                     // rate-independent models)
    unsigned int cycles = 1;         // load-hold-unload cycles to the same maximum
    unsigned int max_cutbacks = 8;   // successive halvings of an increment before giving up
    double       max_strain = 0.2;   // tensile test: final logarithmic strain along z [-]
    // uniform: equal increments; geometric: the first increment to first_fraction of the
    // maximum, then each a constant ratio larger (increments proportional to depth or force).
    Choice<Spacing> spacing = Spacing::uniform;
    double          first_fraction = 1.0 / 64; // geometric: the first target / the maximum [-]
    PartialUnloads  partial_unloads;

    bool operator==(const LoadingParameters &) const = default;
  };

  struct ContactParameters
  {
    double       friction_coefficient = 0.0;   // Coulomb mu [-], 0 <= mu <= 2 (0: frictionless)
    double       penalty = 0.0;                // augmentation parameter [GPa/um]; 0: automatic
    double       penetration_tolerance = 1e-6; // largest admissible penetration at convergence [um]
    unsigned int max_augmentations = 30;

    bool operator==(const ContactParameters &) const = default;
  };

  struct SolverParameters
  {
    double residual_tolerance =
        1e-7; // indentation: relative to the run's largest indenter force; tensile: to the first residual
    double       absolute_tolerance = 1e-10; // [mN]
    unsigned int max_newton_iterations = 25;
    // Linear solver of the Newton iterations (linalg/LinearSolver.h): auto (the kind of lower
    // predicted cost, LinearSolver::choose_kind) | direct (MUMPS LU) |
    // iterative (CG/GMRES with ML smoothed-aggregation AMG, rigid-body modes).
    Choice<LinearSolverChoice> linear_solver = LinearSolverChoice::automatic;
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
    std::string experimental_curve = "";
    // Indentation: wall time between checkpoints of a run [s] (0: only when stopped by
    // SIGINT/SIGTERM); `indentsim run CASE --resume` continues from the last one.
    double checkpoint_interval_s = 300;
    // Whether the run draws its PNG plots (Python); the CSV, JSON and VTU files are written
    // either way. Off in a calibration's forward runs.
    bool plots = true;

    bool operator==(const OutputParameters &) const = default;
  };

  struct Case
  {
    std::string      source_file; // the YAML file this case was read from
    Choice<TestKind> test = TestKind::indentation;
    bool compare_j2 = false; // tensile: also run the J2 model (material.young_modulus...)
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

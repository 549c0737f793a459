// The automatic mesh (specimen.contact_elements: auto): an octree graded toward the tip, designed
// from the indenter's area function and the loading. Units: um.
//
// The rule. a_d is the predicted contact radius at the maximum: the radius of the circle of the
// same area as the indenter's cross-section (a pyramid's corners reach further) at the predicted
// contact height (mesh/MeshAdequacy.h: h_c = 1.2 h_max for plastic models, the pile-up
// allowance; 2/pi h_max for neo-Hookean; under force control the area F/H with H = 3 sigma_y
// if smaller). An element at the distance rho from the tip (the apex's point on the undeformed
// surface) gets the edge
//     s(rho) = max(h_min, rho / n)       for rho <= rho_p = 3 a_d   (contact and plastic zone)
//     s(rho) = rho / n_far               beyond                     (elastic far field)
// so the contact radius a(h) spans about n elements at every depth h: for a self-similar tip
// a ~ h, and s(a) = a / n. h_min = a(h_max / 8) / n keeps the rule down to an eighth of the
// maximum depth (below it the contact spans fewer elements). The octree halves cells until
// each is no larger than s(rho) at its point nearest to the tip, so edges lie within
// (s/2, s]; p4est's 2:1 balance grades the steps. The specimen is a block (a cylinder in
// axisymmetric mode) of half-width and depth 160 a_d unless specimen.size is given: its fixed
// bottom then stiffens an elastic contact by about 0.4 % (Hertz: +2.6 % at 40 a_d, +1.6 % at
// 80 a_d, +1.25 % at 160 a_d, of which about 0.9 % is the finite-strain excess at h/R = 0.01).
// A depth-graded specimen (material.layers) gets edges of at most t_min / m across its layers
// in the near field (boxes within rho_p of the tip that reach above the last layer's bottom),
// t_min the thinnest layer's thickness: m = specimen.elements_across_layers (default 4) elements
// across every layer, so that the boundaries are resolved where the plastic zone meets them. A damage profile
// (material.damage_profile) is refined in the same way to its last depth, t_min the width of
// its damage peak at half maximum (case/DamageProfile.h).
// Contact nodes are the top face's nodes in the box of 1.5 times the cross-section's extent
// along x and y (a Berkovich corner reaches 1.56 a_d; the refined region the guards watch).
#pragma once

#include "case/Case.h"
#include "indenter/IndenterSurface.h"

#include <array>

namespace indentsim::mesh
{
  namespace design
  {
    // n: elements per distance from the tip in the near field, by the model's dimension (the
    // 3D quarter model costs about n^3 cells per octave of rho, the axisymmetric section n^2),
    // unless specimen.elements_per_radius gives it: the paper's J2 case then has 4 300 DOFs in
    // 2D and 23 000 in the 3D quarter model (the paper's 48 x 48 quarter mesh: 36 000).
    inline constexpr double elements_per_radius_2d = 10;
    inline constexpr double elements_per_radius_3d = 6;
    // m: the top face's cells within the contact nodes' reach are halved m times more, so that
    // the contact edge passes nodes 2^m times closer together and the force's ripple as it
    // passes them shrinks, unless specimen.surface_refinement gives 2^m. Measured on the paper's
    // J2 case with 192 geometric steps (C = P/(h + delta)^2 over 1-6 um against the converged
    // 23.065 GPa, docs/user-guide.md, "Automatic meshes"): in 2D, m = 1 gives -1.9 ... -0.4 %
    // (4 300 DOFs, 980 Newton iterations), m = 2 -1.2 ... -0.4 % (5 100 DOFs, 1 700 iterations:
    // more nodes enter per increment, and such increments take more iterations); in the 3D
    // quarter model m = 0 gives -3.1 ... -0.3 % (24 400 DOFs, 130 s) and m = 1 -1.7 ... -0.8 %
    // (35 500 DOFs, 305 s). The defaults keep the cheaper design.
    inline constexpr unsigned int surface_halvings_2d = 1;
    inline constexpr unsigned int surface_halvings_3d = 0;
    // h_min resolves the contact from this fraction of the maximum depth.
    inline constexpr double smallest_resolved_depth = 1. / 8;
    // rho_p / a_d: the near field, holding the plastic zone (about 2.5 a for E/sigma_y ~ 200).
    inline constexpr double near_field_radii = 3;
    // n_far / n beyond rho_p.
    inline constexpr double far_field_ratio = 0.5;
    // Half-width and depth of the specimen / a_d when specimen.size is not given.
    inline constexpr double specimen_radii = 160;
    // The contact nodes' region (its half-width) / a_d; the guards stop a run whose contact
    // passes 90 % of it.
    inline constexpr double contact_region_radii = 1.5;
  } // namespace design

  // Designs the mesh of a case with specimen.contact_elements: auto: fills specimen.grading and
  // specimen.refined_region, and specimen.size unless `size_given`.
  void design_mesh(io::Case &the_case, const indenter::IndenterSurface &surface, bool size_given);

  // s(rho): the target element edge at the distance rho from the tip [um].
  double target_element_size(const io::MeshGrading &grading, double rho);

  // The octree's coarse grid: about cubic cells of edge min(half-width, depth) / 2 over the
  // modelled part of the block (3D: x, y, z) or of the (r, z) section (axisymmetric: the first
  // two entries), from `lower` to `upper` [um].
  struct CoarseGrid
  {
    unsigned int          dim = 3;
    std::array<long, 3>   cells = {{1, 1, 1}};
    std::array<double, 3> lower = {{0., 0., 0.}}, upper = {{0., 0., 0.}};
  };
  CoarseGrid coarse_grid(const io::SpecimenParameters &specimen);

  // Whether the box [lower, upper] (its first `dim` coordinates) is larger than s(rho) at its
  // point nearest to the tip (the origin), or s(rho) / 2^m if it lies on the top face within
  // the surface radius: the octree halves it.
  bool needs_halving(const io::MeshGrading &grading, const std::array<double, 3> &lower,
                     const std::array<double, 3> &upper, unsigned int dim);
} // namespace indentsim::mesh

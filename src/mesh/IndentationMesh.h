// Block specimen refined toward the indent through hanging nodes. Units: um.
//
// Geometry: the specimen occupies [-Lx/2, Lx/2] x [-Ly/2, Ly/2] x [-Lz, 0] (full model) or
// [0, Lx/2] x [0, Ly/2] x [-Lz, 0] (quarter model with symmetry planes x = 0 and y = 0).
// The indenter axis is the z axis and the top face z = 0 is the contact surface.
// The axisymmetric model (dim = 2) is the cylinder of radius Lx/2 and height Lz, meshed in its
// (r, z) section [0, Lx/2] x [-Lz, 0] (point coordinates x = r, y = z) by the same rule along r
// and z: its refined region is r <= refined_region_x / 2, z >= -refined_region_z.
//
// The automatic mesh (specimen.contact_elements: auto, mesh/MeshDesign.h) is an octree on a
// coarse grid of about cubic cells, each halved until its edge is at most the design's target
// s(rho) at its point nearest to the tip.
//
// Construction of the paper's mesh: a tensor-product coarse grid whose cells inside the refined region have edge
// length s = 2^L h (h = refined_region_x / N is the contact-element size) and grow geometrically
// outside it; the coarse cells of the refined region are then refined L times. p4est's 2:1
// balance produces the coarsening by 2:1 steps with depth and distance; the resulting hanging
// nodes are handled by exact AffineConstraints (DoFTools::make_hanging_node_constraints).
#pragma once

#include "case/Case.h"

#include <deal.II/distributed/tria.h>

namespace indentsim::mesh
{
  // Boundary ids of the block's faces.
  namespace boundary
  {
    constexpr dealii::types::boundary_id x_min = 0, x_max = 1, y_min = 2, y_max = 3, bottom = 4,
                                         top = 5;
    // The axisymmetric section's edges: the axis r = 0 (x_min), the outer cylinder r = Lx/2
    // (x_max), the bottom and the top.
    constexpr dealii::types::boundary_id axis = x_min, outer = x_max;
  } // namespace boundary

  struct MeshInfo
  {
    double       contact_element_size = 0; // h: edge of the refined cells on the top face [um]
    double       fine_layer_thickness = 0; // z-size of the refined cells [um]
    unsigned int refinement_levels = 0;    // L
    bool         quarter = false;
    bool         axisymmetric = false; // the (r, z) section of the cylinder (dim = 2)
    // The refined region's footprint on the top face: |x| <= half_x, |y| <= half_y.
    double refined_half_x = 0, refined_half_y = 0, refined_depth = 0;
    // specimen.contact_elements: auto: the octree graded toward the tip (mesh/MeshDesign.h);
    // contact_element_size is then the target edge at the design contact radius.
    bool            graded = false;
    io::MeshGrading grading;

    // The edge of the contact elements at the distance `radius` from the axis [um].
    double element_size_at(double radius) const;
  };

  // Number of refinement levels L used for N contact elements: the largest L with 2^(L+1) | N
  // (so that the quarter model is exactly a quarter of the full one) and 2^L <= N/3 (so that the
  // refined region spans at least three coarse cells). Returns -1 if N cannot be meshed (N < 2 or
  // odd N).
  int refinement_levels_for(unsigned int n_contact_elements);

  template <int dim>
  MeshInfo build_indentation_mesh(dealii::parallel::distributed::Triangulation<dim> &triangulation,
                                  const io::SpecimenParameters                      &specimen);

  // Geometric grading: cell sizes starting at `first` and growing by `ratio` that fill `length`
  // exactly (the sizes are rescaled so that they sum to `length`).
  std::vector<double> graded_spacing(double length, double first, double ratio);
} // namespace indentsim::mesh

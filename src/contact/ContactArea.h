// True (projected) contact area and contact radius from the nodal contact state, with the
// contact perimeter interpolated between nodes instead of jumping from node to node.
// Units: um, GPa.
//
// Each contact node carries the indicator phi = lambda - eps g of the augmented Lagrangian:
// the pressure p > 0 on active nodes and -eps g <= 0 (the scaled gap) on open ones. phi is
// interpolated linearly over the four triangles of each top face (split at the face centre,
// where phi is the mean of the corners), in the current positions projected onto the x-y plane.
// The contact zone is {phi > 0}: its area is exact for the piecewise-linear phi, and its
// perimeter passes through the zero crossings of phi on the triangle edges.
#pragma once

#include <deal.II/base/point.h>

#include <array>

namespace indentsim::contact
{
  struct ContactPatch
  {
    double area = 0;       // projected area of {phi > 0} [um^2]
    double max_radius = 0; // largest distance from the axis of a point with phi >= 0 [um]
    double max_abs_x = 0, max_abs_y = 0; // largest |x| and |y| of such a point [um]
  };

  // Exact for phi linear on the triangle.
  ContactPatch triangle_contact_patch(const std::array<dealii::Point<2>, 3> &xy,
                                      const std::array<double, 3>           &phi);

  // The axisymmetric model's top edge from radius r[0] to r[1] (current positions), phi linear
  // along it: the ring {phi > 0} has the area pi (r_2^2 - r_1^2) of its radii r_1 < r_2, and
  // max_abs_x = max_abs_y = max_radius = r_2 (exact for phi linear in r).
  ContactPatch segment_contact_patch(const std::array<double, 2> &r,
                                     const std::array<double, 2> &phi);

  // Corners in cyclic order (either orientation).
  ContactPatch quad_contact_patch(const std::array<dealii::Point<2>, 4> &xy,
                                  const std::array<double, 4>           &phi);
} // namespace indentsim::contact

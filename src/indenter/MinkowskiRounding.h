// Rounding a sharp convex indenter by a ball: the rounded solid is the Minkowski sum K + B(R) of
// a sharp convex solid K and a ball of radius R. Units: um.
//
// For a convex K the signed distance to K + B(R) is the signed distance to K minus R, the
// closest point is the closest boundary point b of K moved by R along the unit direction n from
// b to the point, and n is the outward normal there. Faces therefore stay exactly flat with
// their exact angles, edges become cylinders of radius R, a sharp apex becomes a sphere of
// radius R, and the surface is C1 (the normal is continuous) wherever R > 0.
//
// The sphere, the cone, the pyramids and the flat punch are all built this way: each computes
// the projection onto its sharp solid K in the indenter's own frame (lowest point of K + B(R) at
// the origin, i.e. K shifted up by R), and offset_projection() turns it into the projection onto
// the rounded surface in the specimen frame.
#pragma once

#include "indenter/IndenterSurface.h"

namespace indentsim::indenter
{
  // Nearest point of the boundary of a sharp convex solid K to a point q (indenter frame).
  struct SharpProjection
  {
    double       signed_distance; // dist(q, K) > 0 outside K; -dist(q, boundary of K) inside [um]
    Point<3>     boundary_point;  // the nearest point of the boundary of K [um]
    Tensor<1, 3> normal;          // unit outward normal of K at boundary_point that points
                                  // towards q: (q - b)/|q - b| outside, the nearest face's
                                  // outward normal inside
  };

  // The projection onto K + B(R) in the specimen frame (apex at (0, 0, -depth)) from the
  // projection onto K in the indenter frame: gap = signed_distance - R, closest point
  // b + R n - depth e_z, normal n. R >= 0.
  SurfaceProjection offset_projection(const SharpProjection &sharp, double R, double depth);

  // The projection reported for a non-finite point or depth: NaN gap, converged = false.
  SurfaceProjection failed_projection();

  // |v| without overflow or underflow for any finite components.
  double robust_norm(const Tensor<1, 3> &v);

  // cos and sin of an angle in degrees, exact at multiples of 90 deg (so that a pyramid at
  // rotation 0 or 45 deg is exactly mirror-symmetric about x = 0 and y = 0).
  void cos_sin_deg(double angle_deg, double &cosine, double &sine);
} // namespace indentsim::indenter

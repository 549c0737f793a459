// A cone of half-angle alpha (between the flank and the axis), sharp or with a spherical tip of
// radius R tangent to the flanks: the sharp cone rounded by a ball of radius R
// (MinkowskiRounding.h). Units: um.
//
// Profile: the spherical cap z = R - sqrt(R^2 - r^2) for r <= R cos(alpha), then the flank
// z = (r - R cos(alpha)) / tan(alpha) + R (1 - sin(alpha)). The flank lies Delta =
// R (1/sin(alpha) - 1) below the sharp cone's, so beyond the cap the rounded cone has the sharp
// cone's area function at h + Delta.
#pragma once

#include "indenter/IndenterSurface.h"

namespace indentsim::indenter
{
  class Cone : public IndenterSurface
  {
  public:
    // 0 < alpha < 90 deg, R >= 0 [um] (0: sharp); throws std::invalid_argument otherwise.
    Cone(double half_angle_deg, double tip_radius);

    double profile(double x, double y) const override;

    // Closed form in the meridian plane: the nearest point of the sharp cone (flank line or
    // apex), moved by R.
    SurfaceProjection project(const Point<3> &x, double depth) const override;

    // pi (2 R h - h^2) on the cap (h <= R (1 - sin(alpha))), pi tan^2(alpha) (h + Delta)^2
    // beyond; pi tan^2(alpha) h^2 for the sharp cone.
    double projected_area(double h) const override;

    bool mirror_symmetric_about_xz_and_yz() const override { return true; }

    std::string name() const override { return "cone"; }

    double half_angle() const { return alpha; } // [rad]
    double tip_radius() const { return R; }
    // Delta = R (1/sin(alpha) - 1): how far the rounded flank lies below the sharp one [um].
    double blunting_offset() const;

  private:
    const double alpha;
    const double R;
    const double sin_alpha, cos_alpha;
  };
} // namespace indentsim::indenter

// A spherical indenter of radius R: the lower hemisphere z = R - sqrt(R^2 - r^2), r <= R, on a
// vertical cylinder of the same radius above the equator (the shank), so that the solid is
// convex and closed for every depth. In the frame of MinkowskiRounding.h it is the half-line
// {(0, 0, z): z >= R} rounded by a ball of radius R. Units: um.
#pragma once

#include "indenter/IndenterSurface.h"

namespace indentsim::indenter
{
  class Sphere : public IndenterSurface
  {
  public:
    // R > 0 [um]; throws std::invalid_argument otherwise.
    explicit Sphere(double radius);

    // R - sqrt(R^2 - r^2) for r <= R; +infinity beyond (the vertical shank).
    double profile(double x, double y) const override;

    // Closed form: the nearest point of the half-line above the centre, moved by R.
    SurfaceProjection project(const Point<3> &x, double depth) const override;

    // pi (2 R h - h^2) for 0 <= h <= R (the spherical cap), pi R^2 beyond.
    double projected_area(double h) const override;

    bool mirror_symmetric_about_xz_and_yz() const override { return true; }

    std::string name() const override { return "sphere"; }

    double radius() const { return R; }

  private:
    const double R;
  };
} // namespace indentsim::indenter

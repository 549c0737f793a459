// A cylindrical flat punch of radius a with a flat end, its rim sharp or rounded with the edge
// radius e <= a: the solid cylinder {r <= a - e, z >= e} rounded by a ball of radius e
// (MinkowskiRounding.h). The flat end (radius a - e) is at the apex height 0, the rim is a
// quarter torus up to z = e, and the wall r = a continues upwards. Units: um.
#pragma once

#include "indenter/IndenterSurface.h"

namespace indentsim::indenter
{
  class FlatPunch : public IndenterSurface
  {
  public:
    // a > 0, 0 <= e <= a [um]; throws std::invalid_argument otherwise.
    FlatPunch(double radius, double edge_radius);

    // 0 on the flat end, e - sqrt(e^2 - (r - a + e)^2) on the rounded rim, +infinity beyond a.
    double profile(double x, double y) const override;

    // Closed form in the meridian plane: clamp to the solid cylinder (outside) or the nearer of
    // wall and end face (inside), moved by e.
    SurfaceProjection project(const Point<3> &x, double depth) const override;

    // pi a^2 for h > 0 with a sharp rim; pi (a - e + sqrt(e^2 - (e - h)^2))^2 for h < e on a
    // rounded one, pi a^2 for h >= e.
    double projected_area(double h) const override;

    bool mirror_symmetric_about_xz_and_yz() const override { return true; }

    std::string name() const override { return "flat_punch"; }

    double radius() const { return a; }
    double edge_radius() const { return e; }

  private:
    const double a;
    const double e;
  };
} // namespace indentsim::indenter

// The paper's rounded-cone indenter (eq. 16): z = f(r) = sqrt(r^2/a^2 + delta^2) - delta,
// a hyperboloid of revolution with tip radius R = a^2 delta and asymptotic cone half-angle
// atan(a). delta = 0 gives the sharp cone z = r/a.
#pragma once

#include "indenter/IndenterSurface.h"

namespace indentsim::indenter
{
  class RoundedCone : public IndenterSurface
  {
  public:
    // a > 0 [-], delta >= 0 [um]; throws std::invalid_argument otherwise.
    RoundedCone(double a, double delta);

    double profile(double x, double y) const override;

    // Exact closest-point projection. The problem is axisymmetric, so it reduces to the closest
    // point on the meridian curve z = f(r), r >= 0, of the point (rho, zeta) (rho = distance from
    // the axis, zeta = height above the apex). That 1-D problem is solved by Newton's method
    // safeguarded by bisection on a bracket that provably holds the unique minimizer.
    SurfaceProjection project(const Point<3> &x, double depth) const override;

    // pi r(h)^2, with r(h) = a sqrt(h (h + 2 delta)) the exact inverse of f.
    double projected_area(double h) const override;

    bool mirror_symmetric_about_xz_and_yz() const override { return true; } // axisymmetric

    std::string name() const override { return "rounded_cone"; }

    // f(r) [um] for radius r >= 0, written without cancellation for r << a delta.
    double profile_at_radius(double r) const;
    // Radius r >= 0 where f(r) = h (0 for h <= 0) [um].
    double radius_at_height(double h) const;
    double tip_radius() const { return a * a * delta; }
    double half_angle() const; // [rad]
    double slope_parameter() const { return a; }
    double tip_rounding() const { return delta; }

  private:
    const double a;
    const double delta;

    // The closest point of the profile to the meridian point (rho, zeta): its radius, the
    // slope f' there, whether it is the apex of a sharp cone, and whether the search converged.
    struct Foot
    {
      double r = 0., slope = 0.;
      bool   is_sharp_apex = false, converged = true;
    };
    Foot foot_on_sharp_cone(double rho, double zeta) const;   // delta = 0
    Foot foot_on_rounded_cone(double rho, double zeta) const; // delta > 0

    // f'(r) and f''(r) for r >= 0 (delta > 0).
    double slope(double r) const;
    double curvature_term(double r) const;
  };
} // namespace indentsim::indenter

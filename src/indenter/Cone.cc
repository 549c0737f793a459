// The sharp or spherically tipped cone as a rounded sharp cone (MinkowskiRounding.h). Units: um.
#include "indenter/Cone.h"
#include "indenter/MinkowskiRounding.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace indentsim::indenter
{
  namespace
  {
    double checked_half_angle(const double half_angle_deg)
    {
      if (!(half_angle_deg > 0. && half_angle_deg < 90.))
        throw std::invalid_argument("Cone: the half-angle must satisfy 0 < alpha < 90 deg, got " +
                                    std::to_string(half_angle_deg));
      return half_angle_deg * std::numbers::pi / 180.;
    }
  } // namespace

  Cone::Cone(const double half_angle_deg, const double tip_radius)
    : alpha(checked_half_angle(half_angle_deg))
    , R(tip_radius)
    , sin_alpha(std::sin(alpha))
    , cos_alpha(std::cos(alpha))
  {
    if (!(tip_radius >= 0.) || !std::isfinite(tip_radius))
      throw std::invalid_argument("Cone: the tip radius must be >= 0 um, got " +
                                  std::to_string(tip_radius));
  }

  double Cone::blunting_offset() const
  {
    return R * (1. / sin_alpha - 1.);
  }

  double Cone::profile(const double x, const double y) const
  {
    const double r = std::hypot(x, y);
    const double r_tangent = R * cos_alpha; // where the cap meets the flank
    if (r == 0.)
      return 0.;
    if (r <= r_tangent)
      return r * r / (R + std::sqrt((R - r) * (R + r))); // R - sqrt(R^2 - r^2), no cancellation
    return (r - r_tangent) * cos_alpha / sin_alpha + R * (1. - sin_alpha);
  }

  SurfaceProjection Cone::project(const Point<3> &x, const double depth) const
  {
    const double height = x[2] + depth;
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(height))
      return failed_projection();

    // Meridian coordinates relative to the sharp cone's apex at (0, 0, R); on the axis every
    // meridian is equivalent: take the x-z plane.
    const double rho = std::hypot(x[0], x[1]);
    const double zeta = height - R;
    const double cos_phi = rho > 0. ? x[0] / rho : 1.;
    const double sin_phi = rho > 0. ? x[1] / rho : 0.;

    // Flank direction (sin alpha, cos alpha) and outward normal (cos alpha, -sin alpha) in the
    // meridian plane: t is the foot's position along the flank, s the signed distance to the
    // flank line (<= 0 exactly inside the cone).
    const double       t = rho * sin_alpha + zeta * cos_alpha;
    const double       s = rho * cos_alpha - zeta * sin_alpha;
    const Tensor<1, 3> flank_normal({cos_alpha * cos_phi, cos_alpha * sin_phi, -sin_alpha});

    SharpProjection sharp;
    if (s <= 0. || t > 0.)
      {
        // Inside, the nearest boundary point is on the flank in the same meridian (t > 0 there);
        // outside with t > 0 the foot on the flank is the nearest point of the cone.
        sharp.signed_distance = s;
        const double foot = std::max(t, 0.);
        sharp.boundary_point =
            Point<3>(foot * sin_alpha * cos_phi, foot * sin_alpha * sin_phi, R + foot * cos_alpha);
        sharp.normal = flank_normal;
      }
    else
      {
        // Behind the apex (t <= 0, outside): the apex is the nearest point.
        sharp.boundary_point = Point<3>(0., 0., R);
        const Tensor<1, 3> offset({x[0], x[1], zeta});
        sharp.signed_distance = robust_norm(offset);
        sharp.normal = sharp.signed_distance > 0. ? offset / sharp.signed_distance
                                                  : Tensor<1, 3>({0., 0., -1.});
      }
    return offset_projection(sharp, R, depth);
  }

  double Cone::projected_area(const double h) const
  {
    if (!(h > 0.))
      return 0.;
    if (h <= R * (1. - sin_alpha))
      return std::numbers::pi * h * (2. * R - h);
    const double r = std::tan(alpha) * (h + blunting_offset());
    return std::numbers::pi * r * r;
  }
} // namespace indentsim::indenter

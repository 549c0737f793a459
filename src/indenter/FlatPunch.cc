// The flat punch as a rounded solid cylinder (MinkowskiRounding.h). Units: um.
#include "indenter/FlatPunch.h"
#include "indenter/MinkowskiRounding.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace indentsim::indenter
{
  FlatPunch::FlatPunch(const double radius, const double edge_radius)
    : a(radius)
    , e(edge_radius)
  {
    if (!(radius > 0.) || !std::isfinite(radius))
      throw std::invalid_argument("FlatPunch: the radius must be > 0 um, got " +
                                  std::to_string(radius));
    if (!(edge_radius >= 0. && edge_radius <= radius))
      throw std::invalid_argument(
          "FlatPunch: the edge radius must satisfy 0 <= e <= a = " + std::to_string(radius) +
          " um, got " + std::to_string(edge_radius));
  }

  double FlatPunch::profile(const double x, const double y) const
  {
    const double r = std::hypot(x, y);
    const double flat = a - e; // radius of the flat end
    if (r <= flat)
      return 0.;
    if (r > a)
      return std::numeric_limits<double>::infinity();
    const double s = r - flat;                         // 0 < s <= e on the rim
    return s * s / (e + std::sqrt((e - s) * (e + s))); // e - sqrt(e^2 - s^2), no cancellation
  }

  SurfaceProjection FlatPunch::project(const Point<3> &x, const double depth) const
  {
    const double height = x[2] + depth;
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(height))
      return failed_projection();

    // The sharp solid {rho <= a - e, z >= e} in the meridian plane (x-z plane on the axis).
    const double       rho = std::hypot(x[0], x[1]);
    const double       cos_phi = rho > 0. ? x[0] / rho : 1.;
    const double       sin_phi = rho > 0. ? x[1] / rho : 0.;
    const double       wall = a - e, end = e;
    const Tensor<1, 3> radial({cos_phi, sin_phi, 0.});
    const Tensor<1, 3> down({0., 0., -1.});

    SharpProjection sharp;
    const bool      beside = rho > wall; // radially outside the wall
    const bool      below = height < end;
    if (!beside && !below)
      {
        // Inside: the nearer of the wall and the end face (ties: the end face).
        const double to_wall = wall - rho, to_end = height - end;
        if (to_wall < to_end)
          {
            sharp.signed_distance = -to_wall;
            sharp.boundary_point = Point<3>(wall * cos_phi, wall * sin_phi, height);
            sharp.normal = radial;
          }
        else
          {
            sharp.signed_distance = -to_end;
            sharp.boundary_point = Point<3>(x[0], x[1], end);
            sharp.normal = down;
          }
      }
    else if (beside && !below)
      {
        sharp.signed_distance = rho - wall;
        sharp.boundary_point = Point<3>(wall * cos_phi, wall * sin_phi, height);
        sharp.normal = radial;
      }
    else if (!beside && below)
      {
        sharp.signed_distance = end - height;
        sharp.boundary_point = Point<3>(x[0], x[1], end);
        sharp.normal = down;
      }
    else
      {
        // Below and beside: the rim circle is the nearest point.
        sharp.boundary_point = Point<3>(wall * cos_phi, wall * sin_phi, end);
        sharp.signed_distance = std::hypot(rho - wall, end - height);
        sharp.normal = ((rho - wall) * radial + (end - height) * down) / sharp.signed_distance;
      }
    return offset_projection(sharp, e, depth);
  }

  double FlatPunch::projected_area(const double h) const
  {
    if (!(h > 0.))
      return 0.;
    if (h >= e)
      return std::numbers::pi * a * a;
    const double r = a - e + std::sqrt(h * (2. * e - h)); // e^2 - (e - h)^2 = h (2e - h)
    return std::numbers::pi * r * r;
  }
} // namespace indentsim::indenter

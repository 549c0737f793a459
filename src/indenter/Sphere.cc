// The spherical indenter as a rounded half-line (MinkowskiRounding.h). Units: um.
#include "indenter/Sphere.h"
#include "indenter/MinkowskiRounding.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace indentsim::indenter
{
  Sphere::Sphere(const double radius)
    : R(radius)
  {
    if (!(radius > 0.) || !std::isfinite(radius))
      throw std::invalid_argument("Sphere: the radius must be > 0 um, got " +
                                  std::to_string(radius));
  }

  // R - sqrt(R^2 - r^2) written as r^2 / (R + sqrt(R^2 - r^2)), without cancellation at r << R.
  double Sphere::profile(const double x, const double y) const
  {
    const double r = std::hypot(x, y);
    if (r > R)
      return std::numeric_limits<double>::infinity();
    return r * r / (R + std::sqrt((R - r) * (R + r)));
  }

  SurfaceProjection Sphere::project(const Point<3> &x, const double depth) const
  {
    const double height = x[2] + depth; // above the apex
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(height))
      return failed_projection();

    // Nearest point of the half-line {(0, 0, z): z >= R} (the centre and the shank's axis).
    const double    rho = std::hypot(x[0], x[1]);
    SharpProjection sharp;
    sharp.boundary_point = Point<3>(0., 0., std::max(height, R));
    const Tensor<1, 3> offset = Point<3>(x[0], x[1], height) - sharp.boundary_point;
    sharp.signed_distance = robust_norm(offset);
    if (sharp.signed_distance > 0.)
      sharp.normal = offset / sharp.signed_distance;
    else
      // On the centre every direction of the lower hemisphere is a closest one: take the apex.
      sharp.normal = Tensor<1, 3>({0., 0., -1.});
    if (rho == 0. && height > R)
      // On the shank's axis every horizontal direction is a closest one: take +x.
      sharp.normal = Tensor<1, 3>({1., 0., 0.});
    return offset_projection(sharp, R, depth);
  }

  double Sphere::projected_area(const double h) const
  {
    if (!(h > 0.))
      return 0.;
    if (h >= R)
      return std::numbers::pi * R * R;
    return std::numbers::pi * h * (2. * R - h);
  }
} // namespace indentsim::indenter

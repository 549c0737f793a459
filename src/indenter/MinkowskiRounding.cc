// Offsetting a sharp convex solid's projection by the rounding radius. Units: um.
#include "indenter/MinkowskiRounding.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace indentsim::indenter
{
  SurfaceProjection offset_projection(const SharpProjection &sharp, const double R,
                                      const double depth)
  {
    SurfaceProjection result;
    result.gap = sharp.signed_distance - R;
    result.normal = sharp.normal;
    result.closest_point = sharp.boundary_point + R * sharp.normal;
    result.closest_point[2] -= depth;
    result.converged = true;
    return result;
  }

  SurfaceProjection failed_projection()
  {
    SurfaceProjection result;
    result.gap = std::numeric_limits<double>::quiet_NaN();
    result.normal = Tensor<1, 3>({0., 0., -1.});
    result.converged = false;
    return result;
  }

  double robust_norm(const Tensor<1, 3> &v)
  {
    const double scale = std::max({std::abs(v[0]), std::abs(v[1]), std::abs(v[2])});
    if (!(scale > 0.) || !std::isfinite(scale))
      return scale;
    const double x = v[0] / scale, y = v[1] / scale, z = v[2] / scale;
    return scale * std::sqrt(x * x + y * y + z * z);
  }

  // Reduced to [0, 45] deg and mapped back by exact swaps and sign changes, so that angles that
  // are mirror images of each other (30 and 150 deg, 45 and 135 deg) give bitwise mirrored values.
  void cos_sin_deg(const double angle_deg, double &cosine, double &sine)
  {
    double reduced = std::fmod(angle_deg, 360.);
    if (reduced < 0.)
      reduced += 360.;
    if (reduced >= 360.)
      reduced = 0.;
    const int    quadrant = std::min(3, static_cast<int>(reduced / 90.));
    const double within = reduced - 90. * quadrant; // [0, 90)
    double       c = 0., s = 0.;
    if (within == 45.)
      c = s = std::sqrt(0.5);
    else if (within < 45.)
      {
        c = std::cos(within * std::numbers::pi / 180.);
        s = std::sin(within * std::numbers::pi / 180.);
      }
    else
      {
        c = std::sin((90. - within) * std::numbers::pi / 180.);
        s = std::cos((90. - within) * std::numbers::pi / 180.);
      }
    switch (quadrant)
      {
      case 0:
        cosine = c, sine = s;
        break;
      case 1:
        cosine = -s, sine = c;
        break;
      case 2:
        cosine = -c, sine = -s;
        break;
      default:
        cosine = s, sine = -c;
        break;
      }
  }
} // namespace indentsim::indenter

// Closest-point projection onto the rounded cone of eq. 16. Units: um.
#include "indenter/RoundedCone.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace indentsim::indenter
{
  RoundedCone::RoundedCone(const double a, const double delta)
    : a(a)
    , delta(delta)
  {
    if (!(a > 0.) || !std::isfinite(a))
      throw std::invalid_argument("RoundedCone: the slope parameter a must be > 0, got " +
                                  std::to_string(a));
    if (!(delta >= 0.) || !std::isfinite(delta))
      throw std::invalid_argument("RoundedCone: the tip rounding delta must be >= 0 um, got " +
                                  std::to_string(delta));
  }

  double RoundedCone::half_angle() const
  {
    return std::atan(a);
  }

  // f = s - delta with s = sqrt(r^2/a^2 + delta^2), rewritten as (r^2/a^2)/(s + delta).
  double RoundedCone::profile_at_radius(const double r) const
  {
    const double q = r / a;
    const double s = std::hypot(q, delta);
    return s > 0. ? q * q / (s + delta) : 0.;
  }

  double RoundedCone::profile(const double x, const double y) const
  {
    return profile_at_radius(std::hypot(x, y));
  }

  // f' = r / (a^2 s)
  double RoundedCone::slope(const double r) const
  {
    return r / (a * a * std::hypot(r / a, delta));
  }

  // f'' = delta^2 / (a^2 s^3)
  double RoundedCone::curvature_term(const double r) const
  {
    const double s = std::hypot(r / a, delta);
    return delta * delta / (a * a * s * s * s);
  }

  // (f + delta)^2 = r^2/a^2 + delta^2  =>  r = a sqrt(h (h + 2 delta)).
  double RoundedCone::radius_at_height(const double h) const
  {
    return h > 0. ? a * std::sqrt(h * (h + 2. * delta)) : 0.;
  }

  double RoundedCone::projected_area(const double h) const
  {
    const double r = radius_at_height(h);
    return std::numbers::pi * r * r;
  }

  RoundedCone::Foot RoundedCone::foot_on_sharp_cone(const double rho, const double zeta) const
  {
    // Sharp cone z = r/a: the foot on the flank line solves (r - rho) + (r/a - zeta)/a = 0; if
    // it falls behind the apex, the apex itself is the closest point.
    const double r_foot = a * (a * rho + zeta) / (a * a + 1.);
    if (r_foot > 0.)
      return {r_foot, 1. / a, false, true};
    return {0., 0., true, true};
  }

  RoundedCone::Foot RoundedCone::foot_on_rounded_cone(const double rho, const double zeta) const
  {
    // Stationarity of the squared distance (r - rho)^2 + (f(r) - zeta)^2:
    //   g(r) = (r - rho) + (f(r) - zeta) f'(r) = 0,
    //   g'(r) = 1 + f'^2 + (f - zeta) f''.
    const auto g = [&](const double r) {
      return (r - rho) + (profile_at_radius(r) - zeta) * slope(r);
    };
    const auto dg = [&](const double r) {
      const double fp = slope(r);
      return 1. + fp * fp + (profile_at_radius(r) - zeta) * curvature_term(r);
    };

    // Bracket [lo, hi] with g(lo) <= 0 < g(hi) holding the unique minimizer:
    //  - outside (zeta <= f(rho)): g < 0 wherever f < zeta, g' > 0 wherever f >= zeta, and
    //    g(rho) >= 0, so the root is unique in [0, rho];
    //  - inside (zeta > f(rho)): g < 0 on [0, rho), g(r_zeta) = r_zeta - rho > 0 at
    //    f(r_zeta) = zeta, and g'' = 3 f' f'' + (f - zeta) f''' >= 0 (f''' <= 0) on
    //    [rho, r_zeta]: the convex g has one root there.
    //  - on the axis inside, r = 0 is the foot while zeta <= R = a^2 delta (g'(0) >= 0);
    //    above the centre of curvature the feet form a circle of radius r > 0.
    const bool inside = zeta > profile_at_radius(rho);
    double     lo = 0., hi = 0.;
    if (!inside)
      {
        hi = rho;
        if (!(rho > 0. && g(rho) > 0.))
          return {rho, slope(rho), false, true}; // the apex, or exactly on the surface
      }
    else
      {
        if (rho == 0. && zeta <= tip_radius())
          return {0., slope(0.), false, true};
        lo = rho;
        hi = radius_at_height(zeta);
        // Guard against round-off in radius_at_height for points just inside.
        while (!(g(hi) > 0.))
          hi = 2. * hi + std::numeric_limits<double>::min();
      }

    // Newton safeguarded by bisection. Start from the end of the bracket where |g| is smaller
    // (near the surface the foot is close to rho); on the axis g(0) = 0 is the distance
    // maximum, so start from hi, where Newton on the convex g descends monotonically to the
    // foot.
    const double tolerance =
        4. * std::numeric_limits<double>::epsilon() * std::max({hi, std::abs(zeta), a * delta});
    const double           g_lo = g(lo), g_hi = g(hi);
    double                 r = (rho > 0. && std::abs(g_lo) < std::abs(g_hi)) ? lo : hi;
    bool                   converged = false;
    constexpr unsigned int max_iterations = 200;
    for (unsigned int iteration = 0; iteration < max_iterations && !converged; ++iteration)
      {
        const double value = g(r);
        if (value == 0.)
          {
            converged = true;
            break;
          }
        if (value < 0.)
          lo = r;
        else
          hi = r;
        const double derivative = dg(r);
        double       r_next = r - value / derivative;
        if (!(derivative > 0.) || !(r_next > lo && r_next < hi))
          r_next = 0.5 * (lo + hi);
        const double step = std::abs(r_next - r);
        r = r_next;
        converged = step <= tolerance || hi - lo <= tolerance;
      }
    return {r, slope(r), false, converged};
  }

  SurfaceProjection RoundedCone::project(const Point<3> &x, const double depth) const
  {
    SurfaceProjection result;
    // Meridian-plane coordinates of x in the indenter frame (apex at the origin).
    const double rho = std::hypot(x[0], x[1]);
    const double zeta = x[2] + depth;
    if (!std::isfinite(rho) || !std::isfinite(zeta))
      {
        result.gap = std::numeric_limits<double>::quiet_NaN();
        result.converged = false;
        return result;
      }
    // On the axis every meridian is a closest one; take the x-z plane.
    const double cos_phi = rho > 0. ? x[0] / rho : 1.;
    const double sin_phi = rho > 0. ? x[1] / rho : 0.;

    const Foot foot = delta == 0. ? foot_on_sharp_cone(rho, zeta) : foot_on_rounded_cone(rho, zeta);
    result.converged = foot.converged;
    const double z_foot = profile_at_radius(foot.r) - depth;
    result.closest_point = Point<3>(foot.r * cos_phi, foot.r * sin_phi, z_foot);

    const Tensor<1, 3> offset = x - result.closest_point;
    if (foot.is_sharp_apex)
      {
        // The sharp apex has no tangent plane: the normal is the direction to the point.
        const double distance = offset.norm();
        if (distance > 0.)
          result.normal = offset / distance;
        else
          result.normal = Tensor<1, 3>({0., 0., -1.});
      }
    else
      {
        // Meridian normal (f', -1)/sqrt(1 + f'^2): from the indenter into the specimen.
        const double norm = std::sqrt(1. + foot.slope * foot.slope);
        result.normal =
            Tensor<1, 3>({foot.slope * cos_phi / norm, foot.slope * sin_phi / norm, -1. / norm});
      }
    // x - closest_point is parallel to the normal at the exact foot, so this is the signed
    // distance: > 0 outside the indenter, < 0 inside.
    result.gap = offset * result.normal;
    return result;
  }
} // namespace indentsim::indenter

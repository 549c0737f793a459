// Sneddon's closed form for the rounded cone (see the header and docs/development.md).
#include "indenter/SneddonReference.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace indentsim::indenter
{
  namespace
  {
    // q(x) = (x^2 - 1) atan(x) + x, so that P = (E* c^2 / A) q(a_c / c). For small x the two
    // terms cancel to O(x^3); the series q = sum_k (-1)^(k-1) 4k/(4k^2-1) x^(2k+1) avoids it.
    double force_shape(const double x)
    {
      if (x < 0.1)
        {
          double sum = 0., power = x, sign = 1.;
          for (int k = 1; k <= 12; ++k)
            {
              power *= x * x;
              sum += sign * 4. * k / (4. * k * k - 1.) * power;
              sign = -sign;
            }
          return sum;
        }
      return (x * x - 1.) * std::atan(x) + x;
    }
  } // namespace

  SneddonReference::SneddonReference(const double reduced_modulus, const double a,
                                     const double delta)
    : E_star(reduced_modulus)
    , A(a)
    , delta(delta)
    , c(a * delta)
  {
    if (!(reduced_modulus > 0.) || !(a > 0.) || !(delta >= 0.))
      throw std::invalid_argument("SneddonReference: need E* > 0, A > 0 and delta >= 0");
  }

  double SneddonReference::depth_at_contact_radius(const double contact_radius) const
  {
    if (contact_radius <= 0.)
      return 0.;
    if (c == 0.) // sharp cone: atan -> pi/2
      return contact_radius / A * std::numbers::pi / 2.;
    return contact_radius / A * std::atan(contact_radius / c);
  }

  double SneddonReference::force_at_contact_radius(const double contact_radius) const
  {
    if (contact_radius <= 0.)
      return 0.;
    if (c == 0.)
      return E_star / A * contact_radius * contact_radius * std::numbers::pi / 2.;
    return E_star * c * c / A * force_shape(contact_radius / c);
  }

  double SneddonReference::stiffness_at_contact_radius(const double contact_radius) const
  {
    return 2. * E_star * std::max(contact_radius, 0.);
  }

  double SneddonReference::contact_radius_at_depth(const double h) const
  {
    if (!(h > 0.))
      return 0.;
    if (c == 0.)
      return 2. * A * h / std::numbers::pi;

    // In x = a_c / c: phi(x) = x atan(x) = h A / c = h / delta, increasing and convex, with
    // phi'(x) = atan(x) + x / (1 + x^2).
    const double target = h / delta;
    const auto   phi = [](const double x) { return x * std::atan(x); };
    const auto   dphi = [](const double x) { return std::atan(x) + x / (1. + x * x); };

    // Bracket: atan x <= x and atan x <= pi/2 give x >= max(sqrt(t), 2t/pi); grow the upper end.
    double lo = std::max(std::sqrt(target), 2. * target / std::numbers::pi) * (1. - 1e-12);
    double hi = std::max(2. * lo, 1.);
    while (phi(hi) < target)
      hi *= 2.;
    lo = std::min(lo, hi);

    double x = hi; // Newton from the right on a convex increasing function is monotone
    for (int iteration = 0; iteration < 200; ++iteration)
      {
        const double value = phi(x) - target;
        if (value == 0.)
          break;
        if (value < 0.)
          lo = x;
        else
          hi = x;
        double x_next = x - value / dphi(x);
        if (!(x_next > lo && x_next < hi))
          x_next = 0.5 * (lo + hi);
        const bool done = std::abs(x_next - x) <= 2. * std::numeric_limits<double>::epsilon() * x;
        x = x_next;
        if (done || hi - lo <= 2. * std::numeric_limits<double>::epsilon() * hi)
          break;
      }
    return c * x;
  }

  double SneddonReference::force_at_depth(const double h) const
  {
    return force_at_contact_radius(contact_radius_at_depth(h));
  }

  double SneddonReference::stiffness_at_depth(const double h) const
  {
    return stiffness_at_contact_radius(contact_radius_at_depth(h));
  }
} // namespace indentsim::indenter

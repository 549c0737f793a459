// Closed-form elastic half-space solution for the rounded cone of eq. 16 (docs/development.md),
// from Sneddon's axisymmetric integrals, for a rigid frictionless indenter:
//   c = A delta,  x = a_c / c,
//   h(a_c) = (a_c / A) atan(a_c / c)
//   P(a_c) = (E* / A) [ (a_c^2 - c^2) atan(a_c / c) + a_c c ]
//   S      = dP/dh = 2 E* a_c
// Limits: h << delta is Hertz with R = A^2 delta, delta -> 0 is Sneddon's cone. Units: um, mN,
// GPa. This is the independent oracle of the elastic indentation verification tests.
#pragma once

namespace indentsim::indenter
{
  class SneddonReference
  {
  public:
    // E* = E / (1 - nu^2) [GPa] (rigid indenter), A > 0 [-], delta >= 0 [um].
    SneddonReference(double reduced_modulus, double a, double delta);

    static double reduced_modulus(double young_modulus, double poisson_ratio)
    {
      return young_modulus / (1. - poisson_ratio * poisson_ratio);
    }

    double depth_at_contact_radius(double contact_radius) const;     // h [um]
    double force_at_contact_radius(double contact_radius) const;     // P [mN]
    double stiffness_at_contact_radius(double contact_radius) const; // S = 2 E* a_c [mN/um]

    // a_c(h) by inverting the monotone h(a_c) (safeguarded Newton); 0 for h <= 0.
    double contact_radius_at_depth(double h) const;
    double force_at_depth(double h) const;
    double stiffness_at_depth(double h) const;

  private:
    const double E_star;
    const double A;
    const double delta;
    const double c; // A delta [um]
  };
} // namespace indentsim::indenter

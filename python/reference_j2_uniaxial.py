#!/usr/bin/env python3
"""Independent reference solution: homogeneous uniaxial tension of the paper's finite-strain J2
model (section 2.1, eqs 1-9: neo-Hookean energy in b_e, Huber-Mises-Hencky yield with linear
hardening, exponential-map flow).

Units: stresses and moduli in GPa, strains and stretches dimensionless.

It does not use the C++ code. Under monotonic uniaxial stress the principal axes are fixed and
the flow direction is constant, so the exponential map integrates exactly and the state follows
from the current stretch alone (docs/development.md, "Homogeneous uniaxial tension"):

  F = diag(lam, lam_t, lam_t),          total log strains (ln lam, ln lam_t, ln lam_t)
  plastic log strain  eps_p = alpha diag(1, -1/2, -1/2)  (alpha = equivalent plastic strain)
  elastic principal stretches squared   b1 = lam^2 exp(-2 alpha),  b2 = lam_t^2 exp(alpha)
  J = lam lam_t^2,  tau_i = mu (b_i - 1) + lambda/2 (J^2 - 1)       (eqs 2-3)
  lateral stress zero:   tau_2 = 0   -> a quadratic in s = lam_t^2, solved in closed form
  yield (eqs 4-6):       mu (b1 - b2) / J^m = sigma_y0 + H alpha,  m = 1 (Cauchy), 0 (Kirchhoff)

The last equation is the only root solve (bisection in alpha to full double precision). If the
elastic solution (alpha = 0) is below yield, alpha = 0.

Usage (needs numpy: Debian package python3-numpy, see scripts/install_dependencies.sh):
  python3 python/reference_j2_uniaxial.py --out tests/unit/data/j2_uniaxial_reference.csv
  python3 python/reference_j2_uniaxial.py --yield-stress-measure kirchhoff \
      --out tests/unit/data/j2_uniaxial_reference_kirchhoff.csv
Defaults are the paper's Table 1 parameters; 101 rows, log strain 0 to 0.2 in steps of 0.002.
"""

import argparse

import numpy as np


def lateral_stretch(lam, alpha, mu, lame_lambda):
    """lam_t with tau_2 = 0: (lambda/2) lam^2 s^2 + mu e^alpha s - (mu + lambda/2) = 0, s = lam_t^2,
    solved with the cancellation-free form of the positive root s = 2c / (b + sqrt(b^2 + 4ac))."""
    a = 0.5 * lame_lambda * lam**2
    b = mu * np.exp(alpha)
    c = mu + 0.5 * lame_lambda
    s = 2.0 * c / (b + np.sqrt(b * b + 4.0 * a * c))
    return np.sqrt(s)


def state(lam, alpha, mu, lame_lambda):
    """Lateral stretch, J, and Kirchhoff stresses tau_1, tau_2 for stretch lam and plastic strain alpha."""
    lam_t = lateral_stretch(lam, alpha, mu, lame_lambda)
    J = lam * lam_t**2
    b1 = lam**2 * np.exp(-2.0 * alpha)
    b2 = lam_t**2 * np.exp(alpha)
    pressure_term = 0.5 * lame_lambda * (J * J - 1.0)
    tau1 = mu * (b1 - 1.0) + pressure_term
    tau2 = mu * (b2 - 1.0) + pressure_term
    return lam_t, J, tau1, tau2


def yield_function(lam, alpha, mu, lame_lambda, sigma_y0, H, cauchy):
    """f = sigma_HMH - sigma_y; for uniaxial stress sigma_HMH = |tau1 - tau2| / J^m."""
    _, J, tau1, tau2 = state(lam, alpha, mu, lame_lambda)
    sigma_hmh = np.abs(tau1 - tau2) / (J if cauchy else 1.0)
    return sigma_hmh - (sigma_y0 + H * alpha)


def solve(log_strain, E, nu, sigma_y0, H, cauchy):
    mu = E / (2.0 * (1.0 + nu))
    lame_lambda = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu))
    lam = np.exp(log_strain)

    # f decreases monotonically in alpha; f(alpha = 0) <= 0 means the point is elastic.
    # In tension the root lies in [0, ln lam] (at alpha = ln lam the deviatoric elastic strain
    # is about zero, so f < 0 there).
    lo = np.zeros_like(lam)
    hi = np.maximum(log_strain, 0.0)
    elastic = yield_function(lam, lo, mu, lame_lambda, sigma_y0, H, cauchy) <= 0.0
    assert np.all(elastic | (yield_function(lam, hi, mu, lame_lambda, sigma_y0, H, cauchy) < 0.0)), \
        "root not bracketed"
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        positive = yield_function(lam, mid, mu, lame_lambda, sigma_y0, H, cauchy) > 0.0
        lo = np.where(positive, mid, lo)
        hi = np.where(positive, hi, mid)
    alpha = np.where(elastic, 0.0, 0.5 * (lo + hi))

    lam_t, J, tau1, tau2 = state(lam, alpha, mu, lame_lambda)
    assert np.all(np.abs(tau2) <= 1e-12 * mu), "lateral stress not zero"
    return tau1 / J, lam_t, alpha


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", required=True, help="CSV file to write")
    parser.add_argument("--yield-stress-measure", choices=["cauchy", "kirchhoff"], default="cauchy")
    parser.add_argument("--young-modulus", type=float, default=69.0, help="E [GPa]")
    parser.add_argument("--poisson-ratio", type=float, default=0.26, help="nu [-]")
    parser.add_argument("--yield-stress", type=float, default=0.305, help="sigma_y0 [GPa]")
    parser.add_argument("--hardening-modulus", type=float, default=0.5, help="H [GPa]")
    parser.add_argument("--max-log-strain", type=float, default=0.2)
    parser.add_argument("--intervals", type=int, default=100, help="rows - 1")
    args = parser.parse_args()

    cauchy = args.yield_stress_measure == "cauchy"
    log_strain = args.max_log_strain * np.arange(args.intervals + 1) / args.intervals
    sigma, lam_t, alpha = solve(log_strain, args.young_modulus, args.poisson_ratio,
                                args.yield_stress, args.hardening_modulus, cauchy)

    with open(args.out, "w") as out:
        out.write("# Homogeneous uniaxial tension, finite-strain J2 (paper eqs 1-9), reference solution\n")
        out.write("# written by python/reference_j2_uniaxial.py (independent of the C++ code)\n")
        out.write(f"# yield_stress_measure = {args.yield_stress_measure}; E = {args.young_modulus} GPa, "
                  f"nu = {args.poisson_ratio}, sigma_y0 = {args.yield_stress} GPa, "
                  f"H = {args.hardening_modulus} GPa\n")
        out.write("# log_strain: ln(axial stretch) [-]; cauchy_stress_GPa: axial Cauchy stress [GPa];\n")
        out.write("# lateral_stretch: lam_t [-] (lateral stress zero); alpha: equivalent plastic strain [-]\n")
        out.write("log_strain,cauchy_stress_GPa,lateral_stretch,alpha\n")
        for row in zip(log_strain, sigma, lam_t, alpha):
            out.write(",".join(f"{value:.17g}" for value in row) + "\n")


if __name__ == "__main__":
    main()

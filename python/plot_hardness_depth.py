#!/usr/bin/env python3
"""Plot the hardness-depth profile of a run with partial unloads: the Oliver-Pharr hardness and
the true-area hardness against depth, the reduced modulus against depth, and the Nix-Gao plot
(H^2 against 1/h) with its bilinear fit.

Reads hardness_depth.json written at the end of `indentsim run` when the case has
loading.partial_unloads.

Usage:
    python3 python/plot_hardness_depth.py results/x/hardness_depth.json -o results/x/hardness_depth.png

Units: depth in um, hardness and moduli in GPa.
"""

import argparse
import json
import sys

from indentsim_plotting import ensure_matplotlib, save_figure  # noqa: E402

ensure_matplotlib("plot_hardness_depth.py")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def values(result, key):
    """A list of the JSON as floats, None (no value) as NaN so that it is not drawn."""
    return np.array([np.nan if v is None else v for v in result[key]], dtype=float)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("json", help="hardness_depth.json")
    parser.add_argument("-o", "--output", required=True, help="PNG file to write")
    args = parser.parse_args()
    try:
        with open(args.json) as stream:
            result = json.load(stream)
        depth = values(result, "depth_um")
        hardness = values(result, "hardness_GPa")
        true_hardness = values(result, "true_hardness_GPa")
        modulus = values(result, "reduced_modulus_GPa")
        fit = result["nix_gao"]
    except (OSError, KeyError, ValueError, TypeError) as error:
        sys.exit(f"plot_hardness_depth.py: {args.json}: not a hardness_depth.json ({error})")

    figure, (left, middle, right) = plt.subplots(1, 3, figsize=(14, 4.5))
    left.plot(depth, hardness, "o-", color="tab:blue", ms=4, label="Oliver-Pharr H = P / A(h_c)")
    if np.isfinite(true_hardness).any():
        left.plot(depth, true_hardness, "s--", color="tab:orange", ms=3, mfc="none",
                  label="true-area H = P / A_true")
    left.set_xlabel("depth h [um]")
    left.set_ylabel("hardness [GPa]")
    left.set_ylim(bottom=0)
    left.legend(fontsize=8)
    left.set_title("hardness from the partial unloads", fontsize=10)

    middle.plot(depth, modulus, "o-", color="tab:green", ms=4)
    middle.set_xlabel("depth h [um]")
    middle.set_ylabel("reduced modulus E_r [GPa]")
    middle.set_ylim(bottom=0)
    middle.set_title("E_r = sqrt(pi)/2 S / sqrt(A(h_c))", fontsize=10)

    inverse = 1 / depth
    right.plot(inverse, hardness ** 2, "o", color="tab:blue", ms=4, label="H^2 (Oliver-Pharr)")
    if fit:
        knee = 1 / fit["knee_depth_um"]
        a = fit["layer_hardness_GPa"] ** 2
        b = fit["layer_characteristic_depth_um"] * a
        shallow = np.linspace(0, inverse.max(), 50)
        shallow = shallow[shallow >= knee * 0.999]
        right.plot(np.concatenate([[0], shallow]), a + b * np.concatenate([[0], shallow]), "-",
                   color="tab:red",
                   label=f"shallow branch: H_0 = {fit['layer_hardness_GPa']:.3g} GPa, "
                         f"h* = {fit['layer_characteristic_depth_um']:.3g} um")
        deep = np.linspace(inverse.min(), knee, 20)
        right.plot(deep, fit["deep_intercept_GPa2"] + fit["deep_slope_GPa2_um"] * deep, "-",
                   color="tab:purple", label="deep branch")
        right.axvline(knee, color="tab:gray", ls=":",
                      label=f"knee at h = {fit['knee_depth_um']:.3g} um")
    right.set_xlabel("1 / h [1/um]")
    right.set_ylabel("H^2 [GPa^2]")
    right.set_xlim(left=0)
    right.set_ylim(bottom=0)
    right.legend(fontsize=7)
    if not fit:
        title = "Nix-Gao plot (too few points for the bilinear fit)"
    elif fit.get("knee_significant"):
        title = f"Nix-Gao plot, bilinear fit (F = {fit['f_statistic']:.3g})"
    else:
        title = f"Nix-Gao plot: no significant knee (F = {fit['f_statistic']:.3g})"
    right.set_title(title, fontsize=10)
    for axes in (left, middle, right):
        axes.grid(alpha=0.3)
    return save_figure(figure, args.output, "plot_hardness_depth.py", dpi=120)


if __name__ == "__main__":
    sys.exit(main())

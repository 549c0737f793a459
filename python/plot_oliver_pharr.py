#!/usr/bin/env python3
"""Plot an Oliver-Pharr analysis: the load-penetration curve, the power-law fit of the upper
unloading, the tangent of slope S at h_max, the contact depth h_c and the residual depth h_r.

Reads oliver_pharr.json written by `indentsim analyze` (or at the end of `indentsim run` with
unloading), which carries the curve itself.

Usage:
    python3 python/plot_oliver_pharr.py results/x/oliver_pharr.json -o results/x/oliver_pharr.png

Units: depth in um, force in mN, stiffness in mN/um, hardness and moduli in GPa.
"""

import argparse
import json
import sys

from indentsim_plotting import ensure_matplotlib, save_figure  # noqa: E402

ensure_matplotlib("plot_oliver_pharr.py")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("json", help="oliver_pharr.json")
    parser.add_argument("-o", "--output", required=True, help="PNG file to write")
    args = parser.parse_args()
    try:
        with open(args.json) as stream:
            result = json.load(stream)
        depth = np.array(result["curve"]["depth_um"], dtype=float)
        force = np.array(result["curve"]["force_mN"], dtype=float)
        fit = result["fit"]
        h_max, p_max = result["max_depth_um"], result["max_force_mN"]
        stiffness = result["stiffness_mN_per_um"]
        h_c, h_r = result["contact_depth_um"], result["residual_depth_um"]
        begin, end = result["unloading_points"]
    except (OSError, KeyError, ValueError, TypeError) as error:
        sys.exit(f"plot_oliver_pharr.py: {args.json}: not an oliver_pharr.json ({error})")

    figure, axes = plt.subplots(figsize=(7, 5))
    axes.plot(depth, force, "k.-", lw=1, ms=3, label="curve")
    low, high = result["fit_range_of_max_force"]
    fitted = (np.arange(len(depth)) >= begin) & (np.arange(len(depth)) < end) \
        & (force >= low * p_max) & (force <= high * p_max)
    axes.plot(depth[fitted], force[fitted], "o", mfc="none", color="tab:blue",
              label=f"fitted points ({fit['n_points']})")
    h = np.linspace(max(fit["h_f_um"], depth[begin:end].min()), h_max, 200)
    axes.plot(h, fit["alpha_mN_per_um_m"] * np.clip(h - fit["h_f_um"], 0, None) ** fit["m"],
              color="tab:blue",
              label=f"P = {fit['alpha_mN_per_um_m']:.4g} (h - {fit['h_f_um']:.4g})^{fit['m']:.3f}")
    tangent_h = np.array([h_max - p_max / stiffness, h_max])
    axes.plot(tangent_h, p_max + stiffness * (tangent_h - h_max), "--", color="tab:red",
              label=f"S = {stiffness:.4g} mN/um")
    axes.axvline(h_c, color="tab:green", ls=":", label=f"h_c = {h_c:.4g} um")
    axes.axvline(h_r, color="tab:gray", ls=":", label=f"h_r = {h_r:.4g} um")
    axes.set_xlabel("depth h [um]")
    axes.set_ylabel("force P [mN]")
    axes.set_ylim(bottom=0)
    title = (f"Oliver-Pharr: H = {result['hardness_GPa']:.4g} GPa, "
             f"E_r = {result['reduced_modulus_GPa']:.4g} GPa, "
             f"W_p/W_t = {result['plastic_work_ratio']:.3f}")
    if result.get("area_error_percent") is not None:
        title += f"\nO-P area vs true contact area: {result['area_error_percent']:+.1f} %"
    axes.set_title(title, fontsize=10)
    axes.grid(alpha=0.3)
    axes.legend(fontsize=8, loc="upper left")
    return save_figure(figure, args.output, "plot_oliver_pharr.py", dpi=120)


if __name__ == "__main__":
    sys.exit(main())

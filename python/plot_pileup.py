#!/usr/bin/env python3
"""Plot the pile-up of an indentation run (the paper's Fig. 7) to PNG files.

Reads, from the output directory of `indentsim run`:
  pileup_max_depth.csv, pileup_unloaded.csv  grid of the surface height h = u_z [um] over the
                                             current in-plane position (columns x_um, y_um,
                                             height_um; empty height where no surface lies)
  pileup_profiles.csv                        radial profiles (stage, azimuth_deg, r_um, height_um)
  pileup.json                                contact and analysis radii, fold and its source,
                                             max pile-up
and writes pileup_max_depth.png and pileup_unloaded.png (colour maps of h, diverging colour map
centred at h = 0, equal aspect; the dashed circle is the contact radius at maximum depth, the
dotted one the analysis radius of the Fourier spectrum) and pileup_profiles.png (h(r) along the
azimuths 0, 45, 90 and 135 deg, both stages). A missing stage (a run without unloading) is
skipped.

Usage:
    python3 python/plot_pileup.py results/paper_j2_n12 [-o OUTPUT_DIRECTORY]
        [--azimuths 0 45 90 135]

Units: um, deg.
"""

import argparse
import csv
import json
import math
import os
import sys

from indentsim_plotting import ensure_matplotlib  # noqa: E402

ensure_matplotlib("plot_pileup.py")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.colors import TwoSlopeNorm  # noqa: E402
import numpy as np  # noqa: E402

STAGES = ("max_depth", "unloaded")
STAGE_TITLES = {"max_depth": "at maximum depth", "unloaded": "after unloading"}
MARKERS = ("o", "s", "^", "v", "D", "x")


def read_rows(path, columns):
    """The rows of a CSV file as dicts; checks that the header holds `columns`."""
    with open(path, newline="", encoding="utf-8-sig") as stream:
        reader = csv.DictReader(row for row in stream if not row.lstrip().startswith("#"))
        if reader.fieldnames is None:
            raise ValueError(f"{path}: empty file, expected a header row with {','.join(columns)}")
        missing = [c for c in columns if c not in reader.fieldnames]
        if missing:
            raise ValueError(f"{path}: no column(s) {', '.join(missing)} "
                             f"(columns: {', '.join(reader.fieldnames)})")
        return list(reader)


def number_or_nan(text):
    """An empty cell (no surface there) becomes NaN for plotting."""
    return float(text) if text.strip() else math.nan


def read_grid(path):
    """x [um] (n), y [um] (m) and the height [um] as an m x n array (NaN where empty)."""
    rows = read_rows(path, ("x_um", "y_um", "height_um"))
    x = np.array([float(r["x_um"]) for r in rows])
    y = np.array([float(r["y_um"]) for r in rows])
    h = np.array([number_or_nan(r["height_um"]) for r in rows])
    xs, ys = np.unique(x), np.unique(y)
    if xs.size * ys.size != h.size:
        raise ValueError(f"{path}: {h.size} rows do not form a regular grid "
                         f"({xs.size} x values, {ys.size} y values)")
    grid = np.full((ys.size, xs.size), math.nan)
    grid[np.searchsorted(ys, y), np.searchsorted(xs, x)] = h
    return xs, ys, grid


def plot_map(xs, ys, grid, info, title, output):
    figure, axes = plt.subplots(figsize=(6.4, 5.4), dpi=150)
    finite = grid[np.isfinite(grid)]
    low = float(finite.min()) if finite.size else -1.0
    high = float(finite.max()) if finite.size else 1.0
    # Diverging map centred at h = 0: sink-in/impression blue, pile-up red, each side scaled to
    # its own extreme so that a small pile-up next to a deep impression stays visible.
    norm = TwoSlopeNorm(vcenter=0.0, vmin=min(low, -1e-12), vmax=max(high, 1e-12))
    masked = np.ma.masked_invalid(grid)
    # Gouraud shading shows the piecewise-linear surface as it is; with empty cells (beyond the
    # specimen) each grid point is drawn as a flat cell instead.
    mesh = axes.pcolormesh(xs, ys, masked, cmap="RdBu_r", norm=norm,
                           shading="nearest" if np.ma.is_masked(masked) else "gouraud")
    # Ticks on both sides of 0 (the two halves of the colour bar have different scales).
    ticks = np.unique(np.concatenate([np.linspace(norm.vmin, 0.0, 5),
                                      np.linspace(0.0, norm.vmax, 5)]))
    colorbar = figure.colorbar(mesh, ax=axes, label="height h = u_z [um]", ticks=ticks)
    colorbar.ax.set_yticklabels([f"{t:.3g}" for t in ticks])
    theta = np.linspace(0.0, 2.0 * math.pi, 361)
    for key, style, label in (("contact_radius_um", "--", "contact radius (max depth)"),
                              ("analysis_radius_um", ":", "analysis radius")):
        radius = info.get(key, 0.0)
        if radius > 0:
            axes.plot(radius * np.cos(theta), radius * np.sin(theta), "k" + style,
                      linewidth=0.8, label=f"{label} {radius:.3g} um")
    axes.set_aspect("equal")
    axes.set_xlabel("x [um]")
    axes.set_ylabel("y [um]")
    axes.set_title(f"{title}\n{fold_title(info)}\n"
                   f"max pile-up {info.get('max_pileup_um', 0.0):.4g} um "
                   f"at r = {info.get('max_pileup_radius_um', 0.0):.3g} um, "
                   f"{info.get('max_pileup_azimuth_deg', 0.0):.3g} deg", fontsize="medium")
    axes.legend(fontsize="x-small", loc="upper right")
    figure.tight_layout()
    figure.savefig(output)
    plt.close(figure)
    print(f"wrote {output}")


def fold_title(info):
    """The fold and where it comes from (pileup.json's symmetry_fold and fold_source), e.g.
    "axisymmetric, no fold (4-fold mesh imprint)" for an isotropic material under a cone,
    "3-fold (from the crystal)" for (111).
    """
    fold = info.get("dominant_fold", 0)
    symmetry_fold = info.get("symmetry_fold", fold)
    source = info.get("fold_source")
    if source == "axisymmetric":
        if fold and fold % 4 == 0:
            return f"axisymmetric, no fold ({fold}-fold mesh imprint)"
        return "axisymmetric, no fold"
    if source is None:  # a pileup.json without the source
        text = f"{fold}-fold" if fold else "no dominant fold"
        if symmetry_fold != fold:
            text += f" ({symmetry_fold}-fold beyond the mesh's 4/8-fold imprint)"
        return text
    origin = {"crystal": "from the crystal",
              "indenter": "from the indenter",
              "crystal_or_indenter": "from the crystal or the indenter",
              "mesh_imprint_possible": "may be the square mesh's imprint",
              "numerical": "numerical asymmetry"}.get(source, source)
    return f"{symmetry_fold}-fold ({origin})"


def plot_profiles(path, azimuths, output):
    rows = read_rows(path, ("stage", "azimuth_deg", "r_um", "height_um"))
    figure, axes = plt.subplots(figsize=(6.4, 4.8), dpi=150)
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for s, stage in enumerate(STAGES):
        for a, azimuth in enumerate(azimuths):
            selected = [r for r in rows if r["stage"] == stage
                        and abs(float(r["azimuth_deg"]) - azimuth) < 1e-6]
            if not selected:
                continue
            r = np.array([float(row["r_um"]) for row in selected])
            h = np.array([number_or_nan(row["height_um"]) for row in selected])
            # Markers tell apart profiles that coincide by symmetry (0 and 90 deg, say).
            axes.plot(r, h, color=colours[a % len(colours)], linestyle="--" if s == 0 else "-",
                      linewidth=1.2, marker=MARKERS[a % len(MARKERS)], markersize=3,
                      markevery=(a, max(1, len(r) // 12)),
                      label=f"{azimuth:g} deg, {STAGE_TITLES[stage]}")
    axes.axhline(0.0, color="k", linewidth=0.5)
    axes.set_xlabel("r [um]")
    axes.set_ylabel("height h = u_z [um]")
    axes.set_title("Surface profiles along azimuths")
    axes.grid(True, alpha=0.3)
    axes.legend(fontsize="x-small")
    figure.tight_layout()
    figure.savefig(output)
    plt.close(figure)
    print(f"wrote {output}")


def main(argv=None):
    parser = argparse.ArgumentParser(description="Plot the pile-up maps and profiles of a run.")
    parser.add_argument("directory", help="output directory of `indentsim run`")
    parser.add_argument("-o", "--output", help="where to write the PNG files (default: directory)")
    parser.add_argument("--azimuths", nargs="+", type=float, default=[0.0, 45.0, 90.0, 135.0],
                        help="azimuths [deg] of the profiles to plot (default 0 45 90 135)")
    args = parser.parse_args(argv)
    output = args.output or args.directory

    try:
        with open(os.path.join(args.directory, "pileup.json")) as stream:
            summary = json.load(stream)
        written = 0
        for stage in STAGES:
            grid_path = os.path.join(args.directory, f"pileup_{stage}.csv")
            if stage not in summary or not os.path.exists(grid_path):
                continue
            xs, ys, grid = read_grid(grid_path)
            info = summary[stage]
            title = f"Surface height {STAGE_TITLES[stage]} (depth {info.get('depth_um', 0):.4g} um)"
            plot_map(xs, ys, grid, info, title, os.path.join(output, f"pileup_{stage}.png"))
            written += 1
        if written == 0:
            raise ValueError(f"{args.directory}: no pile-up grid (pileup_max_depth.csv)")
        plot_profiles(os.path.join(args.directory, "pileup_profiles.csv"), args.azimuths,
                      os.path.join(output, "pileup_profiles.png"))
    except (OSError, ValueError, KeyError) as error:
        print(f"plot_pileup.py: {error}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

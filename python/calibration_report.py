#!/usr/bin/env python3
"""Write the report of an `indentsim calibrate` run: report.md and PNG figures.

`indentsim calibrate CONFIG.yaml` calls this script at the end; it can be rerun on its own:

    python3 python/calibration_report.py OUTPUT_DIRECTORY

It reads calibration.json (parameters, errors, correlations, identifiability, misfits, the
minimiser's summary), fit_data<k>.csv (per data set: measured, simulated at the start and at the
fit) and iterations.csv (the history) in OUTPUT_DIRECTORY, and writes there fit_data<k>.png (a
data set against the start and the fit, with the misfit), iterations.png (cost and parameters
per iteration, rejected steps marked) and report.md. A missing fit_data<k>.csv (the forward runs
at the start failed) leaves out its figure with a note. Exit code 0 on success, 1 if
calibration.json is missing or unreadable or a figure could not be drawn.

Units: lengths um (µm in the text), forces mN, stresses GPa, times s.
"""

import argparse
import csv
import json
import math
import os
import sys

try:
    import matplotlib
    import numpy as np
except ImportError:  # another python3 first on PATH: rerun once with the system interpreter
    if os.environ.get("INDENTSIM_PLOT_REEXEC") != "1" and os.path.exists("/usr/bin/python3") \
            and os.path.realpath(sys.executable) != os.path.realpath("/usr/bin/python3"):
        os.environ["INDENTSIM_PLOT_REEXEC"] = "1"
        os.execv("/usr/bin/python3", ["/usr/bin/python3"] + sys.argv)
    sys.exit(f"calibration_report.py: numpy and matplotlib are not installed for this Python "
             f"({sys.executable}); run scripts/install_dependencies.sh")
matplotlib.use("Agg")  # files only, never a display
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.ticker import MaxNLocator  # noqa: E402

DASH = "—"
AXES = {"load_penetration": ("depth [um]", "force [mN]"),
        "pileup_profile": ("radius [um]", "height [um]"),
        "hardness_depth": ("depth [um]", "hardness [GPa]"),
        "tensile": ("log strain [-]", "true stress [GPa]")}


def fmt(value, digits=5):
    """A number with `digits` significant digits; None and non-finite numbers as a dash."""
    if value is None:
        return DASH
    if isinstance(value, bool):
        return "yes" if value else "no"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return f"{value:.{digits}g}" if math.isfinite(value) else DASH
    return str(value)


def fmt_unit(value, unit, digits=4):
    """A number and its unit; a dash alone when there is no number."""
    text = fmt(value, digits)
    return text if text == DASH or not unit else f"{text} {unit}"


def table(header, rows):
    """A Markdown table (cells escaped) and a blank line."""
    def line(cells):
        return "| " + " | ".join(str(c).replace("|", "\\|").replace("\n", " ")
                                 for c in cells) + " |"
    return [line(header), "|" + "---|" * len(header)] + [line(row) for row in rows] + [""]


def read_table(path):
    """Header and columns (numpy arrays, NaN for empty or non-numeric cells) of a CSV file
    whose comment lines start with '#'."""
    with open(path, newline="", encoding="utf-8-sig") as stream:
        lines = [line for line in stream if line.strip() and not line.lstrip().startswith("#")]
    if not lines:
        raise ValueError("no header row")
    header = [name.strip() for name in next(csv.reader(lines[:1]))]
    values = np.genfromtxt(lines[1:], delimiter=",", dtype=float) if lines[1:] else np.empty(0)
    values = values.reshape(-1, len(header))  # ValueError if the rows do not fit the header
    return header, {name: values[:, i] for i, name in enumerate(header)}


def save(figure, directory, name):
    figure.tight_layout()
    figure.savefig(os.path.join(directory, name))
    plt.close(figure)
    return name


def plot_features(directory, entry, index, header, columns):
    """fit_data<k>.png of indentation features: every test's value and the simulated one at the
    start and at the fit, each relative to its feature's mean measured value."""
    feature, measured, start, fitted = (columns[name] for name in header[:4])
    labels = entry.get("features") or []
    figure, axes = plt.subplots(figsize=(6.4, 4.2), dpi=150)
    for k in sorted(set(int(f) for f in feature)):
        rows = feature == k
        mean = np.mean(np.abs(measured[rows]))
        spread = np.linspace(-0.15, 0.15, rows.sum()) if rows.sum() > 1 else np.zeros(1)
        axes.plot(k + spread, measured[rows] / mean, "o", markersize=4, color="k",
                  label="measured (each test)" if k == 0 else None)
        axes.plot(k - 0.3, np.mean(start[rows]) / mean, "s", markersize=6, color="tab:blue",
                  label="simulated at the start" if k == 0 else None)
        axes.plot(k + 0.3, np.mean(fitted[rows]) / mean, "D", markersize=6, color="tab:red",
                  label="fitted" if k == 0 else None)
    axes.axhline(1.0, color="0.6", linewidth=0.8)
    axes.set_xticks(range(len(labels)))
    axes.set_xticklabels([label.replace(" [", "\n[") for label in labels], fontsize="small")
    axes.set_ylabel("value / mean measured value [-]")
    axes.set_title(entry.get("label", f"data[{index}]"), fontsize="medium")
    axes.legend(fontsize="small")
    axes.grid(True, alpha=0.3)
    return save(figure, directory, f"fit_data{index}.png")


def plot_fit(directory, entry, index):
    """fit_data<k>.png of one data set; returns its file name."""
    header, columns = read_table(os.path.join(directory, entry.get("curve")))
    if entry.get("kind") == "indentation_features":
        return plot_features(directory, entry, index, header, columns)
    x_label, y_label = AXES.get(entry.get("kind"), (header[0], "value"))
    x, measured, start, fitted = (columns[name] for name in header[:4])  # may raise ValueError
    if not x.size:
        raise ValueError("no data rows")
    figure, (top, bottom) = plt.subplots(2, 1, sharex=True, figsize=(6.4, 6.0), dpi=150,
                                         gridspec_kw={"height_ratios": [3, 1]})
    top.plot(x, measured, "o", markersize=3, color="k", label="measured")
    top.plot(x, start, "--", linewidth=1.2, color="tab:blue", label="simulated at the start")
    top.plot(x, fitted, "-", linewidth=1.2, color="tab:red", label="fitted")
    top.set_ylabel(y_label)
    top.set_title(entry.get("label", f"data[{index}]"), fontsize="medium")
    top.legend(fontsize="small")
    bottom.axhline(0.0, color="0.6", linewidth=0.8)
    bottom.plot(x, fitted - measured, "o-", markersize=2.5, linewidth=1.0, color="tab:red")
    bottom.set_xlabel(x_label)
    bottom.set_ylabel(f"fit - measured\n[{entry.get('misfit_unit') or '-'}]", fontsize="small")
    for axes in (top, bottom):
        axes.grid(True, alpha=0.3)
    return save(figure, directory, f"fit_data{index}.png")


def plot_iterations(directory, parameters, final_cost):
    """iterations.png: the cost and each parameter (own panel) against the iteration."""
    header, columns = read_table(os.path.join(directory, "iterations.csv"))
    keys = [h for h in header if h not in ("iteration", "cost", "step_accepted",
                                           "forward_runs", "wall_time_s")]
    iteration, accepted = columns["iteration"], columns["step_accepted"] != 0
    figure, axes = plt.subplots(1 + len(keys), 1, sharex=True, dpi=150,
                                figsize=(6.4, 2.8 + 1.6 * len(keys)), squeeze=False)
    axes = axes[:, 0]
    series = [("cost", "cost [-]", final_cost)] + [
        (key, f"{key}\n[{(parameters.get(key) or {}).get('unit', '-')}]",
         (parameters.get(key) or {}).get("value")) for key in keys]
    for panel, (name, label, final) in zip(axes, series):
        values = columns[name]
        panel.plot(iteration[accepted], values[accepted], "o-", markersize=3, linewidth=1.2,
                   color="tab:blue", label="accepted step")
        if (~accepted).any():
            panel.plot(iteration[~accepted], values[~accepted], "x", markersize=6,
                       color="tab:red", label="rejected step")
        if isinstance(final, (int, float)) and math.isfinite(final):
            panel.axhline(final, color="0.5", linestyle="--", linewidth=0.8, label="final value")
        if name == "cost" and (values[np.isfinite(values)] > 0).any():
            panel.set_yscale("log")
        panel.set_ylabel(label, fontsize="small")
        panel.grid(True, alpha=0.3)
    axes[0].set_title("Minimiser history")
    axes[0].legend(fontsize="small")
    axes[-1].set_xlabel("iteration")
    axes[-1].xaxis.set_major_locator(MaxNLocator(integer=True))
    return save(figure, directory, "iterations.png")


def identifiability_section(result):
    lines = ["## Identifiability", ""]
    lines.append("**Identifiable: yes.** The data determine each parameter." if
                 result.get("identifiable") is True else "**Identifiable: NO. The data do not "
                 "determine every parameter on its own: do not trust the single values (see the "
                 "warnings).**")
    lines.append("")
    lines += [f"- {w}" for w in result.get("warnings") or []] or ["- No warnings."]
    return lines + ["", f"Scaled condition number {fmt(result.get('scaled_condition_number'))}, "
                        f"residual variance {fmt(result.get('residual_variance'))}, "
                        f"{fmt(result.get('degrees_of_freedom'))} degrees of freedom.", ""]


def digits_for(value, error):
    """Significant digits that show a value to two digits of its standard error (5 to 10)."""
    try:
        needed = math.ceil(math.log10(abs(value) / error)) + 2
    except (TypeError, ValueError, ZeroDivisionError, OverflowError):
        return 5
    return max(5, min(10, needed))


def parameter_section(parameters):
    rows = []
    for key, p in parameters.items():
        ci = p.get("ci95") or [None, None]
        n = digits_for(p.get("value"), p.get("standard_error"))
        rows.append([f"`{key}`", fmt(p.get("value"), n), p.get("unit", DASH),
                     fmt(p.get("standard_error"), 3), f"[{fmt(ci[0], n)}, {fmt(ci[1], n)}]",
                     fmt(p.get("start")), f"[{fmt(p.get('min'))}, {fmt(p.get('max'))}]"])
    return ["## Parameters", ""] + table(
        ["parameter", "value", "unit", "standard error", "95 % interval", "start", "bounds"],
        rows)


def correlation_section(keys, correlation):
    rows = [[f"`{key}`"] + [fmt(c, 4) for c in (row or [])] for key, row in zip(keys, correlation)]
    if not rows:
        return ["## Correlation", "", "No correlation matrix.", ""]
    return ["## Correlation", ""] + table(["", *(f"`{k}`" for k in keys)], rows)


def data_section(data):
    rows = []
    for k, d in enumerate(data):
        relative = d.get("rms_relative_misfit")
        relative = 100.0 * relative if isinstance(relative, (int, float)) else None
        rows.append([k, d.get("label", DASH), d.get("kind", DASH), fmt(d.get("weight")),
                     fmt(d.get("points")), fmt_unit(d.get("rms_misfit"), d.get("misfit_unit")),
                     fmt_unit(relative, "%")])
    return ["## Data sets", ""] + table(
        ["#", "label", "kind", "weight", "points", "rms misfit", "rms relative misfit"], rows)


def minimiser_section(r):
    return ["## Minimiser", "",
            f"- Iterations: {fmt(r.get('iterations'))}; converged: {fmt(r.get('converged'))}",
            f"- Termination: {r.get('termination') or DASH}",
            f"- Cost (1/2 sum of squared weighted residuals): initial "
            f"{fmt(r.get('initial_cost'))}, final {fmt(r.get('cost'))}",
            f"- Forward runs: {fmt(r.get('forward_runs'))} computed, "
            f"{fmt(r.get('forward_runs_reused'))} reused, "
            f"{fmt(r.get('forward_runs_failed'))} failed, "
            f"{fmt(r.get('forward_runs_warned'))} warned",
            f"- Wall time: {fmt_unit(r.get('wall_time_s'), 's')}", ""]


def figure_link(directory, title, source, draw, problems, missing_note=""):
    """A Markdown link to the figure draw() makes from the file `source`, or why there is none."""
    if not os.path.exists(os.path.join(directory, source)):
        return [f"*{title}: no figure, `{source}` is missing{missing_note}.*", ""]
    try:
        alt = title.replace("[", "\\[").replace("]", "\\]")
        return [f"![{alt}]({draw()})", ""]
    except (OSError, ValueError, KeyError, IndexError) as error:
        problems.append(f"{source}: {error}")
        return [f"*{title}: the figure could not be drawn ({error}).*", ""]


def figure_section(directory, result, problems):
    lines = ["## Figures", ""]
    for k, entry in enumerate(result.get("data") or []):
        entry["curve"] = entry.get("curve") or f"fit_data{k}.csv"
        lines += figure_link(directory, entry.get("label", f"data[{k}]"), entry["curve"],
                             lambda: plot_fit(directory, entry, k), problems,
                             " (the forward runs at the start failed)")
    return lines + figure_link(
        directory, "Minimiser history", "iterations.csv",
        lambda: plot_iterations(directory, result["parameters"], result.get("cost")), problems)


def write_report(directory, result):
    """Draws the figures and writes report.md; returns the problems met."""
    problems = []
    parameters = result["parameters"] = result.get("parameters") or {}
    lines = ["# Calibration report", "",
             "Units: lengths µm, forces mN, stresses GPa, times s. calibration.json: "
             f"*{result.get('units', DASH)}*.",
             "Values and 95 % intervals show 5 significant digits, more (up to 10) where their "
             "standard error needs them.", "",
             f"- Calibration file: `{result.get('calibration_file', DASH)}`",
             f"- Base case: `{result.get('base_case', DASH)}`",
             f"- Software: {result.get('version', DASH)}", ""]
    lines += identifiability_section(result) + parameter_section(parameters)
    lines += correlation_section(list(parameters), result.get("correlation") or [])
    lines += data_section(result.get("data") or []) + minimiser_section(result)
    lines += figure_section(directory, result, problems)
    with open(os.path.join(directory, "report.md"), "w", encoding="utf-8") as stream:
        stream.write("\n".join(lines).rstrip() + "\n")
    return problems


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Write report.md and the figures of an `indentsim calibrate` run.")
    parser.add_argument("directory", help="the calibration's output directory")
    args = parser.parse_args(argv)
    path = os.path.join(args.directory, "calibration.json")
    try:
        with open(path, encoding="utf-8") as stream:
            result = json.load(stream)
        if not isinstance(result, dict):
            raise ValueError("not a JSON object")
    except (OSError, ValueError) as error:
        print(f"calibration_report.py: cannot read {path}: {error}", file=sys.stderr)
        return 1
    try:
        problems = write_report(args.directory, result)
    except OSError as error:
        print(f"calibration_report.py: cannot write the report: {error}", file=sys.stderr)
        return 1
    print(f"wrote {os.path.join(args.directory, 'report.md')}")
    for problem in problems:
        print(f"calibration_report.py: {problem}", file=sys.stderr)
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())

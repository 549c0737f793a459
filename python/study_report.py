#!/usr/bin/env python3
"""Write the report of an `indentsim study` run: report.md, report.html and PNG figures.

`indentsim study STUDY.yaml` calls this script at the end; it can be rerun on its own:

    python3 python/study_report.py OUTPUT_DIRECTORY

It reads OUTPUT_DIRECTORY/study.json (written by the study runner: the cases, their groups,
keys, directories and status, and the report settings) and, for every finished case, the run's
own files in OUTPUT_DIRECTORY/cases/<name>-<key>/ (run_summary.json, load_penetration.csv,
stress_strain.csv, stress_strain_j2.csv, pileup.json, pileup_*.png, study_case.json). It writes

    report.md, report.html            the report (the HTML is rendered from the Markdown here)
    figures/tensile.png               true stress against log strain: crystal per seed and J2
    figures/mesh_<group>.png          load-penetration curves per mesh
    figures/mesh_force.png            force at maximum depth against element size h
    figures/orientations.png          load-penetration curves per orientation
    figures/irradiation_<kind>.png    hardness against depth, its ratio to the pristine case, the
                                      Nix-Gao plots and the plastic zone's share in the layer

Sections: the cases; the tensile calibration (stress at the report's strains, the spread over
the orientation seeds); the mesh convergence (force at maximum depth per mesh, observed order
and Richardson extrapolation); the orientations (spread of the force); the pile-up (fold and
height from pileup.json, maps); the paper's numbers beside ours; the Oliver-Pharr analysis; the
irradiated layer against the pristine metal (groups irradiation_j2 and irradiation_crystal, the
first case of each the pristine reference: hardness_depth.csv/json and the plastic-zone columns
of load_penetration.csv); how to reproduce. A section whose cases are missing says so.

The numbers (observed order, Richardson extrapolation, grid convergence index, interpolation)
are plain Python functions, tested by tests/unit/python/test_study_report.py.

Units: lengths um (µm in the text), forces mN, stresses GPa, times s.
"""

import csv
import datetime
import html
import json
import math
import os
import re
import sys

# ---------------------------------------------------------------------------------------------
# Numbers.


def observed_order(h, f, p_max=50.0):
    """Observed order of convergence p from three meshes.

    h: element sizes, coarse to fine (h1 > h2 > h3); f: the values on them. For an error
    f_h = f_0 + C h^p the differences obey (f1 - f2) / (f2 - f3) = (h1^p - h2^p) / (h2^p - h3^p),
    which is r^p for a constant refinement ratio r = h1/h2 = h2/h3 (p = ln R / ln r) and is solved
    for p by bisection otherwise (the right side increases with p, Celik et al. 2008).
    Returns (p, None), or (None, reason) when the sequence does not converge monotonically.
    """
    h1, h2, h3 = (float(v) for v in h)
    f1, f2, f3 = (float(v) for v in f)
    if not (h1 > h2 > h3 > 0.0):
        raise ValueError(f"element sizes must decrease: {h}")
    if f2 == f3 or f1 == f2:
        return None, "two meshes give the same value"
    ratio = (f1 - f2) / (f2 - f3)
    if ratio <= 0.0:
        return None, "the differences change sign (oscillatory convergence)"

    def ratio_of(p):
        return (h1 ** p - h2 ** p) / (h2 ** p - h3 ** p)

    a, b = h1 / h2, h2 / h3
    if abs(a - b) <= 1e-12 * b:
        p = math.log(ratio) / math.log(a)
        return (p, None) if p > 0.0 else (None, "the differences grow (no convergence)")
    lower = math.log(a) / math.log(b)  # the limit of ratio_of(p) for p -> 0
    if ratio <= lower:
        return None, "the differences do not shrink fast enough (p <= 0, no convergence)"
    if ratio >= ratio_of(p_max):
        return None, f"observed order above {p_max:g}"
    low, high = 1e-9, p_max
    for _ in range(200):
        middle = 0.5 * (low + high)
        if ratio_of(middle) < ratio:
            low = middle
        else:
            high = middle
    return 0.5 * (low + high), None


def richardson_extrapolation(h, f, p):
    """Richardson-extrapolated value from the two finest of three meshes (h decreasing):
    f_0 = f3 + (f3 - f2) / ((h2 / h3)^p - 1)."""
    h2, h3 = float(h[-2]), float(h[-1])
    f2, f3 = float(f[-2]), float(f[-1])
    return f3 + (f3 - f2) / ((h2 / h3) ** p - 1.0)


def grid_convergence_index(h, f, p, safety_factor=1.25):
    """Roache's grid convergence index of the finest mesh, relative:
    GCI = F_s |(f3 - f2) / f3| / ((h2 / h3)^p - 1)."""
    h2, h3 = float(h[-2]), float(h[-1])
    f2, f3 = float(f[-2]), float(f[-1])
    return safety_factor * abs((f3 - f2) / f3) / ((h2 / h3) ** p - 1.0)


def interpolate(x, xs, ys):
    """Linear interpolation of ys(xs) at x (xs increasing); None outside the range."""
    if not xs or x < xs[0] or x > xs[-1]:
        return None
    for i in range(1, len(xs)):
        if x <= xs[i]:
            if xs[i] == xs[i - 1]:
                return ys[i]
            t = (x - xs[i - 1]) / (xs[i] - xs[i - 1])
            return ys[i - 1] + t * (ys[i] - ys[i - 1])
    return ys[-1]


def depth_at_force(depth, force, target):
    """The depth at which the force first reaches `target`, interpolated linearly between the
    two rows around it; None if it never does. Pass the loading branch only."""
    for i in range(1, len(force)):
        if force[i - 1] < target <= force[i]:
            t = (target - force[i - 1]) / (force[i] - force[i - 1])
            return depth[i - 1] + t * (depth[i] - depth[i - 1])
    if force and force[0] >= target:
        return depth[0]
    return None


def curve_difference(depth_ref, force_ref, depth, force):
    """How far a load-penetration curve lies from a reference curve: (RMS, largest |difference|,
    number of points) of force(d) - force_ref(d) over the reference's points d inside both depth
    ranges, force(d) interpolated linearly; (None, None, 0) if they do not overlap. Pass loading
    branches (depth increasing). Units of the forces."""
    differences = []
    for d, f_ref in zip(depth_ref, force_ref):
        f = interpolate(d, depth, force)
        if f is not None:
            differences.append(f - f_ref)
    if not differences:
        return None, None, 0
    rms = math.sqrt(sum(x * x for x in differences) / len(differences))
    return rms, max(abs(x) for x in differences), len(differences)


def spread(values):
    """(smallest, largest, mean, (largest - smallest) / mean) of a list of numbers."""
    smallest, largest = min(values), max(values)
    mean = sum(values) / len(values)
    return smallest, largest, mean, (largest - smallest) / mean if mean != 0.0 else float("nan")


def constant_ratio_triples(h):
    """Index triples (i, j, k), h decreasing, with h_i / h_j = h_j / h_k (to 1e-9)."""
    triples = []
    n = len(h)
    for i in range(n):
        for j in range(i + 1, n):
            for k in range(j + 1, n):
                if abs(h[i] / h[j] - h[j] / h[k]) <= 1e-9 * h[i] / h[j]:
                    triples.append((i, j, k))
    return triples


# ---------------------------------------------------------------------------------------------
# Markdown to HTML: the subset this report writes (headings, paragraphs, lists, tables, images,
# links, code, bold, code blocks).


def _inline(text):
    text = html.escape(text, quote=False)
    parts = re.split(r"(`[^`]*`)", text)
    out = []
    for part in parts:
        if part.startswith("`") and part.endswith("`") and len(part) >= 2:
            out.append("<code>" + part[1:-1] + "</code>")
            continue
        part = re.sub(r"!\[([^\]]*)\]\(([^)]+)\)",
                      lambda m: f'<img src="{m.group(2)}" alt="{m.group(1)}">', part)
        part = re.sub(r"\[([^\]]+)\]\(([^)]+)\)",
                      lambda m: f'<a href="{m.group(2)}">{m.group(1)}</a>', part)
        part = re.sub(r"\*\*([^*]+)\*\*", r"<strong>\1</strong>", part)
        out.append(part)
    return "".join(out)


def _table_cells(line):
    line = line.strip()
    if line.startswith("|"):
        line = line[1:]
    if line.endswith("|"):
        line = line[:-1]
    return [cell.strip() for cell in line.split("|")]


def markdown_to_html(markdown, title):
    lines = markdown.split("\n")
    body = []
    paragraph = []
    i = 0

    def flush_paragraph():
        if paragraph:
            body.append("<p>" + _inline(" ".join(paragraph)) + "</p>")
            paragraph.clear()

    while i < len(lines):
        line = lines[i]
        stripped = line.strip()
        if stripped.startswith("```"):
            flush_paragraph()
            block = []
            i += 1
            while i < len(lines) and not lines[i].strip().startswith("```"):
                block.append(html.escape(lines[i], quote=False))
                i += 1
            body.append("<pre><code>" + "\n".join(block) + "</code></pre>")
        elif stripped.startswith("#"):
            flush_paragraph()
            level = len(stripped) - len(stripped.lstrip("#"))
            body.append(f"<h{level}>" + _inline(stripped[level:].strip()) + f"</h{level}>")
        elif stripped.startswith("|"):
            flush_paragraph()
            rows = []
            while i < len(lines) and lines[i].strip().startswith("|"):
                rows.append(_table_cells(lines[i]))
                i += 1
            i -= 1
            body.append("<table>")
            for index, cells in enumerate(rows):
                if index == 1 and all(re.fullmatch(r":?-+:?", c) for c in cells):
                    continue
                tag = "th" if index == 0 else "td"
                body.append("<tr>" + "".join(f"<{tag}>{_inline(c)}</{tag}>" for c in cells)
                            + "</tr>")
            body.append("</table>")
        elif stripped.startswith("- "):
            flush_paragraph()
            body.append("<ul>")
            while i < len(lines) and lines[i].strip().startswith("- "):
                body.append("<li>" + _inline(lines[i].strip()[2:]) + "</li>")
                i += 1
            i -= 1
            body.append("</ul>")
        elif not stripped:
            flush_paragraph()
        else:
            paragraph.append(stripped)
        i += 1
    flush_paragraph()
    style = ("body{font-family:sans-serif;max-width:70em;margin:2em auto;padding:0 1em;}"
             "table{border-collapse:collapse;margin:0.5em 0;}"
             "td,th{border:1px solid #bbb;padding:0.2em 0.5em;text-align:left;}"
             "th{background:#eee;}img{max-width:48%;margin:0.2em;}"
             "pre{background:#f4f4f4;padding:0.5em;overflow-x:auto;}")
    return ("<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" +
            html.escape(title) + "</title><style>" + style + "</style></head><body>\n" +
            "\n".join(body) + "\n</body></html>\n")


# ---------------------------------------------------------------------------------------------
# Reading the cases.


def read_json(path):
    with open(path) as stream:
        return json.load(stream)


def read_columns(path, numeric, text=()):
    """Columns of a CSV file: numbers for `numeric`, strings for `text` (missing: absent)."""
    with open(path, newline="", encoding="utf-8-sig") as stream:
        rows = [row for row in stream if not row.lstrip().startswith("#")]
    reader = csv.DictReader(rows)
    fields = [name.strip() for name in (reader.fieldnames or [])]
    reader.fieldnames = fields
    for column in numeric:
        if column not in fields:
            raise ValueError(f"{path}: no column '{column}' (columns: {', '.join(fields)})")
    columns = {name: [] for name in list(numeric) + [t for t in text if t in fields]}
    for row in reader:
        for name in numeric:
            columns[name].append(float(row[name]))
        for name in text:
            if name in fields:
                columns[name].append(row[name].strip())
    return columns


def format_number(value, digits=1):
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "–"
    return f"{value:.{digits}f}"


def format_percent(value, digits=2):
    return "–" if value is None else f"{100.0 * value:+.{digits}f} %"


def orientation_name(case):
    orientation = case.get("orientation", {})

    def index_text(values):
        numbers = [int(round(v)) if abs(v - round(v)) < 1e-9 else v for v in values]
        if all(isinstance(n, int) and abs(n) < 10 and n >= 0 for n in numbers):
            return "".join(str(n) for n in numbers)
        return ",".join(str(n) for n in numbers)

    if "surface_normal" in orientation:
        return (f"({index_text(orientation['surface_normal'])}) "
                f"[{index_text(orientation['reference_direction'])}] along x")
    angles = orientation.get("euler_bunge_deg", [0, 0, 0])
    return "Euler (" + ", ".join(f"{a:g}" for a in angles) + ") deg"


class StudyData:
    """study.json plus the files of the finished cases."""

    def __init__(self, directory):
        self.directory = directory
        self.index = read_json(os.path.join(directory, "study.json"))
        self.settings = self.index.get("report", {})
        self.cases = self.index["cases"]
        for case in self.cases:
            case["path"] = os.path.join(directory, case["directory"])
            case["summary"] = self._json(case, "run_summary.json")
            case["mark"] = self._json(case, "study_case.json")
            case["pileup"] = self._json(case, "pileup.json")
            case["oliver_pharr"] = self._json(case, "oliver_pharr.json")
            case["experiment"] = self._json(case, "comparison_with_experiment.json")
            refined_x = case.get("refined_region_um", [0.0])[0]
            n = case.get("contact_elements", 0)
            case["h_um"] = refined_x / n if n else float("nan")

    @staticmethod
    def _json(case, name):
        path = os.path.join(case["path"], name)
        try:
            return read_json(path) if os.path.exists(path) else None
        except (OSError, ValueError):
            return None

    def finished(self, group):
        return [c for c in self.cases if group in c["groups"] and c["status"] == "finished"]

    def missing(self, group):
        return [c for c in self.cases if group in c["groups"] and c["status"] != "finished"]

    @staticmethod
    def force_at_max_depth(case):
        summary = case.get("summary") or {}
        return summary.get("force_at_max_depth_mN")

    def load_curve(self, case):
        """Depth [um], force [mN] and the loading-branch flags of a finished indentation."""
        columns = read_columns(os.path.join(case["path"], "load_penetration.csv"),
                               ("depth_um", "force_mN"), ("segment", "cycle"))
        depth, force = columns["depth_um"], columns["force_mN"]
        if "segment" in columns:
            loading = [s in ("start", "load") and c in ("0", "1")
                       for s, c in zip(columns["segment"], columns.get("cycle", ["1"] * len(depth)))]
        else:
            peak = depth.index(max(depth)) if depth else 0
            loading = [i <= peak for i in range(len(depth))]
        return depth, force, loading


# ---------------------------------------------------------------------------------------------
# The report.


class Report:
    def __init__(self, data, plt):
        self.data = data
        self.plt = plt
        self.lines = []
        self.figures = os.path.join(data.directory, "figures")
        os.makedirs(self.figures, exist_ok=True)
        self.problems = []

    def add(self, *lines):
        self.lines.extend(lines)

    def table(self, header, rows):
        self.add("| " + " | ".join(header) + " |", "|" + "---|" * len(header))
        for row in rows:
            self.add("| " + " | ".join(str(cell) for cell in row) + " |")
        self.add("")

    def figure(self, figure, name, caption):
        path = os.path.join(self.figures, name)
        figure.tight_layout()
        figure.savefig(path)
        self.plt.close(figure)
        self.add(f"![{name}](figures/{name})", "", caption, "")

    def missing_note(self, group, what):
        missing = self.data.missing(group)
        if missing:
            self.add("Not (yet) available for " + what + ": " +
                     ", ".join(f"`{c['name']}` ({c['status']})" for c in missing) + ".", "")

    def case_link(self, case):
        if os.path.isdir(case["path"]):
            return f"[{case['name']}]({case['directory']}/)"
        return case["name"]

    # -- sections --------------------------------------------------------------------------

    def header(self):
        index = self.data.index
        self.add(f"# {self.data.settings.get('title', 'indentsim study')}", "",
                 "**Units: lengths µm, forces mN, stresses GPa (1 GPa·µm² = 1 mN), times s.**",
                 "",
                 f"Study file: `{index['study_file']}` (copy: [study.yaml](study.yaml)); "
                 f"software: `{index['version']}`; report written "
                 f"{datetime.datetime.now().strftime('%Y-%m-%d %H:%M')}.", "")

    def cases_section(self):
        self.add("## Cases", "",
                 "Each case is the base case file with the study's overrides; its directory "
                 "`cases/<name>-<key>/` is named by the hash of its resolved case "
                 "(`resolved_case.yaml` there; `console.log` holds the run's output). "
                 "Wall time as measured by the study (whole process, plots included). "
                 "Warnings: the topics of the run's warnings (their texts are in the case's "
                 "`run_summary.json` and `run.log`).", "")
        rows = []
        for case in self.data.cases:
            mark = case.get("mark") or {}
            summary = case.get("summary") or {}
            resolved = os.path.join(case["directory"], "resolved_case.yaml")
            rows.append([
                self.case_link(case), case["label"], ", ".join(case["groups"]) or "–",
                f"`{case['key']}`",
                case["status"] + (" (run now)" if case.get("ran_now") else
                                  " (earlier run)" if case["status"] == "finished" else ""),
                summary.get("dofs", "–"), summary.get("mpi_ranks", "–"),
                format_number(mark.get("wall_time_s"), 1),
                ", ".join(f"`{w['topic']}`" for w in summary.get("warnings", [])) or "–",
                f"[resolved_case.yaml]({resolved})" if os.path.exists(
                    os.path.join(self.data.directory, resolved)) else "–"])
        self.table(["case", "label", "groups", "key", "status", "DOFs", "MPI ranks",
                    "wall time [s]", "warnings", "resolved case"], rows)

    def tensile_section(self):
        self.add("## 1. Tensile calibration (Table 1 against Table 2, Fig. 3)", "")
        cases = self.data.finished("tensile")
        self.missing_note("tensile", "the tensile calibration")
        if not cases:
            self.add("No finished tensile case: this section is empty.", "")
            return
        from plot_stress_strain import read_curve  # noqa: E402 (needs matplotlib)
        curves = []
        j2 = None
        for case in cases:
            path = os.path.join(case["path"], "stress_strain.csv")
            strain, stress = read_curve(path)
            curves.append((case, list(strain), list(stress)))
            j2_path = os.path.join(case["path"], "stress_strain_j2.csv")
            if j2 is None and os.path.exists(j2_path):
                j2_strain, j2_stress = read_curve(j2_path)
                j2 = (case, list(j2_strain), list(j2_stress))

        figure, axes = self.plt.subplots(figsize=(6.4, 4.8), dpi=150)
        for case, strain, stress in curves:
            label = case["label"] if case["label"] != case["name"] else \
                f"{case['model']}, seed {case['seed']}"
            axes.plot(strain, stress, linewidth=1.0, label=label)
        if j2 is not None:
            axes.plot(j2[1], j2[2], "k--", linewidth=1.8, label="J2 (Table 1)")
        axes.set_xlabel("logarithmic strain [-]")
        axes.set_ylabel("true stress [GPa]")
        axes.set_xlim(left=0.0)
        axes.set_ylim(bottom=0.0)
        axes.grid(True, alpha=0.3)
        axes.legend(fontsize="x-small")
        self.figure(figure, "tensile.png",
                    "Tensile calibration: true stress [GPa] against logarithmic strain; "
                    "crystal plasticity per orientation seed and J2.")

        strains = self.data.settings.get("tensile_strains", [0.02, 0.05, 0.1, 0.2])
        header = ["log strain", "J2 [GPa]"] + [f"{c['label']} [GPa]" for c, _, _ in curves] + \
                 ["crystal mean [GPa]", "mean vs J2", "crystal range [GPa]", "spread ±"]
        rows = []
        for eps in strains:
            values = [interpolate(eps, s, t) for _, s, t in curves]
            present = [v for v in values if v is not None]
            j2_value = interpolate(eps, j2[1], j2[2]) if j2 is not None else None
            row = [f"{eps:g}", format_number(j2_value, 3)] + [format_number(v, 3) for v in values]
            if present:
                low, high, mean, relative = spread(present)
                row += [format_number(mean, 3),
                        format_percent((mean - j2_value) / j2_value, 1) if j2_value else "–",
                        f"{low:.3f}–{high:.3f}", f"{50.0 * relative:.1f} %"]
            else:
                row += ["–"] * 4
            rows.append(row)
        self.table(header, rows)
        self.add(f"{len(curves)} crystal run(s); spread ± = half the range over the mean. "
                 + ("J2 from the compare_j2 run of `" + j2[0]["name"] + "`." if j2 is not None
                    else "No case has compare_j2: true, so no J2 curve."), "")

    def mesh_section(self):
        self.add("## 2. Mesh convergence of the load–penetration curve (Fig. 5)", "")
        self.convergence = {}
        force_figure, force_axes = self.plt.subplots(figsize=(6.4, 4.8), dpi=150)
        any_force = False
        for group, title in (("mesh_j2", "J2 (Table 1)"), ("mesh_crystal", "crystal plasticity")):
            self.add(f"### {title} (`{group}`)", "")
            self.missing_note(group, title)
            cases = sorted(self.data.finished(group), key=lambda c: c["contact_elements"])
            if not cases:
                self.add("No finished case: nothing to show.", "")
                continue
            figure, axes = self.plt.subplots(figsize=(6.4, 4.8), dpi=150)
            for case in cases:
                depth, force, _ = self.data.load_curve(case)
                axes.plot(depth, force, linewidth=1.1,
                          label=f"{case['contact_elements']}×{case['contact_elements']} "
                                f"({case['symmetry']})")
            axes.set_xlabel("depth [µm]")
            axes.set_ylabel("force [mN]")
            axes.set_title(title)
            axes.set_xlim(left=0.0)
            axes.set_ylim(bottom=0.0)
            axes.grid(True, alpha=0.3)
            axes.legend(fontsize="small", title="contact elements")
            self.figure(figure, f"{group}.png",
                        f"Load–penetration curves of {title} per mesh (force [mN] against "
                        f"depth [µm]).")

            finest = cases[-1]
            finest_depth, finest_force = self.loading_branch(finest)
            finest_max = max(finest_force) if finest_force else None
            rows, previous = [], None
            for case in cases:
                f = self.data.force_at_max_depth(case)
                rms, largest, n = curve_difference(finest_depth, finest_force,
                                                   *self.loading_branch(case))
                rows.append([f"{case['contact_elements']}×{case['contact_elements']}",
                             format_number(case["h_um"], 3), case["symmetry"],
                             f"{case['max_depth_um']:g}", (case["summary"] or {}).get("dofs", "–"),
                             format_number(f, 1),
                             format_percent((f - previous) / previous, 2)
                             if previous and f is not None else "–",
                             "–" if case is finest or rms is None else
                             f"{rms:.1f} ({100.0 * rms / finest_max:.1f} %) / {largest:.1f}"])
                previous = f
            self.table(["contact elements", "h [µm]", "symmetry", "max depth [µm]", "DOFs",
                        "force at max depth [mN]", "change vs previous mesh",
                        f"loading curve vs {finest['contact_elements']}×"
                        f"{finest['contact_elements']}: RMS (/ its max force) / largest [mN]"],
                       rows)
            self.add("Node-to-surface contact makes each curve a sawtooth: the force rises "
                     "faster each time a new ring of nodes touches the indenter, so the force "
                     "at one depth depends on where that depth falls between two ring entries "
                     "(the rings are h apart; see the `n_active_nodes` column of each "
                     "`load_penetration.csv`). The last column compares whole loading curves "
                     "(the finest curve's points, the coarser curve interpolated linearly), "
                     "which that timing affects far less than the force at one depth.", "")

            h = [c["h_um"] for c in cases]
            f = [self.data.force_at_max_depth(c) for c in cases]
            force_axes.plot(h, f, "o-", label=title)
            any_force = True
            result = self.convergence_table(h, f, cases)
            self.convergence[group] = result
            if result and result.get("extrapolated") is not None:
                force_axes.plot([0.0], [result["extrapolated"]], "x", markersize=9,
                                label=f"{title}, Richardson")
        if any_force:
            force_axes.set_xlabel("contact element size h [µm]")
            force_axes.set_ylabel("force at maximum depth [mN]")
            force_axes.set_xlim(left=0.0)
            force_axes.grid(True, alpha=0.3)
            force_axes.legend(fontsize="small")
            self.figure(force_figure, "mesh_force.png",
                        "Force at maximum depth [mN] against the contact element size h [µm]; "
                        "crosses: Richardson-extrapolated values (h → 0).")
        else:
            self.plt.close(force_figure)

    def loading_branch(self, case):
        """Depth [um] and force [mN] of the loading rows of a finished indentation."""
        depth, force, loading = self.data.load_curve(case)
        return ([d for d, keep in zip(depth, loading) if keep],
                [f for f, keep in zip(force, loading) if keep])

    def convergence_table(self, h, f, cases):
        """Observed order and extrapolation: the three finest meshes (any ratios) and every
        constant-ratio triple. Returns the finest triple's result."""
        if len(cases) < 3:
            self.add(f"{len(cases)} mesh(es): the observed order needs three.", "")
            return None
        triples = [(len(h) - 3, len(h) - 2, len(h) - 1)]
        for triple in constant_ratio_triples(h):
            if triple not in triples:
                triples.append(triple)
        rows, finest = [], None
        for triple in triples:
            hs = [h[i] for i in triple]
            fs = [f[i] for i in triple]
            meshes = ", ".join(str(cases[i]["contact_elements"]) for i in triple)
            ratios = f"{hs[0] / hs[1]:g}, {hs[1] / hs[2]:g}"
            p, reason = observed_order(hs, fs)
            if p is None:
                rows.append([meshes, ratios, "–", "–", "–", reason])
                result = {"meshes": meshes, "p": None, "extrapolated": None, "reason": reason}
            else:
                extrapolated = richardson_extrapolation(hs, fs, p)
                gci = grid_convergence_index(hs, fs, p)
                rows.append([meshes, ratios, f"{p:.2f}", format_number(extrapolated, 1),
                             f"{100.0 * gci:.2f} %", ""])
                result = {"meshes": meshes, "p": p, "extrapolated": extrapolated, "gci": gci}
            if finest is None:
                finest = result
        self.table(["meshes (contact elements)", "refinement ratios h1/h2, h2/h3",
                    "observed order p", "Richardson-extrapolated force [mN]",
                    "GCI of the finest mesh", "note"], rows)
        self.add("p solves (F1 − F2)/(F2 − F3) = (h1^p − h2^p)/(h2^p − h3^p) (for a constant "
                 "ratio r: p = ln((F1 − F2)/(F2 − F3))/ln r); the extrapolation is "
                 "F3 + (F3 − F2)/((h2/h3)^p − 1); GCI = 1.25 |(F3 − F2)/F3|/((h2/h3)^p − 1) "
                 "(Roache). The first row uses the three finest meshes whatever their ratios "
                 "(48 → 72 is 1.5), the others the triples of constant ratio.", "")
        return finest

    def orientation_section(self):
        self.add("## 3. Orientations (Fig. 6)", "")
        self.missing_note("orientation", "the orientations")
        cases = sorted(self.data.finished("orientation"),
                       key=lambda c: (c["contact_elements"], orientation_name(c)))
        if not cases:
            self.add("No finished orientation case: nothing to show.", "")
            return
        figure, axes = self.plt.subplots(figsize=(6.4, 4.8), dpi=150)
        styles = ["-", "--", ":", "-."]
        meshes = sorted({c["contact_elements"] for c in cases})
        for case in cases:
            depth, force, _ = self.data.load_curve(case)
            axes.plot(depth, force, styles[meshes.index(case["contact_elements"]) % 4],
                      linewidth=1.1, label=case["label"])
        axes.set_xlabel("depth [µm]")
        axes.set_ylabel("force [mN]")
        axes.set_xlim(left=0.0)
        axes.set_ylim(bottom=0.0)
        axes.grid(True, alpha=0.3)
        axes.legend(fontsize="x-small")
        self.figure(figure, "orientations.png",
                    "Load–penetration curves per crystal orientation (force [mN] against depth "
                    "[µm]); line style by mesh.")
        rows = []
        for n in meshes:
            group = [c for c in cases if c["contact_elements"] == n]
            forces = []
            for case in group:
                force = self.data.force_at_max_depth(case)
                rows.append([f"{n}×{n}", orientation_name(case), case["label"], case["symmetry"],
                             format_number(force, 1)])
                if force is not None:
                    forces.append(force)
            if len(forces) >= 2:
                low, high, mean, relative = spread(forces)
                rows.append([f"{n}×{n}", "**spread**", f"{len(forces)} orientations", "",
                             f"{low:.1f}–{high:.1f} (mean {mean:.1f}, (max − min)/mean "
                             f"{100.0 * relative:.1f} %)"])
        self.table(["mesh", "orientation (plane, direction along x)", "case", "symmetry",
                    "force at max depth [mN]"], rows)

    def pileup_section(self):
        self.add("## 4. Pile-up at maximum depth and after unloading (Fig. 7)", "")
        cases = sorted([c for c in self.data.finished("orientation")],
                       key=lambda c: (orientation_name(c), c["contact_elements"]))
        if not cases:
            self.add("No finished orientation case: no pile-up maps.", "")
            return
        rows = []
        for case in cases:
            pileup = case.get("pileup")
            if not pileup:
                rows.append([case["name"], "–", "no pileup.json", "", "", "", ""])
                continue
            for stage in ("max_depth", "unloaded"):
                s = pileup.get(stage)
                if not s:
                    continue
                rows.append([case["label"], f"{case['contact_elements']}×{case['contact_elements']}",
                             stage.replace("_", " "), s.get("dominant_fold", "–"),
                             s.get("symmetry_fold", "–"), format_number(s.get("max_pileup_um"), 3),
                             f"{s.get('max_pileup_radius_um', float('nan')):.1f} / "
                             f"{s.get('max_pileup_azimuth_deg', float('nan')):.0f}"])
        self.table(["case", "mesh", "stage", "dominant fold", "symmetry fold",
                    "max pile-up [µm]", "at radius [µm] / azimuth [deg]"], rows)
        self.add("Dominant fold: the largest Fourier harmonic k ≥ 2 of the height on the crest "
                 "circle; symmetry fold: the largest one a square mesh cannot produce (not a "
                 "multiple of 4), when significant (see the README, Pile-up). The paper "
                 "reports 4, 2 and 3 for (001), (011) and (111).", "")
        finest = {}
        for case in cases:
            name = orientation_name(case)
            if name not in finest or case["contact_elements"] > finest[name]["contact_elements"]:
                finest[name] = case
        for name, case in finest.items():
            self.add(f"**{case['label']}** ({name}, {case['contact_elements']}×"
                     f"{case['contact_elements']}), height [µm] at maximum depth and after "
                     "unloading:", "")
            images = []
            for stage in ("max_depth", "unloaded"):
                image = f"{case['directory']}/pileup_{stage}.png"
                if os.path.exists(os.path.join(self.data.directory, image)):
                    images.append(f"![{case['label']}, {stage.replace('_', ' ')}]({image})")
            self.add(" ".join(images) if images else "(no pile-up maps)", "")

    def paper_section(self):
        settings = self.data.settings
        self.add("## 5. The paper's numbers beside ours", "")
        paper = settings.get("paper_forces_mN", {})
        paper_depth = settings.get("paper_max_depth_um", 0.0)
        rows = []
        titles = {"mesh_j2": "J2", "mesh_crystal": "crystal"}
        for group in ("mesh_j2", "mesh_crystal"):
            cases = {c["contact_elements"]: c for c in self.data.finished(group)}
            listed = {c["contact_elements"] for c in self.data.cases if group in c["groups"]}
            for elements, value in sorted(paper.get(group, {}).items(), key=lambda e: int(e[0])):
                n = int(elements)
                case = cases.get(n)
                ours = self.data.force_at_max_depth(case) if case else None
                absent = "not finished" if n in listed else "not in this study"
                rows.append([f"{titles[group]}, {n}×{n}", format_number(value, 1),
                             format_number(ours, 1) if ours is not None else absent,
                             format_percent((ours - value) / value, 2) if ours else "–",
                             f"{case['max_depth_um']:g}" if case else "–"])
            result = getattr(self, "convergence", {}).get(group)
            if paper.get(group) and result and result.get("extrapolated") is not None:
                finest_paper = paper[group][max(paper[group], key=int)]
                extrapolated = result["extrapolated"]
                rows.append([f"{titles[group]}, Richardson-extrapolated ({result['meshes']}) "
                             f"vs the paper's finest", format_number(finest_paper, 1),
                             format_number(extrapolated, 1),
                             format_percent((extrapolated - finest_paper) / finest_paper, 2), ""])
        if rows:
            self.table(["force at maximum depth", "paper [mN]", "ours [mN]", "ours vs paper",
                        "our max depth [µm]"], rows)
        else:
            self.add("The study lists no paper values (report.paper_forces_mN).", "")
        if paper_depth:
            self.add(f"The paper's values are taken at a maximum depth of {paper_depth:g} µm.", "")
        if settings.get("paper_note"):
            self.add(settings["paper_note"], "")

        target = settings.get("depth_at_force_mN", 0.0)
        if target:
            cases = sorted(self.data.finished("mesh_j2"), key=lambda c: c["contact_elements"])
            if not cases:
                self.add(f"Depth at {target:g} mN: no finished J2 mesh case.", "")
                return
            case = cases[-1]
            branch_depth, branch_force = self.loading_branch(case)
            reached = depth_at_force(branch_depth, branch_force, target)
            mesh = f"{case['contact_elements']}×{case['contact_elements']}"
            if reached is None:
                self.add(f"Our finest J2 curve (`{case['name']}`, {mesh}) does not reach "
                         f"{target:g} mN on loading (largest force "
                         f"{max(branch_force):.1f} mN at {max(branch_depth):g} µm).", "")
            else:
                self.add(f"Our finest J2 curve (`{case['name']}`, {mesh}) reaches **{target:g} mN "
                         f"at a depth of {reached:.3f} µm** on loading (interpolated linearly "
                         f"between the load steps).", "")

    def analysis_section(self):
        """Oliver-Pharr results of every finished indentation and the deviation from measured
        curves (cases with output.experimental_curve)."""
        self.add("## 6. Oliver–Pharr analysis and measured curves", "")
        cases = [c for c in self.data.cases if c["status"] == "finished" and c.get("oliver_pharr")]
        if cases:
            rows = []
            for case in cases:
                op = case["oliver_pharr"]
                error = op.get("area_error_percent")
                rows.append([case["label"], format_number(op.get("max_force_mN"), 1),
                             format_number(op.get("stiffness_mN_per_um"), 0),
                             format_number(op.get("contact_depth_um"), 3),
                             format_number(op.get("hardness_GPa"), 3),
                             format_number(op.get("reduced_modulus_GPa"), 1),
                             format_number(op.get("true_hardness_GPa"), 3),
                             f"{error:+.1f} %" if error is not None else "–",
                             format_number(op.get("residual_depth_ratio"), 3),
                             format_number(op.get("plastic_work_ratio"), 3)])
            self.table(["case", "P_max [mN]", "S [mN/µm]", "h_c [µm]", "H [GPa]", "E_r [GPa]",
                        "H, true area [GPa]", "O–P area vs true", "h_r/h_max", "W_p/W_t"], rows)
            self.add("Oliver–Pharr on each case's own unloading (`oliver_pharr.json`); the true "
                     "area is the simulation's projected contact area at maximum depth, so the "
                     "last columns show the method's pile-up error.", "")
        else:
            self.add("No finished case with an Oliver–Pharr analysis (cases with unloading).", "")
        measured = [c for c in self.data.cases if c["status"] == "finished" and c.get("experiment")]
        if measured:
            rows = []
            for case in measured:
                e = case["experiment"]
                at_max = e.get("deviation_at_max_depth_percent")
                rows.append([case["label"], f"`{e.get('measured_curve', '?')}`",
                             e.get("n_points", "–"), format_number(e.get("rms_deviation_mN"), 2),
                             format_percent(e.get("rms_deviation_relative"), 2),
                             format_number(e.get("max_depth_um"), 3),
                             format_number(e.get("computed_force_at_max_depth_mN"), 1),
                             format_number(e.get("measured_force_at_max_depth_mN"), 1),
                             f"{at_max:+.2f} %" if at_max is not None else "–"])
            self.table(["case", "measured curve", "points", "RMS [mN]", "RMS / P_max",
                        "max depth [µm]", "computed [mN]", "measured [mN]", "deviation"], rows)
            self.add("Loading branches compared at the measured depths inside the computed "
                     "range; each case's `load_penetration.png` overlays the measured curve.", "")

    def hardness_profile(self, case):
        """hardness_depth.csv and .json of a case with partial unloads, or None."""
        path = os.path.join(case["path"], "hardness_depth.csv")
        if not os.path.exists(path):
            return None
        profile = read_columns(path, ("depth_um", "hardness_GPa", "true_hardness_GPa"))
        profile["json"] = self.data._json(case, "hardness_depth.json") or {}
        return profile

    def plastic_zone(self, case):
        """Depth [um] and the plastic zone's share in the layer along the loading, and the first
        loading depth at which the zone reaches below the layer (None if it never does, or the
        specimen has no layer: every share 0)."""
        columns = read_columns(os.path.join(case["path"], "load_penetration.csv"),
                               ("depth_um", "plastic_zone_volume_um3",
                                "plastic_zone_layer_fraction"), ("segment",))
        depth, share, reached = [], [], None
        for h, volume, fraction, segment in zip(columns["depth_um"],
                                                columns["plastic_zone_volume_um3"],
                                                columns["plastic_zone_layer_fraction"],
                                                columns.get("segment", [])):
            if segment != "load" or not volume > 0:
                continue
            depth.append(h)
            share.append(fraction)
            if reached is None and fraction < 0.999:
                reached = h
        return depth, share, (reached if any(f > 0 for f in share) else None)

    def layer_bulk_bias(self, bulk, cases, profiles):
        """The layer's bulk hardness (a `_bulk` case: the specimen made of the layer's material
        throughout) against what the usual analyses of the irradiated cases give."""
        bulk_h = profiles[bulk["name"]]["hardness_GPa"]
        h_bulk = sum(bulk_h) / len(bulk_h)
        lines = [f"The layer's bulk hardness: {format_number(h_bulk, 3)} GPa, the mean over the "
                 f"partial unloads of `{bulk['name']}` ({bulk['label']}; "
                 f"{format_number(min(bulk_h), 3)}–{format_number(max(bulk_h), 3)} GPa). Against "
                 "it:"]
        for case in cases:
            if case is bulk or case is cases[0]:
                continue
            profile = profiles[case["name"]]
            fit = profile["json"].get("nix_gao") or {}
            h0 = fit.get("layer_hardness_GPa")
            shallow = profile["hardness_GPa"][0]
            text = (f"- {case['label']}: the shallowest partial unload's H "
                    f"{format_number(shallow, 3)} GPa ({100 * (shallow / h_bulk - 1):+.0f} %)")
            if h0:
                text += (f"; the Nix–Gao H_0 {format_number(h0, 3)} GPa "
                         f"({100 * (h0 / h_bulk - 1):+.0f} %"
                         + ("" if fit.get("knee_significant") else ", knee not significant")
                         + ")")
            lines.append(text + ".")
        self.add(*lines, "")

    def irradiation_section(self):
        """The irradiated layer against the pristine metal, per group: the first case of the
        group is the pristine reference; a case whose name ends in `_bulk` is the layer's
        material throughout, the truth the analyses of the layer are measured against."""
        groups = [g for g in ("irradiation_j2", "irradiation_crystal")
                  if any(g in c["groups"] for c in self.data.cases)]
        if not groups:
            return
        self.add("## 7. Irradiated layer against the pristine metal", "",
                 "Each case indents with partial unloads (`loading.partial_unloads`), each "
                 "analysed by Oliver–Pharr (`hardness_depth.csv`); the first case of a group is "
                 "the pristine reference. The Nix–Gao fit (H² against 1/h, bilinear, Kasada et al.) "
                 "gives the knee depth and the shallow branch's bulk-equivalent hardness H_0 of "
                 "the layer; F tests the knee against one line (significant above 4). The plastic "
                 "zone's share in the layer is the part of its volume above the layer's bottom "
                 "(the last layer's, or the damage profile's last depth). A knee without "
                 "significance is shown in parentheses. A case named `..._bulk` is the layer's "
                 "material throughout: the bulk hardness the analyses of the layer try to "
                 "recover.",
                 "")
        for group in groups:
            cases = [c for c in self.data.finished(group) if self.hardness_profile(c)]
            self.missing_note(group, f"the group {group}")
            if not cases:
                self.add(f"No finished case of {group} with partial unloads.", "")
                continue
            reference = cases[0]
            profiles = {c["name"]: self.hardness_profile(c) for c in cases}
            zones = {c["name"]: self.plastic_zone(c) for c in cases}
            rows = []
            for case in cases:
                profile = profiles[case["name"]]
                fit = profile["json"].get("nix_gao") or {}
                reached = zones[case["name"]][2]
                # A knee that one line explains as well is shown in parentheses.
                shown = (lambda text: text) if fit.get("knee_significant") else \
                    (lambda text: f"({text})")
                rows.append([case["label"], len(profile["depth_um"]),
                             format_number(profile["hardness_GPa"][0], 3) + " / " +
                             format_number(profile["hardness_GPa"][-1], 3),
                             shown(format_number(fit.get("knee_depth_um"), 2)),
                             shown(format_number(fit.get("layer_hardness_GPa"), 3)),
                             format_number(fit.get("f_statistic"), 1) +
                             (" (significant)" if fit.get("knee_significant") else
                              " (no significant knee)"),
                             format_number(reached, 3) if reached is not None else "–"])
            bulk = next((c for c in cases if c["name"].endswith("_bulk")), None)
            self.table(["case", "partial unloads", "H shallowest / deepest [GPa]",
                        "Nix–Gao knee [µm]", "H_0 of the layer [GPa]", "F",
                        "zone reaches the substrate at h [µm]"], rows)
            if bulk is not None and bulk is not reference:
                self.layer_bulk_bias(bulk, cases, profiles)
            plt = self.plt
            figure, axes = plt.subplots(2, 2, figsize=(11, 8))
            ref = profiles[reference["name"]]
            for case in cases:
                profile = profiles[case["name"]]
                line, = axes[0][0].plot(profile["depth_um"], profile["hardness_GPa"], "o-",
                                        ms=3, label=case["label"])
                axes[0][0].plot(profile["depth_um"], profile["true_hardness_GPa"], "--",
                                color=line.get_color(), lw=1)
                ratio = [(h, value / interpolate(h, ref["depth_um"], ref["hardness_GPa"]))
                         for h, value in zip(profile["depth_um"], profile["hardness_GPa"])
                         if ref["depth_um"][0] <= h <= ref["depth_um"][-1]]
                if case is not reference and ratio:
                    axes[0][1].plot([r[0] for r in ratio], [r[1] for r in ratio], "o-", ms=3,
                                    color=line.get_color(), label=case["label"])
                inverse = [1 / h for h in profile["depth_um"]]
                axes[1][0].plot(inverse, [h * h for h in profile["hardness_GPa"]], "o", ms=3,
                                color=line.get_color(), label=case["label"])
                fit = profile["json"].get("nix_gao") or {}
                if fit.get("layer_range_um") and fit.get("deep_range_um"):
                    h0, hs = fit["layer_hardness_GPa"], fit["layer_characteristic_depth_um"]
                    lo, hi = fit["layer_range_um"]
                    xs = [1 / hi, 1 / lo]
                    axes[1][0].plot(xs, [h0 * h0 * (1 + hs * x) for x in xs], "-",
                                    color=line.get_color(), lw=1)
                    lo, hi = fit["deep_range_um"]
                    xs = [1 / hi, 1 / lo]
                    axes[1][0].plot(xs, [fit["deep_intercept_GPa2"] +
                                         fit["deep_slope_GPa2_um"] * x for x in xs], ":",
                                    color=line.get_color(), lw=1)
                depth, share, _ = zones[case["name"]]
                if case is not reference and any(f > 0 for f in share):
                    axes[1][1].plot(depth, share, "-", color=line.get_color(),
                                    label=case["label"])
            axes[0][0].set(xlabel="depth h [µm]", ylabel="hardness H [GPa]",
                           title="H(h): Oliver–Pharr (solid), true contact area (dashed)")
            axes[0][1].axhline(1.0, color="0.6", lw=0.8)
            axes[0][1].set(xlabel="depth h [µm]", ylabel="H / H pristine [-]",
                           title=f"ratio to {reference['label']}")
            axes[1][0].set(xlabel="1/h [1/µm]", ylabel="H² [GPa²]",
                           title="Nix–Gao: fits, layer branch (solid) and deep branch (dotted)")
            axes[1][1].set(xlabel="depth h [µm]", ylabel="share in the layer [-]", ylim=(0, 1.05),
                           title="plastic zone's volume share in the layer")
            for axis in (axes[0][0], axes[0][1], axes[1][0], axes[1][1]):
                axis.grid(alpha=0.3)
                if axis.get_legend_handles_labels()[0]:
                    axis.legend(fontsize=8)
            self.figure(figure, f"{group}.png",
                        f"{group}: hardness against depth, its ratio to the pristine case, the "
                        "Nix–Gao plots with their fits and the plastic zone's share in the layer "
                        "(µm, GPa). The pile-up of each case is in the pile-up section.")

    def reproduce_section(self):
        index = self.data.index
        versions = sorted({(c.get("summary") or {}).get("version", "?")
                           for c in self.data.cases if c.get("summary")})
        self.add("## How to reproduce", "",
                 f"- Software: `{index['version']}` (the runs: "
                 + (", ".join(f"`{v}`" for v in versions) if versions else "none") + ").",
                 f"- The whole study (finished cases are skipped): "
                 f"`indentsim study {index['study_file']} --output {index['output_directory']}`"
                 f" (this run: {index.get('mpi_ranks', 1)} MPI rank(s) per case, "
                 f"{index.get('jobs', 1)} case(s) side by side).",
                 "- One case: `indentsim run cases/<name>-<key>/resolved_case.yaml --output DIR` "
                 "(the resolved case lists every key; linked in the table of cases).",
                 "- The report alone: `python3 python/study_report.py "
                 f"{index['output_directory']}`.", "")

    def write(self):
        sections = [self.header, self.cases_section, self.tensile_section, self.mesh_section,
                    self.orientation_section, self.pileup_section, self.paper_section,
                    self.analysis_section, self.irradiation_section, self.reproduce_section]
        for section in sections:
            try:
                section()
            except Exception as error:  # a report with a gap beats no report
                message = f"{section.__name__}: {type(error).__name__}: {error}"
                self.problems.append(message)
                self.add(f"**This section could not be written** ({message}).", "")
        markdown = "\n".join(self.lines).rstrip() + "\n"
        with open(os.path.join(self.data.directory, "report.md"), "w") as stream:
            stream.write(markdown)
        with open(os.path.join(self.data.directory, "report.html"), "w") as stream:
            stream.write(markdown_to_html(markdown, self.data.settings.get("title", "study")))


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 1 or argv[0] in ("-h", "--help"):
        print(__doc__)
        return 0 if argv and argv[0] in ("-h", "--help") else 2
    directory = argv[0]
    if not os.path.exists(os.path.join(directory, "study.json")):
        print(f"study_report.py: {directory}/study.json does not exist (run indentsim study "
              "first)", file=sys.stderr)
        return 1
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    from indentsim_plotting import ensure_matplotlib  # noqa: E402
    ensure_matplotlib("study_report.py")
    import matplotlib.pyplot as plt  # noqa: E402

    report = Report(StudyData(directory), plt)
    report.write()
    print(f"wrote {os.path.join(directory, 'report.md')} and report.html")
    for problem in report.problems:
        print(f"study_report.py: {problem}", file=sys.stderr)
    return 1 if report.problems else 0


if __name__ == "__main__":
    sys.exit(main())

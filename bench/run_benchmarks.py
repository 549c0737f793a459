#!/usr/bin/python3
"""Benchmark harness of indentsim: runs named cases and records their cost.

Usage (from anywhere; the program is <repo>/build/indentsim, built beforehand):
  python3 bench/run_benchmarks.py --list
  python3 bench/run_benchmarks.py CASE [CASE ...] [--ranks N] [--threads N]
      [--linear-solver auto|direct|iterative] [--steps N] [--set KEY=VALUE ...] [--out DIR]
      [--dry-run]

  --ranks N          MPI ranks (default 1); N > 1 runs under
                     mpirun --oversubscribe -np N, with solver.threads 1 unless --threads is given
  --threads N        solver.threads, assembly threads per rank (0: automatic, the default for 1 rank)
  --linear-solver S  solver.linear_solver (default auto)
  --steps N          override loading.steps (quick tries; results are then not comparable)
  --set KEY=VALUE    override one case-file key, dotted (e.g. contact.penetration_tolerance=1e-7);
                     the value is a number, true/false or text; repeatable. The row's case name
                     gets the overrides appended, so that such rows are not mistaken for the case
  --out DIR          results directory (default <repo>/bench/results; git-ignored)
  --dry-run          write the case files and print the commands, run nothing

Each case is generated from the definitions below into its own run directory
<out>/<case>_np<N>_<timestamp>/ (case.yaml; indentsim writes its outputs there too) and run as
  build/indentsim run case.yaml --output RUN_DIR --overwrite
The program's stdout and stderr go to run_output.txt there and, prefixed by the case name, to
the terminal. After each case one row is appended to <out>/benchmarks.csv and one to
<out>/benchmarks.md (both created with a header if missing), taken from the run_summary.json
that indentsim writes; the table of this invocation's cases is printed at the end.

Units: times in s (phases from run_summary.json; wall_time_s measured here around the process),
memory in MiB, force_or_stress in mN for indentation (force at maximum depth) and in GPa for the
tensile test (final true stress). Derived columns:
  time_per_newton_s         (time_total - time_setup - time_output) / newton_iterations
  newton_over_linear_solve  time_per_newton_s / (time_linear_solve / linear_solves)
A failed case (nonzero exit status or no run_summary.json) is reported with the last 20 lines of
its output and recorded with empty numbers and its status; the next case runs anyway, and the
script's exit status is 1.

Benchmarks are run on demand, never as tests: timings are facts about a machine, not
requirements a test can check.
"""

import argparse
import collections
import copy
import csv
import datetime
import json
import os
import subprocess
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
PROGRAM = REPO / "build" / "indentsim"
MPI_ENVIRONMENT = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}

# ----------------------------------------------------------------------------------------------
# Case definitions (units: um, mN, GPa). The paper's Table 1 (J2) and Table 2 (crystal).

J2 = {"model": "j2", "young_modulus": 69.0, "poisson_ratio": 0.26, "yield_stress": 0.305,
      "hardening_modulus": 0.5}
CRYSTAL = {"model": "crystal", "lattice": "fcc",
           "elastic": {"C11": 106.7, "C12": 60.4, "C44": 28.3},
           "hardening": {"tau0": 0.12, "tau1": 0.02, "theta0": 0.1, "theta1": 0.006, "q": 1.4},
           "yield_exponent_n": 10}


def indentation(material, contact_elements, symmetry="full"):
    """The paper's indentation by the rounded cone to 6 um and back."""
    return {"test": "indentation", "material": material,
            "indenter": {"shape": "rounded_cone", "a": 2.48, "delta": 0.005},
            "specimen": {"size": [360, 360, 180], "refined_region": [120, 120, 30],
                         "contact_elements": contact_elements, "symmetry": symmetry},
            "loading": {"max_depth": 6.0, "steps": 64, "unload": True}}


CASES = {"j2_12_quarter": ("smoke test: J2 indentation, 12x12 contact elements, quarter model",
                           indentation(J2, 12, "quarter"))}
for n in (12, 24, 48, 72):
    CASES[f"j2_{n}"] = (f"J2 indentation (Table 1), {n}x{n} contact elements, full model",
                        indentation(J2, n))
for n in (24, 48):
    CASES[f"j2_{n}_quarter"] = (
        f"J2 indentation (Table 1), {n}x{n} contact elements, quarter model",
        indentation(J2, n, "quarter"))
for n in (12, 24, 48, 72):
    CASES[f"crystal_{n}"] = (
        f"crystal indentation of (001) (Table 2), {n}x{n} contact elements, full model",
        indentation({**CRYSTAL, "orientation": {"euler_bunge_deg": [0, 0, 0]}}, n))
CASES["berkovich_j2_24"] = (
    "J2 indentation (Table 1) by a Berkovich pyramid (tip radius 0.05 um), 24x24, full model: "
    "the case that needs GMRES's true-residual test (docs/performance.md)",
    {**indentation(J2, 24),
     "indenter": {"shape": "berkovich", "tip_radius": 0.05, "rotation_deg": 0}})
CASES["j2_axi_auto"] = (
    "J2 indentation (Table 1) in axisymmetric mode on the automatic mesh, 185 geometric steps "
    "(dh/h = 1.64 % from 0.3 um on) to 6 um and back, contact tolerance 1e-5 um, Newton "
    "tolerance 1e-4 (the default example, examples/paper_j2_auto_axisymmetric.yaml)",
    {**indentation(J2, "auto", "axisymmetric"),
     "specimen": {"contact_elements": "auto", "symmetry": "axisymmetric"},
     "contact": {"friction_coefficient": 0.0, "penetration_tolerance": 1e-5},
     "solver": {"residual_tolerance": 1e-4},
     "loading": {"max_depth": 6.0, "steps": 185, "spacing": "geometric", "first_fraction": 0.05,
                 "unload": True}})
# The same with 8 elements per radius and without plots: the cheapest design found within 0.5 %
# RMS of the converged curve (docs/performance.md, "Axisymmetric mode").
CASES["j2_axi_fast"] = (
    "the default example (j2_axi_auto) with 8 elements per radius (3 016 DOFs) and no plots",
    {**CASES["j2_axi_auto"][1],
     "specimen": {"contact_elements": "auto", "symmetry": "axisymmetric",
                  "elements_per_radius": 8},
     "output": {"plots": False}})
# The 3D quarter model of the default example for a loading curve (docs/performance.md, "The 3D
# quarter model for a loading curve"): uniform steps, loading only, at the default 3D design and
# with 4 elements per radius; no plots (the figure is the computation's).
for name, n, steps in (("j2_quarter_auto_u32", None, 32), ("j2_quarter_auto_n4_u64", 4, 64)):
    CASES[name] = (
        f"J2 indentation (Table 1), 3D quarter model on the automatic mesh"
        f"{'' if n is None else f' with {n} elements per radius'}, {steps} uniform steps to 6 um, "
        "loading only, contact tolerance 1e-5 um (the comparison with an independent code in "
        "docs/performance.md)",
        {**indentation(J2, "auto", "quarter"),
         "specimen": {"contact_elements": "auto", "symmetry": "quarter",
                      **({} if n is None else {"elements_per_radius": n})},
         "contact": {"friction_coefficient": 0.0, "penetration_tolerance": 1e-5},
         "loading": {"max_depth": 6.0, "steps": steps, "spacing": "uniform", "unload": False},
         "output": {"plots": False}})
# The irradiated-versus-pristine pair with a hardness-depth profile: to 3 um with 19 partial
# unloads (every 0.15 um, 10 % of the force) and the full unload, axisymmetric automatic mesh.
CSM_LOADING = {"max_depth": 3.0, "steps": 128, "spacing": "geometric", "unload": True,
               "partial_unloads": {"every": 0.15, "fraction": 0.1}}
for name, layers, what in (("pristine", None, "pristine"),
                           ("layer", [{"thickness": 1.5, "yield_stress": 0.6}],
                            "under a 1.5 um layer of twice the yield stress")):
    CASES[f"j2_axi_csm_{name}"] = (
        f"J2 indentation (Table 1), {what}, axisymmetric automatic mesh, 128 geometric steps to "
        "3 um with partial unloads every 0.15 um (the J2 pair of the irradiated-layer study)",
        {**indentation({**J2, **({"layers": layers} if layers else {})}, "auto", "axisymmetric"),
         "specimen": {"contact_elements": "auto", "symmetry": "axisymmetric"},
         "contact": {"friction_coefficient": 0.0, "penetration_tolerance": 1e-5},
         "loading": CSM_LOADING})
# The same under the synthetic self-ion damage profile of studies/irradiated_layer/self_ion_dpa.csv (inline;
# peak 1.28 dpa at 0.6 um, to 0.8 um), raising the yield stress by up to sigma_y0.
SELF_ION_PROFILE = {
    "depth": [0, 0.1, 0.2, 0.3, 0.4, 0.45, 0.5, 0.55, 0.6, 0.65, 0.7, 0.75, 0.8],
    "dpa": [0.40, 0.45, 0.52, 0.62, 0.78, 0.90, 1.05, 1.20, 1.28, 1.20, 0.85, 0.35, 0.0],
    "law": {"form": "saturation", "saturation_increment": 0.305, "saturation_dose": 0.5,
            "exponent": 0.5}}
CASES["j2_axi_csm_profile"] = (
    "J2 indentation (Table 1) under a self-ion damage profile (to 0.8 um, yield stress up to "
    "doubled), axisymmetric automatic mesh, 128 geometric steps to 3 um with partial unloads "
    "every 0.15 um",
    {**indentation({**J2, "damage_profile": SELF_ION_PROFILE}, "auto", "axisymmetric"),
     "specimen": {"contact_elements": "auto", "symmetry": "axisymmetric"},
     "contact": {"friction_coefficient": 0.0, "penetration_tolerance": 1e-5},
     "loading": CSM_LOADING})
CASES["tensile_27"] = (
    "tensile test of 27 random grains (crystal, 3x3x3 elements, 100 steps), no J2 comparison",
    {"test": "tensile", "material": {**J2, **CRYSTAL},
     "specimen": {"elements_per_side": 3, "grains": "per_element", "seed": 1},
     "loading": {"max_strain": 0.2, "steps": 100}})

# ----------------------------------------------------------------------------------------------
# Records

COLUMNS = ["date", "case", "machine", "mpi_ranks", "threads_per_rank", "linear_solver", "cells",
           "dofs", "steps", "cutbacks", "newton_iterations", "linear_iterations", "time_setup_s",
           "time_assembly_s", "time_contact_s", "time_linear_solve_s", "time_output_s",
           "time_total_s", "wall_time_s", "peak_memory_total_mib", "force_or_stress",
           "time_per_newton_s", "newton_over_linear_solve", "status"]
FINAL_VALUE_KEYS = ("force_at_max_depth_mN", "final_true_stress_GPa")


def render_yaml(value, indent=0):
    """YAML text of nested dicts (block style) with lists and scalars (flow style)."""
    def scalar(item):
        if isinstance(item, bool):
            return "true" if item else "false"
        if isinstance(item, list):
            return "[" + ", ".join(scalar(element) for element in item) + "]"
        if isinstance(item, dict):
            return "{" + ", ".join(f"{k}: {scalar(v)}" for k, v in item.items()) + "}"
        return str(item)

    lines = []
    for key, item in value.items():
        if isinstance(item, dict):
            lines.append(f"{' ' * indent}{key}:\n" + render_yaml(item, indent + 2))
        else:
            lines.append(f"{' ' * indent}{key}: {scalar(item)}\n")
    return "".join(lines)


def machine():
    """CPU model and core count, e.g. 'AMD EPYC, 2 cores'."""
    model = "unknown CPU"
    try:
        with open("/proc/cpuinfo") as cpuinfo:
            model = next(line.split(":", 1)[1].strip() for line in cpuinfo
                         if line.startswith("model name"))
    except (OSError, StopIteration):
        pass
    return f"{model}, {os.cpu_count()} cores"


def number(text, digits):
    """A float column formatted to `digits` significant digits; other values unchanged."""
    return f"{text:.{digits}g}" if isinstance(text, float) else ("" if text is None else str(text))


def summary_columns(summary):
    """The CSV columns taken or derived from run_summary.json."""
    row = {key: summary.get(key) for key in COLUMNS if key in summary}
    row["force_or_stress"] = next((summary[key] for key in FINAL_VALUE_KEYS if key in summary),
                                  None)
    newton, solves = summary.get("newton_iterations", 0), summary.get("linear_solves", 0)
    if newton:
        per_newton = (summary["time_total_s"] - summary["time_setup_s"]
                      - summary["time_output_s"]) / newton
        row["time_per_newton_s"] = per_newton
        if solves and summary.get("time_linear_solve_s", 0) > 0:
            row["newton_over_linear_solve"] = per_newton / (summary["time_linear_solve_s"] / solves)
    return row


def markdown_row(row):
    cells = (number(row.get(key), 4).replace("|", "\\|") for key in COLUMNS)
    return "| " + " | ".join(cells) + " |\n"


MARKDOWN_HEADER = ("| " + " | ".join(COLUMNS) + " |\n"
                   + "|" + "---|" * len(COLUMNS) + "\n")


def append_records(out, row):
    """Appends the row to benchmarks.csv and benchmarks.md, each with a header when new."""
    csv_path, markdown_path = out / "benchmarks.csv", out / "benchmarks.md"
    new_csv, new_markdown = not csv_path.exists(), not markdown_path.exists()
    with open(csv_path, "a", newline="") as stream:
        writer = csv.DictWriter(stream, fieldnames=COLUMNS)
        if new_csv:
            writer.writeheader()
        writer.writerow({key: number(row.get(key), 10) for key in COLUMNS})
    with open(markdown_path, "a") as stream:
        stream.write((MARKDOWN_HEADER if new_markdown else "") + markdown_row(row))


def check_csv_header(out):
    """Refuses to append to a benchmarks.csv written with other columns."""
    path = out / "benchmarks.csv"
    if path.exists():
        with open(path, newline="") as stream:
            header = next(csv.reader(stream), None)
        if header != COLUMNS:
            sys.exit(f"error: {path} has other columns than this script writes; "
                     "move it away first")

# ----------------------------------------------------------------------------------------------
# Running


def parse_setting(text):
    """'a.b=1e-7' -> (['a', 'b'], 1e-07); raises ValueError naming the text if malformed."""
    key, separator, value = text.partition("=")
    path = key.strip().split(".")
    if not separator or not all(path) or not value.strip():
        raise ValueError(f"--set {text!r}: expected KEY=VALUE with a dotted key, "
                         "e.g. contact.penetration_tolerance=1e-7")
    value = value.strip()
    if value in ("true", "false"):
        return path, value == "true"
    for convert in (int, float):
        try:
            return path, convert(value)
        except ValueError:
            pass
    return path, value


def apply_settings(case, settings):
    """Sets each (path, value) of `settings` in the nested dict `case`, creating sections."""
    for path, value in settings:
        section = case
        for key in path[:-1]:
            if not isinstance(section.setdefault(key, {}), dict):
                raise ValueError(f"--set {'.'.join(path)}: '{key}' is a value, not a section")
            section = section[key]
        section[path[-1]] = value


def case_label(name, options):
    """The case name as recorded: with the --set overrides appended."""
    return name + "".join(f" [{text}]" for text in options.set)


def prepare(name, options):
    """Creates the run directory with case.yaml; returns (directory, command, threads)."""
    ranks = options.ranks
    threads = options.threads if options.threads is not None else (1 if ranks > 1 else 0)
    case = copy.deepcopy(CASES[name][1])
    if options.steps is not None:
        case["loading"]["steps"] = options.steps
    case["solver"] = {**case.get("solver", {}), "linear_solver": options.linear_solver,
                      "threads": threads}
    apply_settings(case, options.settings)

    stamp = datetime.datetime.now().strftime("%Y%m%d-%H%M%S")
    directory = options.out / f"{name}_np{ranks}_{stamp}"
    suffix = 1
    while directory.exists():
        suffix += 1
        directory = options.out / f"{name}_np{ranks}_{stamp}_{suffix}"
    directory.mkdir(parents=True)
    case_file = directory / "case.yaml"
    case_file.write_text(f"# {name}: {CASES[name][0]}\n"
                         "# Written by bench/run_benchmarks.py. Units: um, mN, GPa.\n"
                         + render_yaml(case))
    command = [str(PROGRAM), "run", str(case_file), "--output", str(directory), "--overwrite"]
    if ranks > 1:
        command = ["mpirun", "--oversubscribe", "-np", str(ranks)] + command
    return directory, command, threads


def run_case(name, options):
    """Runs one case, streaming its output; returns its record row."""
    directory, command, threads = prepare(name, options)
    print(f"[{name}] $ {' '.join(command)}", flush=True)
    row = {"date": datetime.datetime.now().strftime("%Y-%m-%d %H:%M"),
           "case": case_label(name, options),
           "machine": machine(), "mpi_ranks": options.ranks, "threads_per_rank": threads,
           "linear_solver": options.linear_solver}
    if options.dry_run:
        return row

    tail = collections.deque(maxlen=20)
    start = time.monotonic()
    with open(directory / "run_output.txt", "w") as log:
        try:
            process = subprocess.Popen(command, cwd=REPO, stdout=subprocess.PIPE,
                                       stderr=subprocess.STDOUT, text=True, bufsize=1,
                                       env={**os.environ, **MPI_ENVIRONMENT})
        except OSError as error:
            row["status"] = f"not started: {error}"
            print(f"[{name}] FAILED: {row['status']}", flush=True)
            return row
        for line in process.stdout:
            log.write(line)
            tail.append(line)
            print(f"[{name}] {line}", end="", flush=True)
        status = process.wait()
    row["wall_time_s"] = time.monotonic() - start

    summary_path = directory / "run_summary.json"
    if status != 0:
        row["status"] = f"failed (exit status {status})"
        print(f"[{name}] FAILED with exit status {status}; last lines of "
              f"{directory / 'run_output.txt'}:\n" + "".join(tail), end="", flush=True)
    elif not summary_path.exists():
        row["status"] = "failed (no run_summary.json)"
        print(f"[{name}] FAILED: the run succeeded but wrote no {summary_path} "
              "(does this build record its statistics for this test?)", flush=True)
    else:
        try:
            row.update(summary_columns(json.loads(summary_path.read_text())))
            row["status"] = "ok"
        except (ValueError, KeyError, TypeError) as error:
            row["status"] = "failed (unreadable run_summary.json)"
            print(f"[{name}] FAILED: cannot read {summary_path}: {error!r}", flush=True)
    return row


def main():
    parser = argparse.ArgumentParser(
        description="Run indentsim benchmark cases and record their cost "
                    "(see the module docstring for the columns and units).")
    parser.add_argument("cases", nargs="*", metavar="CASE", help="case names (see --list)")
    parser.add_argument("--ranks", type=int, default=1, help="MPI ranks (default 1)")
    parser.add_argument("--threads", type=int, default=None,
                        help="solver.threads per rank (default: 0 = automatic for one rank, "
                             "1 for several)")
    parser.add_argument("--linear-solver", choices=("auto", "direct", "iterative"),
                        default="auto", help="solver.linear_solver (default auto)")
    parser.add_argument("--steps", type=int, default=None, help="override loading.steps")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="override a case-file key, e.g. contact.penetration_tolerance=1e-7")
    parser.add_argument("--out", type=Path, default=REPO / "bench" / "results",
                        help="results directory (default <repo>/bench/results)")
    parser.add_argument("--list", action="store_true", help="list the cases and exit")
    parser.add_argument("--dry-run", action="store_true",
                        help="write the case files and print the commands, run nothing")
    options = parser.parse_args()

    if options.list:
        width = max(map(len, CASES))
        for name, (description, _) in CASES.items():
            print(f"{name:<{width}}  {description}")
        return 0
    unknown = [name for name in options.cases if name not in CASES]
    if not options.cases or unknown:
        parser.error((f"unknown case(s): {', '.join(unknown)}; " if unknown else
                      "no case given; ") + "allowed: " + ", ".join(CASES))
    if options.ranks < 1 or (options.threads is not None and options.threads < 0) or (
            options.steps is not None and options.steps < 1):
        parser.error("--ranks and --steps must be >= 1, --threads >= 0")
    try:
        options.settings = [parse_setting(text) for text in options.set]
        for name in options.cases:
            apply_settings(copy.deepcopy(CASES[name][1]), options.settings)
    except ValueError as error:
        parser.error(str(error))
    if not options.dry_run and not PROGRAM.exists():
        sys.exit(f"error: {PROGRAM} not found; build the project first")
    options.out = options.out.resolve()
    check_csv_header(options.out)

    rows = []
    for name in options.cases:
        row = run_case(name, options)
        if not options.dry_run:
            append_records(options.out, row)
        rows.append(row)
    if options.dry_run:
        return 0

    print("\n" + MARKDOWN_HEADER + "".join(map(markdown_row, rows)), end="")
    failed = [row["case"] for row in rows if row["status"] != "ok"]
    if failed:
        print(f"\nfailed: {', '.join(failed)}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Compare an `indentsim study` of sharp cones with published finite-element data.

    python3 python/published_cones.py STUDY_OUTPUT [--data CSV]
                                      [--max-c-deviation X] [--max-wp-deviation Y]

For every finished case of the study (STUDY_OUTPUT/study.json, the run's own files in
STUDY_OUTPUT/cases/<name>-<key>/) whose material (E, sigma_y, n of the power law) is a row of the
data (default: tests/data/lu2020_fem_70deg_cone.csv, the 70.3 deg cone of Lu et al., PNAS 117
(2020) 7052, on the materials of Dao et al., Acta Mater. 49 (2001) 3899), it tabulates

    C = P/h^2        least-squares fit of P = C h^2 to the loading points with h >= h_max/2
                     (the contact advances by node rings, so single points scatter slightly);
                     also P_max/h_max^2
    W_p/W_t          plastic_work_ratio of the case's oliver_pharr.json
    dP/dh            stiffness_mN_per_um of oliver_pharr.json, scaled to the data's maximum
                     depth (0.2 um, see the data file) for comparison: dP/dh is proportional to
                     h_max for a sharp cone; shown, not checked

against the published values, with relative differences (ours - published) / published, and
writes STUDY_OUTPUT/published_cones.md, published_cones.csv and figures/published_cones.png.
A case run with another Poisson ratio, friction coefficient, cone angle, hardening law or
indenter than the data's is refused (exit code 1), as is a data file without the expected
columns. With --max-c-deviation / --max-wp-deviation the exit code is 1 when any matched case
differs by more (relative, e.g. 0.05) or when no case matched: the verification test uses this.

Units: lengths um, forces mN, stresses GPa (1 GPa = 1 mN/um^2), stiffness mN/um (1 N/m =
0.001 mN/um).
"""

import argparse
import csv
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_DATA = os.path.join(HERE, "..", "tests", "data", "lu2020_fem_70deg_cone.csv")

# The conditions of the data's runs (see the header of the data file).
DATA_POISSON_RATIO = 0.3
DATA_FRICTION = 0.15
DATA_HALF_ANGLE_DEG = 70.3
DATA_MAX_DEPTH_UM = 0.2
DATA_COLUMNS = ("case", "n", "E_GPa", "sigma_y_GPa", "C_GPa", "dPdh_N_per_m", "Wp_Wt")


class DataError(Exception):
    """Bad input: the message names the file, the key or column, the value and the rule."""


def read_published(path):
    """The rows of the data file ('#' lines are comments) as dicts of floats."""
    with open(path, newline="") as stream:
        lines = [line for line in stream if line.strip() and not line.lstrip().startswith("#")]
    reader = csv.DictReader(lines)
    missing = [c for c in DATA_COLUMNS if c not in (reader.fieldnames or [])]
    if missing:
        raise DataError(f"{path}: missing column(s) {', '.join(missing)}; expected the header "
                        f"{','.join(DATA_COLUMNS)}")
    rows = []
    for number, row in enumerate(reader, start=2):
        try:
            rows.append({key: float(row[key]) for key in DATA_COLUMNS})
        except (TypeError, ValueError):
            raise DataError(f"{path}: data row {number - 1}: {row} is not all numbers")
    return rows


def fit_c(depth, force, fraction=0.5):
    """C of P = C h^2 fitted by least squares to the points with h >= fraction * max(h):
    C = sum(P h^2) / sum(h^4)."""
    h_max = max(depth)
    pairs = [(h, p) for h, p in zip(depth, force) if h >= fraction * h_max]
    denominator = sum(h**4 for h, _ in pairs)
    if not pairs or denominator <= 0:
        raise DataError("no loading points to fit P = C h^2")
    return sum(p * h * h for h, p in pairs) / denominator


def loading_branch(path):
    """Depth [um] and force [mN] of the first loading of a run's load_penetration.csv."""
    depth, force = [], []
    with open(path, newline="") as stream:
        for row in csv.DictReader(stream):
            if row["segment"] in ("start", "load") and row["cycle"] in ("0", "1"):
                depth.append(float(row["depth_um"]))
                force.append(float(row["force_mN"]))
    if len(depth) < 3:
        raise DataError(f"{path}: fewer than 3 loading rows")
    return depth, force


def relative(ours, published):
    return (ours - published) / published


def check_conditions(resolved, where):
    """The case must be run as the data were: J2 power law, sharp 70.3 deg cone, nu, mu."""
    material, indenter = resolved["material"], resolved["indenter"]
    checks = [
        ("material.model", material.get("model"), "j2"),
        ("material.hardening.law", (material.get("hardening") or {}).get("law"), "power"),
        ("indenter.shape", indenter.get("shape"), "cone"),
        ("indenter.tip_radius", float(indenter.get("tip_radius", 0.0)), 0.0),
        ("indenter.half_angle_deg", float(indenter.get("half_angle_deg")), DATA_HALF_ANGLE_DEG),
        ("material.poisson_ratio", float(material.get("poisson_ratio")), DATA_POISSON_RATIO),
        ("contact.friction_coefficient", float(resolved["contact"]["friction_coefficient"]),
         DATA_FRICTION),
    ]
    for key, value, wanted in checks:
        same = abs(value - wanted) <= 1e-12 if isinstance(wanted, float) else value == wanted
        if not same:
            raise DataError(f"{where}: {key} = {value}, but the published data were computed "
                            f"with {wanted}: compare only cases run as the data were")


def match_row(rows, young, yield_stress, exponent):
    for row in rows:
        if (abs(row["E_GPa"] - young) <= 1e-9 * young and
                abs(row["sigma_y_GPa"] - yield_stress) <= 1e-9 * yield_stress and
                abs(row["n"] - exponent) <= 1e-9):
            return row
    return None


def compare(study_directory, rows):
    """One dict per finished case whose material is in the data; the unmatched case names."""
    import yaml

    index_path = os.path.join(study_directory, "study.json")
    with open(index_path) as stream:
        index = json.load(stream)
    results, unmatched = [], []
    for case in index["cases"]:
        if case.get("status") != "finished" or case.get("test") != "indentation":
            continue
        directory = os.path.join(study_directory, case["directory"])
        resolved_path = os.path.join(directory, "resolved_case.yaml")
        with open(resolved_path) as stream:
            resolved = yaml.safe_load(stream)
        material = resolved["material"]
        hardening = material.get("hardening") or {}
        if material.get("model") != "j2" or hardening.get("law") != "power":
            unmatched.append(case["name"])
            continue
        row = match_row(rows, float(material["young_modulus"]), float(material["yield_stress"]),
                        float(hardening["exponent"]))
        if row is None:
            unmatched.append(case["name"])
            continue
        check_conditions(resolved, resolved_path)
        with open(os.path.join(directory, "oliver_pharr.json")) as stream:
            oliver_pharr = json.load(stream)
        with open(os.path.join(directory, "run_summary.json")) as stream:
            summary = json.load(stream)
        depth, force = loading_branch(os.path.join(directory, "load_penetration.csv"))
        h_max = float(case["max_depth_um"])
        c_fit = fit_c(depth, force)
        c_peak = summary["force_at_max_depth_mN"] / h_max**2
        wp = oliver_pharr["plastic_work_ratio"]
        # mN/um at h_max -> N/m at the data's depth (1 mN/um = 1000 N/m).
        slope = oliver_pharr["stiffness_mN_per_um"] * DATA_MAX_DEPTH_UM / h_max * 1000.0
        results.append({
            "name": case["name"], "label": case.get("label", case["name"]),
            "data_case": int(row["case"]), "E_GPa": row["E_GPa"],
            "sigma_y_GPa": row["sigma_y_GPa"], "n": row["n"],
            "E_over_sigma_y": row["E_GPa"] / row["sigma_y_GPa"],
            "contact_elements": case.get("contact_elements"), "max_depth_um": h_max,
            "C_GPa": c_fit, "C_peak_GPa": c_peak, "C_published_GPa": row["C_GPa"],
            "C_deviation": relative(c_fit, row["C_GPa"]),
            "Wp_Wt": wp, "Wp_Wt_published": row["Wp_Wt"],
            "Wp_Wt_deviation": relative(wp, row["Wp_Wt"]),
            "dPdh_N_per_m_at_0.2um": slope, "dPdh_published_N_per_m": row["dPdh_N_per_m"],
            "dPdh_deviation": relative(slope, row["dPdh_N_per_m"]),
            "wall_time_s": summary.get("time_total_s"),
        })
    results.sort(key=lambda r: (-r["E_over_sigma_y"], r["n"]))
    return results, unmatched


def percent(value):
    return f"{100.0 * value:+.1f} %"


def markdown(results, unmatched, data_path):
    lines = ["# Sharp 70.3° cone on power-law solids against published FEM data", "",
             "**Units: moduli, stresses and C in GPa (1 GPa = 1 mN/µm²), dP/dh in N/m "
             "(1 N/m = 0.001 mN/µm), depths µm.**", "",
             f"Data: `{os.path.relpath(data_path)}` (Lu et al., PNAS 117 (2020) 7052, the "
             "materials of Dao et al., Acta Mater. 49 (2001) 3899; ν = 0.3, friction 0.15). "
             "C: least-squares fit of P = C h² to the loading points with h ≥ h_max/2 "
             "(P_max/h_max² beside it); W_p/W_t from `oliver_pharr.json`; dP/dh: our "
             "Oliver–Pharr stiffness scaled to h_max = 0.2 µm (not checked: the data's "
             "maximum depth is inferred).", "",
             "| data case | E [GPa] | σy [GPa] | E/σy | n | C [GPa] | P_max/h² [GPa] | "
             "C published [GPa] | ΔC | W_p/W_t | published | ΔW_p/W_t | dP/dh at 0.2 µm [N/m] "
             "| published [N/m] | Δ(dP/dh) |",
             "|" + "---|" * 15]
    for r in results:
        lines.append(
            f"| {r['data_case']} | {r['E_GPa']:g} | {r['sigma_y_GPa']:g} | "
            f"{r['E_over_sigma_y']:.0f} | {r['n']:g} | {r['C_GPa']:.3f} | {r['C_peak_GPa']:.3f} | "
            f"{r['C_published_GPa']:g} | {percent(r['C_deviation'])} | {r['Wp_Wt']:.3f} | "
            f"{r['Wp_Wt_published']:.3f} | {percent(r['Wp_Wt_deviation'])} | "
            f"{r['dPdh_N_per_m_at_0.2um']:.0f} | {r['dPdh_published_N_per_m']:g} | "
            f"{percent(r['dPdh_deviation'])} |")
    if results:
        for key, name in (("C_deviation", "C"), ("Wp_Wt_deviation", "W_p/W_t"),
                          ("dPdh_deviation", "dP/dh")):
            values = [r[key] for r in results]
            mean = sum(values) / len(values)
            largest = max(values, key=abs)
            lines.append("")
            lines.append(f"{name}: mean difference {percent(mean)}, largest {percent(largest)} "
                         f"over {len(values)} cases.")
    if unmatched:
        lines += ["", "Cases not in the data (not compared): " +
                  ", ".join(f"`{name}`" for name in unmatched) + "."]
    return "\n".join(lines) + "\n"


def write_csv(results, path):
    if not results:
        return
    with open(path, "w", newline="") as stream:
        writer = csv.DictWriter(stream, fieldnames=list(results[0].keys()))
        writer.writeheader()
        writer.writerows(results)


def plot(results, path):
    sys.path.insert(0, HERE)
    from indentsim_plotting import ensure_matplotlib  # noqa: E402
    ensure_matplotlib("published_cones.py")
    import matplotlib.pyplot as plt  # noqa: E402

    figure, axes = plt.subplots(1, 2, figsize=(10, 4.5))
    exponents = sorted({r["n"] for r in results})
    markers = dict(zip(exponents, "osD^v<>"))
    for n in exponents:
        chosen = [r for r in results if r["n"] == n]
        axes[0].loglog([r["C_published_GPa"] for r in chosen], [r["C_GPa"] for r in chosen],
                       markers[n], label=f"n = {n:g}", fillstyle="none")
        axes[1].plot([r["Wp_Wt_published"] for r in chosen], [r["Wp_Wt"] for r in chosen],
                     markers[n], label=f"n = {n:g}", fillstyle="none")
    c_values = [r["C_published_GPa"] for r in results] + [r["C_GPa"] for r in results]
    low, high = min(c_values) / 1.2, max(c_values) * 1.2
    axes[0].plot([low, high], [low, high], "k-", lw=0.8, label="equal")
    axes[0].set_xlabel("C published [GPa]")
    axes[0].set_ylabel("C indentsim [GPa]")
    axes[0].set_title("C = P/h² (70.3° cone)")
    axes[1].plot([0.3, 1.0], [0.3, 1.0], "k-", lw=0.8, label="equal")
    axes[1].set_xlabel("W_p/W_t published [-]")
    axes[1].set_ylabel("W_p/W_t indentsim [-]")
    axes[1].set_title("plastic work ratio")
    for axis in axes:
        axis.grid(True, which="both", alpha=0.3)
        axis.legend(fontsize=8)
    figure.tight_layout()
    os.makedirs(os.path.dirname(path), exist_ok=True)
    figure.savefig(path)
    plt.close(figure)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("study_output", help="the study's output directory (with study.json)")
    parser.add_argument("--data", default=DEFAULT_DATA, help="the published data (CSV)")
    parser.add_argument("--max-c-deviation", type=float, default=None,
                        help="fail if any |C - C_published| / C_published exceeds this")
    parser.add_argument("--max-wp-deviation", type=float, default=None,
                        help="fail if any |W_p/W_t - published| / published exceeds this")
    parser.add_argument("--no-plot", action="store_true", help="write no figure")
    args = parser.parse_args(argv)
    try:
        rows = read_published(args.data)
        results, unmatched = compare(args.study_output, rows)
    except (DataError, OSError, KeyError) as error:
        print(f"published_cones.py: error: {error}", file=sys.stderr)
        return 1
    text = markdown(results, unmatched, args.data)
    with open(os.path.join(args.study_output, "published_cones.md"), "w") as stream:
        stream.write(text)
    write_csv(results, os.path.join(args.study_output, "published_cones.csv"))
    if results and not args.no_plot:
        plot(results, os.path.join(args.study_output, "figures", "published_cones.png"))
    print(text, end="")

    failures = []
    checks = (("C", "C_deviation", args.max_c_deviation),
              ("W_p/W_t", "Wp_Wt_deviation", args.max_wp_deviation))
    for name, key, limit in checks:
        if limit is None:
            continue
        if not results:
            failures.append(f"no finished case matches a row of {args.data}")
        for r in results:
            if abs(r[key]) > limit:
                failures.append(f"data case {r['data_case']} (`{r['name']}`): {name} differs by "
                                f"{percent(r[key])}, more than the allowed {100 * limit:g} %")
    for failure in failures:
        print(f"FAIL: {failure}", file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

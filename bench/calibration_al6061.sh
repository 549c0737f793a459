#!/usr/bin/env bash
# Benchmark of `indentsim calibrate` on measured data nobody here produced (docs/calibration.md,
# "Al 6061 from published tests"; docs/performance.md, "Calibration"): the yield stress and
# hardening exponent of aluminium alloy 6061 from the loading curvature C and the plastic work
# ratio Wp/Wt of six Berkovich tests (Lu et al., PNAS 117, 2020), with the equivalent sharp cone
# in the axisymmetric mode (calibrations/al6061_lu2020/calibrate.yaml), two forward runs side
# by side. Then the tensile test's values (sigma_y = 0.284 GPa, n = 0.08, the base case's) are
# run and tested against the fit without linearisation: the F statistic
#   F = ((SSR_tensile - SSR_fit) / p) / (SSR_fit / (m - p))
# of the two sums of squared relative misfits (m values, p = 2 parameters); below the 95 % point
# of F(p, m - p) the tensile values lie inside the data's joint 95 % confidence region.
# Usage (from the repository root, after building): bash bench/calibration_al6061.sh [OUT]
# Units: lengths um, forces mN, stresses GPa, times s.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(realpath -m "${1:-$root/bench/results/calibration_al6061}")"
here="$root/calibrations/al6061_lu2020"
export OMP_NUM_THREADS=1
rm -rf "$out" "$out.txt"
mkdir -p "$out"
"$root/build/indentsim" calibrate "$here/calibrate.yaml" --jobs 2 --output "$out/fit" \
  | tee "$out.txt"
"$root/build/indentsim" run "$here/cone_al6061.yaml" --output "$out/tensile_values" \
  > "$out/tensile_values.txt" 2>&1
/usr/bin/python3 - "$out" "$here/Al6061.csv" <<'PY' | tee -a "$out.txt"
import csv, json, sys
out, measured_csv = sys.argv[1:3]
c = json.load(open(f"{out}/fit/calibration.json"))
p = c["parameters"]
for key, tensile in (("material.yield_stress", 0.284), ("material.hardening.exponent", 0.08)):
    v = p[key]
    print(f"{key}: fitted {v['value']:.4g} +- {v['standard_error']:.2g} "
          f"(95 %: {v['ci95'][0]:.4g} to {v['ci95'][1]:.4g}); tensile test {tensile}")
print(f"forward runs {c['forward_runs']}, wall time {c['wall_time_s']:.0f} s, "
      f"identifiable: {c['identifiable']}")

# C (Kick's law over the loading rows) and Wp/Wt of the run at the tensile values.
run = f"{out}/tensile_values"
rows = [r for r in csv.DictReader(open(f"{run}/load_penetration.csv")) if r["segment"] == "load"]
h = [float(r["depth_um"]) for r in rows]
P = [float(r["force_mN"]) for r in rows]
C = sum(Pi * hi * hi for hi, Pi in zip(h, P)) / sum(hi ** 4 for hi in h)
W = json.load(open(f"{run}/oliver_pharr.json"))["plastic_work_ratio"]
tests = list(csv.DictReader(line for line in open(measured_csv) if not line.startswith("#")))
measured = [(float(t["C (GPa)"]), float(t["Wp/Wt"])) for t in tests]
mean_C = sum(m[0] for m in measured) / len(measured)
mean_W = sum(m[1] for m in measured) / len(measured)
ssr_tensile = sum(((C - mc) / mean_C) ** 2 + ((W - mw) / mean_W) ** 2 for mc, mw in measured)
n_values, n_parameters = 2 * len(measured), 2
ssr_fit = 2 * c["cost"] * n_values  # cost = 1/2 sum (rel / sqrt(m))^2
F = ((ssr_tensile - ssr_fit) / n_parameters) / (ssr_fit / (n_values - n_parameters))
nu = n_values - n_parameters  # F(2, nu) has the CDF 1 - (1 + 2 x / nu)^(-nu / 2)
F95 = nu / 2 * (0.05 ** (-2 / nu) - 1)
print(f"tensile values: C {C:.4g} GPa (tests {mean_C:.4g}), Wp/Wt {W:.4g} (tests {mean_W:.4g}); "
      f"rms relative misfit {100 * (ssr_tensile / n_values) ** 0.5:.3g} % against "
      f"{100 * (ssr_fit / n_values) ** 0.5:.3g} % at the fit; F = {F:.3g}, "
      f"95 % point {F95:.3g}: the tensile values are "
      f"{'inside' if F < F95 else 'outside'} the joint 95 % region")
PY

#!/usr/bin/env bash
# Benchmark of `indentsim calibrate` with four crystal hardening parameters (docs/performance.md,
# "Calibration"): tau0, tau1, theta0 and theta1 of the paper's FCC crystal (Table 2: 0.12, 0.02,
# 0.1 and 0.006 GPa; q = 1.4 fixed) from two synthetic curves of the true crystal: the 27-grain
# tensile test to a log strain of 0.2 (examples/tensile_27_grains.yaml) and the (001) indentation
# under the paper's rounded cone to 6.0 um on the 24 x 24 quarter model (loading only). The start
# lies 25-50 % off each value; two forward runs side by side, one thread each.
# Usage (from the repository root, after building): bash bench/calibration_crystal_four.sh [OUT]
# Prints the calibration's summary and each parameter against its true value; calibration.json
# holds the wall time and the forward runs.
# Units: lengths um, forces mN, stresses GPa, times s.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(realpath -m "${1:-$root/bench/results/calibration_crystal_four}")"
indentsim="$root/build/indentsim"
export OMP_NUM_THREADS=1
rm -rf "$out"
mkdir -p "$out"
crystal='model: crystal
  lattice: fcc
  elastic: {C11: 106.7, C12: 60.4, C44: 28.3}
  hardening: {tau0: 0.12, tau1: 0.02, theta0: 0.1, theta1: 0.006, q: 1.4}
  yield_exponent_n: 10'
cat > "$out/indentation.yaml" <<YAML
# The paper's crystal on (001), rounded cone, 24 x 24 quarter model, 6.0 um, loading only.
# Units: lengths um, forces mN, stresses GPa.
test: indentation
material:
  $crystal
  orientation: {surface_normal: [0, 0, 1], reference_direction: [1, 0, 0]}
indenter: {shape: rounded_cone, a: 2.48, delta: 0.005}
specimen: {size: [360, 360, 180], refined_region: [120, 120, 30], contact_elements: 24,
           symmetry: quarter}
loading: {max_depth: 6.0, steps: 64, unload: false}
output: {directory: indentation, plots: false}
YAML
cat > "$out/tensile.yaml" <<YAML
# The paper's 27-grain tensile test of the same crystal to a log strain of 0.2.
# Units: stresses GPa.
test: tensile
material:
  $crystal
specimen: {elements_per_side: 3, grains: per_element, seed: 1}
loading: {max_strain: 0.2, steps: 100}
output: {directory: tensile, plots: false}
YAML
for case in indentation tensile; do
  "$indentsim" run "$out/$case.yaml" --output "$out/truth_$case" > "$out/truth_$case.txt" 2>&1
done
cat > "$out/calibrate.yaml" <<YAML
base_case: $out/indentation.yaml
output: $out/calibration
parameters:
  material.hardening.tau0:   {start: 0.15,  min: 0.05,  max: 0.5}
  material.hardening.tau1:   {start: 0.03,  min: 0.002, max: 0.2}
  material.hardening.theta0: {start: 0.15,  min: 0.01,  max: 1.0}
  material.hardening.theta1: {start: 0.009, min: 0.0,   max: 0.1}
data:
  - {kind: load_penetration, file: $out/truth_indentation/load_penetration.csv, branch: loading}
  - {kind: tensile, file: $out/truth_tensile/stress_strain.csv, case: $out/tensile.yaml}
YAML
"$indentsim" calibrate "$out/calibrate.yaml" --jobs 2 | tee "$out/calibrate.txt"
/usr/bin/python3 - "$out/calibration/calibration.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
truth = {"tau0": 0.12, "tau1": 0.02, "theta0": 0.1, "theta1": 0.006}
for name, t in truth.items():
    p = c["parameters"]["material.hardening." + name]
    print(f"{name}: {p['value']:.6g} GPa against {t} ({100 * (p['value'] / t - 1):+.3f} %), "
          f"95 % [{p['ci95'][0]:.4g}, {p['ci95'][1]:.4g}]")
print("identifiable:", c["identifiable"], " forward runs:", c["forward_runs"],
      " wall time:", round(c["wall_time_s"]), "s")
PY

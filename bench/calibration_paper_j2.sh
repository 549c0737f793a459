#!/usr/bin/env bash
# Benchmark of `indentsim calibrate` (docs/performance.md, "Calibration"): the yield stress and
# the hardening modulus of the paper's J2 case (Table 1: 0.305 GPa and 0.5 GPa) from its own
# load-penetration curve, loading and unloading, on the automatic axisymmetric mesh of the
# default example (examples/paper_j2_auto_axisymmetric.yaml, 4 274 DOFs, 212 steps a run), from
# a start at 0.25 GPa and 1.0 GPa, two forward runs side by side.
# Usage (from the repository root, after building): bash bench/calibration_paper_j2.sh [OUT]
# Prints the calibration's summary; calibration.json holds the wall time and the forward runs.
# Units: lengths um, forces mN, stresses GPa, times s.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(realpath -m "${1:-$root/bench/results/calibration_paper_j2}")"
indentsim="$root/build/indentsim"
export OMP_NUM_THREADS=1
rm -rf "$out"
mkdir -p "$out"
"$indentsim" run "$root/examples/paper_j2_auto_axisymmetric.yaml" --output "$out/truth" \
  > "$out/truth.txt" 2>&1
cat > "$out/calibrate.yaml" <<YAML
base_case: $root/examples/paper_j2_auto_axisymmetric.yaml
output: $out/calibration
parameters:
  material.yield_stress:      {start: 0.25, min: 0.05, max: 1.0}
  material.hardening_modulus: {start: 1.0,  min: 0.0,  max: 5.0}
data:
  - {kind: load_penetration, file: $out/truth/load_penetration.csv, branch: loading}
  - {kind: load_penetration, file: $out/truth/load_penetration.csv, branch: unloading, weight: 0.5}
YAML
"$indentsim" calibrate "$out/calibrate.yaml" --jobs 2 | tee "$out/calibrate.txt"

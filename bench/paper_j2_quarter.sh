#!/usr/bin/env bash
# The 3D quarter model of the paper's J2 case on the automatic mesh against the converged curve:
# bench/paper_j2_quarter.yaml (four runs, two side by side, one thread each, about 15 minutes on
# the project's 2-core machine), then each loading curve's pointwise, mean and RMS error against
# P = 23.065 GPa (h + delta)^2 over 1-6 um (bench/curve_error.py; table in OUT/accuracy.md).
# The figures and what they mean: docs/validation.md ("The paper's J2 case on the automatic
# mesh") and docs/performance.md ("The 3D quarter model for a loading curve", whose times are
# of single runs with two threads on a quiet machine, not of these runs side by side).
# Usage (from the repository root, after building): bash bench/paper_j2_quarter.sh [OUT]
# A rerun into the same OUT skips the finished runs.
# Units: lengths um, forces mN, stresses GPa, times s.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(realpath -m "${1:-$root/bench/results/paper_j2_quarter}")"
export OMP_NUM_THREADS=1 DEAL_II_NUM_THREADS=1
start=$(date +%s)
"$root/build/indentsim" study "$root/bench/paper_j2_quarter.yaml" --jobs 2 --output "$out"
/usr/bin/python3 "$root/bench/curve_error.py" "$out"/cases/*/ | tee "$out/accuracy.md"
echo "wall time $(( $(date +%s) - start )) s; table in $out/accuracy.md"

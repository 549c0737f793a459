#!/usr/bin/env bash
# Step and mesh convergence of the paper's J2 case in axisymmetric mode: the default example
# with n = 10, 14 and 20 elements per radius and 192, 384 and 768 geometric steps
# (bench/paper_j2_convergence.yaml, seven runs, two side by side, about 5 minutes on the
# project's 2-core machine), then the table of C = P/(h + delta)^2 over 1-6 um, the observed
# order of the step sequence and its Richardson value (bench/paper_j2_convergence.py).
# The figures and what they mean: docs/validation.md, "The paper's J2 case on the automatic mesh".
# Usage (from the repository root, after building): bash bench/paper_j2_convergence.sh [OUT]
# A rerun into the same OUT skips the finished runs.
# Units: lengths um, forces mN, stresses GPa, times s.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(realpath -m "${1:-$root/bench/results/paper_j2_convergence}")"
export OMP_NUM_THREADS=1
start=$(date +%s)
"$root/build/indentsim" study "$root/bench/paper_j2_convergence.yaml" --jobs 2 --output "$out"
/usr/bin/python3 "$root/bench/paper_j2_convergence.py" "$out" | tee "$out/convergence.md"
echo "wall time $(( $(date +%s) - start )) s; table in $out/convergence.md"

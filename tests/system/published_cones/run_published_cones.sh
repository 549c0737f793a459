#!/usr/bin/env bash
# Verification against published finite-element data (CTest: PublishedCones.SixMaterials).
# Requirement: the sharp 70.3 deg cone on power-law J2 solids (nu 0.3, friction 0.15,
# axisymmetric) reproduces the loading curvature C = P/h^2 and the plastic work ratio W_p/W_t of
# Lu et al. (2020) / Dao et al. (2001) for six materials spanning E/sigma_y = 30 ... 700 and
# n = 0 ... 0.5, within the tolerances below.
#
# The six cases (six_materials.yaml) are cases 83, 4, 86, 49, 12 and 53 of the data, run exactly
# as in studies/published_cones.yaml (48 contact elements over r <= 6 um, 0.25 um cells, 40
# loading steps to 1 um). Tolerances, relative to the published value:
#   C = P/h^2: 4 %. Our own discretisation error: the fitted C changes by at most 0.6 % from
#     48 to 96 and 192 contact elements (cases 51 and 81), and 40 loading steps give C 0.6 to
#     1.4 % below 80 steps (cases 81 and 86). Beyond that our values scatter about the published
#     ones: -1.7 ... +1.1 % for n >= 0.1 and -2.7 ... +4.7 % for n = 0 over the study's 24
#     materials; the largest of these six is -2.4 % (case 49, n = 0). 4 % holds that with the
#     step error on top; in the data, n off by 0.1 moves C by 4 % or more (up to 36 %).
#   W_p/W_t: 3 %. Mesh: 0.4 % (case 51 at 48, 96, 192 elements); the largest difference over the
#     24 materials is -1.9 % (case 53, n = 0; -1.5 % for case 49); in the data, n off by 0.1
#     moves W_p/W_t by 1 to 6 %, so this check is the weaker of the two for E/sigma_y >= 300.
#
# Usage: run_published_cones.sh INDENTSIM_EXECUTABLE SCRATCH_DIRECTORY
set -euo pipefail
indentsim="$1"
out="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
rm -rf "$out"
mkdir -p "$(dirname "$out")"

start=$(date +%s)
"$indentsim" study "$here/six_materials.yaml" --output "$out" --jobs 1 > "$out.txt" 2>&1 \
  || { cat "$out.txt"; echo "FAIL: the study failed" >&2; exit 1; }
grep -q "6 case(s) run, 0 skipped" "$out.txt" || { cat "$out.txt"; echo "FAIL: not all 6 cases ran" >&2; exit 1; }
echo "six cases in $(( $(date +%s) - start )) s"

python3 "$root/python/published_cones.py" "$out" --no-plot \
  --max-c-deviation 0.04 --max-wp-deviation 0.03
n_compared=$(grep -c "^lu70_" "$out/published_cones.csv" || true)
[[ "$n_compared" -eq 6 ]] || { echo "FAIL: $n_compared of 6 cases compared" >&2; exit 1; }
echo "PASS"

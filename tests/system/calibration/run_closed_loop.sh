#!/usr/bin/env bash
# Closed-loop test of `indentsim calibrate` (CTest: Calibration.ClosedLoopJ2Cone). Synthetic data
# from known parameters (J2, yield stress 0.3 GPa and hardening modulus 2 GPa, sharp cone,
# axisymmetric, cone_j2.yaml) are fitted from a start 17 % and 50 % off:
#   1. the fit is stopped with SIGINT while its forward runs go through a stand-in launcher
#      (exit code 130; the launcher saw the cases and {ranks});
#   2. the same command continues (finished forward runs reused) and recovers both parameters
#      within 0.5 %, and reports no forward-run warning (this mesh resolves the contact);
#   3. a third run computes nothing (every forward run cached) and gives the same values;
#   4. with 1 % noise (standard deviation 1 % of the largest force; cost tolerance 1e-4) in five
#      seeded draws, both true values lie inside their reported 95 % intervals in at least 4 of
#      the 5 draws. The two
#      estimates correlate at about -0.97, so they miss together: a draw misses with a
#      probability of 5-10 % for true 95 % intervals, two draws of five with 2-8 %;
#   5. the curve of one noisy draw alone leaves the two not identifiable (the warning names both);
#      with a tensile curve added (tensile_j2.yaml at the true values) they are identifiable,
#      within 2 % of the truth and inside their 95 % intervals;
#   6. the scalar features of the true curve (C = P/h^2 fitted here to the loading branch, S and
#      Wp/Wt from the run's Oliver-Pharr analysis, S written in N/m; 40 unloading points) in
#      place of the curve give both parameters back within 0.5 %, and the warning that one test's
#      three numbers do not identify the two (they correlate at about -0.99);
#   7. the hardness-depth profile of the true case with partial unloads (every 0.2 um, 10 % of the
#      force) gives the yield stress back within 1 % (the hardening modulus fixed) with a
#      finite-difference step of 0.01 GPa; with the default narrow step the partial unloads'
#      small jumps can hide the trend, and then the fit must say that it stayed at its start
#      rather than report the start as the optimum.
# Usage: run_closed_loop.sh INDENTSIM_EXECUTABLE SCRATCH_DIRECTORY
# Units: lengths um, forces mN, stresses GPa.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/closed_loop_common.sh" "$@"

"$indentsim" run "$here/cone_j2.yaml" --output "$out/truth" > "$out/truth.txt" 2>&1 \
  || { cat "$out/truth.txt"; fail "the run at the true parameters failed"; }

# calibration_file NAME MEASURED_CSV: a calibration of the two parameters to both branches.
calibration_file() {
  cat > "$out/$1.yaml" <<YAML
base_case: $here/cone_j2.yaml
output: $out/$1
parameters:
  material.yield_stress:      {start: 0.25, min: 0.05, max: 1.0}
  material.hardening_modulus: {start: 1.0,  min: 0.0,  max: 5.0}
data:
  - {kind: load_penetration, file: $2, branch: loading}
  - {kind: load_penetration, file: $2, branch: unloading, weight: 0.5}
YAML
}
# value FILE EXPRESSION: a Python expression of the calibration.json `c`.
value() { "$python" -c "import json,sys; c=json.load(open(sys.argv[1])); print($2)" "$1"; }
# recovered JSON TOLERANCE: both fitted values within TOLERANCE (relative) of the truth.
recovered() {
  local key name truth error
  for key in material.yield_stress:0.3 material.hardening_modulus:2.0; do
    name=${key%%:*}; truth=${key##*:}
    error=$(value "$1" "abs(c['parameters']['$name']['value'] / $truth - 1)")
    echo "$name: relative error $error"
    "$python" -c "import sys; sys.exit(0 if $error < $2 else 1)" \
      || fail "$name recovered with a relative error $error (allowed $2) in $1"
  done
}
# inside JSON: the number of true values (of 2) inside their 95 % intervals.
inside() {
  value "$1" "sum(int(c['parameters'][k]['ci95'][0] <= t <= c['parameters'][k]['ci95'][1])
    for k, t in (('material.yield_stress', 0.3), ('material.hardening_modulus', 2.0)))"
}

calibration_file exact "$out/truth/load_penetration.csv"
status=0
timeout --preserve-status -s INT 8 "$indentsim" calibrate "$out/exact.yaml" --jobs 2 \
  --launcher "bash $here/stand_in_launcher.sh $out/launcher.log {ranks} {command}" \
  > "$out/first.txt" 2>&1 || status=$?
cat "$out/first.txt"
[[ $status -eq 130 ]] || fail "the interrupted calibration ended with $status, not 130"
[[ ! -e "$out/exact/calibration.json" ]] || fail "an interrupted calibration wrote results"
grep -q "^ranks=1 .* run $out/exact/forward/cases/c0-.*/case.yaml" "$out/launcher.log" \
  || fail "the stand-in launcher did not run the forward cases: $(cat "$out/launcher.log")"

"$indentsim" calibrate "$out/exact.yaml" --jobs 2 > "$out/second.txt" 2>&1 \
  || { cat "$out/second.txt"; fail "the continued calibration failed"; }
cat "$out/second.txt"
json="$out/exact/calibration.json"
recovered "$json" 0.005
# This mesh resolves the contact: no forward run warns, and the fit says nothing of them.
[[ $(value "$json" "c['forward_runs_warned']") -eq 0 ]] || fail "forward runs warned: $(cat "$json")"
! grep -q "forward run at the fitted values" "$out/second.txt" || fail "a warning of no run"
[[ $(value "$json" "c['forward_runs_reused']") -gt 0 ]] || fail "nothing of the stopped run reused"
grep -q "Identifiable: NO" "$out/exact/report.md" || fail "report.md does not say NOT identifiable"
for file in iterations.csv fit_data0.csv fit_data1.csv fit_data0.png iterations.png; do
  [[ -s "$out/exact/$file" ]] || fail "no $file"
done

"$indentsim" calibrate "$out/exact.yaml" > "$out/third.txt" 2>&1 || fail "the rerun failed"
[[ $(value "$json" "c['forward_runs']") -eq 0 ]] || fail "the rerun computed forward runs again"
fitted=$(grep "material.yield_stress =" "$out/second.txt")
[[ -n $fitted && "$(grep "material.yield_stress =" "$out/third.txt")" == "$fitted" ]] \
  || fail "the rerun changed the fit: $(grep "material.yield_stress =" "$out/third.txt")"

covered=0
for seed in 1 2 3 4 5; do
  "$python" "$here/add_noise.py" "$out/truth/load_penetration.csv" "$out/noisy$seed.csv" $seed 0.01
  calibration_file "noisy$seed" "$out/noisy$seed.csv"
  # 1 % noise: a relative change of the cost below 1e-4 moves nothing the intervals show.
  echo "solver: {function_tolerance: 1.0e-4, parameter_tolerance: 1.0e-3}" >> "$out/noisy$seed.yaml"
  "$indentsim" calibrate "$out/noisy$seed.yaml" --jobs 2 > "$out/noisy$seed.txt" 2>&1 \
    || { cat "$out/noisy$seed.txt"; fail "the calibration of seed $seed failed"; }
  grep -A2 "^Fitted" "$out/noisy$seed.txt"
  inside=$(inside "$out/noisy$seed/calibration.json")
  echo "seed $seed: $inside of 2 true values inside their 95 % intervals"
  [[ $inside -eq 2 ]] && covered=$((covered + 1))
done
echo "draws with both true values inside the 95 % intervals: $covered of 5"
[[ $covered -ge 4 ]] || fail "only $covered of 5 draws hold both true values"
grep -q "NOT identifiable" "$out/noisy1.txt" || fail "one cone curve reported as identifiable"
grep -q "material.yield_stress and material.hardening_modulus correlate" "$out/noisy1.txt" \
  || fail "the warning does not name the correlated parameters"
"$indentsim" run "$here/tensile_j2.yaml" --output "$out/tensile_truth" > "$out/tensile.txt" 2>&1 \
  || { cat "$out/tensile.txt"; fail "the tensile run at the true parameters failed"; }
calibration_file both "$out/noisy1.csv"
echo "  - {kind: tensile, file: $out/tensile_truth/stress_strain.csv, case: $here/tensile_j2.yaml}" \
  >> "$out/both.yaml"
"$indentsim" calibrate "$out/both.yaml" --jobs 2 > "$out/both.txt" 2>&1 \
  || { cat "$out/both.txt"; fail "the calibration with the tensile curve failed"; }
grep -A2 "^Fitted" "$out/both.txt"
[[ $(value "$out/both/calibration.json" "c['identifiable']") == True ]] \
  || fail "with the tensile curve the parameters are still not identifiable"
recovered "$out/both/calibration.json" 0.02
[[ $(inside "$out/both/calibration.json") -eq 2 ]] \
  || fail "with the tensile curve a 95 % interval misses the true value"

# The same case with 40 unloading points (Oliver-Pharr fits S to those above 0.5 P_max); C by
# least squares of P = C h^2 over the loading rows (segment load), independently of the
# program's own fit.
sed 's/unload: true}/unload: true, unload_points: 40}/' "$here/cone_j2.yaml" \
  > "$out/cone_features.yaml"
grep -q "unload_points: 40" "$out/cone_features.yaml" || fail "no unload_points in the case"
"$indentsim" run "$out/cone_features.yaml" --output "$out/features_truth" \
  > "$out/features_truth.txt" 2>&1 || { cat "$out/features_truth.txt"; fail "the run failed"; }
"$python" - "$out/features_truth" "$out/features.csv" <<'PY'
import csv, json, sys
rows = list(csv.DictReader(open(sys.argv[1] + "/load_penetration.csv")))
loading = [(float(r["depth_um"]), float(r["force_mN"])) for r in rows if r["segment"] == "load"]
C = sum(P * h * h for h, P in loading) / sum(h ** 4 for h, P in loading)
op = json.load(open(sys.argv[1] + "/oliver_pharr.json"))
with open(sys.argv[2], "w") as out:
    out.write("C (GPa),dP/dh (N/m),Wp/Wt,hm (um)\n")
    out.write(f"{C!r},{op['stiffness_mN_per_um'] * 1e3!r},{op['plastic_work_ratio']!r},"
              f"{op['max_depth_um']!r}\n")
PY
cat "$out/features.csv"
calibration_file features "$out/features.csv"
sed -i -e '/kind: load_penetration/d' -e "s#^base_case: .*#base_case: $out/cone_features.yaml#" \
  "$out/features.yaml"
echo "  - {kind: indentation_features, file: $out/features.csv}" >> "$out/features.yaml"
"$indentsim" calibrate "$out/features.yaml" --jobs 2 > "$out/features.txt" 2>&1 \
  || { cat "$out/features.txt"; fail "the calibration to the features failed"; }
grep -A2 "^Fitted" "$out/features.txt"
recovered "$out/features/calibration.json" 0.005
grep -q "NOT identifiable" "$out/features.txt" || fail "one test's C, S and Wp/Wt identify both"
[[ -s "$out/features/fit_data0.png" ]] || fail "no figure of the features"

sed 's/unload: true}/unload: true, partial_unloads: {every: 0.2, fraction: 0.1}}/' \
  "$here/cone_j2.yaml" > "$out/cone_hardness.yaml"
grep -q "partial_unloads" "$out/cone_hardness.yaml" || fail "no partial_unloads in the case"
"$indentsim" run "$out/cone_hardness.yaml" --output "$out/hardness_truth" \
  > "$out/hardness_truth.txt" 2>&1 || { cat "$out/hardness_truth.txt"; fail "the run failed"; }
# hardness_fit NAME EXTRA_BOUND_KEYS: the yield stress fitted to the true hardness profile.
hardness_fit() {
  cat > "$out/$1.yaml" <<YAML
base_case: $out/cone_hardness.yaml
output: $out/$1
parameters:
  material.yield_stress: {start: 0.25, min: 0.05, max: 1.0$2}
data:
  - {kind: hardness_depth, file: $out/hardness_truth/hardness_depth.csv}
YAML
  "$indentsim" calibrate "$out/$1.yaml" --jobs 2 > "$out/$1.txt" 2>&1 \
    || { cat "$out/$1.txt"; fail "the calibration $1 failed"; }
  grep -A1 "^Fitted" "$out/$1.txt"
  value "$out/$1/calibration.json" "abs(c['parameters']['material.yield_stress']['value'] / 0.3 - 1)"
}
error=$(hardness_fit hardness ", step: 0.01" | tail -n 1)
echo "yield stress from the hardness profile: relative error $error"
"$python" -c "import sys; sys.exit(0 if $error < 0.01 else 1)" \
  || fail "the yield stress from the hardness profile is off by $error"
error=$(hardness_fit hardness_narrow "" | tail -n 1)
echo "with the default step: relative error $error"
"$python" -c "import sys; sys.exit(0 if $error < 0.01 else 1)" \
  || grep -q "no trial step lowered the cost" "$out/hardness_narrow.txt" \
  || fail "the fit with the default step is off by $error and does not say it stayed at its start"
echo "PASS"

#!/usr/bin/env bash
# Closed-loop test of `indentsim calibrate` for a crystal (CTest: Calibration.ClosedLoopCrystal).
# Synthetic data from known parameters, the paper's FCC crystal (Table 2: tau0 = 0.12 GPa,
# theta0 = 0.1 GPa): the 27-grain tensile curve (tensile_crystal.yaml) and one indentation curve
# of (001) (cone_crystal.yaml). From a start 17 % and 50 % off, the fit of tau0 and theta0 to both
# curves recovers both within 2 % and calls them identifiable (their correlation below 0.95: the
# tensile curve fixes tau0 and the hardening, the indentation adds the larger strains). Without
# noise the residual, and with it the 95 % intervals, shrink to the solver's tolerance; the
# intervals' coverage under noise is the J2 loop's (run_closed_loop.sh, stage 4).
# The indentation case's coarse mesh puts about 1.3 elements across the contact radius, so each of
# its forward runs warns (contact_resolution in its run_summary.json) and the tensile runs do
# not: the calibration names the indentation run at the fitted values, and counts as many warned
# runs as it computed indentation runs.
# Usage: run_closed_loop_crystal.sh INDENTSIM_EXECUTABLE SCRATCH_DIRECTORY
# Units: lengths um, forces mN, stresses GPa.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/closed_loop_common.sh" "$@"

run_truth cone_crystal tensile_crystal
cat > "$out/fit.yaml" <<YAML
base_case: $here/cone_crystal.yaml
output: $out/fit
parameters:
  material.hardening.tau0:   {start: 0.14, min: 0.05, max: 0.5}
  material.hardening.theta0: {start: 0.15, min: 0.01, max: 1.0}
data:
  - {kind: load_penetration, file: $out/cone_crystal/load_penetration.csv, branch: loading}
  - {kind: tensile, file: $out/tensile_crystal/stress_strain.csv, case: $here/tensile_crystal.yaml}
YAML
calibrate_and_check "$out/fit.yaml" 0.02 material.hardening.tau0=0.12 material.hardening.theta0=0.1
grep -q "the forward run at the fitted values, $out/fit/forward/cases/c0-[0-9a-f]*, warned: contact_resolution" \
  "$out/fit.txt" || fail "the calibration did not name the warning of the indentation run at the fit"
if grep -q "the forward run at the fitted values, $out/fit/forward/cases/c1-" "$out/fit.txt"; then
  fail "the calibration says a tensile run warned"
fi
indentation_runs=$(ls -d "$out"/fit/forward/cases/c0-*/ | wc -l)
warned=$("$python" -c "import json,sys; print(json.load(open(sys.argv[1]))['forward_runs_warned'])" \
  "$out/fit/calibration.json")
[[ $warned -eq $indentation_runs && $warned -gt 0 ]] \
  || fail "forward_runs_warned is $warned; the fit computed $indentation_runs indentation runs"
echo "PASS"

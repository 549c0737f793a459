#!/usr/bin/env bash
# Closed-loop test of `indentsim calibrate` for a depth-graded specimen (CTest:
# Calibration.ClosedLoopLayer). Synthetic data from known parameters: the indentation curve of a
# hard surface layer on a J2 substrate (cone_layer.yaml: the layer's yield stress 0.9 GPa, the
# substrate's 0.3 GPa) and the substrate's tensile curve (tensile_j2.yaml, the same 0.3 GPa). The
# fit of the substrate's yield stress (material.yield_stress, seen by both cases) and the
# layer's (material.layers[0].yield_stress, seen by the indentation only) from a start 17 % and
# 33 % off recovers both within 0.5 % and calls them identifiable. Points that differ in the
# layer's value only share their tensile run, so fewer tensile than indentation runs are made.
# The same fit again, with the forward run at the first Jacobian's upward step of the
# substrate's yield stress (0.25 + 1e-3 x 0.25) failing on purpose (failing_launcher.sh): that
# column is differenced downward instead, the fit recovers both values within 0.5 % all the
# same, and the console names the failed run with its last lines.
# Usage: run_closed_loop_layer.sh INDENTSIM_EXECUTABLE SCRATCH_DIRECTORY
# Units: lengths um, forces mN, stresses GPa.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/closed_loop_common.sh" "$@"

run_truth cone_layer tensile_j2
cat > "$out/fit.yaml" <<YAML
base_case: $here/cone_layer.yaml
output: $out/fit
parameters:
  material.yield_stress:           {start: 0.25, min: 0.05, max: 1.0}
  material.layers[0].yield_stress: {start: 0.6,  min: 0.05, max: 3.0}
data:
  - {kind: load_penetration, file: $out/cone_layer/load_penetration.csv, branch: loading}
  - {kind: tensile, file: $out/tensile_j2/stress_strain.csv, case: $here/tensile_j2.yaml}
YAML
calibrate_and_check "$out/fit.yaml" 0.005 material.yield_stress=0.3 \
  "material.layers[0].yield_stress=0.9"
indentation=$(ls "$out/fit/forward/cases" | grep -c '^c0-' || true)
tensile=$(ls "$out/fit/forward/cases" | grep -c '^c1-' || true)
echo "forward runs: $indentation indentation, $tensile tensile"
[ "$tensile" -gt 0 ] && [ "$tensile" -lt "$indentation" ] \
  || fail "points that differ only in the layer's value did not share their tensile run"
sed "s|^output: .*|output: $out/failing|" "$out/fit.yaml" > "$out/failing.yaml"
calibrate_options=(--launcher "bash $here/failing_launcher.sh ^[[:space:]]{2}yield_stress:[[:space:]]0\.25025 {command}")
calibrate_and_check "$out/failing.yaml" 0.005 material.yield_stress=0.3 \
  "material.layers[0].yield_stress=0.9"
grep -q "^WARNING: the forward run $out/failing/forward/cases/c0-.* failed (exit code 1)" \
  "$out/failing.txt" || fail "no warning naming the failed forward run"
grep -q "failed on purpose" "$out/failing.txt" || fail "the warning does not show the run's output"
[[ $("$python" -c "import json,sys; print(json.load(open(sys.argv[1]))['forward_runs_failed'])" \
  "$out/failing/calibration.json") -ge 1 ]] || fail "calibration.json counts no failed run"
echo "PASS"

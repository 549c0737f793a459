# Shared steps of the closed-loop tests of `indentsim calibrate` (run_closed_loop*.sh), sourced
# after `set -euo pipefail` with the script's two arguments: INDENTSIM_EXECUTABLE and
# SCRATCH_DIRECTORY (emptied). Units: lengths um, forces mN, stresses GPa.
indentsim="$1"
out="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
python=/usr/bin/python3
rm -rf "$out"
mkdir -p "$out"
fail() { echo "FAIL: $*" >&2; exit 1; }

# run_truth CASE...: each case file of this folder (without .yaml) run at the true parameters
# into $out/CASE.
run_truth() {
  local case
  for case in "$@"; do
    "$indentsim" run "$here/$case.yaml" --output "$out/$case" > "$out/$case.txt" 2>&1 \
      || { cat "$out/$case.txt"; fail "the run of $case.yaml at the true parameters failed"; }
  done
}

# calibrate_and_check FIT_YAML TOLERANCE KEY=TRUTH...: the calibration with two forward runs
# side by side (and the options in the array calibrate_options, if any), its summary printed;
# every KEY recovered within the relative TOLERANCE and the parameters called identifiable. The
# results are in the `output` the file names.
calibrate_options=()
calibrate_and_check() {
  local fit="$1" tolerance="$2"
  shift 2
  "$indentsim" calibrate "$fit" --jobs 2 "${calibrate_options[@]}" > "${fit%.yaml}.txt" 2>&1 \
    || { cat "${fit%.yaml}.txt"; fail "the calibration failed"; }
  cat "${fit%.yaml}.txt"
  "$python" - "$(sed -n 's/^output: //p' "$fit")/calibration.json" "$tolerance" "$@" <<'PY' \
    || fail "see above"
import json, sys
c = json.load(open(sys.argv[1]))
tolerance = float(sys.argv[2])
ok = c["identifiable"] is True
print("identifiable:", c["identifiable"], "correlation:", c["correlation"])
for pair in sys.argv[3:]:
    name, truth = pair.rsplit("=", 1)
    truth = float(truth)
    p = c["parameters"][name]
    error = abs(p["value"] / truth - 1)
    print(f"{name}: {p['value']} (truth {truth}, relative error {error:.2e}), 95 % {p['ci95']}")
    ok = ok and error < tolerance
sys.exit(0 if ok else 1)
PY
}

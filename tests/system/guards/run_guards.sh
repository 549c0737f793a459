#!/usr/bin/env bash
# End-to-end test of the guards of `indentsim check` and `run` (CTest: Guards.EndToEnd).
# Requirements: a contact that outgrows the refined region stops the run with exit code 5, a
# message naming specimen.refined_region and specimen.contact_elements, and the curve and
# run.log so far kept; check and run refuse (exit code 1, nothing written) a refined region that
# cannot hold the predicted contact, a case whose memory estimate exceeds the available memory,
# and a count key beyond its bound, each naming the key and what is allowed; a run warns once,
# on stderr and in run.log (and once more by topic at the end, and in run_summary.json), when the
# plastic zone nears the bottom face, when a damage profile is
# cut off above 1 % of its peak and when fewer than 5
# contact elements lie across the contact radius at the maximum depth.
# Usage: run_guards.sh INDENTSIM_EXECUTABLE SCRATCH_DIRECTORY
set -uo pipefail
indentsim="$1"
out="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
rm -rf "$out"
mkdir -p "$out"

fail() { echo "FAIL: $*" >&2; exit 1; }
# expect CODE NAME COMMAND...: runs the command, its output in $out/NAME.txt, checks the code.
expect() {
  local code="$1" name="$2"
  shift 2
  "$@" > "$out/$name.txt" 2>&1
  local got=$?
  [[ $got -eq $code ]] || { cat "$out/$name.txt"; fail "$name exited with $got, expected $code"; }
}
has() { grep -qF -- "$2" "$out/$1.txt" || { cat "$out/$1.txt"; fail "$1 lacks: $2"; }; }

# 1. The contact outgrows the refined region during the run: exit code 5, outputs kept.
expect 0 outgrown_check "$indentsim" check "$here/outgrown_force_control.yaml"
expect 5 outgrown "$indentsim" run "$here/outgrown_force_control.yaml" --output "$out/outgrown"
has outgrown "the computation stopped: the contact reached"
has outgrown "specimen.refined_region: ["
has outgrown "specimen.contact_elements: "
has outgrown "a smaller loading.max_force"
rows=$(($(wc -l < "$out/outgrown/load_penetration.csv") - 1))
[[ $rows -ge 2 ]] || fail "the stopped run kept $rows rows of load_penetration.csv"
grep -qF "# stopped: the contact reached" "$out/outgrown/run.log" || fail "run.log lacks the stop"

# 2. check (and run) refuse the issue's case: the predicted contact does not fit.
expect 1 issue_check "$indentsim" check "$here/issue_cone.yaml"
has issue_check "specimen.refined_region = [16, 16, 4]: the refined region cannot hold the contact"
has issue_check "specimen.contact_elements: "
has issue_check "loading.max_depth <= "
expect 1 issue_run "$indentsim" run "$here/issue_cone.yaml" --output "$out/issue"
[[ ! -e "$out/issue" ]] || fail "the refused run wrote $out/issue"

# 3. The plastic zone nears the bottom of a thin layer: one warning, on stderr and in run.log.
expect 0 thin "$indentsim" run "$here/thin_specimen.yaml" --output "$out/thin"
has thin "indentsim: warning: the plastic zone"
has thin "from the fixed bottom face z = -3"
has thin "specimen.size[2] (now 3 um) at least"
[[ $(grep -c "fixed bottom face" "$out/thin.txt") -eq 1 ]] || fail "the bottom warning is not once"
has thin "warnings in this run (plastic_zone_bottom, contact_resolution); the texts are in run.log"
grep -qF '{"topic": "plastic_zone_bottom", "text": "the plastic zone' "$out/thin/run_summary.json" \
  || fail "run_summary.json lacks the bottom warning"
[[ $(grep -c "# warning: the plastic zone.*fixed bottom face" "$out/thin/run.log") -eq 1 ]] \
  || fail "run.log lacks the bottom warning (once)"

# 4. Too few contact elements across the contact radius at the maximum depth.
expect 0 coarse "$indentsim" run "$here/coarse_contact.yaml" --output "$out/coarse"
has coarse "contact elements across the contact radius at the maximum"
has coarse "specimen.contact_elements: 32 (now 8"
grep -qF "# warning: " "$out/coarse/run.log" || fail "run.log lacks the resolution warning"
has coarse "warning in this run (contact_resolution)"

# 6. A damage profile cut off above 1 % of its peak's dose: one warning, on stderr and in run.log.
sed 's/^  model: j2$/  model: j2\n  damage_profile: {depth: [0, 0.5], dpa: [1, 0.5], law: {form: saturation, saturation_increment: 0.2, saturation_dose: 0.5}}/' \
  "$here/coarse_contact.yaml" > "$out/cut_profile.yaml"
expect 0 cut "$indentsim" run "$out/cut_profile.yaml" --output "$out/cut"
has cut "indentsim: warning: material.damage_profile ends at 0.5 dpa (50 % of its peak)"
[[ $(grep -c "material.damage_profile ends" "$out/cut.txt") -eq 1 ]] \
  || fail "the damage profile warning is not once"
grep -qF "# warning: material.damage_profile ends" "$out/cut/run.log" \
  || fail "run.log lacks the damage profile warning"

# 5. The memory estimate: printed by check; a case that does not fit in the memory available
# (fixed here to 2000 MiB so that the test does not depend on the machine) is refused.
expect 0 default_check "$indentsim" check "$here/coarse_contact.yaml"
has default_check "# Estimated size: "
sed 's/^  contact_elements: 8$/  contact_elements: 128/' "$here/coarse_contact.yaml" \
  > "$out/huge.yaml"
expect 1 huge_check env INDENTSIM_AVAILABLE_MEMORY_MB=2000 "$indentsim" check "$out/huge.yaml"
has huge_check "specimen.contact_elements = 128: the case needs about"
has huge_check "available"
has huge_check " fits"
expect 1 huge_run env INDENTSIM_AVAILABLE_MEMORY_MB=2000 "$indentsim" run "$out/huge.yaml" \
  --output "$out/huge"
[[ ! -e "$out/huge" ]] || fail "the refused run wrote $out/huge"

# 6. A count key beyond its bound.
sed 's/^  contact_elements: 8$/  contact_elements: 100000/' "$here/coarse_contact.yaml" \
  > "$out/typo.yaml"
expect 1 typo_check "$indentsim" check "$out/typo.yaml"
has typo_check "specimen.contact_elements = 100000"
has typo_check "4 <= N <= 512"

echo "Guards.EndToEnd: OK"

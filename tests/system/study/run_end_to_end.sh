#!/usr/bin/env bash
# End-to-end test of `indentsim study` (CTest: Study.EndToEnd). Requirement: the command runs a
# study's cases and writes report.md / report.html with the tensile, mesh-convergence,
# orientation, pile-up and paper tables; a rerun skips every finished case, runs no simulation
# and rewrites only the report.
# Usage: run_end_to_end.sh INDENTSIM_EXECUTABLE SCRATCH_DIRECTORY
set -euo pipefail
indentsim="$1"
out="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
rm -rf "$out"
mkdir -p "$(dirname "$out")"

fail() { echo "FAIL: $*" >&2; exit 1; }

start=$(date +%s%N)
"$indentsim" study "$here/tiny_study.yaml" --output "$out" --jobs 2 > "$out.first.txt" 2>&1 \
  || { cat "$out.first.txt"; fail "the first study run failed"; }
first=$(( ($(date +%s%N) - start) / 1000000 ))
cat "$out.first.txt"
grep -q "6 case(s) run, 0 skipped" "$out.first.txt" || fail "not all 6 cases ran"

report="$out/report.md"
[[ -s "$report" ]] || fail "no report.md"
[[ -s "$out/report.html" ]] || fail "no report.html"
for figure in tensile.png mesh_j2.png mesh_crystal.png mesh_force.png orientations.png; do
  [[ -s "$out/figures/$figure" ]] || fail "no figure $figure"
done
expect() { grep -qF -- "$1" "$report" || fail "report.md lacks: $1"; }
expect "**Units: lengths µm, forces mN, stresses GPa"
expect "| case | label | groups | key | status |"
expect "## 1. Tensile calibration"
expect "| log strain | J2 [GPa] | seed 1 [GPa] | crystal mean [GPa] |"
expect "| 0.05 | 0.328 |"                       # J2 at 5 % (closed form 0.328 GPa, README)
expect "| contact elements | h [µm] | symmetry | max depth [µm] | DOFs | force at max depth [mN] |"
expect "| 4, 8, 12 | 2, 1.5 |"                  # observed order from the three meshes
expect "observed order p"
expect "| 8×8 | **spread** | 2 orientations |"
expect "| dominant fold | symmetry fold | max pile-up [µm] |"
expect "pileup_unloaded.png)"
expect "| J2, 12×12 | 10.0 |"
expect "reaches **5 mN at a depth of"
expect "## 6. Oliver–Pharr analysis and measured curves"
expect "| case | P_max [mN] | S [mN/µm] | h_c [µm] | H [GPa] | E_r [GPa] |"
expect "| case | measured curve | points | RMS [mN] |"
expect "indentsim 0.1.0"
expect "resolved_case.yaml](cases/"
grep -q "This section could not be written" "$report" && fail "a report section failed"
grep -q "<table>" "$out/report.html" || fail "report.html has no table"

# The rerun: every case skipped, no run_summary.json rewritten.
stamp_before=$(stat -c %Y "$out"/cases/*/run_summary.json | sort | tr '\n' ' ')
sleep 1
start=$(date +%s%N)
"$indentsim" study "$here/tiny_study.yaml" --output "$out" > "$out.second.txt" 2>&1 \
  || { cat "$out.second.txt"; fail "the rerun failed"; }
second=$(( ($(date +%s%N) - start) / 1000000 ))
cat "$out.second.txt"
grep -q "6 finished case(s) skipped, 0 to run" "$out.second.txt" || fail "rerun did not skip all"
grep -q "0 case(s) run, 6 skipped" "$out.second.txt" || fail "rerun summary wrong"
[[ $(grep -c "finished: skipped" "$out.second.txt") -eq 6 ]] || fail "not every case says skipped"
grep -q "^run " "$out.second.txt" && fail "the rerun started a case"
stamp_after=$(stat -c %Y "$out"/cases/*/run_summary.json | sort | tr '\n' ' ')
[[ "$stamp_before" == "$stamp_after" ]] || fail "a finished case was recomputed"
[[ -s "$report" ]] || fail "the rerun lost report.md"
echo "first run ${first} ms, rerun ${second} ms (report only)"
echo "PASS"

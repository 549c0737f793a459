#!/usr/bin/env bash
# End-to-end test of stopping and resuming `indentsim run` (CTest: Resume.EndToEnd).
# Requirement: a run stopped after step 3 (INDENTSIM_STOP_AFTER_STEP, as Ctrl-C would) exits
# with code 130 and says how to resume; `--resume` finishes it, and its load_penetration.csv
# equals an uninterrupted run's in every column but wall_time_s; the finished run leaves no
# checkpoint; --resume with --overwrite, a plain rerun and a resume without checkpoint are refused.
# Usage: run_end_to_end.sh INDENTSIM_EXECUTABLE SCRATCH_DIRECTORY [CASE_FILE]
# (CASE_FILE: small_j2.yaml next to this script by default.)
set -uo pipefail
indentsim="$1"
out="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
case_file="${3:-$here/small_j2.yaml}"
rm -rf "$out"
mkdir -p "$out"

fail() { echo "FAIL: $*" >&2; exit 1; }

"$indentsim" run "$case_file" --output "$out/reference" > "$out/reference.txt" 2>&1 \
  || { cat "$out/reference.txt"; fail "the uninterrupted run failed"; }

INDENTSIM_STOP_AFTER_STEP=3 "$indentsim" run "$case_file" --output "$out/resumed" \
  > "$out/stopped.txt" 2>&1
code=$?
cat "$out/stopped.txt"
[[ $code -eq 130 ]] || fail "the stopped run exited with $code, expected 130"
grep -qE "^stopped at step 3 \(depth [0-9.]+ um\); resume with: " "$out/stopped.txt" \
  || fail "no stop message"
grep -qF "resume with: $indentsim run $case_file --output" "$out/stopped.txt" \
  || fail "the stop message lacks the command"
grep -qF -- "--resume" "$out/stopped.txt" || fail "the stop message lacks --resume"
[[ -f "$out/resumed/checkpoint/rank_0.bin" ]] || fail "no checkpoint written"
[[ ! -f "$out/resumed/pileup.json" ]] || fail "a stopped run wrote end-of-run outputs"

"$indentsim" run "$case_file" --output "$out/resumed" > "$out/plain_rerun.txt" 2>&1
[[ $? -eq 1 ]] || fail "a plain rerun into the stopped run's directory was not refused"
"$indentsim" run "$case_file" --output "$out/resumed" --resume --overwrite > "$out/both.txt" 2>&1
[[ $? -eq 2 ]] || fail "--resume with --overwrite was not refused as bad usage"
"$indentsim" run "$case_file" --output "$out/none" --resume > "$out/none.txt" 2>&1
code=$?
[[ $code -eq 1 ]] || { cat "$out/none.txt"; fail "--resume without a directory exited with $code, expected 1"; }

"$indentsim" run "$case_file" --output "$out/resumed" --resume > "$out/resume.txt" 2>&1 \
  || { cat "$out/resume.txt"; fail "the resumed run failed"; }
grep -qF "Resumed at step 3" "$out/resume.txt" || fail "no resume message"
grep -qF "# resumed at step 3" "$out/resumed/run.log" || fail "run.log lacks the resume line"
[[ ! -e "$out/resumed/checkpoint" ]] || fail "the finished run left its checkpoint"
[[ -f "$out/resumed/pileup.json" ]] || fail "the resumed run wrote no pileup.json"

# All columns but the last (wall_time_s) must be equal (the CSV holds 10 digits).
strip() { sed 's/,[^,]*$//' "$1"; }
diff <(strip "$out/reference/load_penetration.csv") <(strip "$out/resumed/load_penetration.csv") \
  || fail "the resumed load_penetration.csv differs from the uninterrupted run's"
echo "Resume.EndToEnd: OK ($(($(wc -l < "$out/reference/load_penetration.csv") - 1)) rows equal)"

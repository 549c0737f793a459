#!/usr/bin/env bash
# Refused and needless resumes of `indentsim run --resume`, and the printed resume command
# (CTest: Resume.RefusedResumeChangesNothing).
# Requirement: a resume with a changed case is refused (exit code 1) before anything is written:
# every file in the directory keeps its checksum and time, and the message names each key that
# differs with its old and new value; the resume command printed by a stopped run, run
# literally from the same working directory, resumes it (it has the case file and --output DIR);
# --resume on a finished directory says so, exits 0 and changes nothing (with a changed case:
# refused, exit 1, nothing changed).
# Usage: refused_resume.sh INDENTSIM_EXECUTABLE SCRATCH_DIRECTORY
set -uo pipefail
indentsim="$1"
out="$2"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
rm -rf "$out"
mkdir -p "$out/work"
cd "$out/work" || exit 1

fail() { echo "FAIL: $*" >&2; exit 1; }
# Every file under $1 with its checksum and modification time (a rewrite with the same content
# counts as a change too).
checksums() {
  (cd "$1" && find . -type f -print0 | sort -z | xargs -0 sha256sum \
    && find . -type f -printf '%p %T@\n' | sort)
}

# The case as the user has it (relative path), and a copy with two result keys changed.
cp "$here/small_j2.yaml" case.yaml
sed -e 's/^  model: j2$/  model: j2\n  yield_stress: 0.5/' -e 's/^  steps: 6$/  steps: 7/' \
  case.yaml > changed.yaml
grep -qF "yield_stress: 0.5" changed.yaml && grep -qF "steps: 7" changed.yaml \
  || fail "the changed case was not made"

INDENTSIM_STOP_AFTER_STEP=2 "$indentsim" run case.yaml --output stopped > stop.txt 2>&1
code=$?
[[ $code -eq 130 ]] || { cat stop.txt; fail "the stopped run exited with $code, expected 130"; }
before="$(checksums stopped)"

# A changed case: refused, named, nothing changed.
"$indentsim" run changed.yaml --output stopped --resume > changed.txt 2>&1
code=$?
cat changed.txt
[[ $code -eq 1 ]] || fail "the changed resume exited with $code, expected 1"
grep -qF "material.yield_stress: 0.305 -> 0.5" changed.txt || fail "yield_stress not named"
grep -qF "loading.steps: 6 -> 7" changed.txt || fail "loading.steps not named"
[[ "$(checksums stopped)" == "$before" ]] || fail "the refused resume changed files"

# The printed command resumes the run, as printed, from the same working directory.
command="$(sed -n 's/^stopped at step 2 (depth [0-9.]* um); resume with: //p' stop.txt)"
[[ -n "$command" ]] || { cat stop.txt; fail "no resume command printed"; }
[[ "$command" == *" run case.yaml --output stopped --resume" ]] \
  || fail "the resume command lacks the case file or --output: $command"
bash -c "$command" > resumed.txt 2>&1 || { cat resumed.txt; fail "the printed command failed: $command"; }
grep -qF "Resumed at step 2" resumed.txt || fail "the printed command did not resume"
[[ -f stopped/run_summary.json && ! -e stopped/checkpoint ]] || fail "the resumed run did not finish"

# --resume on the finished directory: says so, changes nothing.
before="$(checksums stopped)"
"$indentsim" run case.yaml --output stopped --resume > finished.txt 2>&1
code=$?
cat finished.txt
[[ $code -eq 0 ]] || fail "--resume on a finished run exited with $code, expected 0"
grep -qF "is finished" finished.txt || fail "no message that the run is finished"
"$indentsim" run changed.yaml --output stopped --resume > finished_changed.txt 2>&1
code=$?
cat finished_changed.txt
[[ $code -eq 1 ]] || fail "--resume of a changed case on a finished run exited with $code, expected 1"
grep -qF "material.yield_stress: 0.305 -> 0.5" finished_changed.txt || fail "yield_stress not named"
[[ "$(checksums stopped)" == "$before" ]] || fail "--resume on a finished run changed files"
echo "Resume.RefusedResumeChangesNothing: OK"

#!/usr/bin/env bash
# Output failures of `indentsim run` end to end (CTest: OutputFailure.EndToEnd and, with the
# argument `mpi`, OutputFailure.Mpi).
# Requirement: a write that fails (a full disk) ends the run with exit code 4 and one message
# naming the file and the system's reason ("No space left on device"), without a library error
# dump; it leaves no partial or temporary file in place of a good one, keeps the last checkpoint
# (checksum unchanged), and the run resumes from it once there is space again. Under mpirun no
# rank is left waiting when another rank's file, or a file of rank 0 alone, fails.
# A full disk is a small tmpfs filled up where the test may mount one (root, a container that
# allows it); otherwise, and for the targeted failures, /dev/full (every write to it fails with
# ENOSPC) behind a symbolic link at the temporary name `<file>.tmp` that the file is written to.
# Usage: run_end_to_end.sh INDENTSIM_EXECUTABLE SCRATCH_DIRECTORY [mpi]
set -uo pipefail
indentsim="$1"
out="$2"
mode="${3:-serial}"
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
case_file="$here/../resume/small_j2.yaml"
no_space="No space left on device"
umount "$out/full_fs" 2> /dev/null
rm -rf "$out"
mkdir -p "$out"

fail() { echo "FAIL: $*" >&2; exit 1; }
[[ -c /dev/full ]] || fail "/dev/full is missing: no way to simulate a full disk"

# Every file under $1 with its checksum.
checksums() { (cd "$1" && find . -type f -print0 | sort -z | xargs -0 sha256sum); }
# Fails if a temporary file was left under $1.
no_temporary_files() {
  local left
  left="$(find "$1" -name '*.tmp')"
  [[ -z "$left" ]] || fail "temporary files left behind: $left"
}
# Fails unless the console output $1 has the I/O message for file $2, and no library dump.
expect_io_message() {
  grep -qF "indentsim: error: cannot write '$2': $no_space" "$1" \
    || { cat "$1"; fail "no message naming '$2' and the reason"; }
  ! grep -qE "Stacktrace|An error occurred in line|ExcIO" "$1" \
    || { cat "$1"; fail "a library error dump instead of the message"; }
}

if [[ "$mode" == mpi ]]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  run_mpi() { timeout 300 mpirun --oversubscribe -np 2 "$indentsim" run "$case_file" "$@"; }

  # Rank 1's piece of the VTU at maximum depth cannot be written: both ranks stop, rank 0's
  # piece of that step is not left without its record.
  dir="$out/mpi_vtu"
  mkdir -p "$dir"
  ln -s /dev/full "$dir/specimen_0001.1.vtu.tmp"
  run_mpi --output "$dir" > "$out/mpi_vtu.txt" 2>&1
  code=$?
  [[ $code -ne 124 ]] || fail "a rank was left waiting (timeout)"
  [[ $code -eq 4 ]] || { cat "$out/mpi_vtu.txt"; fail "mpirun exited with $code, expected 4"; }
  expect_io_message "$out/mpi_vtu.txt" "$dir/specimen_0001.1.vtu"
  [[ ! -e "$dir/specimen_0001.0.vtu" && ! -e "$dir/specimen_0001.pvtu" ]] \
    || fail "a piece of the failed output step was left"
  [[ -s "$dir/specimen_0000.0.vtu" && -s "$dir/specimen_0000.1.vtu" ]] \
    || fail "the earlier VTU pieces are missing"
  no_temporary_files "$dir"

  # pileup.json, written by rank 0 alone at the end of the run: rank 1 does not wait for it.
  dir="$out/mpi_pileup"
  mkdir -p "$dir"
  ln -s /dev/full "$dir/pileup.json.tmp"
  run_mpi --output "$dir" > "$out/mpi_pileup.txt" 2>&1
  code=$?
  [[ $code -ne 124 ]] || fail "a rank was left waiting (timeout)"
  [[ $code -eq 4 ]] || { cat "$out/mpi_pileup.txt"; fail "mpirun exited with $code, expected 4"; }
  expect_io_message "$out/mpi_pileup.txt" "$dir/pileup.json"
  [[ ! -e "$dir/pileup.json" && ! -e "$dir/run_summary.json" ]] \
    || fail "end-of-run files written after the failure"
  no_temporary_files "$dir"
  echo "OutputFailure.Mpi: OK"
  exit 0
fi

# 1. No checkpoint: the VTU at maximum depth cannot be written.
dir="$out/vtu"
mkdir -p "$dir"
ln -s /dev/full "$dir/specimen_0001.0.vtu.tmp"
"$indentsim" run "$case_file" --output "$dir" > "$out/vtu.txt" 2>&1
code=$?
[[ $code -eq 4 ]] || { cat "$out/vtu.txt"; fail "the run exited with $code, expected 4"; }
expect_io_message "$out/vtu.txt" "$dir/specimen_0001.0.vtu"
[[ ! -e "$dir/specimen_0001.0.vtu" ]] || fail "a partial VTU was left"
[[ -s "$dir/specimen_0000.0.vtu" ]] || fail "the earlier VTU is missing or empty"
grep -qF "specimen_0000.pvtu" "$dir/specimen.pvd" || fail "specimen.pvd lost its earlier step"
! grep -qF "specimen_0001" "$dir/specimen.pvd" || fail "specimen.pvd names the missing step"
awk -F, 'NR == 1 { n = NF } NF != n { exit 1 }' "$dir/load_penetration.csv" || fail "a cut row in load_penetration.csv"
no_temporary_files "$dir"

# 2. With a checkpoint: the next checkpoint cannot be written; the previous one is kept intact
#    and the run resumes from it.
dir="$out/checkpoint"
INDENTSIM_STOP_AFTER_STEP=2 "$indentsim" run "$case_file" --output "$dir" > "$out/stop.txt" 2>&1
code=$?
[[ $code -eq 130 ]] || { cat "$out/stop.txt"; fail "the stopped run exited with $code, expected 130"; }
before="$(sha256sum < "$dir/checkpoint/rank_0.bin")"
ln -s /dev/full "$dir/checkpoint/rank_0.bin.tmp"
INDENTSIM_STOP_AFTER_STEP=4 "$indentsim" run "$case_file" --output "$dir" --resume \
  > "$out/checkpoint.txt" 2>&1
code=$?
[[ $code -eq 4 ]] || { cat "$out/checkpoint.txt"; fail "the run exited with $code, expected 4"; }
expect_io_message "$out/checkpoint.txt" "$dir/checkpoint/rank_0.bin"
[[ "$(sha256sum < "$dir/checkpoint/rank_0.bin")" == "$before" ]] \
  || fail "the previous checkpoint changed"
no_temporary_files "$dir"
"$indentsim" run "$case_file" --output "$dir" --resume > "$out/checkpoint_resumed.txt" 2>&1 \
  || { cat "$out/checkpoint_resumed.txt"; fail "the resume from the kept checkpoint failed"; }
grep -qF "Resumed at step 2" "$out/checkpoint_resumed.txt" || fail "not resumed at step 2"

# 3. A full file system when the run resumes: every file stays as it was.
fs_root="$out/full_fs"
mkdir -p "$fs_root"
if mount -t tmpfs -o size=16m indentsim_test "$fs_root" 2> /dev/null; then
  mechanism="a full tmpfs"
  trap 'umount "$fs_root" 2> /dev/null' EXIT
else
  mechanism="/dev/full (mounting a tmpfs is not permitted here)"
fi
echo "full file system: $mechanism"
dir="$fs_root/run"
INDENTSIM_STOP_AFTER_STEP=2 "$indentsim" run "$case_file" --output "$dir" > "$out/fs_stop.txt" 2>&1
code=$?
[[ $code -eq 130 ]] || { cat "$out/fs_stop.txt"; fail "the stopped run exited with $code, expected 130"; }
before="$(checksums "$dir")"
if [[ "$mechanism" == "a full tmpfs" ]]; then
  dd if=/dev/zero of="$fs_root/filler" bs=64k > /dev/null 2>&1
  ! echo x 2> /dev/null > "$fs_root/probe" || fail "the tmpfs is not full"
  rm -f "$fs_root/probe"
else
  ln -s /dev/full "$dir/load_penetration.csv.tmp" # the first file a resume writes
fi
INDENTSIM_STOP_AFTER_STEP=4 "$indentsim" run "$case_file" --output "$dir" --resume \
  > "$out/fs_full.txt" 2>&1
code=$?
[[ $code -eq 4 ]] || { cat "$out/fs_full.txt"; fail "the run exited with $code, expected 4"; }
grep -qF "indentsim: error: cannot write '$dir/" "$out/fs_full.txt" \
  && grep -qF "': $no_space" "$out/fs_full.txt" \
  || { cat "$out/fs_full.txt"; fail "no message naming the file and the reason"; }
[[ "$(checksums "$dir")" == "$before" ]] || fail "files changed by the failed resume"
no_temporary_files "$dir"
rm -f "$fs_root/filler" "$dir/load_penetration.csv.tmp"
"$indentsim" run "$case_file" --output "$dir" --resume > "$out/fs_resumed.txt" 2>&1 \
  || { cat "$out/fs_resumed.txt"; fail "the resume with space again failed"; }
echo "OutputFailure.EndToEnd: OK ($mechanism)"

#!/usr/bin/env bash
# Rewrites the gold curves of the regression tests (tests/regression/gold/) after an intended
# change of the results: runs every shipped example (examples/*.yaml) with build/indentsim, one
# thread per process as CTest does, and keeps its curve CSV (load_penetration.csv, or
# stress_strain.csv of a tensile test) without the wall_time_s column, so that only results
# enter the gold file. Explain the change in the commit that updates the gold files.
# The gold file of the small J2 regression test (gold/small_j2.csv) comes from the same case as
# a file, tests/regression/small_j2.yaml.
# Usage: bash scripts/regenerate_gold.sh [NAME ...]   (default: every example and small_j2)
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
indentsim="$root/build/indentsim"
[[ -x "$indentsim" ]] || { echo "build/indentsim is missing: run bash scripts/build.sh" >&2; exit 1; }
gold="$root/tests/regression/gold"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
export OMP_NUM_THREADS=1

names=()
if [[ $# -eq 0 ]]; then
  for file in examples/*.yaml; do names+=("$(basename "$file" .yaml)"); done
else
  for name in "$@"; do [[ "$name" == small_j2 ]] || names+=("$name"); done
fi

for name in "${names[@]+"${names[@]}"}"; do
  case_file="examples/$name.yaml"
  [[ -f "$case_file" ]] || { echo "no example $case_file" >&2; exit 1; }
  csv=load_penetration.csv
  grep -q "^test: *tensile" "$case_file" && csv=stress_strain.csv
  start=$(date +%s)
  "$indentsim" run "$case_file" --output "$scratch/$name" --overwrite > "$scratch/$name.txt" 2>&1 \
    || { cat "$scratch/$name.txt"; echo "indentsim run $case_file failed" >&2; exit 1; }
  {
    echo "# gold curve of examples/$name.yaml ($csv without wall_time_s; scripts/regenerate_gold.sh)"
    awk -F, -v OFS=, '
      NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "wall_time_s") drop = i }
      { line = ""; for (i = 1; i <= NF; ++i) if (i != drop) line = line (line == "" ? "" : OFS) $i
        print line }' "$scratch/$name/$csv"
  } > "$gold/$name.csv"
  echo "$gold/$name.csv: $(($(wc -l < "$gold/$name.csv") - 2)) rows ($(($(date +%s) - start)) s)"
done

# The small J2 case of tests/regression/test_regression.cc (depth, force, active nodes).
if [[ $# -eq 0 || " $* " == *" small_j2 "* ]]; then
  "$indentsim" run tests/regression/small_j2.yaml --output "$scratch/small_j2" --overwrite \
    > "$scratch/small_j2.txt" 2>&1 || { cat "$scratch/small_j2.txt"; exit 1; }
  {
    echo "# small J2 indentation (tests/regression/test_regression.cc); units um, mN"
    awk -F, -v OFS=, '
      NR == 1 { for (i = 1; i <= NF; ++i) column[$i] = i; print "depth_um,force_mN,n_active_nodes"; next }
      { print $column["depth_um"], $column["force_mN"], $column["n_active_nodes"] }' \
      "$scratch/small_j2/load_penetration.csv"
  } > "$gold/small_j2.csv"
  echo "$gold/small_j2.csv: $(($(wc -l < "$gold/small_j2.csv") - 2)) rows"
fi

#!/usr/bin/env bash
# The installed program works on its own (CTest: Install.RunsAnExampleAnywhere).
# Requirement: `cmake --install BUILD --prefix P` puts indentsim into P/bin, its Python helpers
# into P/share/indentsim/python and the examples into P/share/indentsim/examples; the binary holds
# no path of the source or build tree; run from an empty directory on a copy of the 12x12
# example (examples/paper_j2_n12.yaml, loading shortened with its own keys to 1.0 um in 4 steps
# and back), it writes load_penetration.csv, load_penetration.png and the ParaView files.
# Usage: run_installed.sh CMAKE BUILD_DIRECTORY SOURCE_DIRECTORY SCRATCH_DIRECTORY
set -uo pipefail
cmake="$1"
build="$2"
source="$3"
out="$4"
rm -rf "$out"
mkdir -p "$out/case"
prefix="$out/prefix"

fail() { echo "FAIL: $*" >&2; exit 1; }

"$cmake" --install "$build" --prefix "$prefix" > "$out/install.txt" 2>&1 \
  || { cat "$out/install.txt"; fail "cmake --install failed"; }
[[ -x "$prefix/bin/indentsim" ]] || fail "no $prefix/bin/indentsim"
for script in indentsim_plotting.py plot_load_penetration.py plot_pileup.py plot_oliver_pharr.py \
              plot_stress_strain.py study_report.py; do
  [[ -f "$prefix/share/indentsim/python/$script" ]] || fail "no share/indentsim/python/$script"
done
[[ -f "$prefix/share/indentsim/examples/paper_j2_n12.yaml" ]] || fail "the examples are not installed"

# Neither the source nor the build tree is compiled into the program: none in what it loads
# (the debug information, which it never reads, names the build folder and is stripped from a
# copy first; the names of source files in assertion messages are allowed, a compiler run
# without ccache's relative paths writes them in full).
command -v strings > /dev/null && command -v strip > /dev/null || fail "binutils are needed"
strip -o "$out/indentsim.stripped" "$prefix/bin/indentsim" || fail "strip failed"
for tree in "$source" "$build"; do
  found=$(strings -n 8 "$out/indentsim.stripped" | grep -F "$tree" | grep -vE '\.(cc|h)$' || true)
  [[ -z "$found" ]] || fail "$prefix/bin/indentsim contains paths into $tree: $found"
done

# A copy of the default example in an empty directory, shortened through its own keys (the
# block and mesh stay those of the example).
sed -e 's/^  max_depth: 6\.0 /  max_depth: 1.0 /' -e 's/^  steps: 64$/  steps: 4/' \
  "$prefix/share/indentsim/examples/paper_j2_n12.yaml" > "$out/case/paper_j2_n12.yaml"
grep -q "^  max_depth: 1.0 " "$out/case/paper_j2_n12.yaml" || fail "max_depth was not shortened"
grep -q "^  steps: 4$" "$out/case/paper_j2_n12.yaml" || fail "steps was not shortened"

# Run there with a bare environment: no INDENTSIM_* variable, no path into the trees.
(cd "$out/case" && env -i PATH=/usr/bin:/bin HOME="$out" OMP_NUM_THREADS=1 \
   "$prefix/bin/indentsim" run paper_j2_n12.yaml > "$out/run.txt" 2>&1) \
  || { cat "$out/run.txt"; fail "the installed indentsim run failed"; }
cat "$out/run.txt"
# The shortened example has a contact radius of about 2.5 um on 10 um contact elements: the
# guard's warning about the contact resolution is right there (also in the end-of-run line of
# the warnings by topic); any other warning fails.
grep "warning" "$out/run.txt" | grep -vF "contact elements across the contact radius" \
  | grep -vF "indentsim: 1 warning in this run (contact_resolution)" | grep -q . \
  && fail "the run printed a warning"
grep -qF "contact elements across the contact radius" "$out/run.txt" \
  || fail "the coarse contact was not reported"
results="$out/case/results/paper_j2_n12"
for file in load_penetration.csv load_penetration.png specimen.pvd; do
  [[ -s "$results/$file" ]] || fail "no $results/$file"
done
ls "$results"/*.vtu > /dev/null 2>&1 || ls "$results"/*/*.vtu > /dev/null 2>&1 \
  || fail "no .vtu files next to specimen.pvd"
echo "Install.RunsAnExampleAnywhere: OK ($(($(wc -l < "$results/load_penetration.csv") - 1)) rows)"

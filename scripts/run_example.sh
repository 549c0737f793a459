#!/usr/bin/env bash
# The main job: installs what is missing, builds, and runs the default example (the paper's J2
# indentation on the automatic axisymmetric mesh, to 6.0 um and back). Results (units um, mN,
# GPa): results/paper_j2_auto_axisymmetric/load_penetration.csv, load_penetration.png,
#   specimen.pvd (ParaView), pile-up profiles, Oliver-Pharr, resolved_case.yaml, run.log
# Usage: bash scripts/run_example.sh [CASE.yaml] [-- extra indentsim options]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
bash scripts/build.sh
case_file="${1:-examples/paper_j2_auto_axisymmetric.yaml}"
shift || true
# The default example is regenerated on every call of this script.
export OMP_NUM_THREADS="${OMP_NUM_THREADS:-1}"
exec ./build/indentsim run "$case_file" --overwrite "$@"

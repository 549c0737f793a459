#!/usr/bin/env bash
# The whole test suite: installs what is missing, builds, runs the unit, verification, system,
# mpi (1 vs 2 ranks) and regression tiers with CTest (tests/CMakeLists.txt; one tier alone:
# cd build && ctest -L unit).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
bash scripts/build.sh indentsim indentsim_tests   # what the tests run; not the benchmarks
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
# One BLAS thread per process: the MPI tests already use both cores.
export OMP_NUM_THREADS=1
export OMPI_MCA_rmaps_base_oversubscribe=1
cd build
ctest --output-on-failure --timeout 1200 -j "${INDENTSIM_TEST_JOBS:-2}"

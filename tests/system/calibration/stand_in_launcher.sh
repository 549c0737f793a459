#!/usr/bin/env bash
# A stand-in for a cluster scheduler's launcher (srun, mpiexec of a batch system) in the
# calibration test: `--launcher "bash stand_in_launcher.sh LOG {ranks} {command}"` logs the
# number of ranks and the command it was given, then runs the command.
# Usage: stand_in_launcher.sh LOG RANKS COMMAND...
set -euo pipefail
log="$1"
ranks="$2"
shift 2
echo "ranks=$ranks $*" >> "$log"
exec "$@"

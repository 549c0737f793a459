#!/usr/bin/env bash
# A stand-in launcher for the calibration tests whose forward runs fail at chosen points:
# `--launcher "bash failing_launcher.sh PATTERN {command}"` ends a forward case whose case file
# has a line matching the extended regular expression PATTERN with exit code 1, as a run that
# diverged would, and runs every other case's command unchanged. The template is split at
# spaces without quoting: write a space in PATTERN as [[:space:]].
# Usage: failing_launcher.sh PATTERN COMMAND...
set -euo pipefail
pattern="$1"
shift
for word in "$@"; do
  if [[ "$word" == *.yaml ]] && grep -Eq "$pattern" "$word"; then
    echo "failing_launcher.sh: this case matches '$pattern': failed on purpose" >&2
    exit 1
  fi
done
exec "$@"

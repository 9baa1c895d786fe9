#!/usr/bin/env bash
# ctest -L regression: the project's own suite (scenes/regression/suite.json)
# rendered as goldens with one seed, then compared at another seed: real
# Monte Carlo noise on both sides, and no alarm may be raised.
# Usage: project_suite.sh VESPER_BINARY SOURCE_DIR WORK_DIR
set -euo pipefail
vesper=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work"
cd "$source"
[ -f scenes/cloud/cloud.vdb ] || "$vesper" vdb cloud -o scenes/cloud/cloud.vdb -q
suite=scenes/regression/suite.json
"$vesper" regress "$suite" --goldens "$work/goldens" --update-goldens --seed 1 --repeats 3 -q
status=0
"$vesper" regress "$suite" --goldens "$work/goldens" --seed 2 --repeats 3 \
  --report "$work/report" --history "$work/history.db" || status=$?
echo "report: $work/report/index.html"
exit $status

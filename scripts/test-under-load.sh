#!/usr/bin/env bash
# Runs the test command (scripts/test.sh) N times in a row (default 10) while another
# CPU-heavy job keeps one core busy, and stops at the first failure: the check that no
# test depends on the machine's speed (issue 9 item 6). Logs go to target/under-load/.
source "$(dirname "$0")/common.sh"
runs="${1:-10}"
mkdir -p target/under-load
( while :; do :; done ) &   # the other CPU-heavy job: one core spinning
hog=$!
trap 'kill $hog 2>/dev/null' EXIT
for i in $(seq 1 "$runs"); do
  start=$(date +%s)
  if ./scripts/test.sh > "target/under-load/run-$i.log" 2>&1; then
    echo "run $i of $runs passed under load in $(( $(date +%s) - start )) s"
  else
    echo "run $i of $runs FAILED under load (target/under-load/run-$i.log)" >&2
    tail -30 "target/under-load/run-$i.log" >&2
    exit 1
  fi
done
echo "$runs passed, 0 failed"

#!/usr/bin/env bash
# Runs a test command N times in a row (default 10) while CPU-heavy jobs keep every core
# busy (one spinning process per core), and stops at the first failure: the check that no
# test depends on the machine's speed. The command defaults to the whole test command
# (scripts/test.sh); give another after N, e.g. the server's tests alone:
#   scripts/test-under-load.sh 10 cargo test --release -p pliant-server
# Build the command's tests first: a build inside the loop only makes each run longer.
# Logs go to target/under-load/.
source "$(dirname "$0")/common.sh"
runs="${1:-10}"
shift || true
if [ "$#" -eq 0 ]; then
  set -- ./scripts/test.sh
fi
mkdir -p target/under-load
hogs=()
for _ in $(seq 1 "$(nproc)"); do
  ( while :; do :; done ) &   # a CPU-heavy job: one core spinning
  hogs+=($!)
done
trap 'kill "${hogs[@]}" 2>/dev/null' EXIT
for i in $(seq 1 "$runs"); do
  start=$(date +%s)
  if "$@" > "target/under-load/run-$i.log" 2>&1; then
    echo "run $i of $runs passed under load in $(( $(date +%s) - start )) s"
  else
    echo "run $i of $runs FAILED under load (target/under-load/run-$i.log)" >&2
    tail -30 "target/under-load/run-$i.log" >&2
    exit 1
  fi
done
echo "$runs passed, 0 failed (with $(nproc) cores kept busy): $*"

#!/usr/bin/env bash
# Head-to-head benchmarks: Pliant vs PyElastica 1.0 vs MuJoCo 3.3 (cable plugin).
#   bench/peers/run.sh           full run (≈ 10 min): results.json + docs/performance.md
#   bench/peers/run.sh --quick   smoke mode: one small case per tool, docs untouched
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
if [ ! -x "$here/.venv/bin/python" ] || ! "$here/.venv/bin/python" -c "import elastica, mujoco" 2>/dev/null; then
    "$here/setup.sh"
fi
if [ -z "${PLIANT_BIN:-}" ]; then
    (cd "$root" && cargo build --release -p pliant --quiet)
fi  # PLIANT_BIN=path: use an already built pliant instead
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target}"
cd "$here"
exec "$here/.venv/bin/python" "$here/run.py" "$@"

#!/usr/bin/env bash
# Builds the Python package `pliant` into .venv (scripts/install-python.sh; skipped with
# `--installed`, as test.sh has done it), checks its type stubs against the module (mypy's
# stubtest) and runs its pytest suite, which also compares timeline runs with the
# `pliant` binary.
source "$(dirname "$0")/common.sh"
if [ "${1:-}" != "--installed" ]; then
  ./scripts/install-python.sh
fi
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$PWD/target}"
export PLIANT_BIN="$CARGO_TARGET_DIR/release/pliant"
cd crates/python
# the type stubs (python/pliant/_pliant.pyi, installed beside the module) checked
# against the compiled module; the allowlist says what may differ and why
../../.venv/bin/python -m mypy.stubtest pliant._pliant --allowlist stubtest-allowlist.txt
../../.venv/bin/python -m pytest -q
# the scripts' own tests (scripts/tests: the performance table)
../../.venv/bin/python -m pytest -q ../../scripts/tests

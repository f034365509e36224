#!/usr/bin/env bash
# Builds the Python package `pliant` (crates/python, maturin + PyO3) into a virtual
# environment at .venv and runs its pytest suite, which also compares timeline runs with
# the `pliant` binary (built here if missing). Needs Python ≥ 3.9 with venv and pip;
# maturin, numpy, pytest and the study packages come from PyPI.
source "$(dirname "$0")/common.sh"
PYTHON="${PYTHON:-$(command -v python3.11 || command -v python3)}"
if [ -z "$PYTHON" ]; then
  echo "pliant: the Python tests need python3 (≥ 3.9)" >&2
  exit 1
fi
if [ ! -x .venv/bin/python ]; then
  "$PYTHON" -m venv .venv
fi
.venv/bin/python -m pip install --quiet --upgrade pip
.venv/bin/python -m pip install --quiet "maturin>=1.5,<2" numpy pytest
# studies (pliant.studies, `pliant study`): Dask (and bokeh for its dashboard), Parquet,
# statistics, marching cubes; duckdb to check the Parquet is readable by it
.venv/bin/python -m pip install --quiet "dask[distributed]" bokeh pyarrow pandas scipy scikit-image duckdb
# STEP import (pliant.cad): OpenCASCADE's Python binding
./scripts/install-cad.sh
# share the workspace's target folder (same release profile: dependencies are reused)
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$PWD/target}"
# the whole workspace, as test.sh builds it: `-p pliant` alone unifies the dependencies'
# features differently and would rebuild every crate
cargo build --release --workspace
export PLIANT_BIN="$CARGO_TARGET_DIR/release/pliant"
.venv/bin/python -m pip install --quiet --force-reinstall --no-deps ./crates/python
cd crates/python
../../.venv/bin/python -m pytest -q

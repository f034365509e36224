#!/usr/bin/env bash
# Builds the Python package `pliant` (crates/python, maturin + PyO3) with its study extras
# and the STEP importer's kernel into a virtual environment at .venv, where `pliant study`,
# `pliant import` of STEP files and the Rust tests that drive Python (the study file's fuzz
# target, `pliant study` end to end) find it. Needs Python ≥ 3.9 with venv and pip;
# maturin, numpy, pytest and the study packages come from PyPI.
source "$(dirname "$0")/common.sh"
PYTHON="${PYTHON:-$(command -v python3.11 || command -v python3)}"
if [ -z "$PYTHON" ]; then
  echo "pliant: the Python package needs python3 (≥ 3.9)" >&2
  exit 1
fi
if [ ! -x .venv/bin/python ]; then
  "$PYTHON" -m venv .venv
fi
.venv/bin/python -m pip install --quiet --upgrade pip
.venv/bin/python -m pip install --quiet "maturin>=1.5,<2" numpy pytest mypy   # mypy: stubtest checks _pliant.pyi
# studies (pliant.studies, `pliant study`): Dask (and bokeh for its dashboard), Parquet,
# statistics, marching cubes, the report's plots (matplotlib); duckdb to check the Parquet is
# readable by it
.venv/bin/python -m pip install --quiet "dask[distributed]" bokeh pyarrow pandas scipy scikit-image matplotlib duckdb
# STEP import (pliant.cad): OpenCASCADE's Python binding
./scripts/install-cad.sh
# share the workspace's target folder (same release profile: dependencies are reused)
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$PWD/target}"
# the whole workspace, as test.sh builds it (there a no-op); one feature set for every build
# (crates/features), so the extension's build below reuses pliant-core and the crates above it
cargo build --release --workspace
.venv/bin/python -m pip install --quiet --force-reinstall --no-deps ./crates/python

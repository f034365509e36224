#!/usr/bin/env bash
# Installs the STEP importer's CAD kernel: OpenCASCADE 7.8+/8 through its Python binding
# OCP (PyPI cadquery-ocp-novtk: a self-contained wheel, no VTK, no system packages) into
# the repository's .venv, which `pliant` finds for `[[parts]] step = …`, hose routes from
# STEP curves and `pliant import`. Idempotent: does nothing when OCP is already there.
# Needs Python ≥ 3.9 with venv and pip.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
PYTHON="${PYTHON:-$(command -v python3.11 || command -v python3)}"
if [ -z "$PYTHON" ]; then
  echo "pliant: the STEP importer needs python3 (≥ 3.9)" >&2
  exit 1
fi
if [ ! -x .venv/bin/python ]; then
  "$PYTHON" -m venv .venv
fi
if .venv/bin/python -c "import importlib.util, sys; sys.exit(importlib.util.find_spec('OCP') is None)"; then
  exit 0
fi
.venv/bin/python -m pip install --quiet --upgrade pip
.venv/bin/python -m pip install --quiet "cadquery-ocp-novtk>=7.8,<9"
.venv/bin/python -c "import OCP.STEPCAFControl" # fails loudly if the wheel cannot load

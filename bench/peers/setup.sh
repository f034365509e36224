#!/usr/bin/env bash
# Creates bench/peers/.venv with the peer simulators (PyElastica 1.0, MuJoCo 3.3).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
if [ ! -x "$here/.venv/bin/python" ]; then
    python3 -m venv "$here/.venv"
fi
"$here/.venv/bin/python" -m pip install --quiet --upgrade pip
"$here/.venv/bin/python" -m pip install --quiet -r "$here/requirements.txt"
"$here/.venv/bin/python" -c "import elastica, mujoco, numpy; print('peers: pyelastica', elastica.__version__ if hasattr(elastica, '__version__') else '?', 'mujoco', mujoco.__version__, 'numpy', numpy.__version__)"

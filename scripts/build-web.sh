#!/usr/bin/env bash
# Builds the browser/VR viewer (web/, TypeScript + three.js, bundled by vite) into
# web/dist, which the pliant binary embeds when it is compiled (crates/server/build.rs):
# run this before `cargo build`. Needs Node.js ≥ 20.19 and npm.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../web"
if ! command -v npm >/dev/null 2>&1; then
  echo "pliant: building the viewer needs Node.js (≥ 20.19) and npm" >&2
  exit 1
fi
# npm ci only when the installed packages do not match the lock file
if [ ! -d node_modules ] || [ package-lock.json -nt node_modules/.package-lock.json ]; then
  npm ci --no-audit --no-fund --loglevel=error
fi
npm run --silent build
echo "viewer built into web/dist"

#!/usr/bin/env bash
# Builds Pliant (with its browser viewer) and runs its main job on the built-in demo scene
# (outputs and the verdict go to out/demo), then serves the demo live: open the printed URL
# to grab the hoses with the mouse (or a VR headset). PLIANT_PORT picks the port (8080).
source "$(dirname "$0")/common.sh"
if command -v npm >/dev/null 2>&1; then
  ./scripts/build-web.sh   # before cargo: the binary embeds web/dist
else
  echo "warning: npm not found, building without the browser viewer (install Node.js ≥ 20.19)" >&2
fi
cargo build --release -p pliant
./target/release/pliant run --out out/demo "$@"
echo
echo "Now serving the demo live; open the URL below in a browser. Ctrl-C stops."
exec ./target/release/pliant serve --port "${PLIANT_PORT:-8080}"

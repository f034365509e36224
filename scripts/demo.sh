#!/usr/bin/env bash
# Builds Pliant and runs its main job on the built-in demo scene; outputs go to out/demo.
source "$(dirname "$0")/common.sh"
cargo build --release -p pliant
./target/release/pliant run --out out/demo "$@"

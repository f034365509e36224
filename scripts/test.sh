#!/usr/bin/env bash
# Builds everything and runs every test: unit tests, scene-format tests, the validation
# suite (each case a test), the CLI end-to-end tests, and a quick benchmark smoke run.
source "$(dirname "$0")/common.sh"
cargo build --release --workspace
cargo test --release --workspace
./target/release/pliant validate
./target/release/pliant bench --quick --json > /dev/null
./scripts/test-python.sh   # the Python API (crates/python): builds it into .venv, runs pytest
echo "all tests passed"

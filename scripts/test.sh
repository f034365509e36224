#!/usr/bin/env bash
# Builds everything and runs every test: formatting, the API docs (broken intra-doc
# links fail) and clippy's lints checked, unit tests, scene-format tests, the validation
# suite (each case a test; `pliant validate` prints the same table), the CLI end-to-end
# tests, a quick benchmark smoke run, the Python API's tests and the browser viewer's
# end-to-end tests in headless Chromium.
source "$(dirname "$0")/common.sh"
./scripts/build-web.sh     # the viewer first: the release build below embeds web/dist
cargo fmt --all --check    # formatting as rustfmt writes it
(cd crates/python && cargo fmt --check)   # the Python extension is its own workspace
RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps   # API docs: every link resolves
cargo clippy --release --workspace --all-targets -- -D warnings   # lints; policy: Cargo.toml [workspace.lints]
cargo build --release --workspace   # one feature set (crates/features): the tests and the Python extension below reuse these builds
./scripts/install-python.sh   # the Python package and the STEP importer's kernel into .venv: some Rust tests drive it
(export PYO3_PYTHON="$PWD/.venv/bin/python" CARGO_TARGET_DIR="$PWD/target"; cd crates/python && cargo clippy --release --features extension-module --all-targets -- -D warnings)   # the extension's lints
cargo test --release --workspace   # every validation case is a test here (crates/validation/tests)
./target/release/pliant bench --quick --json > /dev/null
./scripts/test-python.sh --installed   # the Python API (crates/python): pytest
./scripts/install-browser.sh   # Debian's chromium, only if /usr/bin/chromium is missing
(cd web && npm run --silent test:unit)   # the viewer's TOML writer (scene authoring)
(cd web && npm run --silent test:e2e)   # viewer end-to-end (target/release/pliant serve)
echo "all tests passed"

# Shared by the scripts: make sure the Rust toolchain is there.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
if ! command -v cargo >/dev/null 2>&1; then
  if [ -x "$HOME/.cargo/bin/cargo" ]; then
    export PATH="$HOME/.cargo/bin:$PATH"
  else
    echo "pliant: needs a Rust toolchain (cargo ≥ 1.85); install it with rustup and run again" >&2
    exit 1
  fi
fi

#!/usr/bin/env bash
# The project's test command: every suite, from a fresh clone, with only the Rust
# toolchain installed. Later suites (Python) add themselves here.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v cargo >/dev/null 2>&1; then
    echo "cargo not found: install the Rust toolchain (https://rustup.rs)" >&2
    exit 1
fi

# Optimised build: the physics tests run thousands of steps.
cargo test --workspace --release --locked

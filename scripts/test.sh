#!/usr/bin/env bash
# The project's test command: every suite, from a fresh clone, with only the Rust
# toolchain installed. Later suites (Python) add themselves here. Ends with one line
# totalling every suite, since cargo's own last line is that of the (empty) doc tests.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v cargo >/dev/null 2>&1; then
    echo "cargo not found: install the Rust toolchain (https://rustup.rs)" >&2
    exit 1
fi

log=$(mktemp)
trap 'rm -f "$log"' EXIT

# Optimised build: the physics tests run thousands of steps.
set +e
cargo test --workspace --release --locked 2>&1 | tee "$log"
status=${PIPESTATUS[0]}
set -e

passed=0
failed=0
while read -r p f; do
    passed=$((passed + p))
    failed=$((failed + f))
done < <(sed -nE 's/^test result: [A-Za-z]+\. ([0-9]+) passed; ([0-9]+) failed.*/\1 \2/p' "$log")
echo
echo "all suites: $passed passed, $failed failed"
exit "$status"

#!/usr/bin/env bash
# The project's test command: every suite, from a fresh clone, with only the Rust
# toolchain, Python 3.11 and pip installed. The Rust suites run first; then a virtual
# environment (target/python-venv) gets the Python package built from this tree by
# `pip install .` (maturin) and the Python suites run under pytest. Ends with one line
# totalling every suite.
set -euo pipefail
cd "$(dirname "$0")/.."

if ! command -v cargo >/dev/null 2>&1; then
    echo "cargo not found: install the Rust toolchain (https://rustup.rs)" >&2
    exit 1
fi
python=""
for candidate in python3.11 python3 python; do
    if command -v "$candidate" >/dev/null 2>&1 \
        && "$candidate" -c 'import sys; sys.exit(sys.version_info < (3, 11))' 2>/dev/null; then
        python=$candidate
        break
    fi
done
if [ -z "$python" ]; then
    echo "Python 3.11 or newer not found: the Python package's tests need it" >&2
    exit 1
fi
if ! "$python" -c 'import ensurepip, venv' 2>/dev/null; then
    echo "$python cannot make virtual environments: install its venv module (Debian: python3-venv)" >&2
    exit 1
fi

log=$(mktemp)
trap 'rm -f "$log"' EXIT

# Optimised build: the physics tests run thousands of steps. The Python module is tested
# from Python below (it cannot be linked into a Rust test binary).
set +e
cargo test --workspace --exclude cloth-py --release --locked 2>&1 | tee "$log"
rust_status=${PIPESTATUS[0]}
set -e

venv=target/python-venv
# `pip install .` is how users install it: maturin builds the extension (abi3, Python
# 3.11+) from this tree, against Cargo.lock. A failed install still ends with the totals.
export MATURIN_PEP517_ARGS="--locked"
set +e
{ [ -x "$venv/bin/python" ] || "$python" -m venv "$venv"; } \
    && "$venv/bin/python" -m pip install --quiet --disable-pip-version-check ".[test]"
install_status=$?
py_status=$install_status
if [ "$install_status" -eq 0 ]; then
    CLOTH_BIN="$PWD/target/release/cloth" "$venv/bin/python" -m pytest python/tests -p no:cacheprovider \
        --color=no 2>&1 | tee -a "$log"
    py_status=${PIPESTATUS[0]}
else
    echo "building or installing the Python package failed: its suites did not run" >&2
fi
set -e

passed=0
failed=0
while read -r p f; do
    passed=$((passed + p))
    failed=$((failed + f))
done < <(sed -nE 's/^test result: [A-Za-z]+\. ([0-9]+) passed; ([0-9]+) failed.*/\1 \2/p' "$log")
# pytest's summary: "== 3 failed, 40 passed in 12.3s ==" (either part may be missing).
summary=$(grep -E '^=+ .*(passed|failed|error).* in [0-9.]+s' "$log" | tail -1 || true)
py_passed=$(sed -nE 's/.* ([0-9]+) passed.*/\1/p' <<<"$summary")
py_failed=$(sed -nE 's/.* ([0-9]+) failed.*/\1/p' <<<"$summary")
py_errors=$(sed -nE 's/.* ([0-9]+) errors?.*/\1/p' <<<"$summary")
passed=$((passed + ${py_passed:-0}))
failed=$((failed + ${py_failed:-0} + ${py_errors:-0} + (install_status != 0)))
echo
echo "all suites: $passed passed, $failed failed"
if [ "$rust_status" -ne 0 ]; then
    exit "$rust_status"
fi
exit "$py_status"

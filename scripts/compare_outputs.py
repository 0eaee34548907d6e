#!/usr/bin/env python3
"""Whether two builds wrote the same outputs: every file under BEFORE and AFTER compared.

Meshes, pictures, frames and everything else must match byte for byte. The reports
(report.json, summary.json and their .md pages) hold wall-clock times, which no two runs
share: in JSON every key naming seconds or milliseconds is left out, in Markdown every
decimal number on a line is masked, and what is left must match exactly.

To compare two builds on the shipped scenes:

    for s in assets/scenes/*.toml; do
        BIN run "$s" --out OUT/$(basename "$s" .toml) --force --quiet
    done
    BIN drape assets/garmentcode/patterns --body assets/garmentcode/bodies/mean_all.obj \\
        --body-up-axis y --out OUT/drape
    python3 scripts/compare_outputs.py OUT_BEFORE OUT_AFTER

Exit status 0 when everything matches, 1 otherwise. Standard library only.
"""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path

TIMING_KEY = re.compile(r"(seconds|_ms)$")
DECIMAL = re.compile(r"\d+\.\d+")


def without_timings(value):
    if isinstance(value, dict):
        return {k: without_timings(v) for k, v in value.items() if not TIMING_KEY.search(k)}
    if isinstance(value, list):
        return [without_timings(v) for v in value]
    return value


def same(a: Path, b: Path) -> tuple[bool, str]:
    x, y = a.read_bytes(), b.read_bytes()
    if x == y:
        return True, "same bytes"
    if a.suffix == ".json":
        if without_timings(json.loads(x)) == without_timings(json.loads(y)):
            return True, "same but for timings"
        return False, "differs beyond timings"
    if a.suffix == ".md":
        mask = lambda t: [DECIMAL.sub("#", line) for line in t.decode().splitlines()]
        if mask(x) == mask(y):
            return True, "same but for numbers on timing lines"
        return False, "differs beyond numbers"
    return False, "bytes differ"


def main() -> int:
    if len(sys.argv) != 3:
        print(__doc__)
        return 2
    before, after = Path(sys.argv[1]), Path(sys.argv[2])
    files = sorted({p.relative_to(before) for p in before.rglob("*") if p.is_file()}
                   | {p.relative_to(after) for p in after.rglob("*") if p.is_file()})
    counts: dict[str, int] = {}
    wrong = 0
    for rel in files:
        a, b = before / rel, after / rel
        if not a.exists() or not b.exists():
            verdict, why = False, f"only in {'after' if not a.exists() else 'before'}"
        else:
            verdict, why = same(a, b)
        counts[why] = counts.get(why, 0) + 1
        if not verdict:
            wrong += 1
            print(f"DIFFERS {rel}: {why}")
    print(f"{len(files)} files: " + ", ".join(f"{n} {why}" for why, n in sorted(counts.items())))
    return 1 if wrong else 0


if __name__ == "__main__":
    sys.exit(main())

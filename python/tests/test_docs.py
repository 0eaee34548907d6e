"""The documentation site: its reference pages are what the code says (they are written
from it by scripts/docs_reference.py), it builds without a warning, and its worked
examples run."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
EXAMPLES = sorted((REPO / "python" / "examples").glob("*.py"))


def test_the_reference_pages_are_what_the_code_says() -> None:
    check = subprocess.run(
        [sys.executable, REPO / "scripts" / "docs_reference.py", "--check"], capture_output=True, text=True
    )
    assert check.returncode == 0, check.stderr


def test_the_site_builds_without_a_warning(tmp_path: Path) -> None:
    build = subprocess.run(
        [sys.executable, "-m", "mkdocs", "build", "--strict", "-f", REPO / "mkdocs.yml", "-d", tmp_path / "site"],
        capture_output=True,
        text=True,
    )
    assert build.returncode == 0, build.stderr
    for page in ["index.html", "scene/index.html", "python/index.html", "examples/index.html"]:
        assert (tmp_path / "site" / page).is_file(), page
    scene = (tmp_path / "site" / "scene" / "index.html").read_text()
    assert "animation" in scene and "pins" in scene


# What each example leaves in its folder.
WRITES = {
    "sheet_on_sphere": ["sheet.obj", "history.csv"],
    "hang_a_garment": ["report.json", "history.csv", "cloth.obj"],
    "fabric_sweep": ["batch.json", "silk/report.json"],
}


def test_every_example_is_checked() -> None:
    assert sorted(p.stem for p in EXAMPLES) == sorted(WRITES)


@pytest.mark.parametrize("example", EXAMPLES, ids=lambda p: p.stem)
def test_the_example_runs(example: Path, tmp_path: Path) -> None:
    out = tmp_path / "out"
    run = subprocess.run([sys.executable, example, out], capture_output=True, text=True, cwd=tmp_path, timeout=600)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip(), "an example says what it did"
    for name in WRITES[example.stem]:
        assert (out / name).is_file(), name

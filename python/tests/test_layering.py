"""The crates read bottom-up: scripts/imports.py finds no import running back up.

Each crate's lib.rs declares its modules bottom-up, each after those it uses; a
module folder's mod.rs does the same for its files. The script is tested first on
small crates written here, so that a check that passes means something.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
SCRIPT = REPO / "scripts" / "imports.py"

# Every crate of the workspace: the root one (".") and those under crates/.
BOTTOM_UP = [
    ".",
    "crates/cloth-formats",
    "crates/cloth-render",
    "crates/cloth-fixtures",
    "crates/cloth-core",
    "crates/cloth-collide",
    "crates/cloth-garment",
    "crates/cloth-cli",
    "crates/cloth-py",
]


def imports(*args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, str(SCRIPT), *args], capture_output=True, text=True, check=False
    )


def write_crate(root: Path, files: dict[str, str]) -> Path:
    (root / "Cargo.toml").write_text('[package]\nname = "toy"\n')
    for name, text in files.items():
        path = root / "src" / name
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)
    return root


@pytest.mark.parametrize("crate", BOTTOM_UP)
def test_the_restructured_crates_read_bottom_up(crate: str) -> None:
    run = imports("--check", "--depth", "2", str(REPO / crate))
    assert run.returncode == 0, run.stdout + run.stderr
    assert "total running back up: 0 in library code, 0 in unit tests" in run.stdout


def test_every_crate_of_the_workspace_is_held_to_it() -> None:
    crates = sorted(f"crates/{p.name}" for p in (REPO / "crates").iterdir() if (p / "src").is_dir())
    assert sorted(c for c in BOTTOM_UP if c != ".") == crates


def test_an_import_of_a_module_declared_later_runs_back_up(tmp_path: Path) -> None:
    crate = write_crate(
        tmp_path,
        {
            "lib.rs": "mod low;\nmod high;\n",
            # A grouped import, through the parent's re-export, in a `use` and inline.
            "low.rs": "use crate::{high::Thing};\nfn f() { let _ = crate::high::make(); }\n",
            "high.rs": "pub struct Thing;\npub fn make() {}\n",
        },
    )
    run = imports("--check", "-v", str(crate))
    assert run.returncode == 1
    assert "up: low -> high: 2 in library code, 0 in unit tests" in run.stdout
    assert "bottom-up would be: high < low" in run.stdout


def test_a_cycle_is_named_and_has_no_bottom_up_order(tmp_path: Path) -> None:
    crate = write_crate(
        tmp_path,
        {
            "lib.rs": "mod a;\nmod b;\n",
            "a.rs": "use crate::b::B;\npub struct A;\n",
            "b.rs": "use super::a::A;\npub struct B;\n",
        },
    )
    run = imports("--check", str(crate))
    assert run.returncode == 1
    assert "cycle: a <-> b" in run.stdout
    assert "bottom-up would be" not in run.stdout


def test_items_of_lib_rs_itself_and_re_exports_are_followed(tmp_path: Path) -> None:
    crate = write_crate(
        tmp_path,
        {
            # `Vec3` defined in lib.rs is above every module; `Shape` is found in
            # `deep::shape` through deep's re-export, and `deep` comes after `top`.
            "lib.rs": "mod top;\nmod deep;\npub type Vec3 = [f64; 3];\n",
            "top.rs": "use crate::Vec3;\nuse crate::deep::Shape;\n",
            "deep/mod.rs": "mod shape;\npub use shape::Shape;\n",
            "deep/shape.rs": "pub struct Shape;\n",
        },
    )
    run = imports("--check", "--depth", "2", str(crate))
    assert run.returncode == 1
    assert "up: top -> (lib.rs itself): 1 in library code" in run.stdout
    assert "up: top -> deep: 1 in library code" in run.stdout


def test_unit_tests_are_counted_apart_and_a_clean_crate_passes(tmp_path: Path) -> None:
    crate = write_crate(
        tmp_path,
        {
            "lib.rs": "mod low;\nmod high;\n",
            "low.rs": "pub fn f() {}\n// crate::high::g() in a comment is no import\n",
            "high.rs": 'use super::low::f;\npub fn g() { f(); let _ = "crate::nowhere"; }\n',
        },
    )
    run = imports("--check", str(crate))
    assert run.returncode == 0, run.stdout
    (crate / "src" / "low.rs").write_text(
        "pub fn f() {}\n#[cfg(test)]\nmod tests {\n    use crate::high::g;\n}\n"
    )
    run = imports("--check", str(crate))
    assert run.returncode == 1
    assert "up: low -> high: 0 in library code, 1 in unit tests" in run.stdout

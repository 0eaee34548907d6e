"""Shared fixtures of the Python suites: the repository, the `cloth` command (to compare
the package with), small scenes written into a test's folder, and readers of the files a
run writes.

The scenes are small (a 12 x 12 sheet, a coarse skirt) so that the whole suite runs in
about a minute on a 2-core machine.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[2]
ASSETS = REPO / "assets"

# The CLI's own small scene (crates/cloth-cli/tests/cli.rs): a 60 cm sheet dropped on a
# 30 cm sphere, 60 steps.
SHEET = """\
name = "small sheet"
[cloth.grid]
nx = 12
ny = 12
size = [0.6, 0.6]
origin = [-0.3, -0.3, 0.35]
[fabric]
preset = "cotton_poplin"
[[bodies]]
sphere = { radius = 0.3 }
[rest]
tolerance = 1e-5
consecutive_steps = 10
max_steps = 60
"""

def flat_grid_obj(n: int, h: float) -> str:
    """An OBJ of an n x n grid of spacing h at z = 1, without texture coordinates."""
    lines = [f"v {h * i} {h * j} 1" for j in range(n) for i in range(n)]
    for j in range(n - 1):
        for i in range(n - 1):
            a = j * n + i + 1
            lines += [f"f {a} {a + 1} {a + n + 1}", f"f {a} {a + n + 1} {a + n}"]
    return "\n".join(lines) + "\n"


# A fully specified fabric in SI, without damping or drag (the cotton-like benchmark
# fabric of the Rust suites).
COTTON_LIKE_SI = {
    "area_density": 0.15,
    "warp": {"law": "linear", "stiffness": 1000.0},
    "weft": {"law": "linear", "stiffness": 1000.0},
    "compression_warp": 100.0,
    "compression_weft": 100.0,
    "shear_modulus": 20.0,
    "bending": {"warp": 1e-5, "weft": 1e-5},
}


@pytest.fixture(scope="session")
def repo_root() -> Path:
    """The repository's root folder."""
    return REPO


@pytest.fixture(scope="session")
def assets() -> Path:
    """The repository's `assets` folder (scenes, patterns, bodies, fabrics)."""
    return ASSETS


@pytest.fixture(scope="session")
def sheet_scene() -> str:
    """The text of the small sheet-on-a-sphere scene."""
    return SHEET


@pytest.fixture(scope="session")
def cotton_si() -> dict:
    """SI values of a cotton-like fabric without damping or drag (a fresh copy)."""
    return json.loads(json.dumps(COTTON_LIKE_SI))


@pytest.fixture(scope="session")
def cloth_bin() -> str:
    """The `cloth` command: $CLOTH_BIN if it names a file, else built by cargo."""
    env = os.environ.get("CLOTH_BIN")
    if env and Path(env).is_file():
        return env
    cargo = shutil.which("cargo")
    if cargo is None:
        pytest.skip("CLOTH_BIN is not set and cargo is not installed: cannot build `cloth`")
    build = subprocess.run(
        [cargo, "build", "--release", "--locked", "-p", "cloth-cli"],
        cwd=REPO,
        capture_output=True,
        text=True,
    )
    if build.returncode != 0:
        pytest.fail(f"cargo build of cloth-cli failed:\n{build.stderr[-4000:]}")
    exe = REPO / "target" / "release" / ("cloth.exe" if os.name == "nt" else "cloth")
    assert exe.is_file(), exe
    return str(exe)


@pytest.fixture
def run_cli(cloth_bin):
    """`run_cli(*args)`: runs the `cloth` command, returns the completed process (text)."""

    def run(*args: str | os.PathLike) -> subprocess.CompletedProcess:
        return subprocess.run(
            [cloth_bin, *map(str, args)], capture_output=True, text=True, timeout=600
        )

    return run


@pytest.fixture
def cli_error(run_cli):
    """`cli_error(scene)`: the message `cloth check SCENE` gives for a bad scene, without
    the `error: ` prefix; asserts the exit status 2 of bad input."""

    def error(scene: Path) -> str:
        done = run_cli("check", scene)
        assert done.returncode == 2, (done.returncode, done.stdout, done.stderr)
        lines = [l for l in done.stderr.splitlines() if not l.startswith("warning: ")]
        text = "\n".join(lines).strip()
        assert text.startswith("error: "), text
        return text[len("error: ") :].strip()

    return error


@pytest.fixture
def write_scene(tmp_path):
    """`write_scene(text, name="scene.toml")`: writes a scene into the test's folder."""

    def write(text: str, name: str = "scene.toml") -> Path:
        path = tmp_path / name
        path.write_text(text)
        return path

    return write


def read_obj_vertices(path: Path) -> np.ndarray:
    """The `v` lines of an OBJ file as an (N, 3) float64 array."""
    rows = [
        [float(x) for x in line.split()[1:4]]
        for line in Path(path).read_text().splitlines()
        if line.startswith("v ")
    ]
    return np.array(rows, dtype=np.float64).reshape(-1, 3)


@pytest.fixture(scope="session")
def obj_vertices():
    """`obj_vertices(path)`: the `v` lines of an OBJ file as an (N, 3) array."""
    return read_obj_vertices

"""The tools Python users already hold: bodies from arrays and trimesh meshes, the cloth
back as a trimesh mesh, per-corner material coordinates, the step history (as the run
folder's history.csv has it) in pandas, progress bars, and a batch as a DataFrame."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas
import pytest
import trimesh

import cloth
import cloth.batch as cb

from conftest import SHEET

# assets/patterns/tube.toml: two 10 x 20 cm panels sewn into a tube, hung by their top
# edges with no body, a garment that sews and drapes in a second.
TUBE_SCENE = """\
[cloth.garment]
pattern = "{pattern}"
edge_length = 0.02
pins = [{ panel = "front", edge = "top" }, { panel = "back", edge = "top" }]
[fabric]
preset = "cotton_poplin"
[rest]
tolerance = 1e-4
consecutive_steps = 10
max_steps = 40
"""

CUBE_VERTICES = np.array([[x, y, z] for z in (-0.5, 0.5) for y in (-0.5, 0.5) for x in (-0.5, 0.5)])
# Outward-wound faces of the unit cube above (vertex 4 z + 2 y + x, each 0 or 1).
CUBE_TRIANGLES = np.array(
    [[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
     [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]]
)


def test_a_body_from_arrays_is_the_box_it_describes() -> None:
    size = np.array([0.4, 0.2, 0.6])
    body = cloth.Body.from_arrays(CUBE_VERTICES * size, CUBE_TRIANGLES, position=(0, 0, 1), name="crate")
    box = cloth.Body.box(size, position=(0, 0, 1))
    points = np.array([[0, 0, 1], [0.3, 0, 1], [0, 0, 1.5], [0.1, 0.05, 0.8]])
    assert body.name == "crate"
    np.testing.assert_allclose(body.signed_distance(points), box.signed_distance(points), atol=1e-12)
    assert body.defects == []


def test_a_y_up_body_from_arrays_stands_up() -> None:
    # 0.6 m along y, y being up: standing, it is 0.6 m tall.
    tall = cloth.Body.from_arrays(CUBE_VERTICES * [0.2, 0.6, 0.2], CUBE_TRIANGLES, up_axis="y")
    extent = tall.vertices.max(axis=0) - tall.vertices.min(axis=0)
    np.testing.assert_allclose(extent, [0.2, 0.2, 0.6], atol=1e-12)


def test_arrays_that_enclose_nothing_or_point_nowhere_are_refused() -> None:
    with pytest.raises(ValueError, match="triangles"):
        cloth.Body.from_arrays(CUBE_VERTICES, CUBE_TRIANGLES + 8)
    flat = CUBE_VERTICES * [1, 1, 0]
    with pytest.raises(ValueError):
        cloth.Body.from_arrays(flat[:4], np.array([[0, 1, 2], [1, 3, 2]]))


def test_a_trimesh_sphere_is_a_body() -> None:
    sphere = trimesh.creation.icosphere(subdivisions=3, radius=0.3)
    body = cloth.Body.from_trimesh(sphere, position=(0, 0, 0.5))
    d = body.signed_distance([[0, 0, 0.5], [0, 0, 1.0]])
    assert d[0] == pytest.approx(-0.3, abs=0.01)
    assert d[1] == pytest.approx(0.2, abs=0.01)
    with pytest.raises(TypeError, match="trimesh"):
        cloth.Body.from_trimesh("sphere.obj")


def test_corner_material_coordinates_are_each_triangles_own() -> None:
    mesh = cloth.ClothMesh.grid(4, 3, (0.3, 0.2))
    corners = mesh.corner_uv
    assert corners.shape == (mesh.triangle_count, 3, 2)
    # A sheet has no seams: every corner has its vertex's coordinates.
    np.testing.assert_array_equal(corners, mesh.uv[mesh.triangles])


def test_a_simulation_keeps_the_history_of_its_steps() -> None:
    sheet = cloth.ClothMesh.grid(8, 8, (0.4, 0.4), origin=(-0.2, -0.2, 0.5))
    sim = cloth.Simulation(sheet, cloth.Fabric.preset("cotton_poplin"), bodies=[cloth.Body.sphere(0.3)])
    sim.step(3)
    sim.run_to_rest(max_steps=5)
    h = sim.history
    assert list(h["step"]) == [1, 2, 3, 4, 5, 6, 7, 8]
    assert h["time"][-1] == pytest.approx(sim.time)
    assert h["stage"] == ["running"] * 8
    # Falling from rest: the kinetic energy grows at first.
    assert h["kinetic_energy"][0] < h["kinetic_energy"][2]
    table = pandas.DataFrame(h)
    assert len(table) == 8 and table["cg_iterations"].dtype == np.int64


def test_a_runs_history_is_its_csv_and_its_cloth_a_trimesh(tmp_path: Path) -> None:
    result = cloth.Scene.from_toml(SHEET).run(tmp_path / "out")
    history = pandas.DataFrame(result.history)
    csv = pandas.read_csv(tmp_path / "out" / "history.csv")
    assert list(history.columns) == list(csv.columns)
    assert len(history) == result.report["stages"][0]["steps"] == 60
    pandas.testing.assert_frame_equal(history, csv, check_exact=False, rtol=1e-12)
    mesh = result.to_trimesh()
    assert isinstance(mesh, trimesh.Trimesh)
    np.testing.assert_array_equal(mesh.vertices, result.positions)
    np.testing.assert_array_equal(mesh.faces, result.mesh.triangles)
    assert result.panel_names is None and result.triangle_panel is None


def test_a_garments_trimesh_carries_its_panels(tmp_path: Path) -> None:
    pattern = Path(__file__).resolve().parents[2] / "assets" / "patterns" / "tube.toml"
    scene = cloth.Scene.from_toml(TUBE_SCENE.replace("{pattern}", pattern.as_posix()))
    result = scene.run(tmp_path / "out")
    assert result.panel_names == ["front", "back"]
    mesh = result.to_trimesh()
    np.testing.assert_array_equal(mesh.face_attributes["panel"], result.triangle_panel)
    assert mesh.metadata["panels"] == ["front", "back"]
    assert set(result.history["stage"]) == {"sewing", "draping"}
    assert result.report["pinned_particles"] == 12


def test_progress_bars_show_the_stages_and_the_runs(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    cloth.Scene.from_toml(SHEET).run(tmp_path / "one", progress=True)
    err = capsys.readouterr().err
    assert "running" in err and "60/60" in err, err
    jobs = [cb.Job(name=f"sheet{k}", scene=cloth.batch.tomllib.loads(SHEET)) for k in range(2)]
    cb.run_batch(jobs, tmp_path / "batch", progress=True)
    err = capsys.readouterr().err
    assert "runs" in err and "2/2" in err, err


def test_progress_without_tqdm_says_what_to_install(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "tqdm", None)
    with pytest.raises(ImportError, match="pip install tqdm"):
        cloth.Scene.from_toml(SHEET).run(tmp_path / "one", progress=True)
    with pytest.raises(ImportError, match="pip install tqdm"):
        cb.run_batch([], tmp_path / "batch", progress=True)


def test_a_batch_is_a_data_frame(tmp_path: Path) -> None:
    good = cb.Job(name="good", scene=cloth.batch.tomllib.loads(SHEET))
    bad = cb.Job(name="bad", scene={**good.scene, "cloth": {"grid": {**good.scene["cloth"]["grid"], "pins": [[20, 0]]}}})
    frame = cb.run_batch([good, bad], tmp_path / "batch").to_pandas()
    assert list(frame["name"]) == ["good", "bad"]
    assert list(frame["status"]) == ["done", "failed"]
    assert frame.loc[1, "error_type"] == "ValueError"
    assert frame.loc[0, "particles"] == 144
    assert frame.loc[0, "max_warp"] > 0

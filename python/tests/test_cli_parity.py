"""The same scene run by the `cloth` command and from Python gives the same results: the
same files, the same cloth (bit for bit when the solver runs serially), the same report
but for the wall-clock times. Also a drape set up through the Python API, piece by piece,
against the command's run of the same scene."""

from __future__ import annotations

import copy
import json
import tomllib
from pathlib import Path

import numpy as np
import pytest

import cloth

# Wall-clock fields of report.json: everything else must agree.
TIMING = {"total_seconds", "seconds", "median_step_ms"}


def without_timing(value):
    if isinstance(value, dict):
        return {k: without_timing(v) for k, v in value.items() if k not in TIMING}
    if isinstance(value, list):
        return [without_timing(v) for v in value]
    return value


def files_under(folder: Path) -> set[str]:
    return {p.relative_to(folder).as_posix() for p in folder.rglob("*") if p.is_file()}


def read_report(folder: Path) -> dict:
    return json.loads((folder / "report.json").read_text())


def run_cli_and_python(run_cli, scene: Path, tmp_path: Path, **kw):
    cli_out, py_out = tmp_path / "cli", tmp_path / "py"
    done = run_cli("run", scene, "--out", cli_out, "--force")
    assert done.returncode == 0, done.stderr
    wrote = [line[len("wrote ") :] for line in done.stdout.splitlines() if line.startswith("wrote ")]
    result = cloth.Scene.load(scene).run(py_out, force=True, **kw)
    return cli_out, py_out, wrote, result


def csv_without_timing(path):
    """history.csv's lines without the step_ms column (the last)."""
    lines = path.read_text().splitlines()
    assert lines[0].endswith(",step_ms")
    return [line.rsplit(",", 1)[0] for line in lines]


SERIAL_SHEET_EXTRA = """
[solver]
parallel = false
[output]
image_size = [160, 100]
frames_every = 20
checkpoints = [1, 30, 60]
"""


def test_a_serial_sheet_run_is_bit_for_bit_the_commands(run_cli, sheet_scene, write_scene, tmp_path, obj_vertices):
    scene = write_scene(sheet_scene + SERIAL_SHEET_EXTRA)
    cli_out, py_out, wrote, result = run_cli_and_python(run_cli, scene, tmp_path)
    names = files_under(cli_out)
    assert names == files_under(py_out)
    assert {"cloth.obj", "cloth.ply", "bodies.obj", "scene.glb", "render.png", "report.json", "report.md"} <= names
    assert any(n.startswith("frames/") for n in names)
    for name in sorted(names - {"report.json", "report.md", "history.csv"}):
        assert (cli_out / name).read_bytes() == (py_out / name).read_bytes(), name
    # The history is the same step for step, but for each step's wall time.
    theirs_steps, ours_steps = (csv_without_timing(out / "history.csv") for out in (cli_out, py_out))
    assert len(ours_steps) == 61 and ours_steps == theirs_steps
    theirs, ours = read_report(cli_out), read_report(py_out)
    assert without_timing(ours) == without_timing(theirs)
    assert [c["step"] for c in ours["checkpoints"]] == [1, 30, 60]
    # The result is the run that wrote those files.
    assert result.report == ours
    assert result.outcome == "finished" and result.finished
    np.testing.assert_array_equal(result.positions, obj_vertices(py_out / "cloth.obj"))
    assert result.positions.dtype == np.float64 and result.positions.shape == (144, 3)
    assert result.mesh.vertex_count == 144 and result.mesh.grid_shape == (12, 12)
    assert sorted(Path(p).name for p in result.outputs) == sorted(Path(p).name for p in wrote)
    for p in result.outputs:
        assert (py_out / Path(p).name).is_file()
    # The report's strain is the strain of the cloth written.
    s = cloth.strain(result.mesh, result.positions)
    assert ours["strain"]["max_warp"] == s.max_warp and ours["strain"]["p99_weft"] == s.p99_weft


def test_the_same_drape_set_up_through_the_api(run_cli, sheet_scene, write_scene, tmp_path, obj_vertices):
    scene = write_scene(sheet_scene + "[solver]\nparallel = false\n[output]\npng = false\nglb = false\n")
    out = tmp_path / "cli"
    done = run_cli("run", scene, "--out", out, "--quiet")
    assert done.returncode == 0, done.stderr
    spec = tomllib.loads(scene.read_text())
    grid, rest = spec["cloth"]["grid"], spec["rest"]
    mesh = cloth.ClothMesh.grid(grid["nx"], grid["ny"], tuple(grid["size"]), origin=tuple(grid["origin"]))
    sim = cloth.Simulation(
        mesh,
        cloth.Fabric.preset(spec["fabric"]["preset"]),
        bodies=[cloth.Body.sphere(spec["bodies"][0]["sphere"]["radius"])],
        settings={"parallel": False},
    )
    outcome = sim.run_to_rest(**rest)
    report = read_report(out)
    assert outcome.steps == report["stages"][0]["steps"]
    assert outcome.reason == report["stages"][0]["ended"]
    np.testing.assert_array_equal(sim.positions, obj_vertices(out / "cloth.obj"))
    assert sim.time == report["simulated_time"]
    assert sim.strain().max_warp == report["strain"]["max_warp"]


def test_scenes_from_text_and_dicts_run_as_from_files(sheet_scene, write_scene, tmp_path):
    text = sheet_scene + "[solver]\nparallel = false\n[output]\npng = false\nglb = false\nply = false\n"
    path = write_scene(text)
    runs = {
        "file": cloth.Scene.load(path),
        "text": cloth.Scene.from_toml(text, base_dir=path.parent),
        "dict": cloth.Scene.from_dict(tomllib.loads(text), base_dir=str(path.parent)),
    }
    objs = {}
    for how, scene in runs.items():
        out = tmp_path / how
        result = scene.run(out)
        assert result.finished
        objs[how] = (out / "cloth.obj").read_bytes()
        assert not (out / "cloth.ply").exists()
    assert objs["file"] == objs["text"] == objs["dict"]


def test_a_parallel_sheet_run_agrees_with_the_command(run_cli, sheet_scene, write_scene, tmp_path, obj_vertices):
    scene = write_scene(sheet_scene + "[output]\npng = false\nglb = false\n")
    cli_out, py_out, _, result = run_cli_and_python(run_cli, scene, tmp_path)
    assert files_under(cli_out) == files_under(py_out)
    np.testing.assert_allclose(obj_vertices(py_out / "cloth.obj"), obj_vertices(cli_out / "cloth.obj"), rtol=0, atol=1e-6)
    theirs, ours = read_report(cli_out), read_report(py_out)
    assert ours["particles"] == theirs["particles"] == 144
    assert [s["steps"] for s in ours["stages"]] == [s["steps"] for s in theirs["stages"]]
    for key in ("max_warp", "max_weft", "p99_warp", "p99_weft"):
        assert ours["strain"][key] == pytest.approx(theirs["strain"][key], abs=1e-6), key


def test_scene_callbacks_and_a_stopped_run(sheet_scene, write_scene, tmp_path, obj_vertices):
    scene = write_scene(sheet_scene + "[solver]\nparallel = false\n[output]\npng = false\nglb = false\n")
    seen = []

    def watch(snap):
        assert snap.stage == "running"
        assert snap.positions.shape == (144, 3)
        seen.append(snap.stats.step)

    result = cloth.Scene.load(scene).run(tmp_path / "all", callback=watch, every=7)
    steps = result.report["stages"][0]["steps"]
    assert seen == list(range(7, steps + 1, 7))

    at_stop = {}

    def stop(snap):
        if snap.stats.step == 20:
            at_stop["positions"] = snap.positions
            return False
        return True

    out = tmp_path / "stopped"
    result = cloth.Scene.load(scene).run(out, callback=stop, every=5)
    assert result.outcome == "interrupted" and not result.finished
    assert result.report["outcome"] == {"kind": "interrupted", "stage": "running", "step": 20}
    assert read_report(out)["outcome"] == result.report["outcome"]
    assert result.report["stages"][0]["steps"] == 20
    np.testing.assert_array_equal(obj_vertices(out / "cloth.obj"), at_stop["positions"])
    np.testing.assert_array_equal(result.positions, at_stop["positions"])


def garment_scene(assets: Path) -> str:
    return f"""
name = "coarse skirt"
[cloth.garment]
pattern = {json.dumps(str(assets / "patterns" / "skirt.toml"))}
edge_length = 0.04
[fabric]
preset = "cotton_poplin"
[[bodies]]
name = "mannequin"
file = {json.dumps(str(assets / "bodies" / "mannequin.obj"))}
[output]
glb = false
image_size = [160, 100]
frames_every = 50
checkpoints = [1, 10]
"""


@pytest.fixture(scope="module")
def garment_runs(tmp_path_factory, cloth_bin, assets):
    """The coarse skirt run by the command and by Scene.run, and sewn and draped through
    the API: (cli folder, python folder, the RunResult, the sewn garment, the draped
    simulation, the stages the callback saw)."""
    import subprocess

    tmp = tmp_path_factory.mktemp("garment")
    scene = tmp / "skirt.toml"
    scene.write_text(garment_scene(assets))
    cli_out, py_out = tmp / "cli", tmp / "py"
    done = subprocess.run([cloth_bin, "run", str(scene), "--out", str(cli_out), "--quiet"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    stages = []
    result = cloth.Scene.load(scene).run(py_out, callback=lambda s: stages.append(s.stage), every=1)
    body = cloth.Body.load(assets / "bodies" / "mannequin.obj", name="mannequin")
    garment = cloth.Garment(cloth.Pattern.load(assets / "patterns" / "skirt.toml"), 0.04)
    sewn = garment.sew([body], cloth.Fabric.preset("cotton_poplin"))
    draped = sewn.drape([body])
    return cli_out, py_out, result, sewn, draped, stages


def test_a_garment_scene_agrees_with_the_command(garment_runs, obj_vertices):
    cli_out, py_out, result, _, _, stages = garment_runs
    assert files_under(cli_out) == files_under(py_out)
    assert any(n.startswith("frames/") for n in files_under(py_out))
    theirs, ours = read_report(cli_out), read_report(py_out)
    assert ours["outcome"] == theirs["outcome"] == {"kind": "finished"}
    assert ours["particles"] == theirs["particles"] and ours["triangles"] == theirs["triangles"]
    assert [(s["stage"], s["steps"], s["ended"]) for s in ours["stages"]] == [
        (s["stage"], s["steps"], s["ended"]) for s in theirs["stages"]
    ]
    for key in ("max_warp", "max_weft", "p99_warp", "p99_weft"):
        assert ours["strain"][key] == pytest.approx(theirs["strain"][key], abs=1e-6), key
    assert ours["largest_seam_gap"] == pytest.approx(theirs["largest_seam_gap"], abs=1e-6)
    assert [(c["stage"], c["step"]) for c in ours["checkpoints"]] == [(c["stage"], c["step"]) for c in theirs["checkpoints"]]
    ours_v, theirs_v = obj_vertices(py_out / "cloth.obj"), obj_vertices(cli_out / "cloth.obj")
    assert ours_v.shape == theirs_v.shape == (ours["particles"], 3)
    np.testing.assert_allclose(ours_v, theirs_v, rtol=0, atol=1e-6)
    # The callback saw both stages, every step.
    assert stages.count("sewing") == ours["stages"][0]["steps"]
    assert stages.count("draping") == ours["stages"][1]["steps"]
    assert result.finished


def test_a_garment_draped_through_the_api_is_the_commands(garment_runs, obj_vertices):
    cli_out, _, _, sewn, draped, _ = garment_runs
    report = read_report(cli_out)
    assert draped.outcome.steps == report["stages"][1]["steps"]
    assert draped.outcome.reason == report["stages"][1]["ended"]
    # What the sewing and the drape did, as the report gives it.
    for key in ("seam_stalls", "caught_layers", "weld_crossings"):
        assert sewn.report[key] == report[key], key
    assert set(sewn.report["weld_crossings"]) == {"found", "left", "regions_moved"}
    assert draped.untangling_at_rest == report["untangling_at_rest"]
    np.testing.assert_allclose(draped.simulation.positions, obj_vertices(cli_out / "cloth.obj"), rtol=0, atol=1e-6)

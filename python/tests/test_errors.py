"""Errors: bad input is a ValueError carrying the `cloth` command's message, a run that
fails on valid input a cloth.SimulationError that keeps (and, for a scene, writes) the last
good state, and no Rust panic ever reaches Python."""

from __future__ import annotations

import json
import math
import os
import pickle
import signal
import threading

import numpy as np
import pytest

import cloth

# Bad variants of the small sheet scene (the CLI's own tests make the same ones).
SI_NEGATIVE = """[fabric.si]
area_density = 0.15
warp = { law = "linear", stiffness = -5.0 }
weft = { law = "linear", stiffness = 1000.0 }
compression_warp = 100.0
compression_weft = 100.0
shear_modulus = 20.0
bending = { warp = 1e-5, weft = 1e-5 }"""
SI_GOOD = SI_NEGATIVE.replace("-5.0", "1000.0")

BAD_SCENES = {
    "syntax": lambda s: s.replace("nx = 12", "nx = = 12"),
    "unknown_key": lambda s: s.replace("nx = 12", "nx = 12\nnz = 3"),
    "length_as_text": lambda s: s.replace("size = [0.6, 0.6]", 'size = ["60cm", "60cm"]'),
    "missing_body_file": lambda s: s.replace("sphere = { radius = 0.3 }", 'file = "missing.obj"'),
    "negative_stiffness": lambda s: s.replace('[fabric]\npreset = "cotton_poplin"', SI_NEGATIVE),
    "pin_outside_grid": lambda s: s.replace("[fabric]", "pins = [[20, 0]]\n[fabric]"),
    "negative_radius": lambda s: s.replace("radius = 0.3", "radius = -0.3"),
    "unknown_preset": lambda s: s.replace('"cotton_poplin"', '"tweed"'),
    "bad_time_step": lambda s: s + "[solver]\ntime_step = -1.0\n",
    "tiny_picture": lambda s: s + "[output]\nimage_size = [5, 400]\n",
    "two_fabrics": lambda s: s.replace('preset = "cotton_poplin"', 'preset = "cotton_poplin"\n' + SI_GOOD),
    "missing_mesh_file": lambda s: s.replace(
        s[s.index("[cloth.grid]") : s.index("[fabric]")], '[cloth.mesh]\nfile = "nothing.obj"\n'
    ),
}


@pytest.mark.parametrize("kind", sorted(BAD_SCENES))
def test_bad_scenes_raise_the_commands_message(kind, sheet_scene, write_scene, cli_error):
    text = BAD_SCENES[kind](sheet_scene)
    assert text != sheet_scene
    path = write_scene(text, f"{kind}.toml")
    expected = cli_error(path)
    with pytest.raises(ValueError) as e:
        cloth.Scene.load(str(path)).check()
    assert expected in str(e.value), f"\nexpected (the command's): {expected}\ngot: {e.value}"


def test_a_bad_scene_runs_nothing(sheet_scene, write_scene, cli_error, tmp_path):
    path = write_scene(BAD_SCENES["pin_outside_grid"](sheet_scene))
    expected = cli_error(path)
    out = tmp_path / "out"
    with pytest.raises(ValueError) as e:
        cloth.Scene.load(str(path)).run(out)
    assert expected in str(e.value)
    assert not out.exists() or not any(out.iterdir())


def test_a_scene_from_text_names_itself_in_errors(sheet_scene):
    with pytest.raises(ValueError) as e:
        cloth.Scene.from_toml(BAD_SCENES["syntax"](sheet_scene), name="inline.toml").check()
    assert "inline.toml" in str(e.value) and "line 3" in str(e.value), str(e.value)
    with pytest.raises(ValueError) as e:
        cloth.Scene.from_dict({"cloth": {"grid": {"nx": 3}}, "fabric": {"preset": "silk"}}, name="d").check()
    assert "ny" in str(e.value) or "size" in str(e.value), str(e.value)


def test_a_missing_scene_file(tmp_path, run_cli):
    path = tmp_path / "nope.toml"
    done = run_cli("check", path)
    assert done.returncode == 2
    expected = done.stderr.strip().removeprefix("error: ")
    with pytest.raises((ValueError, OSError)) as e:
        cloth.Scene.load(path)
    if isinstance(e.value, ValueError):
        assert expected in str(e.value), str(e.value)
    else:
        assert isinstance(e.value, FileNotFoundError) and "nope.toml" in str(e.value)


# ------------------------------------------------------------------------ divergence


def small_sheet():
    return cloth.ClothMesh.grid(8, 8, (0.4, 0.4), origin=(0.0, 0.0, 1.0))


def test_a_speed_limit_breach_is_a_simulation_error_that_keeps_the_state():
    mesh = small_sheet()
    sim = cloth.Simulation(mesh, cloth.Fabric.preset("cotton_poplin"), settings={"max_speed": 0.01})
    with pytest.raises(cloth.SimulationError) as e:
        sim.step()
    err = e.value
    assert isinstance(err, RuntimeError)
    assert err.step == 1 and err.report is None
    assert "step 1" in str(err), str(err)
    assert sim.step_count == 0
    np.testing.assert_array_equal(sim.positions, mesh.positions)
    # It survives pickling, as a worker process sends it back.
    back = pickle.loads(pickle.dumps(err))
    assert type(back) is cloth.SimulationError and str(back) == str(err) and back.step == 1
    # The same through run_to_rest.
    with pytest.raises(cloth.SimulationError) as e:
        sim.run_to_rest(max_steps=10)
    assert e.value.step == 1


def test_an_explicit_run_that_blows_up_keeps_the_last_good_state():
    mesh = small_sheet()
    pins = [mesh.grid_index(0, 0), mesh.grid_index(7, 0)]
    settings = {"integrator": "explicit_euler", "time_step": 0.05}
    sim = cloth.Simulation(mesh, cloth.Fabric.preset("denim"), pins=pins, settings=settings)
    good = []
    with pytest.raises(cloth.SimulationError) as e:
        sim.run_to_rest(max_steps=200, callback=lambda s: good.append(s.positions), every=1)
    err = e.value
    assert 1 <= err.step <= 200
    assert sim.step_count == err.step - 1
    p = sim.positions
    assert np.isfinite(p).all() and np.isfinite(sim.velocities).all()
    if good:
        np.testing.assert_array_equal(p, good[-1])
    assert str(err.step) in str(err)


def test_a_diverging_scene_writes_the_last_good_state_and_the_report(
    sheet_scene, write_scene, tmp_path, run_cli, obj_vertices
):
    path = write_scene(sheet_scene + "[solver]\nmax_speed = 0.01\n[output]\nimage_size = [160, 100]\n")
    out = tmp_path / "py"
    with pytest.raises(cloth.SimulationError) as e:
        cloth.Scene.load(path).run(out)
    err = e.value
    assert err.step == 1
    assert isinstance(err.report, dict) and err.report["outcome"]["kind"] == "failed"
    report = json.loads((out / "report.json").read_text())
    assert report["outcome"]["kind"] == "failed"
    assert "step 1" in report["outcome"]["error"]
    assert report["outcome"]["error"] in str(err), str(err)
    assert err.report["outcome"] == report["outcome"]
    # The last good state is the sheet as placed.
    placed = cloth.ClothMesh.grid(12, 12, (0.6, 0.6), origin=(-0.3, -0.3, 0.35)).positions
    np.testing.assert_array_equal(obj_vertices(out / "cloth.obj"), placed)
    assert (out / "report.md").exists()
    # The command fails the same way, with status 1.
    cli_out = tmp_path / "cli"
    done = run_cli("run", path, "--out", cli_out, "--quiet")
    assert done.returncode == 1, done.stderr
    theirs = json.loads((cli_out / "report.json").read_text())
    assert theirs["outcome"] == report["outcome"]
    assert sorted(os.listdir(cli_out)) == sorted(os.listdir(out))


def test_a_non_empty_output_folder_is_refused_without_force(sheet_scene, write_scene, tmp_path, run_cli):
    path = write_scene(sheet_scene + "[output]\npng = false\nglb = false\n")
    out = tmp_path / "out"
    out.mkdir()
    (out / "keep.txt").write_text("mine")
    done = run_cli("run", path, "--out", out, "--quiet")
    assert done.returncode == 2
    expected = done.stderr.strip().removeprefix("error: ").split(": pass --force")[0]
    with pytest.raises(ValueError) as e:
        cloth.Scene.load(path).run(out)
    assert expected in str(e.value), str(e.value)
    assert sorted(os.listdir(out)) == ["keep.txt"]
    # An existing empty folder is fine without force.
    empty = tmp_path / "empty"
    empty.mkdir()
    assert cloth.Scene.load(path).run(empty).finished
    result = cloth.Scene.load(path).run(out, force=True)
    assert result.finished and (out / "report.json").exists()
    assert (out / "keep.txt").read_text() == "mine"


def test_seams_that_do_not_close_are_a_simulation_error(assets):
    pattern = cloth.Pattern.load(assets / "patterns" / "skirt.toml")
    garment = cloth.Garment(pattern, 0.05)
    body = cloth.Body.load(assets / "bodies" / "mannequin.obj")
    fabric = cloth.Fabric.preset("cotton_poplin")
    with pytest.raises(cloth.SimulationError):
        garment.sew([body], fabric, settings={"max_steps": 2})
    # A callback returning False stops the sewing.
    with pytest.raises(cloth.SimulationError):
        garment.sew([body], fabric, callback=lambda s: False)
    with pytest.raises(ValueError) as e:
        garment.sew([body], fabric, settings={"max_stepz": 2})
    assert "max_stepz" in str(e.value)


# ------------------------------------------------------------------------- no panics


def _pattern():
    from pathlib import Path

    return cloth.Pattern.load(Path(__file__).resolve().parents[2] / "assets" / "patterns" / "skirt.toml")


def _sim():
    return cloth.Simulation(small_sheet(), cloth.Fabric.preset("cotton_poplin"))


VALUE_ERRORS = {
    "sphere radius < 0": lambda: cloth.Body.sphere(-0.3),
    "sphere radius 0": lambda: cloth.Body.sphere(0.0),
    "sphere radius nan": lambda: cloth.Body.sphere(math.nan),
    "box of no width": lambda: cloth.Body.box((0.0, 1.0, 1.0)),
    "cylinder height < 0": lambda: cloth.Body.cylinder(0.1, -1.0),
    "table height < 0": lambda: cloth.Body.table((1.0, 1.0, 0.04), -0.5),
    "mannequin height 0": lambda: cloth.Body.mannequin(height=0.0),
    "body thickness 0": lambda: cloth.Body.sphere(0.1, thickness=0.0),
    "grid nx = 0": lambda: cloth.ClothMesh.grid(0, 5, (1.0, 1.0)),
    "grid nx = 1": lambda: cloth.ClothMesh.grid(1, 5, (1.0, 1.0)),
    "grid of no width": lambda: cloth.ClothMesh.grid(3, 3, (0.0, 1.0)),
    "grid of negative size": lambda: cloth.ClothMesh.grid(3, 3, (-1.0, 1.0)),
    "grid of a zero axis": lambda: cloth.ClothMesh.grid(3, 3, (1.0, 1.0), u_axis=(0.0, 0.0, 0.0)),
    "grid of parallel axes": lambda: cloth.ClothMesh.grid(3, 3, (1.0, 1.0), v_axis=(1.0, 0.0, 0.0)),
    "empty mesh": lambda: cloth.ClothMesh.from_arrays(np.zeros((0, 3)), np.zeros((0, 2)), np.zeros((0, 3), dtype=np.int64)),
    "edge_length 0": lambda: cloth.Garment(_pattern(), 0.0),
    "edge_length < 0": lambda: cloth.Garment(_pattern(), -0.01),
    "edge_length nan": lambda: cloth.Garment(_pattern(), math.nan),
    "every = 0": lambda: _sim().run_to_rest(max_steps=3, callback=lambda s: None, every=0),
    "max_steps = 0": lambda: _sim().run_to_rest(max_steps=0),
    "tolerance < 0": lambda: _sim().run_to_rest(tolerance=-1.0, max_steps=3),
    "consecutive_steps = 0": lambda: _sim().run_to_rest(consecutive_steps=0, max_steps=3),
    "fabric area_density < 0": lambda: cloth.Fabric.preset("silk").with_values(area_density=-1.0),
    "empty strain positions": lambda: cloth.strain(small_sheet(), np.zeros((0, 3))),
}


@pytest.mark.parametrize("case", sorted(VALUE_ERRORS))
def test_invalid_arguments_are_value_errors_not_panics(case):
    # PanicException derives from BaseException: `raises(ValueError)` lets it through.
    with pytest.raises(ValueError):
        VALUE_ERRORS[case]()


def test_scene_run_every_zero_is_a_value_error_and_runs_nothing(sheet_scene, tmp_path):
    scene = cloth.Scene.from_toml(sheet_scene)
    out = tmp_path / "out"
    with pytest.raises(ValueError):
        scene.run(out, callback=lambda s: None, every=0)
    assert not out.exists() or not any(out.iterdir())
    with pytest.raises(ValueError):
        cloth.Garment(_pattern(), 0.05).sew([], cloth.Fabric.preset("silk"), callback=lambda s: None, every=0)


NO_PANIC = {
    "step(0)": lambda: _sim().step(0),
    "step(-1)": lambda: _sim().step(-1),
    "step(2**70)": lambda: _sim().step(2**70),
    "grid_index(-1, 0)": lambda: small_sheet().grid_index(-1, 0),
    "grid(-3, 3)": lambda: cloth.ClothMesh.grid(-3, 3, (1.0, 1.0)),
    "sphere('a')": lambda: cloth.Body.sphere("a"),
    "no points": lambda: cloth.Body.sphere(0.1).signed_distance(np.zeros((0, 3))),
    "fabric from None": lambda: cloth.Fabric.from_si(None),
    "simulation of None": lambda: cloth.Simulation(None, cloth.Fabric.preset("silk")),
    "bodies of None": lambda: cloth.Simulation(small_sheet(), cloth.Fabric.preset("silk"), bodies=[None]),
    "settings not a dict": lambda: cloth.Simulation(small_sheet(), cloth.Fabric.preset("silk"), settings=[1, 2]),
    "pattern of nothing": lambda: cloth.Pattern.from_toml(""),
    "garmentcode of nothing": lambda: cloth.Pattern.from_garmentcode("{}"),
    "scene of nothing": lambda: cloth.Scene.from_toml("").check(),
    "scene dict of junk": lambda: cloth.Scene.from_dict({"cloth": 3}).check(),
    "kes of nothing": lambda: cloth.Fabric.from_kes({}),
}


@pytest.mark.parametrize("case", sorted(NO_PANIC))
def test_odd_calls_never_panic(case):
    try:
        NO_PANIC[case]()
    except Exception as e:  # a PanicException is a BaseException: it is not caught here
        assert isinstance(e, (ValueError, TypeError, OverflowError, IndexError)), repr(e)


# ----------------------------------------------------------------------------- Ctrl-C


@pytest.mark.skipif(
    signal.getsignal(signal.SIGINT) is not signal.default_int_handler or os.name == "nt",
    reason="needs Python's own SIGINT handler",
)
def test_ctrl_c_stops_a_run_and_keeps_the_state():
    mesh = cloth.ClothMesh.grid(20, 20, (0.6, 0.6), origin=(0.0, 0.0, 1.0))
    sim = cloth.Simulation(mesh, cloth.Fabric.preset("cotton_poplin"), pins=[0, 19])
    started = threading.Event()
    steps = []

    def callback(snap):
        steps.append(snap.stats.step)
        started.set()

    def interrupt():
        started.wait()
        os.kill(os.getpid(), signal.SIGINT)

    killer = threading.Thread(target=interrupt)
    killer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            sim.run_to_rest(tolerance=1e-14, max_steps=20_000, callback=callback, every=5)
    finally:
        started.set()
        killer.join()
    assert 5 <= sim.step_count < 20_000
    assert steps and sim.step_count >= steps[-1]
    assert np.isfinite(sim.positions).all()
    # It can go on from there.
    n = sim.step_count
    sim.step()
    assert sim.step_count == n + 1


@pytest.mark.skipif(
    signal.getsignal(signal.SIGINT) is not signal.default_int_handler or os.name == "nt",
    reason="needs Python's own SIGINT handler",
)
def test_ctrl_c_stops_a_scene_and_writes_the_state_reached(sheet_scene, tmp_path, obj_vertices):
    text = sheet_scene.replace("nx = 12", "nx = 20").replace("ny = 12", "ny = 20")
    text = text.replace("max_steps = 60", "max_steps = 20000").replace("tolerance = 1e-5", "tolerance = 1e-14")
    text += "[output]\npng = false\nglb = false\n"
    scene = cloth.Scene.from_toml(text)
    started = threading.Event()

    def interrupt():
        started.wait()
        os.kill(os.getpid(), signal.SIGINT)

    killer = threading.Thread(target=interrupt)
    killer.start()
    out = tmp_path / "out"
    try:
        with pytest.raises(KeyboardInterrupt):
            scene.run(out, callback=lambda s: started.set(), every=5)
    finally:
        started.set()
        killer.join()
    report = json.loads((out / "report.json").read_text())
    assert report["outcome"]["kind"] == "interrupted", report["outcome"]
    step = report["outcome"]["step"]
    assert 5 <= step < 20000
    assert report["stages"][0]["steps"] == step
    assert obj_vertices(out / "cloth.obj").shape == (400, 3)


def test_an_exception_in_a_scene_callback_propagates(sheet_scene, tmp_path):
    class Boom(Exception):
        pass

    def callback(snap):
        if snap.stats.step == 10:
            raise Boom("stop here")

    with pytest.raises(Boom, match="stop here"):
        cloth.Scene.from_toml(sheet_scene + "[output]\npng = false\nglb = false\n").run(tmp_path / "out", callback=callback)

"""The Python API against the engine it mirrors: fabrics (presets, SI, KES), bodies,
patterns and garments, and simulations (stepping, callbacks, pins, the integrators'
exact free fall, strain)."""

from __future__ import annotations

import math
import re
import threading
import tomllib
from pathlib import Path

import numpy as np
import pytest

import cloth
from conftest import flat_grid_obj

G = 9.81


def kget(d: dict, key: str):
    """`d[key]`, the key's case ignored (KES records name their fields in capitals)."""
    for k, v in d.items():
        if k.lower() == key.lower():
            return v
    raise KeyError(f"{key} not in {sorted(d)}")


def close_nested(a, b, rel=1e-9, path="") -> None:
    """Asserts two nested dicts/lists of numbers and strings are equal, numbers within rel."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and set(a) == set(b), (path, a, b)
        for k in a:
            close_nested(a[k], b[k], rel, f"{path}.{k}")
    elif isinstance(a, (list, tuple)):
        assert isinstance(b, (list, tuple)) and len(a) == len(b), (path, a, b)
        for k, (x, y) in enumerate(zip(a, b)):
            close_nested(x, y, rel, f"{path}[{k}]")
    elif isinstance(a, float) or isinstance(b, float):
        if a is None or b is None:
            assert a == b, (path, a, b)
        elif math.isinf(a) or math.isinf(b):
            assert a == b, (path, a, b)
        else:
            assert a == pytest.approx(b, rel=rel, abs=1e-300), (path, a, b)
    else:
        assert a == b, (path, a, b)


# ------------------------------------------------------------------------------ fabrics


def test_presets_are_the_commands_presets(run_cli):
    presets = cloth.Fabric.presets()
    assert isinstance(presets, dict) and presets
    listed = {}
    out = run_cli("fabrics")
    assert out.returncode == 0, out.stderr
    for line in out.stdout.splitlines():
        if line.strip():
            name, _, description = line.partition(" ")
            listed[name] = description.strip()
    assert presets == listed


def test_every_preset_round_trips_through_si():
    names = list(cloth.Fabric.presets())
    fabrics = [cloth.Fabric.preset(n) for n in names]
    for name, f in zip(names, fabrics):
        si = f.to_si()
        assert isinstance(si, dict)
        back = cloth.Fabric.from_si(si)
        assert back == f, name
        assert f.area_density == si["area_density"]
        assert f.thickness == si["thickness"]
        assert f.friction == si["friction"]
    # Different presets are different fabrics.
    assert fabrics[0] != fabrics[1]
    assert not (fabrics[0] == "cotton_poplin")


def test_preset_values_match_the_command(run_cli):
    f = cloth.Fabric.preset("silk")
    out = run_cli("fabrics", "silk")
    assert out.returncode == 0, out.stderr
    stiffness = float(re.search(r"secant stiffness at 1 % strain: ([0-9.]+) N/m", out.stdout).group(1))
    assert f.membrane_stiffness == pytest.approx(stiffness, abs=0.051)
    w, t = map(float, re.search(r"W ([0-9.]+) mg/cm2, T ([0-9.]+) mm", out.stdout).groups())
    kes = f.to_kes()
    assert kget(kes, "W") == pytest.approx(w, abs=5e-4)
    assert kget(kes, "T") == pytest.approx(t, abs=5e-4)


def test_unknown_preset_names_the_known_ones():
    with pytest.raises(ValueError) as e:
        cloth.Fabric.preset("tweed")
    msg = str(e.value)
    assert "tweed" in msg
    for name in cloth.Fabric.presets():
        assert name in msg, (name, msg)


def test_from_si(cotton_si):
    f = cloth.Fabric.from_si(cotton_si)
    assert f.area_density == 0.15
    assert f.membrane_stiffness == pytest.approx(1000.0, rel=1e-9)
    si = f.to_si()
    for key, value in cotton_si.items():
        assert si[key] == value, key
    # Optional values take defaults; they are given back.
    for key in ("thickness", "damping", "drag", "friction", "bending_law"):
        assert key in si, key


def test_from_si_refuses_unknown_keys_and_bad_values(cotton_si):
    with pytest.raises(ValueError) as e:
        cloth.Fabric.from_si({**cotton_si, "stiffnes": 3.0})
    assert "stiffnes" in str(e.value), str(e.value)
    bad = {**cotton_si, "warp": {"law": "linear", "stiffness": -5.0}}
    with pytest.raises(ValueError) as e:
        cloth.Fabric.from_si(bad)
    assert "warp" in str(e.value) and "-5" in str(e.value), str(e.value)
    missing = dict(cotton_si)
    del missing["shear_modulus"]
    with pytest.raises(ValueError) as e:
        cloth.Fabric.from_si(missing)
    assert "shear_modulus" in str(e.value), str(e.value)
    with pytest.raises(ValueError) as e:
        cloth.Fabric.from_si({**cotton_si, "area_density": 0.0})
    assert "area_density" in str(e.value), str(e.value)


def test_with_values_copies(cotton_si):
    f = cloth.Fabric.from_si(cotton_si)
    g = f.with_values(damping=0.01, friction=0.2)
    assert g.to_si()["damping"] == 0.01 and g.friction == 0.2
    assert f.to_si()["damping"] == 0.0 and f.friction != 0.2
    assert g != f
    assert g.with_values(damping=0.0, friction=f.friction) == f
    with pytest.raises((ValueError, TypeError)) as e:
        f.with_values(dampng=0.01)
    assert "dampng" in str(e.value), str(e.value)
    with pytest.raises(ValueError) as e:
        f.with_values(damping=-1.0)
    assert "damping" in str(e.value), str(e.value)


def test_kes_records_convert_as_the_presets_do(assets):
    table = tomllib.loads((assets / "fabrics.toml").read_text())
    for name in ("cotton_poplin", "silk", "denim"):
        record = table[name]["kes"]
        f = cloth.Fabric.from_kes(record)
        assert f == cloth.Fabric.preset(name), name
        # What the instruments would read off the model is the record back.
        back = f.to_kes()
        for key in ("W", "T", "MIU"):
            assert kget(back, key) == pytest.approx(record[key], rel=1e-9), (name, key)
        for d in ("warp", "weft"):
            for key in ("EMT", "LT", "WT", "B"):
                assert kget(kget(back, d), key) == pytest.approx(record[d][key], rel=1e-9), (name, d, key)
            # One shear modulus: both directions read the mean G.
            mean_g = 0.5 * (record["warp"]["G"] + record["weft"]["G"])
            assert kget(kget(back, d), "G") == pytest.approx(mean_g, rel=1e-9)
        # And the inverse of the inverse.
        again = cloth.Fabric.from_kes(back)
        close_nested(again.to_si(), f.to_si(), rel=1e-9)


def test_bad_kes_records_name_the_field(assets):
    record = tomllib.loads((assets / "fabrics.toml").read_text())["cotton_poplin"]["kes"]
    bad = {**record, "warp": {**record["warp"], "LT": 0.9}}
    with pytest.raises(ValueError) as e:
        cloth.Fabric.from_kes(bad)
    assert "warp.LT" in str(e.value), str(e.value)
    with pytest.raises(ValueError) as e:
        cloth.Fabric.from_kes({**record, "W": -1.0})
    assert re.search(r"\bW\b", str(e.value)), str(e.value)
    with pytest.raises(ValueError) as e:
        cloth.Fabric.from_kes({**record, "XYZ": 1.0})
    assert "XYZ" in str(e.value), str(e.value)


# ------------------------------------------------------------------------------- bodies


def directions(n: int, seed: int) -> np.ndarray:
    d = np.random.default_rng(seed).normal(size=(n, 3))
    return d / np.linalg.norm(d, axis=1, keepdims=True)


def test_sphere_signed_distance_against_the_analytic_one():
    r, c = 0.3, np.array([0.2, -0.1, 0.5])
    body = cloth.Body.sphere(r, position=tuple(c))
    assert np.allclose(np.linalg.norm(body.vertices - c, axis=1), r, rtol=1e-9)
    # A closed surface: V - E + F = 2.
    t = body.triangles
    edges = {tuple(sorted(e)) for tri in t.tolist() for e in ((tri[0], tri[1]), (tri[1], tri[2]), (tri[2], tri[0]))}
    assert len(body.vertices) - len(edges) + len(t) == 2
    d = directions(200, 4)
    for radius in (0.05, 0.15, 0.29, 0.31, 0.5, 1.0):
        points = c + radius * d
        got = body.signed_distance(points)
        # The icosphere's faces lie within a millimetre inside the sphere.
        np.testing.assert_allclose(got, radius - r, atol=1e-3)
        assert (np.sign(got) == np.sign(radius - r)).all(), radius
    assert body.signed_distance([c])[0] == pytest.approx(-r, abs=1e-3)


def test_box_cylinder_and_table_distances():
    box = cloth.Body.box((0.4, 0.6, 0.2), position=(1.0, 0.0, 0.0))
    d = box.signed_distance([[1.0, 0.0, 0.0], [1.3, 0.0, 0.0], [1.0, 0.0, 0.25], [1.0, 0.0, 0.05]])
    np.testing.assert_allclose(d, [-0.1, 0.1, 0.15, -0.05], atol=1e-12)
    cyl = cloth.Body.cylinder(0.2, 1.0)
    d = cyl.signed_distance([[0.0, 0.0, 0.0], [0.0, 0.0, 0.6], [0.0, 0.0, -0.45]])
    np.testing.assert_allclose(d, [-0.2, 0.1, -0.05], atol=2e-3)
    assert cyl.signed_distance([[0.5, 0.0, 0.0]])[0] == pytest.approx(0.3, abs=2e-3)
    table = cloth.Body.table((1.2, 0.8, 0.04), 0.75)
    z = table.vertices[:, 2]
    assert z.min() == pytest.approx(0.0, abs=1e-9) and z.max() == pytest.approx(0.75, abs=1e-9)
    assert table.signed_distance([[0.0, 0.0, 0.8]])[0] == pytest.approx(0.05, abs=1e-9)
    assert table.signed_distance([[0.0, 0.0, 0.74]])[0] < 0.0


def test_names_thickness_and_friction():
    assert "sphere" in cloth.Body.sphere(0.1).name
    assert cloth.Body.sphere(0.1, name="ball").name == "ball"
    b = cloth.Body.box((0.1, 0.1, 0.1), name="crate", thickness=0.002, friction=0.3)
    assert b.name == "crate" and len(b.parts) == 1 and "crate" in b.parts[0]
    for bad in (dict(thickness=-0.001), dict(friction=-0.5)):
        with pytest.raises(ValueError) as e:
            cloth.Body.sphere(0.1, **bad)
        assert next(iter(bad)) in str(e.value), str(e.value)


def sorted_rows(a: np.ndarray) -> np.ndarray:
    return a[np.lexsort(a.T[::-1])]


@pytest.mark.parametrize(
    "measurements, args",
    [
        (dict(arms=True), ["--arms"]),
        (dict(height=1.75, hip=1.02), ["--height", "1.75", "--hip", "1.02"]),
        # arms=True are the command's --arms: their length scaled to the height.
        (dict(height=1.75, arms=True), ["--height", "1.75", "--arms"]),
    ],
    ids=["arms", "measurements", "tall_with_arms"],
)
def test_mannequins_are_the_commands(run_cli, tmp_path, obj_vertices, measurements, args):
    body = cloth.Body.mannequin(**measurements)
    path = tmp_path / "m.obj"
    out = run_cli("mannequin", *args, "-o", path)
    assert out.returncode == 0, out.stderr
    objects = [l.split(None, 1)[1].strip() for l in path.read_text().splitlines() if l.startswith("o ")]
    assert len(body.parts) == len(objects) == (3 if "arms" in measurements else 1)
    for o in objects:
        assert any(o in p for p in body.parts), (o, body.parts)
    theirs, ours = obj_vertices(path), body.vertices
    assert ours.shape == theirs.shape
    np.testing.assert_allclose(sorted_rows(ours), sorted_rows(theirs), atol=1e-12)
    assert len(body.triangles) == sum(1 for l in path.read_text().splitlines() if l.startswith("f "))


def test_taller_is_taller():
    plain, tall = cloth.Body.mannequin(), cloth.Body.mannequin(height=1.75)
    assert np.ptp(tall.vertices[:, 2]) > np.ptp(plain.vertices[:, 2])


def test_mannequin_errors_name_the_measurement():
    with pytest.raises(ValueError) as e:
        cloth.Body.mannequin(waist=-1.0)
    assert "waist" in str(e.value), str(e.value)
    with pytest.raises((ValueError, TypeError)) as e:
        cloth.Body.mannequin(wingspan=1.7)
    assert "wingspan" in str(e.value), str(e.value)
    with pytest.raises((ValueError, TypeError)) as e:
        cloth.Body.mannequin(arms={"lenght": 0.5})
    assert "lenght" in str(e.value), str(e.value)
    with_arm = cloth.Body.mannequin(arms={"length": 0.5})
    assert len(with_arm.parts) == 3


def test_body_files_round_trip(tmp_path):
    sphere = cloth.Body.sphere(0.25, position=(0.0, 0.0, 1.0))
    path = tmp_path / "ball.obj"
    sphere.save_obj(path)
    back = cloth.Body.load(path)
    # The same surface (a body may number its vertices its own way).
    assert back.vertices.shape == sphere.vertices.shape and back.triangles.shape == sphere.triangles.shape
    np.testing.assert_allclose(sorted_rows(back.vertices), sorted_rows(sphere.vertices), atol=1e-12)
    points = np.array([[0.0, 0.0, 1.0], [0.0, 0.0, 1.5], [0.3, 0.0, 1.0], [0.1, 0.2, 1.1]])
    np.testing.assert_allclose(back.signed_distance(points), sphere.signed_distance(points), atol=1e-12)
    # Centimetres, and a placement.
    cm = cloth.Body.load(str(path), scale=100.0, position=(1.0, 0.0, 0.0))
    np.testing.assert_allclose(
        sorted_rows(cm.vertices), sorted_rows(100.0 * sphere.vertices + [1.0, 0.0, 0.0]), atol=1e-9
    )
    # An ASCII STL of the same triangles.
    v, t = sphere.vertices, sphere.triangles
    lines = ["solid ball"]
    for a, b, c in t:
        n = np.cross(v[b] - v[a], v[c] - v[a])
        n /= np.linalg.norm(n)
        lines += [f"facet normal {n[0]} {n[1]} {n[2]}", "outer loop"]
        lines += [f"vertex {v[i][0]} {v[i][1]} {v[i][2]}" for i in (a, b, c)]
        lines += ["endloop", "endfacet"]
    lines.append("endsolid ball")
    stl = tmp_path / "ball.stl"
    stl.write_text("\n".join(lines) + "\n")
    from_stl = cloth.Body.load(stl)
    # STL stores single precision.
    np.testing.assert_allclose(from_stl.signed_distance(points), sphere.signed_distance(points), atol=1e-6)


def test_flat_or_missing_body_files_are_refused_naming_the_file(tmp_path):
    # A lone triangle encloses nothing: no inside at all.
    flat = tmp_path / "flat.obj"
    flat.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    with pytest.raises(ValueError) as e:
        cloth.Body.load(flat)
    assert "flat.obj" in str(e.value) and "encloses no volume" in str(e.value), str(e.value)
    with pytest.raises((ValueError, OSError)) as e:
        cloth.Body.load(tmp_path / "nothing.obj")
    assert "nothing.obj" in str(e.value), str(e.value)


def test_shipped_mannequin_file_loads(assets):
    body = cloth.Body.load(assets / "bodies" / "mannequin.obj", name="mannequin")
    assert body.name == "mannequin"
    # The torso surrounds its own axis at hip height.
    assert body.signed_distance([[0.0, 0.0, 0.9]])[0] < 0.0
    assert body.signed_distance([[0.0, 0.0, 2.5]])[0] > 0.0


# ---------------------------------------------------------------------------- patterns


@pytest.mark.parametrize("name", ["skirt.toml", "dress.toml", "tshirt.toml"])
def test_toml_patterns_load(assets, name):
    path = assets / "patterns" / name
    spec = tomllib.loads(path.read_text())
    p = cloth.Pattern.load(path)
    assert p.panel_names == [panel["name"] for panel in spec["panels"]]
    assert p.seam_count == len(spec["seams"])
    q = cloth.Pattern.from_toml(path.read_text(), name=str(path))
    assert q.panel_names == p.panel_names and q.seam_count == p.seam_count


@pytest.mark.parametrize("name", ["straight_skirt_specification.json", "shift_dress_specification.json"])
def test_garmentcode_patterns_load(assets, name):
    import json

    path = assets / "patterns" / "garmentcode" / name
    spec = json.loads(path.read_text())["pattern"]
    p = cloth.Pattern.load(path)
    if "panel_order" in spec:
        assert p.panel_names == spec["panel_order"]
    else:
        assert sorted(p.panel_names) == sorted(spec["panels"])
    assert p.seam_count == len(spec["stitches"])
    q = cloth.Pattern.from_garmentcode(path.read_text())
    assert q.panel_names == p.panel_names
    # It meshes: every panel has triangles, and the seams pair vertices of two panels.
    garment = cloth.Garment(p, 0.05)
    assert set(garment.triangle_panel.tolist()) == set(range(len(p.panel_names)))
    assert len(garment.seam_pairs) > 0


def test_bad_patterns_name_the_file_and_the_line():
    with pytest.raises(ValueError) as e:
        cloth.Pattern.from_toml('name = "x"\nunits = = "cm"\n', name="mine.toml")
    assert "mine.toml" in str(e.value) and "line 2" in str(e.value), str(e.value)
    with pytest.raises(ValueError) as e:
        cloth.Pattern.from_garmentcode("{not json", name="spec.json")
    assert "spec.json" in str(e.value), str(e.value)


def components(n: int, pairs: np.ndarray) -> np.ndarray:
    """The root of each vertex once the seam pairs are joined (union-find)."""
    parent = list(range(n))

    def root(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for a, b in pairs.tolist():
        ra, rb = root(a), root(b)
        if ra != rb:
            parent[max(ra, rb)] = min(ra, rb)
    return np.array([root(i) for i in range(n)])


def test_garment_mesh_and_seams(assets):
    pattern = cloth.Pattern.load(assets / "patterns" / "skirt.toml")
    coarse = cloth.Garment(pattern, edge_length=0.04)
    fine = cloth.Garment(pattern, 0.02)
    assert coarse.panel_names == pattern.panel_names
    mesh = coarse.mesh
    assert fine.mesh.vertex_count > 2 * mesh.vertex_count
    tp = coarse.triangle_panel
    assert tp.dtype == np.int64 and tp.shape == (mesh.triangle_count,)
    assert set(tp.tolist()) == set(range(len(pattern.panel_names)))
    pairs = coarse.seam_pairs
    assert pairs.dtype == np.int64 and pairs.ndim == 2 and pairs.shape[1] == 2 and len(pairs) > 0
    assert pairs.min() >= 0 and pairs.max() < mesh.vertex_count
    # Each seam joins two panels: the panels of its vertices differ.
    panel_of_vertex = np.empty(mesh.vertex_count, dtype=np.int64)
    panel_of_vertex[mesh.triangles.reshape(-1)] = np.repeat(tp, 3)
    assert (panel_of_vertex[pairs[:, 0]] != panel_of_vertex[pairs[:, 1]]).all()
    # The panels are placed apart; moved together, the gap closes.
    assert coarse.widest_gap() > 0.005
    p = mesh.positions
    assert coarse.widest_gap(p) == pytest.approx(coarse.widest_gap(), rel=1e-12)
    roots = components(mesh.vertex_count, pairs)
    closed = p[roots]
    assert coarse.widest_gap(closed) == pytest.approx(0.0, abs=1e-12)
    # The material area is the panels' whatever the discretisation.
    assert fine.mesh.rest_area == pytest.approx(mesh.rest_area, rel=0.02)
    with pytest.raises(ValueError):
        cloth.Garment(pattern, edge_length=0.0)
    with pytest.raises(ValueError):
        cloth.Garment(pattern, edge_length=-0.01)


def test_sew_and_drape_a_coarse_skirt(assets):
    pattern = cloth.Pattern.load(assets / "patterns" / "skirt.toml")
    garment = cloth.Garment(pattern, 0.04)
    body = cloth.Body.load(assets / "bodies" / "mannequin.obj", name="mannequin")
    assert garment.placement_warnings([body]) == []
    seen = {"sewing": [], "draping": []}

    def callback(snap):
        seen[snap.stage].append(snap.stats.step)

    sewn = garment.sew([body], cloth.Fabric.preset("cotton_poplin"), callback=callback, every=2)
    roots = components(garment.mesh.vertex_count, garment.seam_pairs)
    assert sewn.mesh.vertex_count == len(set(roots.tolist()))
    assert sewn.mesh.triangle_count == garment.mesh.triangle_count
    report = sewn.report
    assert isinstance(report, dict)
    assert report["steps"] > 0 and report["max_gap"] <= 1e-3 and report["pull"] > 0.0
    assert len(seen["sewing"]) == report["steps"] // 2
    draped = sewn.drape([body], callback=callback, every=5)
    assert draped.outcome.reason in ("at_rest", "step_limit")
    assert len(seen["draping"]) == draped.outcome.steps // 5
    assert draped.seconds > 0.0
    sim = draped.simulation
    assert sim.mesh.vertex_count == sewn.mesh.vertex_count
    p = sim.positions
    assert np.isfinite(p).all()
    # The skirt hangs on the hips: below the waist, above the floor, nothing deep inside.
    assert p[:, 2].max() < 1.2 and p[:, 2].min() > 0.2
    assert sim.deepest_penetration() < 0.01
    # It can be stepped on.
    before = sim.step_count
    sim.step(2)
    assert sim.step_count == before + 2


def test_sew_takes_one_fabric_per_panel(assets):
    pattern = cloth.Pattern.load(assets / "patterns" / "skirt.toml")
    garment = cloth.Garment(pattern, 0.05)
    body = cloth.Body.load(assets / "bodies" / "mannequin.obj")
    with pytest.raises(ValueError):
        garment.sew([body], [cloth.Fabric.preset("silk")] * (len(pattern.panel_names) + 1))
    sewn = garment.sew([body], [cloth.Fabric.preset("cotton_poplin"), cloth.Fabric.preset("silk")])
    assert sewn.mesh.vertex_count > 0


# ---------------------------------------------------------------------------- simulation


def sheet(nx=6, ny=5, z=1.0, **kw):
    return cloth.ClothMesh.grid(nx, ny, (0.5, 0.4), origin=(0.0, 0.0, z), **kw)


def test_step_advances_time_and_counts(cotton_si):
    h = 0.01
    sim = cloth.Simulation(sheet(), cloth.Fabric.from_si(cotton_si), settings={"time_step": h})
    assert sim.step_count == 0 and sim.time == 0.0
    stats = sim.step()
    assert isinstance(stats, cloth.StepStats)
    assert stats.step == 1 and stats.time == pytest.approx(h)
    stats = sim.step(4)
    assert stats.step == 5 and sim.step_count == 5
    assert sim.time == pytest.approx(5 * h, rel=1e-12)
    assert isinstance(stats.cg_iterations, int) and stats.cg_converged
    assert stats.max_speed > 0.0 and stats.kinetic_energy > 0.0
    d = stats.to_dict()
    assert d["step"] == 5 and d["cg_iterations"] == stats.cg_iterations
    assert set(d) >= {"time", "max_speed", "kinetic_energy", "contacts"}
    assert sim.settings["time_step"] == h
    assert sim.settings["integrator"] == "implicit_euler"
    assert sim.fabrics == [cloth.Fabric.from_si(cotton_si)]
    v = sim.velocities
    m = sim.masses
    assert sim.kinetic_energy == pytest.approx(0.5 * float((m[:, None] * v * v).sum()), rel=1e-9)


def test_settings_are_checked(cotton_si):
    f = cloth.Fabric.from_si(cotton_si)
    with pytest.raises(ValueError) as e:
        cloth.Simulation(sheet(), f, settings={"time_stepp": 0.01})
    assert "time_stepp" in str(e.value), str(e.value)
    with pytest.raises(ValueError) as e:
        cloth.Simulation(sheet(), f, settings={"time_step": -1.0})
    assert "time_step" in str(e.value), str(e.value)
    with pytest.raises(ValueError) as e:
        cloth.Simulation(sheet(), f, settings={"integrator": "runge_kutta"})
    assert "runge_kutta" in str(e.value), str(e.value)


def test_run_to_rest_calls_back_every_n_steps(cotton_si):
    sim = cloth.Simulation(sheet(), cloth.Fabric.from_si(cotton_si))
    seen = []

    def callback(snap):
        assert isinstance(snap, cloth.Snapshot)
        assert snap.stage == "running"
        assert isinstance(snap.stats, cloth.StepStats)
        assert snap.positions.shape == (30, 3) and snap.velocities.shape == (30, 3)
        seen.append(snap.stats.step)
        return None

    out = sim.run_to_rest(tolerance=1e-12, max_steps=20, callback=callback, every=3)
    assert isinstance(out, cloth.RestOutcome)
    assert out.reason == "step_limit" and out.steps == 20
    assert seen == [3, 6, 9, 12, 15, 18]
    assert out.last.step == 20 == sim.step_count
    # True continues as None does; every=1 sees every step.
    seen.clear()
    out = sim.run_to_rest(tolerance=1e-12, max_steps=4, callback=lambda s: seen.append(s) or True)
    assert out.steps == 4 and len(seen) == 4


def test_returning_false_stops_the_run(cotton_si):
    sim = cloth.Simulation(sheet(), cloth.Fabric.from_si(cotton_si))
    calls = []

    def callback(snap):
        calls.append(snap.stats.step)
        return len(calls) < 3

    out = sim.run_to_rest(tolerance=1e-12, max_steps=100, callback=callback, every=2)
    assert out.reason == "stopped"
    assert out.steps == 6 and sim.step_count == 6 and calls == [2, 4, 6]


def test_an_exception_in_the_callback_propagates_and_keeps_the_state(cotton_si):
    sim = cloth.Simulation(sheet(), cloth.Fabric.from_si(cotton_si))

    class Boom(Exception):
        pass

    last = {}

    def callback(snap):
        last["positions"] = snap.positions
        if snap.stats.step == 4:
            raise Boom("from the callback")

    with pytest.raises(Boom, match="from the callback"):
        sim.run_to_rest(tolerance=1e-12, max_steps=100, callback=callback, every=2)
    assert sim.step_count == 4
    np.testing.assert_array_equal(sim.positions, last["positions"])
    sim.step()
    assert sim.step_count == 5


def test_rest_is_reached_and_reported(cotton_si):
    # A sheet lying on a box: it settles at once.
    fabric = cloth.Fabric.from_si(cotton_si).with_values(damping=0.01)
    box = cloth.Body.box((1.0, 1.0, 0.2), position=(0.25, 0.2, 0.9 - 0.003 - 0.0005))
    sim = cloth.Simulation(sheet(z=1.0), fabric, bodies=[box])
    out = sim.run_to_rest(tolerance=1e-4, consecutive_steps=5, max_steps=500)
    assert out.reason == "at_rest" and out.steps < 500
    assert out.steps == sim.step_count


def test_a_run_to_rest_may_grow_its_step(cotton_si):
    # Let go flat from one edge, the sheet swings down; longer steps damp the swing.
    def hanging():
        mesh = sheet(nx=10, ny=10)
        pins = [mesh.grid_index(i, 0) for i in range(10)]
        return cloth.Simulation(mesh, cloth.Fabric.from_si(cotton_si), pins=pins)

    fixed, grown = hanging(), hanging()
    h = fixed.settings["time_step"]
    a = fixed.run_to_rest(tolerance=1e-4 * h, max_steps=3000)
    b = grown.run_to_rest(tolerance=1e-4 * h, max_steps=3000, max_time_step=3 * h)
    assert a.reason == b.reason == "at_rest"
    assert b.steps < a.steps
    assert np.abs(fixed.positions - grown.positions).max() < 1e-3
    assert grown.settings["time_step"] == h
    with pytest.raises(ValueError, match="max_time_step"):
        grown.run_to_rest(max_time_step=-1.0)


def test_pins_hold_exactly(cotton_si):
    mesh = sheet(nx=6, ny=6)
    pins = [mesh.grid_index(0, 0), mesh.grid_index(5, 0)]
    sim = cloth.Simulation(mesh, cloth.Fabric.from_si(cotton_si), pins=pins)
    start = sim.positions
    sim.step(30)
    p = sim.positions
    np.testing.assert_array_equal(p[pins], start[pins])
    free = [mesh.grid_index(0, 5), mesh.grid_index(5, 5)]
    assert (p[free, 2] < start[free, 2] - 0.02).all()
    # A pinned particle moved by hand goes back to its pin in the next step.
    moved = sim.positions
    moved[pins[0]] += [0.0, 0.0, 0.1]
    sim.positions = moved
    np.testing.assert_array_equal(sim.positions[pins[0]], moved[pins[0]])
    sim.step()
    np.testing.assert_allclose(sim.positions[pins[0]], start[pins[0]], rtol=0, atol=1e-12)


def test_pins_go_to_their_positions(cotton_si):
    mesh = sheet()
    pins = [0, 5]
    targets = mesh.positions[pins] + [[0.0, 0.0, 0.02], [0.0, 0.0, 0.02]]
    sim = cloth.Simulation(mesh, cloth.Fabric.from_si(cotton_si), pins=pins, pin_positions=targets)
    sim.step(3)
    np.testing.assert_allclose(sim.positions[pins], targets, atol=1e-12)


@pytest.mark.parametrize(
    "integrator, sum_of_steps",
    [
        # Forward Euler: x += h v0, then v += h g: the fall is g h^2 n(n-1)/2.
        ("explicit_euler", lambda n: n * (n - 1) / 2),
        # Symplectic and backward Euler under a constant force: v += h g, then x += h v.
        ("symplectic_euler", lambda n: n * (n + 1) / 2),
        ("implicit_euler", lambda n: n * (n + 1) / 2),
    ],
)
def test_free_fall_follows_the_integrators_discrete_law(cotton_si, integrator, sum_of_steps):
    # A step small enough that forward Euler stays stable on the stiff fabric.
    h, n = 2e-4, 40
    gravity = np.array([0.5, 0.0, -G])
    settings = {
        "integrator": integrator,
        "time_step": h,
        "gravity": gravity.tolist(),
        "pcg": {"rel_tolerance": 1e-10},
    }
    mesh = sheet()
    sim = cloth.Simulation(mesh, cloth.Fabric.from_si(cotton_si), settings=settings)
    sim.step(n)
    m = sim.masses
    com0 = (m[:, None] * mesh.positions).sum(0) / m.sum()
    com = (m[:, None] * sim.positions).sum(0) / m.sum()
    expected = com0 + gravity * h * h * sum_of_steps(n)
    np.testing.assert_allclose(com, expected, rtol=0, atol=1e-9)
    # A uniform fall: every particle at the same velocity, undeformed.
    np.testing.assert_allclose(sim.velocities, np.tile(gravity * n * h, (mesh.vertex_count, 1)), atol=1e-8)
    assert sim.strain().max_warp == pytest.approx(0.0, abs=1e-6)
    # Distinct from the other laws by far more than the tolerance.
    other = n * (n - 1) / 2 if sum_of_steps(n) != n * (n - 1) / 2 else n * (n + 1) / 2
    assert abs(G * h * h * (other - sum_of_steps(n))) > 1e3 * 1e-9


def test_strain_of_a_stretched_grid():
    # Warp along +y, weft along -x: the stretch must follow the material axes.
    mesh = cloth.ClothMesh.grid(
        5, 4, (0.4, 0.3), origin=(0.1, 0.2, 0.3), u_axis=(0.0, 1.0, 0.0), v_axis=(-1.0, 0.0, 0.0)
    )
    s0 = cloth.strain(mesh, mesh.positions)
    assert np.abs(s0.warp).max() < 1e-9 and np.abs(s0.weft).max() < 1e-9
    assert cloth.grid_stretch(mesh, mesh.positions) == pytest.approx((0.0, 0.0), abs=1e-9)
    p = mesh.positions
    stretched = p.copy()
    stretched[:, 1] = p[0, 1] + 1.02 * (p[:, 1] - p[0, 1])
    s = cloth.strain(mesh, stretched)
    assert isinstance(s, cloth.Strain)
    np.testing.assert_allclose(s.warp, 2.0, atol=1e-9)
    np.testing.assert_allclose(s.weft, 0.0, atol=1e-9)
    assert s.max_warp == pytest.approx(2.0, abs=1e-9) and s.p99_warp == pytest.approx(2.0, abs=1e-9)
    assert s.max_weft == pytest.approx(0.0, abs=1e-9)
    h, v = cloth.grid_stretch(mesh, stretched)
    assert h == pytest.approx(2.0, abs=1e-9) and v == pytest.approx(0.0, abs=1e-9)
    # The same through a simulation.
    sim = cloth.Simulation(mesh, cloth.Fabric.preset("cotton_poplin"))
    assert sim.strain().max_warp == pytest.approx(0.0, abs=1e-9)
    sim.positions = stretched
    np.testing.assert_array_equal(sim.strain().warp, s.warp)
    assert sim.grid_stretch() == pytest.approx((2.0, 0.0), abs=1e-9)
    # Not a grid: no grid stretch.
    loose = cloth.ClothMesh.from_arrays(mesh.positions, mesh.uv, mesh.triangles)
    assert cloth.grid_stretch(loose, stretched) is None
    assert cloth.Simulation(loose, cloth.Fabric.preset("silk")).grid_stretch() is None


def test_deepest_penetration():
    mesh = sheet(z=0.0)
    sim = cloth.Simulation(mesh, cloth.Fabric.preset("cotton_poplin"), bodies=[cloth.Body.sphere(0.3, position=(0.0, 0.0, 5.0))])
    assert sim.deepest_penetration() == 0.0
    p = sim.positions
    p[7] = [0.0, 0.0, 5.0 - 0.1]
    sim.positions = p
    assert sim.deepest_penetration() == pytest.approx(0.2, abs=1e-3)


def two_sheets(gap):
    """A 9 x 9 sheet and a second one `gap` above it, turned, as one mesh."""
    low = cloth.ClothMesh.grid(9, 9, (0.4, 0.4), origin=(-0.2, -0.2, 0.0))
    high = cloth.ClothMesh.grid(9, 9, (0.4, 0.4), origin=(-0.19, -0.18, gap))
    n = len(low.positions)
    return cloth.ClothMesh.from_arrays(
        np.vstack([low.positions, high.positions]),
        np.vstack([low.uv, high.uv]),
        np.vstack([low.triangles, high.triangles + n]),
    ), n


@pytest.mark.parametrize("self_collision", [None, True, {"friction": 0.3}, False])
def test_self_collision_keeps_a_falling_sheet_above_a_held_one(self_collision):
    mesh, n = two_sheets(0.01)
    v = np.zeros((2 * n, 3))
    v[n:, 2] = -3.0
    sim = cloth.Simulation(
        mesh,
        cloth.Fabric.preset("cotton_poplin"),
        pins=list(range(n)),
        velocities=v,
        settings={"time_step": 1 / 60, "gravity": [0.0, 0.0, 0.0]},
        self_collision=self_collision,
    )
    most, contacts = 0, 0
    for _ in range(20):
        stats = sim.step()
        contacts = max(contacts, stats.self_contacts)
        most = max(most, sim.self_intersections())
    # Every particle of the falling sheet over the held one stays above it.
    upper = sim.positions[n:]
    over = (np.abs(upper[:, 0]) < 0.19) & (np.abs(upper[:, 1]) < 0.19)
    above = bool((upper[over, 2] > 0.0).all())
    if self_collision is False:
        # Without it, the falling sheet goes through.
        assert not above and contacts == 0
    else:
        assert most == 0 and above and contacts > 0, (most, above, contacts)
        gap = sim.closest_self_approach(0.01)
        thickness = cloth.Fabric.preset("cotton_poplin").to_si()["thickness"]
        assert gap is not None and gap >= 0.5 * thickness, gap
    assert sim.body_intersections() == 0


def test_self_collision_settings_are_checked():
    mesh, _ = two_sheets(0.01)
    f = cloth.Fabric.preset("silk")
    with pytest.raises(ValueError) as e:
        cloth.Simulation(mesh, f, self_collision={"thickness": -1.0})
    assert "self_collision.thickness" in str(e.value), str(e.value)
    with pytest.raises(ValueError) as e:
        cloth.Simulation(mesh, f, self_collision={"thicknes": 0.001})
    assert "thicknes" in str(e.value), str(e.value)
    # Self-collision is the scene's, not the solver's.
    with pytest.raises(ValueError) as e:
        cloth.Simulation(mesh, f, settings={"self_collision": {"enabled": False}})
    assert "self_collision" in str(e.value), str(e.value)


# --------------------------------------------------------------------------------- scenes


def test_scene_properties_and_check(write_scene, sheet_scene):
    path = write_scene(sheet_scene)
    scene = cloth.Scene.load(path)
    assert scene.name == "small sheet"
    assert Path(scene.path) == path
    assert Path(scene.base_dir) == path.parent
    assert scene.check() == []
    from_text = cloth.Scene.from_toml(sheet_scene, base_dir=path.parent, name="mine.toml")
    assert from_text.name == "small sheet" and from_text.path == "mine.toml"
    assert from_text.check() == []
    from_dict = cloth.Scene.from_dict(tomllib.loads(sheet_scene))
    assert from_dict.name == "small sheet" and from_dict.check() == []


@pytest.mark.parametrize(
    "name",
    ["dress.toml", "skirt.toml", "tshirt.toml", "sheet_on_sphere.toml", "tablecloth.toml", "cantilever.toml", "cusick.toml"],
)
def test_shipped_scenes_check_with_the_commands_warnings(assets, run_cli, name):
    path = assets / "scenes" / name
    out = run_cli("check", path)
    assert out.returncode == 0, out.stderr
    theirs = [l[len("warning: ") :] for l in out.stderr.splitlines() if l.startswith("warning: ")]
    assert cloth.Scene.load(path).check() == theirs


def test_mesh_scene_pins_are_the_files_vertex_numbers(write_scene, tmp_path):
    # A flat 4 x 4 sheet whose faces use its vertices out of file order; pin file vertex 3,
    # the corner at (0.3, 0, 1).
    n, h = 4, 0.1
    (tmp_path / "sheet.obj").write_text(flat_grid_obj(n, h))
    scene = write_scene(
        '[cloth.mesh]\nfile = "sheet.obj"\npins = [3]\n[fabric]\npreset = "cotton_poplin"\n'
        "[rest]\ntolerance = 1e-5\nconsecutive_steps = 5\nmax_steps = 20\n[output]\nglb = false\npng = false\n"
    )
    result = cloth.Scene.load(scene).run(tmp_path / "out")
    unmoved = [tuple(p) for p in result.positions.tolist() if p[2] == 1.0]
    assert unmoved == [(3 * h, 0.0, 1.0)], f"pinned: {unmoved}, but file vertex 3 is at (0.3, 0, 1)"
    # The mesh read from the file numbers its vertices as the file does.
    mesh = cloth.ClothMesh.load(tmp_path / "sheet.obj")
    np.testing.assert_allclose(mesh.positions, [[h * i, h * j, 1.0] for j in range(n) for i in range(n)], atol=1e-15)


def test_version_is_the_packages():
    assert isinstance(cloth.__version__, str) and re.match(r"\d+\.\d+", cloth.__version__)
    from importlib.metadata import version

    # The distribution is cloth-drape (PyPI's `cloth` is another project's); the import is cloth.
    assert version("cloth-drape") == cloth.__version__


def test_sizes_take_any_sequence_and_none_leaves_a_key_out():
    for size in ([0.4, 0.6, 0.2], np.array([0.4, 0.6, 0.2]), (0.4, 0.6, 0.2)):
        box = cloth.Body.box(size)
        np.testing.assert_allclose(np.ptp(box.vertices, axis=0), [0.4, 0.6, 0.2], atol=1e-12)
    assert cloth.ClothMesh.grid(3, 4, np.array([0.2, 0.3])).rest_area == pytest.approx(0.06)
    silk = cloth.Fabric.preset("silk").to_si()
    # None is a missing key: the default (no damping) instead of silk's.
    undamped = cloth.Fabric.from_si({**silk, "damping": None})
    assert undamped == cloth.Fabric.from_si({k: v for k, v in silk.items() if k != "damping"})


def test_nesting_that_never_ends_is_an_error_not_a_crash():
    loop: list = []
    loop.append(loop)
    with pytest.raises(ValueError, match="nested too deeply"):
        cloth.Fabric.from_si({"area_density": loop})

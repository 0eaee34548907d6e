"""numpy in and out of the native module: dtypes and shapes of what it returns, copies
both ways, conversion of lists and other dtypes, and errors that name the argument (and,
for shapes, the expected shape) for what cannot be converted."""

from __future__ import annotations

import re

import numpy as np
import pytest

import cloth
from conftest import flat_grid_obj

NX, NY, SIZE = 4, 3, (0.3, 0.2)

# "(N, 3)", "(12, 3)", "N x 3", "Nx3": the expected shape named in a message.
SHAPE3 = re.compile(r"\(\s*\w+\s*,\s*3\s*\)|\b\w+\s*[x×]\s*3\b")
SHAPE2 = re.compile(r"\(\s*\w+\s*,\s*2\s*\)|\b\w+\s*[x×]\s*2\b")


def grid_mesh(**kw):
    return cloth.ClothMesh.grid(NX, NY, SIZE, **kw)


def fabric():
    return cloth.Fabric.preset("cotton_poplin")


def edges_of(triangles: np.ndarray) -> set[tuple[int, int]]:
    out = set()
    for a, b, c in triangles.tolist():
        for p, q in ((a, b), (b, c), (c, a)):
            out.add((min(p, q), max(p, q)))
    return out


# --------------------------------------------------------------------------- meshes


def test_grid_arrays_have_the_documented_dtypes_shapes_and_layout():
    origin = np.array([0.1, -0.2, 0.5])
    mesh = grid_mesh(origin=tuple(origin))
    n = NX * NY
    assert mesh.vertex_count == n
    assert mesh.grid_shape == (NX, NY)
    p, uv, t = mesh.positions, mesh.uv, mesh.triangles
    assert p.dtype == np.float64 and p.shape == (n, 3)
    assert uv.dtype == np.float64 and uv.shape == (n, 2)
    assert t.dtype == np.int64 and t.ndim == 2 and t.shape[1] == 3
    assert t.shape[0] == mesh.triangle_count == 2 * (NX - 1) * (NY - 1)
    assert t.min() >= 0 and t.max() < n
    du, dv = SIZE[0] / (NX - 1), SIZE[1] / (NY - 1)
    corner = mesh.grid_index(0, 0)
    for j in range(NY):
        for i in range(NX):
            k = mesh.grid_index(i, j)
            assert k == j * NX + i
            np.testing.assert_allclose(p[k], origin + [i * du, j * dv, 0.0], atol=1e-12)
            np.testing.assert_allclose(uv[k] - uv[corner], [i * du, j * dv], atol=1e-12)
    assert mesh.rest_area == pytest.approx(SIZE[0] * SIZE[1], rel=1e-12)


def test_grid_axes_place_the_warp_and_weft():
    # The README's hanging sheet: warp along x, weft down -z.
    mesh = grid_mesh(u_axis=(1.0, 0.0, 0.0), v_axis=(0.0, 0.0, -1.0))
    p = mesh.positions
    far = mesh.grid_index(NX - 1, NY - 1)
    np.testing.assert_allclose(p[far] - p[mesh.grid_index(0, 0)], [SIZE[0], 0.0, -SIZE[1]], atol=1e-12)


def test_edges_are_the_distinct_edges_of_the_triangles():
    mesh = grid_mesh()
    e = mesh.edges
    assert e.dtype == np.int64 and e.ndim == 2 and e.shape[1] == 2
    as_set = {(min(a, b), max(a, b)) for a, b in e.tolist()}
    assert len(as_set) == len(e), "edges repeat"
    assert as_set == edges_of(mesh.triangles)
    # A disk: V - E + F = 1.
    assert mesh.vertex_count - len(e) + mesh.triangle_count == 1


def test_from_arrays_round_trips_exactly():
    g = grid_mesh(origin=(0.3, 0.1, 1.0))
    rng = np.random.default_rng(1)
    positions = g.positions + rng.normal(scale=1e-3, size=g.positions.shape)
    mesh = cloth.ClothMesh.from_arrays(positions, g.uv, g.triangles)
    np.testing.assert_array_equal(mesh.positions, positions)
    np.testing.assert_array_equal(mesh.uv, g.uv)
    np.testing.assert_array_equal(mesh.triangles, g.triangles)
    assert mesh.positions.dtype == np.float64 and mesh.triangles.dtype == np.int64
    assert mesh.grid_shape is None
    assert mesh.rest_area == pytest.approx(g.rest_area, rel=1e-12)


def test_from_arrays_accepts_lists_and_other_numeric_dtypes():
    g = grid_mesh()
    p32 = g.positions.astype(np.float32)
    uv32 = g.uv.astype(np.float32)
    for positions, uv, triangles in [
        (g.positions.tolist(), g.uv.tolist(), g.triangles.tolist()),
        (p32, uv32, g.triangles.astype(np.int32)),
        (g.positions, g.uv, g.triangles.astype(np.uint32)),
        # Fortran order and a non-contiguous view.
        (np.asfortranarray(g.positions), g.uv[:, :], np.ascontiguousarray(g.triangles[:, ::-1])[:, ::-1]),
    ]:
        mesh = cloth.ClothMesh.from_arrays(positions, uv, triangles)
        assert mesh.positions.dtype == np.float64 and mesh.uv.dtype == np.float64
        assert mesh.triangles.dtype == np.int64
        np.testing.assert_array_equal(mesh.positions, np.asarray(positions, dtype=np.float64))
        np.testing.assert_array_equal(mesh.uv, np.asarray(uv, dtype=np.float64))
        np.testing.assert_array_equal(mesh.triangles, g.triangles)


def test_mesh_arrays_are_copies_and_read_only_properties():
    mesh = grid_mesh()
    before = mesh.positions.copy()
    p = mesh.positions
    p += 1.0
    mesh.uv[:] = 7.0
    mesh.triangles[:] = 0
    np.testing.assert_array_equal(mesh.positions, before)
    assert mesh.triangles.max() == mesh.vertex_count - 1
    # Given arrays are copied: changing them afterwards changes nothing.
    positions, uv, tri = mesh.positions, mesh.uv, mesh.triangles
    other = cloth.ClothMesh.from_arrays(positions, uv, tri)
    positions[:] = 0.0
    tri[:] = 0
    np.testing.assert_array_equal(other.positions, before)
    with pytest.raises(AttributeError):
        mesh.positions = before


@pytest.mark.parametrize(
    "bad",
    [
        lambda p: p[:, :2],  # (N, 2)
        lambda p: p.reshape(-1),  # 1-D
        lambda p: np.concatenate([p, p[:, :1]], axis=1),  # (N, 4)
        lambda p: p.reshape(1, -1, 3),  # 3-D
    ],
    ids=["N-by-2", "1-D", "N-by-4", "3-D"],
)
def test_from_arrays_refuses_wrong_position_shapes_naming_the_argument(bad):
    g = grid_mesh()
    with pytest.raises((ValueError, TypeError)) as e:
        cloth.ClothMesh.from_arrays(bad(g.positions), g.uv, g.triangles)
    msg = str(e.value)
    assert "positions" in msg, msg
    assert SHAPE3.search(msg), f"expected shape not named: {msg}"


def test_from_arrays_refuses_wrong_uv_and_triangle_shapes():
    g = grid_mesh()
    with pytest.raises((ValueError, TypeError)) as e:
        cloth.ClothMesh.from_arrays(g.positions, g.positions, g.triangles)
    assert "uv" in str(e.value) and SHAPE2.search(str(e.value)), str(e.value)
    with pytest.raises((ValueError, TypeError)) as e:
        cloth.ClothMesh.from_arrays(g.positions, g.uv, g.triangles[:, :2])
    assert "triangles" in str(e.value) and SHAPE3.search(str(e.value)), str(e.value)
    # One position fewer than material coordinates.
    with pytest.raises(ValueError) as e:
        cloth.ClothMesh.from_arrays(g.positions[:-1], g.uv, g.triangles)
    assert re.search(r"position|uv|\(u, v\)", str(e.value)), str(e.value)


@pytest.mark.parametrize(
    "make",
    [
        lambda p: np.full(p.shape, "a", dtype=object),
        lambda p: p.astype(str),
        lambda p: p.astype(np.complex128) + 1j,
        lambda p: [["x", "y", "z"]] * len(p),
    ],
    ids=["object-strings", "unicode", "complex", "list-of-strings"],
)
def test_from_arrays_refuses_non_numeric_positions(make):
    g = grid_mesh()
    with pytest.raises((ValueError, TypeError)) as e:
        cloth.ClothMesh.from_arrays(make(g.positions), g.uv, g.triangles)
    assert "positions" in str(e.value), str(e.value)


def test_from_arrays_refuses_fractional_or_non_numeric_triangles():
    g = grid_mesh()
    with pytest.raises((ValueError, TypeError)) as e:
        cloth.ClothMesh.from_arrays(g.positions, g.uv, g.triangles.astype(str))
    assert "triangles" in str(e.value), str(e.value)


def test_non_finite_positions_name_the_vertex():
    g = grid_mesh()
    for bad in (np.nan, np.inf):
        p = g.positions
        p[4, 1] = bad
        with pytest.raises(ValueError) as e:
            cloth.ClothMesh.from_arrays(p, g.uv, g.triangles)
        msg = str(e.value)
        assert "position" in msg and re.search(r"\b4\b", msg), msg
    uv = g.uv
    uv[5, 0] = np.nan
    with pytest.raises(ValueError) as e:
        cloth.ClothMesh.from_arrays(g.positions, uv, g.triangles)
    assert re.search(r"\b5\b", str(e.value)), str(e.value)


def names_triangle(msg: str, k: int) -> bool:
    """"triangle 2", "triangles[2, 0]", "triangle #2"."""
    return re.search(rf"triangles?\W{{0,2}}{k}\b", msg) is not None


def test_bad_triangle_indices_name_the_triangle():
    g = grid_mesh()
    t = g.triangles
    t[1, 2] = 99
    with pytest.raises(ValueError) as e:
        cloth.ClothMesh.from_arrays(g.positions, g.uv, t)
    msg = str(e.value)
    assert names_triangle(msg, 1) and "99" in msg, msg
    t = g.triangles
    t[2, 0] = -1
    with pytest.raises(ValueError) as e:
        cloth.ClothMesh.from_arrays(g.positions, g.uv, t)
    assert names_triangle(str(e.value), 2), str(e.value)
    # A repeated vertex: a degenerate triangle.
    t = g.triangles
    t[3, 1] = t[3, 0]
    with pytest.raises(ValueError) as e:
        cloth.ClothMesh.from_arrays(g.positions, g.uv, t)
    assert names_triangle(str(e.value), 3), str(e.value)


def test_grid_index_of_a_non_grid_or_outside_the_grid_is_an_error():
    g = grid_mesh()
    with pytest.raises((ValueError, IndexError)):
        g.grid_index(NX, 0)
    with pytest.raises((ValueError, IndexError)):
        g.grid_index(0, NY)
    other = cloth.ClothMesh.from_arrays(g.positions, g.uv, g.triangles)
    with pytest.raises(ValueError):
        other.grid_index(0, 0)


def test_obj_round_trip_of_a_mesh(tmp_path):
    g = grid_mesh(origin=(0.0, 0.0, 1.0))
    rng = np.random.default_rng(2)
    moved = g.positions + rng.normal(scale=0.01, size=g.positions.shape)
    path = tmp_path / "sheet.obj"
    g.save_obj(path, moved)
    back = cloth.ClothMesh.load(path)
    np.testing.assert_array_equal(back.positions, moved)
    np.testing.assert_array_equal(back.triangles, g.triangles)
    np.testing.assert_allclose(back.uv, g.uv, atol=1e-12)
    # str paths too, scale and position applied in that order.
    scaled = cloth.ClothMesh.load(str(path), scale=2.0, position=(1.0, 0.0, 0.0))
    np.testing.assert_allclose(scaled.positions, 2.0 * moved + [1.0, 0.0, 0.0], atol=1e-12)
    with pytest.raises((ValueError, TypeError)) as e:
        g.save_obj(tmp_path / "bad.obj", moved[:-1])
    assert "positions" in str(e.value), str(e.value)


def test_a_flat_obj_without_uv_is_its_own_rest_shape(tmp_path):
    n, h = 5, 0.1
    path = tmp_path / "flat.obj"
    path.write_text(flat_grid_obj(n, h))
    mesh = cloth.ClothMesh.load(path)
    assert mesh.vertex_count == n * n and mesh.triangle_count == 2 * (n - 1) ** 2
    assert mesh.rest_area == pytest.approx(((n - 1) * h) ** 2, rel=1e-9)
    # The warp (u) along x; the weft's sign is the plane's normal's.
    du = mesh.uv - mesh.uv[0]
    dxy = mesh.positions[:, :2] - mesh.positions[0, :2]
    np.testing.assert_allclose(du[:, 0], dxy[:, 0], atol=1e-12)
    np.testing.assert_allclose(np.abs(du[:, 1]), np.abs(dxy[:, 1]), atol=1e-12)


# ----------------------------------------------------------------------- simulation


def simulation(**kw):
    return cloth.Simulation(grid_mesh(origin=(0.0, 0.0, 1.0)), fabric(), **kw)


def test_simulation_state_is_n_by_3_float64_copies():
    sim = simulation()
    n = NX * NY
    for name in ("positions", "velocities"):
        a = getattr(sim, name)
        assert a.dtype == np.float64 and a.shape == (n, 3), name
    np.testing.assert_array_equal(sim.positions, sim.mesh.positions)
    np.testing.assert_array_equal(sim.velocities, np.zeros((n, 3)))
    p = sim.positions
    p[:] = 5.0
    v = sim.velocities
    v[:] = 5.0
    np.testing.assert_array_equal(sim.positions, sim.mesh.positions)
    np.testing.assert_array_equal(sim.velocities, np.zeros((n, 3)))
    m = sim.masses
    assert m.dtype == np.float64 and m.shape == (n,)
    assert m.sum() == pytest.approx(sim.fabrics[0].area_density * sim.mesh.rest_area, rel=1e-9)
    assert (m > 0).all()


def test_simulation_setters_round_trip_and_convert():
    sim = simulation()
    rng = np.random.default_rng(3)
    n = NX * NY
    p = sim.positions + rng.normal(scale=1e-3, size=(n, 3))
    sim.positions = p
    np.testing.assert_array_equal(sim.positions, p)
    v = rng.normal(size=(n, 3))
    sim.velocities = v
    np.testing.assert_array_equal(sim.velocities, v)
    # The array given is copied.
    p[:] = 0.0
    assert not (sim.positions == 0.0).all()
    # Lists and float32.
    sim.velocities = v.tolist()
    np.testing.assert_array_equal(sim.velocities, v)
    v32 = v.astype(np.float32)
    sim.velocities = v32
    np.testing.assert_array_equal(sim.velocities, v32.astype(np.float64))
    sim.positions = np.zeros((n, 3), dtype=np.int64)
    np.testing.assert_array_equal(sim.positions, np.zeros((n, 3)))


def test_initial_velocities_are_taken():
    n = NX * NY
    v = np.tile([0.1, -0.2, 0.3], (n, 1))
    sim = simulation(velocities=v)
    np.testing.assert_array_equal(sim.velocities, v)
    with pytest.raises((ValueError, TypeError)) as e:
        simulation(velocities=v[:-1])
    assert "velocities" in str(e.value), str(e.value)


@pytest.mark.parametrize("name", ["positions", "velocities"])
def test_simulation_setters_refuse_bad_arrays_and_keep_the_state(name):
    sim = simulation()
    sim.step()
    n = NX * NY
    before = getattr(sim, name)
    good = before + 0.5
    for bad, shape_named in [
        (good[:, :2], True),
        (good[:-1], True),
        (good.reshape(-1), True),
        (np.full((n, 3), "q"), False),
        (good.astype(np.complex128) * 1j, False),
    ]:
        with pytest.raises((ValueError, TypeError)) as e:
            setattr(sim, name, bad)
        msg = str(e.value)
        assert name in msg, msg
        if shape_named:
            assert SHAPE3.search(msg) or str(n) in msg, f"expected shape not named: {msg}"
        np.testing.assert_array_equal(getattr(sim, name), before)
    nan = good.copy()
    nan[2, 2] = np.nan
    with pytest.raises(ValueError) as e:
        setattr(sim, name, nan)
    assert name in str(e.value), str(e.value)
    np.testing.assert_array_equal(getattr(sim, name), before)


def test_pins_are_int64_and_accept_lists_and_other_integer_dtypes():
    mesh = grid_mesh(origin=(0.0, 0.0, 1.0))
    wanted = [mesh.grid_index(0, NY - 1), mesh.grid_index(NX - 1, NY - 1)]
    for pins in (wanted, np.array(wanted, dtype=np.int32), np.array(wanted, dtype=np.uint64), tuple(wanted)):
        sim = cloth.Simulation(mesh, fabric(), pins=pins)
        got = sim.pins
        assert got.dtype == np.int64 and got.ndim == 1
        assert sorted(got.tolist()) == sorted(wanted)
    sim = cloth.Simulation(mesh, fabric())
    assert sim.pins.dtype == np.int64 and sim.pins.shape == (0,)


def test_bad_pins_are_refused_naming_them():
    mesh = grid_mesh()
    n = mesh.vertex_count
    with pytest.raises(ValueError) as e:
        cloth.Simulation(mesh, fabric(), pins=[0, n + 5])
    assert str(n + 5) in str(e.value), str(e.value)
    with pytest.raises((ValueError, OverflowError, TypeError)):
        cloth.Simulation(mesh, fabric(), pins=[-1])
    with pytest.raises((ValueError, TypeError)) as e:
        cloth.Simulation(mesh, fabric(), pins=[[0, 1]])
    assert "pins" in str(e.value), str(e.value)
    with pytest.raises((ValueError, TypeError)):
        cloth.Simulation(mesh, fabric(), pins=[0.5])
    # pin_positions must give one point per pin.
    with pytest.raises((ValueError, TypeError)) as e:
        cloth.Simulation(mesh, fabric(), pins=[0, 1], pin_positions=np.zeros((3, 3)))
    assert "pin_positions" in str(e.value), str(e.value)
    with pytest.raises((ValueError, TypeError)) as e:
        cloth.Simulation(mesh, fabric(), pins=[0, 1], pin_positions=np.zeros((2, 2)))
    assert "pin_positions" in str(e.value), str(e.value)


def test_body_and_metric_functions_check_their_arrays():
    body = cloth.Body.sphere(0.3)
    d = body.signed_distance(np.zeros((4, 3)))
    assert d.dtype == np.float64 and d.shape == (4,)
    d1 = body.signed_distance([[0.0, 0.0, 1.0]])
    assert d1.shape == (1,)
    for bad in (np.zeros((4, 2)), np.zeros(3), np.full((2, 3), "x")):
        with pytest.raises((ValueError, TypeError)) as e:
            body.signed_distance(bad)
        assert "points" in str(e.value), str(e.value)
    assert body.vertices.dtype == np.float64 and body.vertices.shape[1] == 3
    assert body.triangles.dtype == np.int64 and body.triangles.shape[1] == 3
    mesh = grid_mesh()
    with pytest.raises((ValueError, TypeError)) as e:
        cloth.strain(mesh, mesh.positions[:-1])
    assert "positions" in str(e.value), str(e.value)
    with pytest.raises((ValueError, TypeError)) as e:
        cloth.grid_stretch(mesh, mesh.positions[:, :2])
    assert "positions" in str(e.value), str(e.value)


def test_strain_arrays():
    mesh = grid_mesh()
    s = cloth.strain(mesh, mesh.positions.tolist())
    for a in (s.warp, s.weft):
        assert a.dtype == np.float64 and a.shape == (mesh.triangle_count,)
    assert isinstance(s.max_warp, float) and isinstance(s.p99_weft, float)


def test_snapshot_arrays_are_copies_of_the_state_after_the_step():
    sim = simulation(pins=[0])
    seen = []

    def callback(snap):
        assert snap.positions.dtype == np.float64 and snap.positions.shape == (NX * NY, 3)
        assert snap.velocities.dtype == np.float64 and snap.velocities.shape == (NX * NY, 3)
        seen.append((snap.stats.step, snap.positions.copy(), snap.velocities.copy()))
        snap.positions[:] = 0.0  # a copy: the simulation is not changed

    sim.run_to_rest(max_steps=6, tolerance=1e-12, callback=callback, every=3)
    assert [s for s, _, _ in seen] == [3, 6]
    np.testing.assert_array_equal(seen[-1][1], sim.positions)
    np.testing.assert_array_equal(seen[-1][2], sim.velocities)

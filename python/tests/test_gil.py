"""The GIL is released while the engine steps: other Python threads make progress during
a long simulation, and two simulations in two threads run side by side.

No timing is measured. Python's forced thread switching is turned off for these tests
(`sys.setswitchinterval` set far beyond their length), so a thread holding the GIL keeps
it until it blocks or returns: then the only way another thread can run while a
simulation steps is that the extension released the GIL. The checks count what the other
thread did between two points the simulating thread marks itself.
"""

from __future__ import annotations

import sys
import threading
from contextlib import contextmanager

import numpy as np
import pytest

import cloth


@contextmanager
def no_forced_switching():
    old = sys.getswitchinterval()
    sys.setswitchinterval(1000.0)
    try:
        yield
    finally:
        sys.setswitchinterval(old)


def long_simulation(n=40, parallel=True):
    mesh = cloth.ClothMesh.grid(n, n, (1.0, 1.0), origin=(-0.5, -0.5, 0.45))
    return cloth.Simulation(
        mesh,
        cloth.Fabric.preset("cotton_poplin"),
        bodies=[cloth.Body.sphere(0.3)],
        settings={"parallel": parallel},
    )


def busy_work(k: int) -> int:
    """Some pure-Python work: its result checks it was done."""
    total = 0
    for i in range(200):
        total += (i * k) % 7
    return total


def progress_while(run) -> tuple[int, int, object]:
    """Runs `run()` in a worker thread while this thread does pure-Python work, yielding
    the GIL between pieces of it (a blocking wait). Returns the pieces done between the
    worker's two marks (just before and just after `run()`), the pieces done in all, and
    what `run()` returned."""
    counter = [0]
    marks = {}
    done = threading.Event()

    def worker():
        try:
            marks["before"] = counter[0]
            marks["result"] = run()
            marks["after"] = counter[0]
        except BaseException as e:  # noqa: BLE001 - re-raised in the main thread
            marks["error"] = e
        finally:
            done.set()

    with no_forced_switching():
        t = threading.Thread(target=worker)
        t.start()
        check = 0
        while not done.wait(0.0002):  # blocks, so the GIL is free for the worker
            check += busy_work(counter[0])
            counter[0] += 1
        t.join()
    if "error" in marks:
        raise marks["error"]
    assert check == sum(busy_work(k) for k in range(counter[0]))
    return marks["after"] - marks["before"], counter[0], marks["result"]


def test_other_threads_run_during_run_to_rest():
    sim = long_simulation()
    during, total, outcome = progress_while(lambda: sim.run_to_rest(tolerance=1e-12, max_steps=80))
    assert outcome.steps == 80 and sim.step_count == 80
    # Held for the whole run, the GIL would let the main thread do nothing between the
    # marks; released, it works all along.
    assert during >= 10, f"the main thread made {during} pieces of progress during the run ({total} in all)"


def test_other_threads_run_during_step():
    sim = long_simulation()
    during, total, stats = progress_while(lambda: sim.step(60))
    assert stats.step == 60
    assert during >= 10, f"the main thread made {during} pieces of progress during step(60) ({total} in all)"


def test_other_threads_run_during_a_scene_run(sheet_scene, tmp_path):
    text = sheet_scene.replace("nx = 12", "nx = 40").replace("ny = 12", "ny = 40")
    text = text.replace("tolerance = 1e-5", "tolerance = 1e-12")
    text += "[output]\npng = false\nglb = false\n"
    scene = cloth.Scene.from_toml(text)
    during, total, result = progress_while(lambda: scene.run(tmp_path / "out"))
    assert result.finished and result.report["stages"][0]["steps"] == 60
    assert during >= 10, f"the main thread made {during} pieces of progress during Scene.run ({total} in all)"


def test_two_simulations_in_two_threads_step_side_by_side():
    sims = {"a": long_simulation(24, parallel=False), "b": long_simulation(24, parallel=False)}
    log = []
    lock = threading.Lock()
    errors = []
    steps = 40
    # Both runs start together, so their overlap does not hang on when each thread is
    # scheduled.
    start = threading.Barrier(len(sims))

    def worker(name):
        def callback(snap):
            with lock:
                log.append((name, snap.stats.step, threading.get_ident()))

        try:
            start.wait(timeout=60)
            out = sims[name].run_to_rest(tolerance=1e-12, max_steps=steps, callback=callback)
            assert out.steps == steps
        except BaseException as e:  # noqa: BLE001
            errors.append(e)

    with no_forced_switching():
        threads = [threading.Thread(target=worker, args=(n,)) for n in sims]
        for t in threads:
            t.start()
        for t in threads:
            t.join()
    assert not errors, errors
    for name, t in zip(sims, threads):
        mine = [(s, ident) for n, s, ident in log if n == name]
        # Every step seen, in order, each on the thread that ran it.
        assert [s for s, _ in mine] == list(range(1, steps + 1))
        assert {ident for _, ident in mine} == {t.ident}
    # Holding the GIL, the first run would finish before the second started: one switch
    # from a to b in the log. Releasing it, their steps interleave.
    switches = sum(1 for x, y in zip(log, log[1:]) if x[0] != y[0])
    assert switches >= 2, f"{switches} switches between the two runs: {[n for n, _, _ in log]}"
    # Two identical simulations, run concurrently, end in the same state.
    np.testing.assert_array_equal(sims["a"].positions, sims["b"].positions)


def test_callbacks_from_a_thread_see_snapshots():
    sim = long_simulation(10)
    seen = []
    main = threading.get_ident()

    def callback(snap):
        assert threading.get_ident() != main
        seen.append((snap.stage, snap.stats.step, snap.positions.shape, snap.velocities.dtype))

    t = threading.Thread(target=lambda: sim.run_to_rest(tolerance=1e-12, max_steps=12, callback=callback, every=4))
    t.start()
    t.join()
    assert seen == [("running", k, (100, 3), np.dtype(np.float64)) for k in (4, 8, 12)]
    assert sim.step_count == 12


def test_a_simulation_used_from_two_threads_at_once_is_refused_or_serialised():
    """The same Simulation stepped from two threads: each call either runs whole (one
    after the other) or is refused with an exception, and never corrupts the state."""
    sim = long_simulation(20, parallel=False)
    errors = []

    def worker():
        try:
            sim.step(15)
        except RuntimeError as e:  # e.g. "already borrowed"
            errors.append(e)

    threads = [threading.Thread(target=worker, daemon=True) for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=120)  # a guard against a deadlock, not a measurement
    assert not any(t.is_alive() for t in threads), "deadlock: a thread never returned"
    assert sim.step_count == 15 * (2 - len(errors))
    assert np.isfinite(sim.positions).all()

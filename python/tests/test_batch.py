"""cloth.batch: many scenes, or a sweep, on an executor; failures recorded, done runs
skipped on a second batch. The scenes are tiny (a 12 x 12 sheet, 60 steps) so that the
whole file runs in seconds, a real two-process Dask cluster included."""

from __future__ import annotations

import json
import logging
import os
import pickle
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

import pytest

import cloth
from cloth import batch
from conftest import COTTON_LIKE_SI
from cloth.batch import BatchResult, Job, RunRecord, run_batch, sweep

REPO = Path(__file__).resolve().parents[2]
PATTERNS = REPO / "assets" / "patterns"

SHEET_TOML = """\
name = "small sheet on a sphere"

[cloth.grid]
nx = 12
ny = 12
size = [0.6, 0.6]
origin = [-0.3, -0.3, 0.25]

[fabric]
preset = "cotton_poplin"

[[bodies]]
sphere = { radius = 0.2 }

[rest]
tolerance = 1e-4
consecutive_steps = 5
max_steps = 60

[output]
png = true
image_size = [64, 48]
"""

# The suites' cotton-like fabric, damped so the sheet settles within the tiny step limit.
SI_FABRIC = {**COTTON_LIKE_SI, "damping": 0.002}

OUTPUTS = ["cloth.obj", "cloth.ply", "bodies.obj", "scene.glb", "render.png", "report.json", "report.md"]

# A pin at thread crossing [20, 0] of a 12 x 12 grid: refused before anything runs.
BROKEN = {"cloth": {"grid": {"pins": [[20, 0]]}}}
# Explicit Euler far beyond its stability limit (stiff membrane, light particles).
DIVERGING = {"solver": {"integrator": "explicit_euler", "time_step": 0.02}}


@pytest.fixture
def sheet_file(tmp_path: Path) -> Path:
    path = tmp_path / "scenes" / "sheet.toml"
    path.parent.mkdir()
    path.write_text(SHEET_TOML)
    return path


def read_json(path: Path) -> Any:
    return json.loads(path.read_text())


def mtimes(folder: Path, names: list[str]) -> dict[str, int]:
    return {n: (folder / n).stat().st_mtime_ns for n in names}


def assert_done(record: RunRecord, job: Job) -> None:
    folder = Path(record.folder)
    assert record.status == "done", record
    assert record.error is None and record.error_type is None
    assert record.summary["particles"] == 144
    assert record.summary["max_warp"] is not None and record.summary["deepest_penetration"] is not None
    for name in OUTPUTS:
        assert (folder / name).is_file(), f"{name} missing from {folder}"
    assert read_json(folder / "report.json")["outcome"]["kind"] == "finished"
    done = read_json(folder / "done.json")
    assert done["key"] == job.key() and done["status"] == "done"
    assert not (folder / "failed.json").exists()


# --- the issue's test: a real Dask cluster of two worker processes -----------------------


def test_dask_cluster_records_the_broken_scene_finishes_the_others_and_skips_them_next_time(
    sheet_file: Path, tmp_path: Path
) -> None:
    from distributed import Client, LocalCluster

    jobs = [
        Job.from_file(sheet_file, name="poplin"),
        Job.from_file(sheet_file, name="denim", overrides={"fabric": {"preset": "denim"}}),
        Job.from_file(sheet_file, name="broken", overrides=BROKEN),
        Job.from_file(sheet_file, name="big_sphere", overrides={"bodies": [{"sphere": {"radius": 0.25}}]}),
    ]
    out = tmp_path / "out"
    with (
        LocalCluster(
            n_workers=2,
            threads_per_worker=1,
            processes=True,
            dashboard_address=None,
            silence_logs=logging.ERROR,
            local_directory=str(tmp_path / "dask"),
        ) as cluster,
        Client(cluster) as client,
    ):
        client.wait_for_workers(2, timeout=60)
        assert len(client.scheduler_info()["workers"]) == 2
        executor = client.get_executor()
        seen: list[RunRecord] = []
        first = run_batch(jobs, out, executor=executor, on_result=seen.append)

        assert [r.name for r in first] == [j.name for j in jobs]  # job order, not finish order
        assert sorted(r.name for r in seen) == sorted(j.name for j in jobs)
        assert {r.name for r in first.done} == {"poplin", "denim", "big_sphere"}
        assert not first.skipped and not first.ok
        for job in jobs:
            if job.name != "broken":
                assert_done(first.record(job.name), job)
                # Ran in a worker process, not here.
                assert read_json(out / job.name / "done.json")["pid"] != os.getpid()
        # Different fabrics and bodies, different drapes.
        assert first.record("poplin").summary != first.record("denim").summary

        broken = first.record("broken")
        assert broken.status == "failed" and broken.error_type == "ValueError"
        assert broken.error is not None
        assert "cloth.grid.pins[0]" in broken.error and "outside the 12 x 12 grid" in broken.error
        assert not (out / "broken" / "done.json").exists()
        failed = read_json(out / "broken" / "failed.json")
        assert failed["error"] == broken.error and failed["key"] == jobs[2].key()

        listing = read_json(out / "batch.json")
        assert [(r["name"], r["status"]) for r in listing["runs"]] == [
            ("poplin", "done"),
            ("denim", "done"),
            ("broken", "failed"),
            ("big_sphere", "done"),
        ]
        assert listing["counts"] == {"done": 3, "skipped": 0, "failed": 1, "pending": 0}

        kept = ["done.json", "report.json", "cloth.obj"]
        before = {j.name: mtimes(out / j.name, kept) for j in jobs if j.name != "broken"}
        failed_before = (out / "broken" / "failed.json").stat().st_mtime_ns
        seen.clear()
        second = run_batch(jobs, out, executor=executor, on_result=seen.append)

    assert [r.name for r in seen] == ["broken"]  # the only run that ran again
    assert {r.name for r in second.skipped} == {"poplin", "denim", "big_sphere"}
    for name, times in before.items():
        assert mtimes(out / name, kept) == times, f"{name} was run again"
        assert second.record(name).summary == first.record(name).summary
    again = second.record("broken")
    assert again.status == "failed" and again.error == broken.error
    assert (out / "broken" / "failed.json").stat().st_mtime_ns != failed_before
    statuses = [r["status"] for r in read_json(out / "batch.json")["runs"]]
    assert statuses == ["skipped", "skipped", "failed", "skipped"]


# --- failures ---------------------------------------------------------------------------


def test_a_diverging_run_is_recorded_as_a_simulation_error_and_its_sibling_finishes(
    sheet_file: Path, tmp_path: Path
) -> None:
    jobs = [
        Job.from_file(sheet_file, name="diverges", overrides=DIVERGING),
        Job.from_file(sheet_file, name="fine"),
    ]
    with ThreadPoolExecutor(max_workers=2) as pool:
        result = run_batch(jobs, tmp_path / "out", executor=pool)

    assert_done(result.record("fine"), jobs[1])
    record = result.record("diverges")
    assert record.status == "failed" and record.error_type == "SimulationError", record
    assert record.error
    folder = Path(record.folder)
    # The last good state and its report were written, but the run is not done.
    report = read_json(folder / "report.json")
    assert report["outcome"]["kind"] == "failed"
    assert record.summary["particles"] == 144
    assert not (folder / "done.json").exists()
    assert read_json(folder / "failed.json")["error_type"] == "SimulationError"
    assert "1 failed" in result.summary() and "diverges: SimulationError" in result.summary()


def test_a_lost_task_is_a_failed_run_and_the_batch_goes_on(
    sheet_file: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    real = batch._run_job

    def flaky(job: Job, folder: str, *rest: str) -> RunRecord:
        if job.name == "lost":
            raise OSError("worker lost")
        return real(job, folder, *rest)

    monkeypatch.setattr(batch, "_run_job", flaky)
    jobs = [Job.from_file(sheet_file, name="lost"), Job.from_file(sheet_file, name="kept")]
    for executor in (None, ThreadPoolExecutor(max_workers=2)):
        out = tmp_path / ("sequential" if executor is None else "threads")
        result = run_batch(jobs, out, executor=executor)
        if executor is not None:
            executor.shutdown()
        lost = result.record("lost")
        assert (lost.status, lost.error_type, lost.error) == ("failed", "OSError", "worker lost")
        assert read_json(out / "lost" / "failed.json")["error"] == "worker lost"
        assert result.record("kept").status == "done"


# --- sequential runs, on_result, rerun_failed, changed jobs -------------------------------


def test_sequential_batch_reports_each_run_and_reruns_only_what_it_should(
    sheet_file: Path, tmp_path: Path
) -> None:
    jobs = [Job.from_file(sheet_file, name="good"), Job.from_file(sheet_file, name="bad", overrides=BROKEN)]
    out = tmp_path / "out"
    seen: list[RunRecord] = []
    first = run_batch(jobs, out, on_result=seen.append)
    assert [(r.name, r.status) for r in seen] == [("good", "done"), ("bad", "failed")]
    assert [(r.name, r.status) for r in first] == [("good", "done"), ("bad", "failed")]
    assert len(first) == 2 and first.done == [seen[0]] and first.failed == [seen[1]]
    assert_done(first.record("good"), jobs[0])

    # rerun_failed=False: the failure is taken from its record, nothing runs.
    seen.clear()
    second = run_batch(jobs, out, rerun_failed=False, on_result=seen.append)
    assert seen == []
    assert [(r.name, r.status) for r in second] == [("good", "skipped"), ("bad", "failed")]
    assert second.record("bad").error == first.record("bad").error
    assert second.record("bad").error_type == "ValueError"

    # The default: the failed one runs again, the done one not.
    seen.clear()
    run_batch(jobs, out, on_result=seen.append)
    assert [r.name for r in seen] == ["bad"]


def test_a_changed_job_under_the_same_name_runs_again(sheet_file: Path, tmp_path: Path) -> None:
    out = tmp_path / "out"
    first = run_batch([Job.from_file(sheet_file, name="sheet")], out)
    assert first.record("sheet").status == "done"
    (out / "sheet" / "notes.txt").write_text("from the old run")

    changed = Job.from_file(
        sheet_file,
        name="sheet",
        overrides={"fabric": {"preset": None, "si": SI_FABRIC}, "output": {"png": False}},
    )
    second = run_batch([changed], out)
    record = second.record("sheet")
    assert record.status == "done", record
    assert read_json(out / "sheet" / "done.json")["key"] == changed.key()
    # The folder holds this run's outputs only: no render.png of the old one.
    assert not (out / "sheet" / "render.png").exists()
    assert not (out / "sheet" / "notes.txt").exists()
    assert record.summary != first.record("sheet").summary

    # A done.json that is cut short is not a run done.
    (out / "sheet" / "done.json").write_text('{"key": ')
    assert run_batch([changed], out).record("sheet").status == "done"
    assert run_batch([changed], out).record("sheet").status == "skipped"


def test_duplicate_names_are_refused_before_anything_runs(sheet_file: Path, tmp_path: Path) -> None:
    out = tmp_path / "out"
    jobs = [
        Job.from_file(sheet_file, name="same"),
        Job.from_file(sheet_file, name="same", overrides=DIVERGING),
    ]
    with pytest.raises(ValueError, match="two jobs are named 'same'"):
        run_batch(jobs, out)
    with pytest.raises(ValueError, match="'Same'"):
        run_batch([Job.from_file(sheet_file, name="same"), Job.from_file(sheet_file, name="Same")], out)
    assert not out.exists()


# --- jobs -------------------------------------------------------------------------------


def test_job_names_must_be_single_folder_names(tmp_path: Path) -> None:
    for bad in ["", ".", "..", "a/b", "a\\b", "../up", " padded", "batch.json", "C:", "D:x"]:
        with pytest.raises(ValueError, match="job name"):
            Job(bad, {}, str(tmp_path))
    name = "cotton_poplin__skirt__height1.60"
    assert Job(name, {}, str(tmp_path)).name == name


def test_job_from_file_merges_overrides_and_keys_what_it_runs(sheet_file: Path) -> None:
    job = Job.from_file(
        sheet_file, overrides={"rest": {"max_steps": 10}, "fabric": {"preset": None, "si": SI_FABRIC}}
    )
    assert job.name == "sheet"
    assert job.base_dir == str(sheet_file.parent.resolve())
    assert job.scene["rest"] == {"tolerance": 1e-4, "consecutive_steps": 5, "max_steps": 10}
    assert job.scene["fabric"] == {"si": SI_FABRIC}
    assert job.scene["cloth"]["grid"]["nx"] == 12

    plain = Job.from_file(sheet_file)
    assert plain.key() == Job.from_file(sheet_file, name="other").key()  # the name is not what runs
    assert plain.key() != job.key()
    reordered = Job("sheet", dict(reversed(list(plain.scene.items()))), plain.base_dir)
    assert reordered.key() == plain.key()
    assert Job("sheet", plain.scene, "/elsewhere").key() != plain.key()

    # The job keeps its own copy of the scene.
    scene = plain.scene
    held = Job("x", scene, plain.base_dir)
    scene["rest"]["max_steps"] = 1
    assert held.scene["rest"]["max_steps"] == 60

    # Jobs and records travel to worker processes.
    assert pickle.loads(pickle.dumps(job)) == job
    record = RunRecord(name="x", status="done", folder="/f", seconds=1.0, summary={"particles": 4})
    assert pickle.loads(pickle.dumps(record)) == record

    with pytest.raises(ValueError, match="bad.toml"):
        bad = sheet_file.with_name("bad.toml")
        bad.write_text("[cloth\n")
        Job.from_file(bad)


# --- sweeps -----------------------------------------------------------------------------


def garment_scene(tmp_path: Path, bodies: str) -> Path:
    path = tmp_path / "garment.toml"
    path.write_text(
        f"""\
name = "skirt"

[cloth.garment]
pattern = "{(PATTERNS / 'skirt.toml').as_posix()}"
edge_length = 0.04

[fabric]
preset = "cotton_poplin"

{bodies}

[drape]
max_steps = 50
"""
    )
    return path


MANNEQUIN_AND_STOOL = """\
[[bodies]]
box = { size = [0.3, 0.3, 0.4] }
position = [0.0, 0.0, 0.2]

[[bodies]]
mannequin = { height = 1.7 }
friction = 0.4
"""


def test_sweep_is_the_product_of_its_axes_with_readable_unique_names(tmp_path: Path) -> None:
    base = garment_scene(tmp_path, MANNEQUIN_AND_STOOL)
    jobs = sweep(
        base,
        fabrics=["cotton_poplin", {"preset": "denim"}, {"si": SI_FABRIC}],
        garments=[PATTERNS / "skirt.toml", str(PATTERNS / "dress.toml")],
        bodies=[{"height": 1.6}, {"height": 1.8, "hip": 1.05}],
    )
    assert len(jobs) == 3 * 2 * 2
    names = [j.name for j in jobs]
    assert len(set(names)) == len(names)
    assert names[:4] == [
        "cotton_poplin__skirt__height1.60",
        "cotton_poplin__skirt__height1.80_hip1.05",
        "cotton_poplin__dress__height1.60",
        "cotton_poplin__dress__height1.80_hip1.05",
    ]
    assert names[-1] == "si__dress__height1.80_hip1.05"
    assert len({j.key() for j in jobs}) == len(jobs)

    by_name = {j.name: j for j in jobs}
    job = by_name["denim__dress__height1.80_hip1.05"]
    assert job.scene["fabric"] == {"preset": "denim"}
    assert job.scene["cloth"]["garment"] == {"pattern": str(PATTERNS / "dress.toml"), "edge_length": 0.04}
    assert job.scene["bodies"] == [
        {"box": {"size": [0.3, 0.3, 0.4]}, "position": [0.0, 0.0, 0.2]},
        {"mannequin": {"height": 1.8, "hip": 1.05}, "friction": 0.4},
    ]
    assert job.scene["drape"] == {"max_steps": 50}
    assert job.base_dir == str(tmp_path.resolve())
    assert by_name["si__skirt__height1.60"].scene["fabric"] == {"si": SI_FABRIC}
    # The jobs do not share tables: changing one leaves the others.
    job.scene["bodies"][1]["mannequin"]["height"] = 2.0
    assert by_name["denim__dress__height1.60"].scene["bodies"][1]["mannequin"] == {"height": 1.6}

    # The engine takes what the sweep wrote (built, not run).
    cloth.Scene.from_dict(by_name["si__skirt__height1.60"].scene, base_dir=job.base_dir).check()


def test_sweep_single_values_names_and_a_changed_fabric_is_a_new_job(tmp_path: Path) -> None:
    base = garment_scene(tmp_path, MANNEQUIN_AND_STOOL)
    # One edge length for all is no axis; a list is one; repeated labels are numbered.
    jobs = sweep(base, fabrics=[{"si": SI_FABRIC}, {"si": {**SI_FABRIC, "damping": 0.01}}], edge_length=0.05)
    assert [j.name for j in jobs] == ["si", "si_2"]
    assert all(j.scene["cloth"]["garment"]["edge_length"] == 0.05 for j in jobs)
    jobs = sweep(Job.from_file(base, name="skirt"), edge_length=[0.03, 0.05])
    assert [j.name for j in jobs] == ["e0.03", "e0.05"]
    assert sweep(base) == [Job.from_file(base)]

    # Same name, another fabric: another key, so a batch runs it again.
    poplin = sweep(base, fabrics=["cotton_poplin"])[0]
    denim = Job(poplin.name, {**poplin.scene, "fabric": {"preset": "denim"}}, poplin.base_dir)
    assert poplin.key() != denim.key()
    done = tmp_path / "out" / poplin.name
    done.mkdir(parents=True)
    record = {"key": poplin.key(), "status": "done", "summary": {"particles": 1}}
    (done / "done.json").write_text(json.dumps(record))
    assert batch._previous(poplin, done, True) is not None
    assert batch._previous(denim, done, True) is None


def test_sweep_refuses_axes_the_scene_cannot_take(sheet_file: Path, tmp_path: Path) -> None:
    no_mannequin = garment_scene(tmp_path, '[[bodies]]\nsphere = { radius = 0.2 }\n')
    with pytest.raises(ValueError, match="no \\[\\[bodies\\]\\] entry with a mannequin"):
        sweep(no_mannequin, bodies=[{"height": 1.6}])
    with pytest.raises(ValueError, match="not a garment"):
        sweep(sheet_file, garments=[PATTERNS / "skirt.toml"])
    with pytest.raises(ValueError, match="not a garment"):
        sweep(sheet_file, edge_length=0.02)
    with pytest.raises(FileNotFoundError, match="nowhere.toml"):
        sweep(no_mannequin, garments=[tmp_path / "nowhere.toml"])
    with pytest.raises(TypeError, match="fabrics must be a list"):
        sweep(sheet_file, fabrics="denim")
    with pytest.raises(ValueError, match="empty"):
        sweep(sheet_file, fabrics=[])
    # Fabrics alone suit any scene.
    assert [j.name for j in sweep(sheet_file, fabrics=["silk", "denim"])] == ["silk", "denim"]


def test_batch_result_helpers(tmp_path: Path) -> None:
    records = [
        RunRecord(name="a", status="done", folder="/o/a", seconds=2.0, summary={"particles": 4}),
        RunRecord(name="b", status="failed", folder="/o/b", error="boom", error_type="SimulationError"),
        RunRecord(name="c", status="skipped", folder="/o/c"),
    ]
    result = BatchResult(records=records, out_dir="/o")
    assert list(result) == records and len(result) == 3
    assert (result.done, result.failed, result.skipped) == ([records[0]], [records[1]], [records[2]])
    assert not result.ok
    assert result.record("b").error == "boom"
    with pytest.raises(KeyError):
        result.record("zzz")
    data = json.loads(result.to_json())
    assert data["counts"] == {"done": 1, "skipped": 1, "failed": 1, "pending": 0}
    assert data["runs"][1]["error_type"] == "SimulationError"
    assert result.summary().splitlines() == [
        "3 runs: 1 done, 1 skipped (done before), 1 failed",
        "  b: SimulationError: boom",
    ]


def test_a_folder_that_is_not_a_runs_is_left_alone(sheet_file: Path, tmp_path: Path) -> None:
    out = tmp_path / "out"
    mine = out / "sheet"
    mine.mkdir(parents=True)
    (mine / "thesis.tex").write_text("years of work")
    result = run_batch([Job.from_file(sheet_file, name="sheet")], out)
    record = result.record("sheet")
    assert record.status == "failed" and record.error_type == "FileExistsError", record
    assert "not a batch run" in (record.error or "")
    assert sorted(p.name for p in mine.iterdir()) == ["thesis.tex"]
    assert (mine / "thesis.tex").read_text() == "years of work"


GARMENTCODE = REPO / "assets" / "garmentcode"


def test_drape_writes_the_commands_summary_and_skips_finished_patterns(tmp_path: Path) -> None:
    """cloth.batch.drape: GarmentCode's waistband on its y-up body through run_batch (here
    on a thread pool), and a pattern refused; summary.json as `cloth drape` writes it."""
    broken = tmp_path / "broken.json"
    broken.write_text('{"pattern": {"panels": ')
    band = GARMENTCODE / "patterns" / "rand_1_001.json"
    body = GARMENTCODE / "bodies" / "mean_all.obj"
    out = tmp_path / "out"
    with ThreadPoolExecutor(2) as pool:
        result = batch.drape(
            [band, broken], body, out, body_up_axis="y", edge_length=0.03, executor=pool
        )
    assert not result.ok
    names = [e["name"] for e in result.entries]
    assert names == ["rand_1_001", "broken"]
    done, refused = result.entries
    assert done["outcome"] == "finished" and not done["skipped"]
    assert done["particles"] > 50 and done["sewing_steps"] > 0 and done["draping_steps"] > 0
    assert refused["outcome"] == "failed" and "broken.json" in refused["failure"]
    on_disk = json.loads((out / "summary.json").read_text())
    assert on_disk == result.entries
    assert "1 of 2 patterns finished" in (out / "summary.md").read_text()
    # The scene each run drapes is the command's: the body turned y-up to z-up.
    scene = (out / "rand_1_001" / "report.json").read_text()
    assert json.loads(scene)["outcome"]["kind"] == "finished"

    again = batch.drape([band], body, out, body_up_axis="y", edge_length=0.03)
    assert again.ok and again.entries[0]["skipped"]
    assert again.batch.records[0].status == "skipped"

    with pytest.raises(ValueError, match="tweed"):
        batch.drape([band], body, out, fabric="tweed")
    with pytest.raises(ValueError, match="min_thickness"):
        batch.drape([band], body, out, min_thickness=0.004)
    empty = tmp_path / "empty"
    empty.mkdir()
    with pytest.raises(ValueError, match="holds no pattern"):
        batch.drape([empty], body, out)


def test_a_y_up_body_loads_turned_and_an_imperfect_one_with_warnings(tmp_path: Path) -> None:
    body = cloth.Body.load(GARMENTCODE / "bodies" / "mean_all.obj", up_axis="y")
    assert body.defects == []
    v = body.vertices
    # Feet on the floor, the head 1.72 m up, facing -y (the nose is the most forward point).
    assert abs(v[:, 2].min()) < 0.02 and abs(v[:, 2].max() - 1.72) < 0.01
    head = v[v[:, 2] > 1.5]
    assert head[:, 1].min() < -0.1 and head[:, 1].max() < 0.1
    # The same turned by hand with rotation, from z-up: the same vertices.
    turned = cloth.Body.load(GARMENTCODE / "bodies" / "mean_all.obj", rotation=(90, 0, 0))
    assert abs(turned.vertices - v).max() < 1e-12
    # An open cube: it loads, with a warning naming the holes.
    open_cube = tmp_path / "open.obj"
    open_cube.write_text(
        "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
        "f 1 4 3\nf 1 3 2\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n"
    )
    with pytest.warns(UserWarning, match="holes"):
        cube = cloth.Body.load(open_cube)
    assert any("holes" in d for d in cube.defects)
    assert cube.signed_distance([[0, 0, 0], [0, 0, 3]]).tolist()[0] < 0

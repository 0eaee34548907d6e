"""Batches beyond one machine: jobs that carry the files their scenes name run on Dask
workers in folders of their own, with none of the client's paths, and their outputs come
back to the client."""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

import pytest
import trimesh

import cloth.batch as cb

REPO = Path(__file__).resolve().parents[2]

SHEET_ON_FILE_BODY = """\
name = "sheet on a ball"
[cloth.grid]
nx = 10
ny = 10
size = [0.5, 0.5]
origin = [-0.25, -0.25, 0.3]
[fabric]
preset = "cotton_poplin"
[[bodies]]
file = "meshes/ball.obj"
[rest]
tolerance = 1e-5
consecutive_steps = 10
max_steps = 30
"""

TUBE = """\
[cloth.garment]
pattern = "tube.toml"
edge_length = 0.02
pins = [{ panel = "front", edge = "top" }]
[fabric]
preset = "silk"
[rest]
tolerance = 1e-4
consecutive_steps = 10
max_steps = 30
"""


def client_jobs(folder: Path) -> list[cb.Job]:
    """Two jobs whose scenes name files in `folder`: a body mesh and a pattern."""
    (folder / "meshes").mkdir(parents=True)
    trimesh.creation.icosphere(subdivisions=2, radius=0.2).export(folder / "meshes" / "ball.obj")
    shutil.copy(REPO / "assets" / "patterns" / "tube.toml", folder / "tube.toml")
    (folder / "sheet.toml").write_text(SHEET_ON_FILE_BODY)
    return [
        cb.Job.from_file(folder / "sheet.toml", name="sheet"),
        cb.Job(name="tube", scene=cb.tomllib.loads(TUBE), base_dir=str(folder)),
    ]


def test_bundled_jobs_carry_their_files_and_are_keyed_by_them(tmp_path: Path) -> None:
    here, there = client_jobs(tmp_path / "a"), client_jobs(tmp_path / "b")
    bundled = [job.bundled() for job in here]
    sheet, tube = bundled
    assert sheet.scene["bodies"][0]["file"] in sheet.files
    assert tube.scene["cloth"]["garment"]["pattern"] in tube.files
    assert tube.files[tube.scene["cloth"]["garment"]["pattern"]] == (REPO / "assets/patterns/tube.toml").read_bytes()
    # Paths differ, contents do not: the same job wherever it was made.
    assert [j.key() for j in bundled] == [j.bundled().key() for j in there]
    assert [j.key() for j in here] != [j.key() for j in there]
    (tmp_path / "a" / "tube.toml").unlink()
    with pytest.raises(FileNotFoundError, match="cloth.garment.pattern"):
        here[1].bundled()


def test_workers_without_the_clients_files_run_the_jobs_and_send_the_outputs_back(tmp_path: Path) -> None:
    distributed = pytest.importorskip("distributed")
    jobs = [job.bundled() for job in client_jobs(tmp_path / "client")]
    # Nothing the scenes name is left where the client had it.
    shutil.rmtree(tmp_path / "client")
    out = tmp_path / "out"
    with distributed.LocalCluster(
        n_workers=2,
        threads_per_worker=1,
        processes=True,
        local_directory=str(tmp_path / "workers"),
        dashboard_address=None,
    ) as cluster, distributed.Client(cluster) as client:
        result = cb.run_batch(jobs, out, executor=client.get_executor())
        worker_pids = set(client.run(os.getpid).values())
    assert result.ok, result.summary()
    assert [r.status for r in result] == ["done", "done"]
    for job in jobs:
        folder = out / job.name
        report = json.loads((folder / "report.json").read_text())
        assert report["outcome"]["kind"] == "finished"
        assert (folder / "cloth.obj").is_file() and (folder / "history.csv").is_file()
        marker = json.loads((folder / "done.json").read_text())
        # Run by a worker, in a folder of its own, and put here by the client.
        assert marker["pid"] in worker_pids and marker["pid"] != os.getpid()
        assert marker["folder"] == str(folder)
        assert all(Path(o).is_file() and Path(o).parent.is_relative_to(folder) for o in marker["outputs"])
    assert json.loads((out / "tube" / "report.json").read_text())["pinned_particles"] == 6
    # Run again here, with no cluster: done already, by what the jobs carry.
    again = cb.run_batch(jobs, out)
    assert [r.status for r in again] == ["skipped", "skipped"]


def test_the_command_drapes_on_a_dask_cluster(tmp_path: Path) -> None:
    distributed = pytest.importorskip("distributed")
    import subprocess
    import sys

    cloth_bin = os.environ.get("CLOTH_BIN")
    if not cloth_bin:
        pytest.skip("CLOTH_BIN (the cloth command, as scripts/test.sh sets it) not given")
    trimesh.creation.icosphere(subdivisions=3, radius=0.2).export(tmp_path / "ball.obj")
    env = {**os.environ, "CLOTH_PYTHON": sys.executable}
    command = [cloth_bin, "drape", str(REPO / "assets/patterns/tube.toml"), "--body", "ball.obj", "--out", "out"]
    with distributed.LocalCluster(
        n_workers=1, threads_per_worker=1, processes=True, dashboard_address=None
    ) as cluster:
        done = subprocess.run(
            [*command, "--up-axis", "y", "--dask", cluster.scheduler_address],
            cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600,
        )
        refused = subprocess.run(
            [*command, "--jobs", "2", "--dask", cluster.scheduler_address],
            cwd=tmp_path, env=env, capture_output=True, text=True, timeout=600,
        )
    assert done.returncode == 0, done.stderr
    assert "1 of 1 patterns finished" in done.stdout
    summary = json.loads((tmp_path / "out" / "summary.json").read_text())
    assert [e["name"] for e in summary] == ["tube"] and summary[0]["outcome"] == "finished"
    assert "# y up" in (tmp_path / "out" / "tube" / "cloth.obj").read_text()[:400]
    assert refused.returncode == 2 and "--jobs is not available with --dask" in refused.stderr


def test_a_job_can_carry_files_named_by_fsspec_urls(tmp_path: Path) -> None:
    fsspec = pytest.importorskip("fsspec")
    pattern = (REPO / "assets" / "patterns" / "tube.toml").read_bytes()
    with fsspec.open("memory://patterns/tube.toml", "wb") as f:
        f.write(pattern)
    scene = cb.tomllib.loads(TUBE)
    scene["cloth"]["garment"]["pattern"] = "memory://patterns/tube.toml"
    job = cb.Job(name="tube", scene=scene).bundled()
    assert list(job.files.values()) == [pattern]
    assert job.scene["cloth"]["garment"]["pattern"] == "inputs/0_tube.toml"
    record = cb.run_batch([job], tmp_path / "out").records[0]
    assert record.status == "done", record.error
    scene["cloth"]["garment"]["pattern"] = "memory://patterns/missing.toml"
    with pytest.raises(FileNotFoundError, match="missing.toml"):
        cb.Job(name="tube", scene=scene).bundled()

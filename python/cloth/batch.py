"""Many runs at once: a list of scenes, or a sweep of fabrics x garments x body
measurements, on any :class:`concurrent.futures.Executor`, a Dask cluster's included.

Each run writes the outputs of ``cloth run`` (``cloth.obj``, ``report.json``, ...) into
its own folder ``OUT_DIR/<job name>`` as it finishes, then a marker: ``done.json``, or
``failed.json`` with the error when the input was bad or the run diverged; the other runs
carry on either way. ``OUT_DIR/batch.json`` lists every run and is rewritten as each one
finishes, so a batch that is killed half way still says what it did. Running the same
batch again skips the runs already done (those whose ``done.json`` names the same job)::

    from concurrent.futures import ProcessPoolExecutor
    import cloth.batch as cb

    jobs = cb.sweep("assets/scenes/skirt.toml",
                    fabrics=["cotton_poplin", "denim", "silk"],
                    edge_length=0.02)
    with ProcessPoolExecutor(2) as pool:
        result = cb.run_batch(jobs, "target/skirts", executor=pool)
    print(result.summary())

On a Dask cluster, pass the client's executor::

    from dask.distributed import Client
    with Client("tcp://scheduler:8786") as client:
        cb.run_batch(jobs, "/shared/skirts", executor=client.get_executor())

The workers then need the ``cloth`` package. Jobs carry paths by default, so the output
folder and every file the scenes name must then be at the same paths on every machine (a
shared file system). ``run_batch(..., portable=True)`` (or :meth:`Job.bundled`) makes
each job carry the files its scene names instead, as bytes (read from local paths or
fsspec URLs): a worker runs it in a temporary folder of its own, and the outputs come
back to the client, which writes them into ``OUT_DIR``. No shared file system is needed.
"""

from __future__ import annotations

import concurrent.futures
import contextlib
import copy
import dataclasses
import hashlib
import itertools
import json
import os
import re
import shutil
import socket
import tempfile
import time
import tomllib
import uuid
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from pathlib import Path
from typing import Any, Literal

from ._cloth import Scene, SimulationError, _drape_scenes, _write_drape_summary

__all__ = [
    "BATCH_FILE",
    "DrapeResult",
    "DONE_FILE",
    "FAILED_FILE",
    "BatchResult",
    "Job",
    "RunRecord",
    "Status",
    "drape",
    "run_batch",
    "sweep",
]

Status = Literal["done", "failed", "skipped"]
"""How a run of a batch ended: ``"done"`` (ran and finished), ``"failed"`` (bad input, a
divergence, or a worker lost), ``"skipped"`` (done by an earlier batch)."""

_PathLike = str | os.PathLike[str]

DONE_FILE = "done.json"
"""Written into a run's folder after all its outputs, when the run finished."""
FAILED_FILE = "failed.json"
"""Written into a run's folder when the run failed, with the error."""
BATCH_FILE = "batch.json"
"""Written into the batch's folder: every run of the batch and how it ended."""


def _check_name(name: object) -> str:
    if not isinstance(name, str):
        raise TypeError(f"a job's name must be a str, not {type(name).__name__}")
    problem = None
    if not name or name in {".", ".."}:
        problem = "it must be a folder name"
    elif any(c in name for c in "/\\\0:") or (os.altsep and os.altsep in name):
        problem = "it must be a single folder name, without path separators or drives (:)"
    elif name != name.strip():
        problem = "it starts or ends with white space"
    elif name == BATCH_FILE:
        problem = f"it is the name of the batch's own record, {BATCH_FILE}"
    elif len(name.encode("utf-8")) > 200:
        problem = "it is too long for a folder name"
    if problem:
        raise ValueError(f"job name {name!r}: {problem}")
    return name


def _safe_name(text: str) -> str:
    """``text`` made into a folder name: letters, digits, ``.``, ``_`` and ``-`` only."""
    cleaned = re.sub(r"[^A-Za-z0-9._-]+", "_", text).strip("._-")
    return cleaned[:120] or "job"


def _merge(base: Mapping[str, Any], overrides: Mapping[str, Any]) -> dict[str, Any]:
    """``base`` with ``overrides`` merged in: tables merge key by key, anything else
    (values, lists, ``[[bodies]]``) is replaced, and ``None`` removes the key (TOML has no
    null, so it cannot mean anything else)."""
    merged = copy.deepcopy(dict(base))
    for key, value in overrides.items():
        if value is None:
            merged.pop(key, None)
        elif isinstance(value, Mapping):
            # Into an empty table too, so that the Nones in a new table are dropped.
            current = merged.get(key)
            merged[key] = _merge(current if isinstance(current, Mapping) else {}, value)
        else:
            merged[key] = copy.deepcopy(value)
    return merged


@dataclasses.dataclass(frozen=True)
class Job:
    """One run of a batch: a scene, and the folder name its outputs go under.

    ``scene`` is the scene's tables, as :mod:`tomllib` reads them from a scene file (it is
    copied, so changing the dict given later does not change the job); ``base_dir`` is the
    folder the scene's relative paths start at (made absolute, since workers may run
    elsewhere). ``name`` is the run's folder in the batch's output folder, so it must be a
    single path component.
    """

    name: str
    scene: dict[str, Any] = dataclasses.field(hash=False)
    base_dir: str = "."
    #: The files the scene names, carried in the job (see :meth:`bundled`): its paths are
    #: these names, and ``base_dir`` is where a worker writes them.
    files: dict[str, bytes] = dataclasses.field(default_factory=dict, hash=False, repr=False)

    def __post_init__(self) -> None:
        _check_name(self.name)
        if not isinstance(self.scene, Mapping):
            raise TypeError(f"job {self.name!r}: scene must be a dict of the scene's tables")
        # Frozen dataclass: the normalised values go in through object.__setattr__.
        object.__setattr__(self, "scene", copy.deepcopy(dict(self.scene)))
        object.__setattr__(self, "base_dir", os.path.abspath(os.fspath(self.base_dir)))

    @classmethod
    def from_file(
        cls,
        path: _PathLike,
        name: str | None = None,
        overrides: Mapping[str, Any] | None = None,
    ) -> Job:
        """The scene file at ``path``, with ``overrides`` (nested dicts, like the file's
        tables) merged in: ``{"fabric": {"preset": "denim"}, "rest": {"max_steps": 500}}``.
        Tables merge key by key, other values are replaced, ``None`` removes a key. The
        name defaults to the file's name without ``.toml``; relative paths in the scene
        start at the file's folder."""
        path = Path(path)
        with path.open("rb") as f:
            try:
                scene = tomllib.load(f)
            except tomllib.TOMLDecodeError as e:
                raise ValueError(f"{path}: {e}") from e
        if overrides:
            scene = _merge(scene, overrides)
        return cls(
            name=_safe_name(path.stem) if name is None else name,
            scene=scene,
            base_dir=str(path.resolve().parent),
        )

    def bundled(self) -> Job:
        """This job carrying every file its scene names (the pattern, a cloth mesh, body
        meshes) as bytes, read from their paths (relative to ``base_dir``) or fsspec URLs
        (``s3://...``, needing fsspec): a worker on any machine runs it in a folder of its
        own. ``FileNotFoundError`` names a file that cannot be read."""
        if self.files:
            return self
        scene = copy.deepcopy(self.scene)
        files: dict[str, bytes] = {}

        def carry(where: str, value: Any) -> str:
            if not isinstance(value, str):
                raise ValueError(f"job {self.name!r}: {where} must be a path, not {value!r}")
            name = f"inputs/{len(files)}_{_safe_name(Path(value.split('://')[-1]).name)}"
            files[name] = _read_input(value, self.base_dir, f"job {self.name!r}: {where}")
            return name

        garment = (scene.get("cloth") or {}).get("garment")
        if isinstance(garment, dict) and "pattern" in garment:
            garment["pattern"] = carry("cloth.garment.pattern", garment["pattern"])
        mesh = (scene.get("cloth") or {}).get("mesh")
        if isinstance(mesh, dict) and "file" in mesh:
            mesh["file"] = carry("cloth.mesh.file", mesh["file"])
        for k, body in enumerate(scene.get("bodies") or []):
            if isinstance(body, dict) and "file" in body:
                body["file"] = carry(f"bodies[{k}].file", body["file"])
        return Job(name=self.name, scene=scene, base_dir=".", files=files)

    def key(self) -> str:
        """A hash of what the job runs (the scene and where its paths start, not its name):
        a run in the job's folder whose ``done.json`` has the same key is this job done.
        Files the scene names are identified by path, not content."""
        # A bundled job is what it carries wherever it runs; else its files are its paths.
        where: Any = (
            {name: hashlib.sha256(data).hexdigest() for name, data in sorted(self.files.items())}
            if self.files
            else self.base_dir
        )
        canonical = json.dumps(
            {"scene": self.scene, "base_dir": where},
            sort_keys=True,
            separators=(",", ":"),
            ensure_ascii=False,
            default=str,  # tomllib's dates and times, should a scene hold any
        )
        return hashlib.sha256(canonical.encode("utf-8")).hexdigest()


@dataclasses.dataclass(frozen=True)
class RunRecord:
    """How one run of a batch ended.

    ``status`` is ``"done"``, ``"failed"`` or ``"skipped"`` (done by an earlier batch, its
    record read from its ``done.json``); ``folder`` holds its outputs; ``seconds`` is the
    wall time of the run (of the earlier run when skipped); ``error`` and ``error_type``
    say why a run failed (the exception's message and class name: ``"ValueError"`` for
    bad input, ``"SimulationError"`` for a divergence); ``summary`` has the report's
    ``particles``, ``max_warp`` and ``max_weft`` (%), ``deepest_penetration`` (m) and
    ``largest_seam_gap`` (m, garments), also for a failed run that wrote a report (its
    last good state). ``key`` is the job's :meth:`Job.key`.
    """

    name: str
    status: Status
    folder: str
    seconds: float = 0.0
    error: str | None = None
    error_type: str | None = None
    summary: dict[str, Any] = dataclasses.field(default_factory=dict, hash=False)
    key: str = ""

    def to_dict(self) -> dict[str, Any]:
        """The record as a JSON-ready dict."""
        return dataclasses.asdict(self)


@dataclasses.dataclass(frozen=True)
class BatchResult:
    """The records of a batch's runs, in the order of its jobs; iterating gives them."""

    records: list[RunRecord]
    out_dir: str

    @property
    def done(self) -> list[RunRecord]:
        """The runs that ran and finished."""
        return [r for r in self.records if r.status == "done"]

    @property
    def failed(self) -> list[RunRecord]:
        """The runs that failed (bad input, a divergence, a lost worker)."""
        return [r for r in self.records if r.status == "failed"]

    @property
    def skipped(self) -> list[RunRecord]:
        """The runs not run because an earlier batch had done them."""
        return [r for r in self.records if r.status == "skipped"]

    @property
    def ok(self) -> bool:
        """Whether no run failed."""
        return not self.failed

    def record(self, name: str) -> RunRecord:
        """The record of the job called ``name`` (``KeyError`` if none is)."""
        for r in self.records:
            if r.name == name:
                return r
        raise KeyError(name)

    def __iter__(self) -> Iterator[RunRecord]:
        return iter(self.records)

    def __len__(self) -> int:
        return len(self.records)

    def to_dict(self) -> dict[str, Any]:
        """What ``batch.json`` holds at the end: the counts and every record."""
        return _batch_document(self.out_dir, self.records, [])

    def to_json(self) -> str:
        """:meth:`to_dict` as JSON text."""
        return json.dumps(self.to_dict(), indent=2)

    def to_pandas(self) -> Any:
        """The records as a ``pandas.DataFrame``, a row per run: ``name``, ``status``,
        ``folder``, ``seconds``, ``error``, ``error_type``, ``key``, and the summary's
        entries as columns of their own (``particles``, ``max_warp``, ``max_weft``,
        ``deepest_penetration``, ``largest_seam_gap``; missing ones NaN). Needs pandas
        (``pip install cloth-drape[pandas]``)."""
        try:
            import pandas
        except ImportError as e:
            raise ImportError("to_pandas needs pandas: pip install pandas (or cloth-drape[pandas])") from e
        rows = []
        for r in self.records:
            row = {k: v for k, v in r.to_dict().items() if k != "summary"}
            row.update(r.summary)
            rows.append(row)
        columns = ["name", "status", "folder", "seconds", "error", "error_type", "key"]
        return pandas.DataFrame(rows, columns=columns + sorted({k for r in rows for k in r} - set(columns)))

    def summary(self) -> str:
        """A few lines for people: the counts, then each failure and its error."""
        lines = [
            f"{len(self.records)} runs: {len(self.done)} done, {len(self.skipped)} skipped "
            f"(done before), {len(self.failed)} failed"
        ]
        lines += [f"  {r.name}: {r.error_type}: {r.error}" for r in self.failed]
        return "\n".join(lines)


def _axis(label: str, values: object) -> list[Any]:
    # A lone string or dict is iterable too, and would sweep over its characters or keys.
    if isinstance(values, (str, bytes, os.PathLike, Mapping)) or not isinstance(values, Sequence):
        raise TypeError(f"sweep: {label} must be a list, not {type(values).__name__}")
    if not values:
        raise ValueError(f"sweep: {label} is empty, so the sweep would have no runs")
    return list(values)


def _number(value: float) -> str:
    # Metres to the centimetre read best ("1.60"); finer values keep every digit.
    return f"{value:.2f}" if round(value, 2) == value else repr(value)


def _fabric_label(fabric: str | Mapping[str, Any]) -> str:
    if isinstance(fabric, str):
        return fabric
    if isinstance(fabric, Mapping):
        if isinstance(fabric.get("preset"), str):
            return str(fabric["preset"])
        return next((k for k in ("si", "kes") if k in fabric), "fabric")
    raise TypeError(f"sweep: a fabric must be a preset name or a [fabric] table (dict), not {fabric!r}")


def _body_label(measurements: Mapping[str, Any]) -> str:
    parts = []
    for key, value in measurements.items():
        if isinstance(value, (int, float)) and not isinstance(value, bool):
            parts.append(f"{key}{_number(float(value))}")
        else:
            parts.append(str(key))  # arms = {...} or true: the name says there are arms
    return "_".join(parts) or "default_body"


def _check_garment(job: Job, what: str) -> None:
    cloth = job.scene.get("cloth")
    if not (isinstance(cloth, dict) and isinstance(cloth.get("garment"), dict)):
        raise ValueError(
            f"sweep: {what} given, but scene {job.name!r} is not a garment "
            "(it has no [cloth.garment] table)"
        )


def _mannequin_index(job: Job) -> int:
    bodies = job.scene.get("bodies")
    entries = bodies if isinstance(bodies, list) else []
    found = [i for i, b in enumerate(entries) if isinstance(b, dict) and "mannequin" in b]
    if len(found) != 1:
        how = "has no [[bodies]] entry with" if not found else f"has {len(found)} [[bodies]] entries with"
        raise ValueError(
            f"sweep: bodies (mannequin measurements) given, but scene {job.name!r} {how} "
            "a mannequin = {...} to replace; the sweep needs exactly one"
        )
    return found[0]


def _unique(names: list[str]) -> list[str]:
    seen: set[str] = set()
    unique = []
    for name in names:
        candidate, n = name, 1
        # Case-folded, as folders on macOS and Windows are.
        while candidate.casefold() in seen:
            n += 1
            candidate = f"{name}_{n}"
        seen.add(candidate.casefold())
        unique.append(candidate)
    return unique


def sweep(
    base: _PathLike | Job,
    *,
    fabrics: Sequence[str | Mapping[str, Any]] | None = None,
    garments: Sequence[_PathLike] | None = None,
    bodies: Sequence[Mapping[str, Any]] | None = None,
    edge_length: float | Sequence[float] | None = None,
) -> list[Job]:
    """Every combination of the given fabrics, garments and bodies, on the scene ``base``
    (a scene file, or a :class:`Job`).

    ``fabrics`` are preset names or ``[fabric]`` tables (``{"preset": ...}``,
    ``{"si": {...}}`` or ``{"kes": {...}}``), each replacing the scene's ``[fabric]``;
    ``garments`` are pattern files (relative to the current folder), each replacing
    ``cloth.garment.pattern``; ``bodies`` are mannequin measurements (``{"height": 1.6,
    "hip": 0.98}``), each replacing the ``mannequin`` of the scene's one body that has
    one. ``edge_length`` sets ``cloth.garment.edge_length`` for all runs, or, a list, is
    one more axis. Axes not given keep the scene's value.

    The jobs are named after their values, ``cotton_poplin__skirt__height1.60`` (preset,
    pattern file, measurements, ``e<edge length>``), made into folder names and unique.
    ``ValueError`` when the scene cannot take an axis (garments or edge lengths for a
    scene that is not a garment, bodies for one without a mannequin);
    ``FileNotFoundError`` for a pattern file that does not exist.
    """
    job = base if isinstance(base, Job) else Job.from_file(base)
    # One scene changed per run; the base (a Job given) stays as it was.
    common = copy.deepcopy(job.scene)

    # Each axis: (label in the names, where in the scene, value), one per point.
    axes: list[list[tuple[str, str, Any]]] = []
    if fabrics is not None:
        axes.append([
            (_fabric_label(f), "fabric", {"preset": f} if isinstance(f, str) else dict(f))
            for f in _axis("fabrics", fabrics)
        ])
    if garments is not None:
        _check_garment(job, "garments")
        patterns = [Path(g).absolute() for g in _axis("garments", garments)]
        for path in patterns:
            if not path.is_file():
                raise FileNotFoundError(f"sweep: pattern file '{path}' does not exist")
        axes.append([(path.stem, "pattern", str(path)) for path in patterns])
    body = -1  # which of the scene's bodies is the mannequin
    if bodies is not None:
        body = _mannequin_index(job)
        measurements = _axis("bodies", bodies)
        for b in measurements:
            if not isinstance(b, Mapping):
                raise TypeError(f"sweep: bodies must be dicts of mannequin measurements, not {b!r}")
        axes.append([(_body_label(b), "mannequin", dict(b)) for b in measurements])
    if edge_length is not None:
        _check_garment(job, "edge_length")
        if isinstance(edge_length, (int, float)):
            # One value for every run: no axis, and not in the names.
            common["cloth"]["garment"]["edge_length"] = float(edge_length)
        else:
            axes.append([(f"e{v:g}", "edge_length", float(v)) for v in _axis("edge_length", edge_length)])

    combos = list(itertools.product(*axes))
    names = _unique(["__".join(_safe_name(label) for label, _, _ in combo) or job.name for combo in combos])
    jobs = []
    for name, combo in zip(names, combos):
        scene = copy.deepcopy(common)
        for _, where, value in combo:
            if where == "fabric":
                scene["fabric"] = copy.deepcopy(value)
            elif where == "mannequin":
                scene["bodies"][body]["mannequin"] = copy.deepcopy(value)
            else:  # pattern, edge_length
                scene["cloth"]["garment"][where] = value
        jobs.append(Job(name=name, scene=scene, base_dir=job.base_dir))
    return jobs


def _read_input(value: str, base_dir: str, what: str) -> bytes:
    """The bytes of a file a scene names: an fsspec URL, or a path from ``base_dir``."""
    try:
        if "://" in value:
            try:
                import fsspec
            except ImportError as e:
                raise ImportError(f"{what}: reading {value} needs fsspec: pip install fsspec") from e
            with fsspec.open(value, "rb") as f:
                return f.read()
        return (Path(base_dir) / value).read_bytes()
    except FileNotFoundError as e:
        raise FileNotFoundError(f"{what}: cannot read '{value}': {e}") from e


def _write_json(path: Path, data: Any) -> None:
    """Writes ``data`` to ``path`` atomically: readers see the old file or the new one."""
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            json.dump(data, f, indent=2)
            f.write("\n")
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def _read_json(path: Path) -> dict[str, Any] | None:
    try:
        with path.open(encoding="utf-8") as f:
            data = json.load(f)
    except (OSError, ValueError):
        return None  # missing, or cut short: either way not a record to trust
    return data if isinstance(data, dict) else None


def _summary(report: Mapping[str, Any] | None) -> dict[str, Any]:
    if not report:
        return {}
    strain = report.get("strain") or {}
    return {
        "particles": report.get("particles"),
        "max_warp": strain.get("max_warp"),
        "max_weft": strain.get("max_weft"),
        "deepest_penetration": report.get("deepest_penetration"),
        "largest_seam_gap": report.get("largest_seam_gap"),
    }


def _empty_folder(folder: Path) -> None:
    """Makes ``folder`` an empty folder for a run. Only a folder a batch run made (it holds
    a marker) or an empty one is emptied: anything else under the job's name is the
    user's, and the job fails instead of deleting it."""
    if folder.is_symlink() or (folder.exists() and not folder.is_dir()):
        raise FileExistsError(f"'{folder}' is in the way of the run's folder and is not a batch run's")
    if folder.exists() and any(folder.iterdir()):
        if not ((folder / DONE_FILE).is_file() or (folder / FAILED_FILE).is_file()):
            raise FileExistsError(
                f"'{folder}' exists and is not a batch run's folder (no {DONE_FILE} or {FAILED_FILE}): "
                "move it away or rename the job"
            )
        # The markers go first: should the rest fail half way, no stale done.json remains.
        for marker in (DONE_FILE, FAILED_FILE):
            (folder / marker).unlink(missing_ok=True)
        # Outputs of an earlier, different job would sit beside this one's (a render.png
        # this scene does not write, old frames/).
        shutil.rmtree(folder)
    folder.mkdir(parents=True, exist_ok=True)


def _marker(record: RunRecord, outputs: list[str]) -> dict[str, Any]:
    return {
        **record.to_dict(),
        "outputs": outputs,
        "host": socket.gethostname(),
        "pid": os.getpid(),
        "finished_at": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
    }


def _run_job(job: Job, folder: str, submission: str = "") -> RunRecord:
    """Runs ``job`` into ``folder`` (emptied first) and writes its marker; the task each
    worker runs. A run that fails is a record, not an exception: only trouble with the
    folder itself raises. ``submission`` is unused: a value new for each submission keeps
    Dask, which takes tasks to be pure by default, from answering a resubmitted job with
    the result of an earlier identical task instead of running it."""
    path = Path(folder)
    start = time.perf_counter()
    report: dict[str, Any] | None = None
    outputs: list[str] = []
    error: str | None = None
    error_type: str | None = None
    _empty_folder(path)
    try:
        result = Scene.from_dict(job.scene, base_dir=job.base_dir, name=job.name).run(path, force=True)
    except SimulationError as e:
        # A divergence: the last good state and its report are written already.
        error, error_type, report = str(e), type(e).__name__, e.report
    except Exception as e:  # bad input (ValueError) or anything else: the batch goes on
        error, error_type = str(e) or repr(e), type(e).__name__
    else:
        report, outputs = result.report, [str(o) for o in result.outputs]
        if result.outcome != "finished":
            outcome = report.get("outcome") or {}
            if result.outcome == "interrupted":
                error_type = "Interrupted"
                error = f"interrupted after step {outcome.get('step')} of {outcome.get('stage')}"
            else:
                error_type = "SimulationError"
                error = str(outcome.get("error") or "the run failed")
    if error_type and path.is_dir():
        # What a failed run wrote (a divergence's last good state), for the record.
        outputs = sorted(str(p) for p in path.iterdir())
    record = RunRecord(
        name=job.name,
        status="failed" if error_type else "done",
        folder=str(path),
        seconds=time.perf_counter() - start,
        error=error,
        error_type=error_type,
        summary=_summary(report),
        key=job.key(),
    )
    # done.json last of all, so that its presence means every output is there.
    _write_json(path / (FAILED_FILE if error_type else DONE_FILE), _marker(record, outputs))
    return record


@dataclasses.dataclass(frozen=True)
class _Delivery:
    """What a worker sends back from a bundled job: the record, the marker, and every
    file the run wrote (relative path to bytes)."""

    record: RunRecord
    marker: dict[str, Any]
    outputs: dict[str, bytes]


def _run_portable(job: Job, folder: str, submission: str = "") -> _Delivery:
    """Runs a bundled job in a temporary folder of this worker's (its files written
    there, the outputs read back): the task a worker runs when jobs carry their files.
    ``folder`` is where the client will put the outputs, for the record."""
    with tempfile.TemporaryDirectory(prefix="cloth-job-") as tmp:
        work = Path(tmp)
        for name, data in job.files.items():
            target = work / name
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(data)
        local = Job(name=job.name, scene=job.scene, base_dir=str(work))
        record = _run_job(local, str(work / "out"), submission)
        out = work / "out"
        outputs = {
            p.relative_to(out).as_posix(): p.read_bytes()
            for p in sorted(out.rglob("*"))
            if p.is_file() and p.name not in (DONE_FILE, FAILED_FILE)
        }
        marker = _read_json(out / (FAILED_FILE if record.status == "failed" else DONE_FILE)) or {}
    record = dataclasses.replace(record, folder=folder, key=job.key())
    marker.update(folder=folder, key=job.key(), outputs=[str(Path(folder) / n) for n in outputs])
    return _Delivery(record=record, marker=marker, outputs=outputs)


def _deliver(delivery: _Delivery, folder: Path) -> RunRecord:
    """Writes a bundled job's outputs into ``folder`` (emptied first, as a run's is), then
    its marker."""
    _empty_folder(folder)
    for name, data in delivery.outputs.items():
        target = (folder / name).resolve()
        if folder.resolve() not in target.parents:
            raise ValueError(f"a delivered output {name!r} lies outside '{folder}'")
        target.parent.mkdir(parents=True, exist_ok=True)
        target.write_bytes(data)
    marker = FAILED_FILE if delivery.record.status == "failed" else DONE_FILE
    _write_json(folder / marker, delivery.marker)
    return delivery.record


def _lost(job: Job, folder: Path, error: BaseException) -> RunRecord:
    """The record of a task that raised instead of returning: its worker died, it could
    not be sent, its folder could not be written."""
    record = RunRecord(
        name=job.name,
        status="failed",
        folder=str(folder),
        error=str(error) or repr(error),
        error_type=type(error).__name__,
        key=job.key(),
    )
    # A folder that is not a batch run's stays as it was: no marker in it.
    if not isinstance(error, FileExistsError):
        with contextlib.suppress(OSError):
            folder.mkdir(parents=True, exist_ok=True)
            _write_json(folder / FAILED_FILE, _marker(record, []))
    return record


def _previous(job: Job, folder: Path, rerun_failed: bool) -> RunRecord | None:
    """The record of an earlier run of this very job that need not run again."""
    key = job.key()
    markers: list[tuple[str, Status]] = [(DONE_FILE, "skipped")]
    if not rerun_failed:
        markers.append((FAILED_FILE, "failed"))
    for marker, status in markers:
        data = _read_json(folder / marker)
        if data is None or data.get("key") != key:
            continue
        return RunRecord(
            name=job.name,
            status=status,
            folder=str(folder),
            seconds=float(data.get("seconds") or 0.0),
            error=data.get("error"),
            error_type=data.get("error_type"),
            summary=dict(data.get("summary") or {}),
            key=key,
        )
    return None


def _batch_document(out_dir: str, records: Sequence[RunRecord | None], jobs: Sequence[Job]) -> dict[str, Any]:
    runs = []
    for i, record in enumerate(records):
        if record is not None:
            runs.append(record.to_dict())
        else:
            job = jobs[i]
            folder = str(Path(out_dir) / job.name)
            runs.append({"name": job.name, "status": "pending", "folder": folder, "key": job.key()})
    counts = {s: sum(1 for r in runs if r["status"] == s) for s in ("done", "skipped", "failed", "pending")}
    return {
        "out_dir": out_dir,
        "updated_at": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
        "counts": counts,
        "runs": runs,
    }


def _check_jobs(jobs: list[Job]) -> None:
    seen: dict[str, str] = {}
    for job in jobs:
        if not isinstance(job, Job):
            raise TypeError(f"run_batch: jobs must be Job objects, not {type(job).__name__}")
        # Case-folded, as folders on macOS and Windows are: two jobs would share a folder.
        folded = job.name.casefold()
        if folded in seen:
            other = seen[folded]
            also = "" if other == job.name else f" and {other!r} (one folder on some systems)"
            raise ValueError(
                f"run_batch: two jobs are named {job.name!r}{also}: each needs a folder of its own"
            )
        seen[folded] = job.name


def run_batch(
    jobs: Iterable[Job],
    out_dir: _PathLike,
    *,
    executor: concurrent.futures.Executor | None = None,
    rerun_failed: bool = True,
    on_result: Callable[[RunRecord], None] | None = None,
    progress: bool = False,
    portable: bool = False,
) -> BatchResult:
    """Runs every job not done yet, each into ``out_dir/<job name>``.

    ``executor`` is any :class:`concurrent.futures.Executor`: a thread or process pool,
    or a Dask cluster's (``distributed.Client(...).get_executor()``); ``None`` runs the
    jobs one after the other in this process. A job is done, and skipped, when its folder
    has a ``done.json`` with the job's :meth:`Job.key`; with ``rerun_failed=False`` a job
    whose ``failed.json`` has its key is not run again either (and is reported failed).
    A job that runs has its folder emptied first.

    A run that fails (bad input, a divergence, or a worker that died) is recorded as
    failed with its error, and the others go on. ``on_result`` is called here, in the
    caller, with the record of each run as it finishes (not for skipped ones); an
    exception it raises stops the batch, cancelling the runs not started.
    ``out_dir/batch.json`` lists every job (``"pending"`` until it ends) and is rewritten
    as each run finishes.

    ``portable=True`` bundles every job (:meth:`Job.bundled`): the workers need no path
    of this machine's, and the outputs come back here to be written into ``out_dir``.
    Jobs bundled already run so anyway.

    ``progress=True`` shows a tqdm bar of the runs ended (those skipped counted from the
    start; ``ImportError`` before anything runs without tqdm).

    Returns the records in the order of ``jobs``. ``ValueError`` before anything runs
    when two jobs share a name.
    """
    jobs = list(jobs)
    _check_jobs(jobs)
    if portable:
        jobs = [job.bundled() for job in jobs]
    bar = _progress_bar(progress, len(jobs))
    # Absolute: workers in other processes, or on other machines, have other working folders.
    out = Path(out_dir).absolute()
    out.mkdir(parents=True, exist_ok=True)
    folders = [out / job.name for job in jobs]

    records: list[RunRecord | None] = [_previous(job, f, rerun_failed) for job, f in zip(jobs, folders)]
    todo = [i for i, r in enumerate(records) if r is None]

    def save() -> None:
        _write_json(out / BATCH_FILE, _batch_document(str(out), records, jobs))

    def finish(i: int, record: RunRecord) -> None:
        records[i] = record
        save()
        if bar is not None:
            bar.update(1)
        if on_result is not None:
            on_result(record)

    if bar is not None:
        bar.update(len(jobs) - len(todo))
    save()
    try:
        _run_all(jobs, folders, todo, executor, finish)
    finally:
        if bar is not None:
            bar.close()
    return BatchResult(records=[r for r in records if r is not None], out_dir=str(out))


def _run_all(
    jobs: list[Job],
    folders: list[Path],
    todo: list[int],
    executor: concurrent.futures.Executor | None,
    finish: Callable[[int, RunRecord], None],
) -> None:
    """Runs the jobs numbered in ``todo`` here or on ``executor``, handing each record to
    ``finish`` as it ends."""
    def task(i: int) -> Callable[..., Any]:
        return _run_portable if jobs[i].files else _run_job

    def ended(i: int, result: RunRecord | _Delivery) -> RunRecord:
        return _deliver(result, folders[i]) if isinstance(result, _Delivery) else result

    if executor is None:
        for i in todo:
            try:
                record = ended(i, task(i)(jobs[i], str(folders[i])))
            except Exception as e:
                record = _lost(jobs[i], folders[i], e)
            finish(i, record)
    else:
        futures = {executor.submit(task(i), jobs[i], str(folders[i]), uuid.uuid4().hex): i for i in todo}
        try:
            for future in concurrent.futures.as_completed(futures):
                i = futures[future]
                try:
                    record = ended(i, future.result())
                except Exception as e:  # the task itself was lost: still only this run's failure
                    record = _lost(jobs[i], folders[i], e)
                finish(i, record)
        finally:
            # Stopped early (Ctrl-C, on_result raised): runs not started are not wanted.
            for future in futures:
                future.cancel()


def _progress_bar(on: bool, total: int) -> Any:
    """A tqdm bar of ``total`` runs when ``on``, else ``None``."""
    if not on:
        return None
    try:
        from tqdm import tqdm
    except ImportError as e:
        raise ImportError("progress=True needs tqdm: pip install tqdm (or cloth-drape[progress])") from e
    return tqdm(total=total, desc="runs", unit="run")


@dataclasses.dataclass(frozen=True)
class DrapeResult:
    """What :func:`drape` did: the batch's records, and the summary's entries (one per
    pattern, as ``summary.json`` holds them: ``name``, ``pattern``, ``outcome``,
    ``skipped``, ``failure``, ``verdict`` (a finished garment's: ``"clean"``, or why not,
    naming the panels), ``seconds``, ``particles``, ``sewing_steps``,
    ``draping_steps``, ``drape_ended``, ``self_intersections``, ``body_intersections``,
    ``thin_parts_passed`` (crossings of the body's thin parts by panels dressing the legs,
    which pass them), ``deepest_penetration`` (m), ``max_warp``, ``max_weft``,
    ``p99_warp``, ``p99_weft`` (%), ``fit_asks`` (what the cut asks of the fabric round
    the body where the garment is most stretched, %; negative, the slack it leaves; ``None``
    where not measured))."""

    batch: BatchResult
    entries: list[dict[str, Any]]

    @property
    def ok(self) -> bool:
        """Whether every pattern finished."""
        return all(e["outcome"] == "finished" for e in self.entries)


def drape(
    patterns: _PathLike | Sequence[_PathLike],
    body: _PathLike,
    out_dir: _PathLike,
    *,
    body_up_axis: Literal["y", "z"] | None = None,
    up_axis: Literal["y", "z"] | None = None,
    fabric: str = "cotton_poplin",
    edge_length: float = 0.015,
    min_thickness: float | None = None,
    executor: concurrent.futures.Executor | None = None,
    progress: bool = False,
    portable: bool = False,
) -> DrapeResult:
    """Drapes every pattern on ``body``, as ``cloth drape`` does, on any executor.

    ``patterns`` are pattern files (our TOML or GarmentCode JSON) or folders searched for
    them; each drapes into ``out_dir/<pattern name>`` with ``fabric`` at ``edge_length``
    (m) on the body file (``body_up_axis`` ``"y"`` for GarmentCode's and SMPL's y-up
    bodies; by default glTF's is y, the other formats' z), its 3 mm contact layer thinned
    where it is flat down to ``min_thickness`` (m; ``None``: 1 mm, as the command's
    ``--min-thickness``; 0.003 keeps it uniform), through :func:`run_batch`, so
    patterns done by an earlier batch are skipped. ``out_dir/summary.json`` and
    ``summary.md`` then say how every pattern ended, in the same form as the command's.
    ``up_axis="y"`` writes the OBJ and PLY outputs y-up, as ``cloth drape --up-axis y``.
    ``ValueError`` before anything runs for a missing pattern or folder, two patterns of
    one name, an unknown fabric, a bad edge length or minimum thickness. ``progress=True``
    shows a tqdm bar of the patterns done; ``portable=True`` sends each pattern and the body
    with its job, for workers without this machine's files (see :func:`run_batch`).
    """
    inputs = [patterns] if isinstance(patterns, (str, os.PathLike)) else list(patterns)
    scenes = _drape_scenes(
        [os.fspath(p) for p in inputs],
        os.fspath(body),
        body_up_axis=body_up_axis,
        up_axis=up_axis,
        fabric=fabric,
        edge_length=edge_length,
        min_thickness=min_thickness,
    )
    jobs = [Job(name=name, scene=tomllib.loads(text)) for name, _, text in scenes]
    result = run_batch(jobs, out_dir, executor=executor, progress=progress, portable=portable)
    pattern_of = {name: path for name, path, _ in scenes}
    runs = [(r.name, pattern_of[r.name], r.status == "skipped", r.error) for r in result.records]
    entries = json.loads(_write_drape_summary(os.fspath(Path(out_dir).absolute()), runs))
    return DrapeResult(batch=result, entries=entries)


def _main(argv: Sequence[str] | None = None) -> int:
    """``python -m cloth drape ...``: :func:`drape` from the command line, on a Dask
    cluster with ``--dask ADDRESS`` (each job carrying its pattern and the body); what
    ``cloth drape --dask`` runs. Exits 0 when every pattern finished, 1 when one did not,
    2 for bad input."""
    import argparse
    import sys

    parser = argparse.ArgumentParser(prog="python -m cloth", description=_main.__doc__)
    commands = parser.add_subparsers(dest="command", required=True)
    d = commands.add_parser("drape", help="drape patterns on a body, as cloth drape")
    d.add_argument("patterns", nargs="+")
    d.add_argument("--body", required=True)
    d.add_argument("--out", required=True)
    d.add_argument("--body-up-axis", choices=["y", "z"])
    d.add_argument("--up-axis", choices=["y", "z"])
    d.add_argument("--fabric", default="cotton_poplin")
    d.add_argument("--edge-length", type=float, default=0.015)
    d.add_argument("--min-thickness", type=float)
    d.add_argument("--dask", metavar="ADDRESS", help="the Dask scheduler's address (tcp://host:8786)")
    d.add_argument("--quiet", action="store_true")
    args = parser.parse_args(argv)

    def run(executor: concurrent.futures.Executor | None) -> DrapeResult:
        return drape(
            args.patterns,
            args.body,
            args.out,
            body_up_axis=args.body_up_axis,
            up_axis=args.up_axis,
            fabric=args.fabric,
            edge_length=args.edge_length,
            min_thickness=args.min_thickness,
            executor=executor,
            portable=args.dask is not None,
        )

    try:
        if args.dask is None:
            result = run(None)
        else:
            from distributed import Client

            with Client(args.dask) as client:
                result = run(client.get_executor())
    except (ValueError, FileNotFoundError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    if not args.quiet:
        for entry in result.entries:
            print(f"{entry['name']}: {entry['outcome']}" + (f" ({entry['verdict']})" if entry.get("verdict") else ""))
    finished = sum(e["outcome"] == "finished" for e in result.entries)
    print(f"{finished} of {len(result.entries)} patterns finished; summary in {Path(args.out) / 'summary.md'}")
    return 0 if result.ok else 1

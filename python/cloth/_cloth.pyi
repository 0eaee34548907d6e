"""Type stubs of the native module ``cloth._cloth`` (Rust, pyo3).

Every array is numpy: points as ``(N, 3)`` float64, material coordinates as ``(N, 2)``
float64, triangles as ``(M, 3)`` int64. Arrays given are copied; arrays returned are
fresh copies the caller owns. Units are SI (m, kg, s, N) throughout.
"""

from collections.abc import Callable, Mapping, Sequence
from os import PathLike
from typing import Any, Literal, final

import numpy as np
import numpy.typing as npt

__version__: str

_Path = str | PathLike[str]
_Vec3 = tuple[float, float, float] | Sequence[float]
_Points = npt.ArrayLike
_Callback = Callable[["Snapshot"], bool | None]

class SimulationError(RuntimeError):
    """A run that diverged or otherwise could not go on, on valid input.

    The simulation keeps the last good state; ``Scene.run`` has written it, with the
    report, before raising. ``step`` is the step that failed (0 if unknown) and
    ``report`` the run's report (a dict) when a scene was running, else ``None``.
    """

    step: int
    report: dict[str, Any] | None

@final
class Fabric:
    """A fabric's mechanical properties in SI units (the model's parameters).

    Made from a preset, from SI values (the keys of a scene's ``[fabric.si]``), or from a
    Kawabata (KES-F) record (the keys of ``[fabric.kes]``, in KES units).
    """

    @staticmethod
    def preset(name: str) -> Fabric:
        """The built-in preset ``name`` (see :meth:`presets`); ``ValueError`` names the
        known ones when it is not one of them."""
    @staticmethod
    def presets() -> dict[str, str]:
        """The built-in presets: name to a one-line description."""
    @staticmethod
    def from_si(values: Mapping[str, Any]) -> Fabric:
        """From SI values, as a scene's ``[fabric.si]`` table: ``area_density`` (kg/m^2),
        ``warp`` and ``weft`` tensile laws, ``compression_warp``/``compression_weft``,
        ``shear_modulus`` (N/m), ``bending`` (N m), and optionally ``thickness``,
        ``bending_law``, ``damping``, ``drag``, ``friction``. Unknown keys are refused."""
    @staticmethod
    def from_kes(record: Mapping[str, Any]) -> Fabric:
        """From a KES-F record, as a scene's ``[fabric.kes]`` table: ``W`` (mg/cm^2), ``T``
        (mm), ``MIU``, and ``warp``/``weft`` tables of ``EMT`` (%), ``LT``, ``WT``
        (gf cm/cm^2), ``G`` (gf/(cm deg)), ``B`` (gf cm^2/cm), and optionally ``RT``,
        ``2HG``, ``2HG5``, ``2HB``."""
    def to_si(self) -> dict[str, Any]:
        """The SI values; ``Fabric.from_si(f.to_si()) == f``."""
    def to_kes(self) -> dict[str, Any]:
        """The KES-F record this fabric would measure (the inverse of :meth:`from_kes`)."""
    def with_values(self, **changes: Any) -> Fabric:
        """A copy with some SI values replaced (``f.with_values(damping=0.01)``)."""
    @property
    def area_density(self) -> float:
        """Mass per area, kg/m^2."""
    @property
    def thickness(self) -> float:
        """m."""
    @property
    def friction(self) -> float:
        """Coulomb coefficient against bodies."""
    @property
    def membrane_stiffness(self) -> float:
        """Secant tensile stiffness at 1 % strain, the larger of warp and weft, N/m."""
    def __eq__(self, other: object) -> bool: ...

@final
class ClothMesh:
    """A triangle mesh with 3D positions and 2D material (warp u, weft v) coordinates in
    metres, which define the flat rest state. A sewn garment's mesh keeps them per
    triangle corner."""

    @staticmethod
    def grid(
        nx: int,
        ny: int,
        size: tuple[float, float] | Sequence[float],
        *,
        origin: _Vec3 = (0.0, 0.0, 0.0),
        u_axis: _Vec3 = (1.0, 0.0, 0.0),
        v_axis: _Vec3 = (0.0, 1.0, 0.0),
    ) -> ClothMesh:
        """A rectangular sheet of ``nx`` by ``ny`` particles, ``size`` m, its corner at
        ``origin``, the warp along ``u_axis`` and the weft along ``v_axis``. Particle
        ``(i, j)`` is number ``j * nx + i`` (see :meth:`grid_index`)."""
    @staticmethod
    def from_arrays(positions: _Points, uv: _Points, triangles: npt.ArrayLike) -> ClothMesh:
        """From ``(N, 3)`` positions, ``(N, 2)`` material coordinates and ``(M, 3)``
        vertex indices. Bad shapes, dtypes, indices or degenerate triangles raise
        ``ValueError``/``TypeError`` naming the array and the element."""
    @staticmethod
    def load(
        path: _Path,
        *,
        scale: float = 1.0,
        uv_scale: float = 1.0,
        up_axis: Literal["y", "z"] = "z",
        rotation: _Vec3 = (0.0, 0.0, 0.0),
        position: _Vec3 = (0.0, 0.0, 0.0),
    ) -> ClothMesh:
        """An OBJ file, as a scene's ``[cloth.mesh]``: its ``vt`` times ``uv_scale`` are the
        material coordinates; a file without them must be flat, and is its own rest shape
        with the warp along x. Coordinates are multiplied by ``scale``, turned from
        ``up_axis`` to z up, then by ``rotation`` (degrees about x, then y, then z), then
        moved by ``position``."""
    @property
    def positions(self) -> npt.NDArray[np.float64]:
        """``(N, 3)`` initial positions."""
    @property
    def uv(self) -> npt.NDArray[np.float64]:
        """``(N, 2)`` material coordinates (for a seam vertex, those of its first triangle)."""
    @property
    def corner_uv(self) -> npt.NDArray[np.float64]:
        """``(M, 3, 2)`` material coordinates of every triangle's corners, m (u along the
        warp, v along the weft): a seam vertex has each panel's own at its corners there."""
    @property
    def triangles(self) -> npt.NDArray[np.int64]:
        """``(M, 3)`` vertex indices."""
    @property
    def edges(self) -> npt.NDArray[np.int64]:
        """``(E, 2)`` vertex indices of the distinct edges."""
    @property
    def vertex_count(self) -> int: ...
    @property
    def triangle_count(self) -> int: ...
    @property
    def grid_shape(self) -> tuple[int, int] | None:
        """``(nx, ny)`` of a grid mesh, else ``None``."""
    def grid_index(self, i: int, j: int) -> int:
        """The particle at thread crossing ``(i, j)`` of a grid mesh."""
    @property
    def rest_area(self) -> float:
        """Total material area, m^2."""
    def save_obj(self, path: _Path, positions: _Points | None = None) -> None:
        """Writes the mesh (at ``positions`` if given) as OBJ with its material coordinates."""

@final
class Body:
    """A rigid body the cloth drapes on: a closed triangle surface placed at ``position``,
    with a contact ``thickness`` (m) and a ``friction`` coefficient (the fabric's when
    ``None``). A mannequin with arms is one Body of three parts."""

    @staticmethod
    def load(
        path: _Path,
        *,
        scale: float = 1.0,
        up_axis: Literal["y", "z"] | None = None,
        rotation: _Vec3 = (0.0, 0.0, 0.0),
        position: _Vec3 = (0.0, 0.0, 0.0),
        thickness: float | None = None,
        friction: float | None = None,
        name: str | None = None,
    ) -> Body:
        """An OBJ, STL, PLY, glTF or GLB file (``scale`` 0.01 for centimetres), turned from
        its ``up_axis`` (``"y"`` or ``"z"``; glTF's is ``"y"`` when not given, the others'
        ``"z"``) to z up, then by ``rotation`` (degrees about x, then y, then z), then moved
        to ``position``. A mesh with holes, stray edges or overlapping parts loads with a
        warning for each kind of defect (see :attr:`defects`); one that encloses nothing
        raises ``ValueError`` naming the file."""
    @staticmethod
    def from_arrays(
        vertices: _Points,
        triangles: npt.ArrayLike,
        *,
        scale: float = 1.0,
        up_axis: Literal["y", "z"] | None = None,
        rotation: _Vec3 = (0.0, 0.0, 0.0),
        position: _Vec3 = (0.0, 0.0, 0.0),
        thickness: float | None = None,
        friction: float | None = None,
        name: str | None = None,
    ) -> Body:
        """A body from a triangle mesh in memory: ``vertices`` ``(V, 3)`` and
        ``triangles`` ``(T, 3)`` indices into them, scaled, turned and placed as
        :meth:`load`'s file is (``up_axis`` ``"z"`` by default) and checked as a file is: a
        mesh with defects loads with a warning for each kind, one that encloses nothing
        raises ``ValueError``."""
    @staticmethod
    def from_trimesh(mesh: Any, **options: Any) -> Body:
        """A body from a ``trimesh.Trimesh`` (or anything with ``vertices`` and
        ``faces``), with :meth:`from_arrays`'s keyword ``options``; ``TypeError`` for
        anything else. Trimesh meshes are y-up as often as not: say ``up_axis="y"`` for
        those."""
    @staticmethod
    def sphere(
        radius: float,
        *,
        position: _Vec3 = (0.0, 0.0, 0.0),
        thickness: float | None = None,
        friction: float | None = None,
        name: str | None = None,
    ) -> Body: ...
    @staticmethod
    def box(
        size: _Vec3,
        *,
        position: _Vec3 = (0.0, 0.0, 0.0),
        thickness: float | None = None,
        friction: float | None = None,
        name: str | None = None,
    ) -> Body:
        """A box of ``size`` (x, y, z) centred on ``position``."""
    @staticmethod
    def cylinder(
        radius: float,
        height: float,
        *,
        position: _Vec3 = (0.0, 0.0, 0.0),
        thickness: float | None = None,
        friction: float | None = None,
        name: str | None = None,
    ) -> Body:
        """A cylinder along z centred on ``position``."""
    @staticmethod
    def table(
        size: _Vec3,
        height: float,
        *,
        leg_width: float = 0.06,
        leg_inset: float = 0.05,
        position: _Vec3 = (0.0, 0.0, 0.0),
        thickness: float | None = None,
        friction: float | None = None,
        name: str | None = None,
    ) -> Body:
        """A table standing on z = 0 below ``position``: a top of ``size`` (width, depth,
        thickness) whose upper face is at ``height``, on four legs."""
    @staticmethod
    def mannequin(
        *,
        position: _Vec3 = (0.0, 0.0, 0.0),
        thickness: float | None = None,
        friction: float | None = None,
        name: str | None = None,
        **measurements: Any,
    ) -> Body:
        """The parametric mannequin: ``height``, ``bust``, ``waist``, ``hip``,
        ``shoulder_width``, ``neck_girth`` (m; missing ones take the average body's), and
        ``arms`` for a form with arms: ``True`` for the average arms scaled to the height
        (as ``cloth mannequin --arms``), or a dict of arm measurements (as a scene's
        ``arms = {...}``)."""
    @property
    def name(self) -> str: ...
    @property
    def parts(self) -> list[str]:
        """The names of the surfaces it is made of."""
    @property
    def defects(self) -> list[str]:
        """What loading found wrong with the mesh and did about it, one line per kind of
        defect (empty for a watertight mesh)."""
    @property
    def vertices(self) -> npt.NDArray[np.float64]:
        """``(V, 3)`` vertices of all its parts, placed."""
    @property
    def triangles(self) -> npt.NDArray[np.int64]:
        """``(T, 3)`` indices into :attr:`vertices`."""
    def signed_distance(self, points: _Points) -> npt.NDArray[np.float64]:
        """Signed distance of each point to the body (negative inside), ``(N,)``."""
    def save_obj(self, path: _Path) -> None:
        """Writes its surface as OBJ."""

@final
class Pattern:
    """A sewing pattern: panels (outlines of lines, Béziers and arcs, with grain lines and
    placements round the body) and the seams between their edges."""

    @staticmethod
    def load(path: _Path) -> Pattern:
        """Our TOML pattern (``.toml``) or GarmentCode's JSON (``.json``)."""
    @staticmethod
    def from_toml(text: str, *, name: str = "<pattern>") -> Pattern:
        """Our TOML pattern format; ``name`` is the file named in errors."""
    @staticmethod
    def from_garmentcode(text: str, *, name: str = "<pattern>") -> Pattern:
        """A GarmentCode specification (JSON text)."""
    @property
    def panel_names(self) -> list[str]: ...
    @property
    def seam_count(self) -> int: ...

@final
class Garment:
    """A pattern meshed for simulation: each panel discretised at ``edge_length`` (m),
    placed in 3D, and the seams' vertex pairs matched one to one."""

    def __init__(self, pattern: Pattern, edge_length: float = 0.015) -> None: ...
    @property
    def mesh(self) -> ClothMesh:
        """The unsewn mesh, panels placed."""
    @property
    def panel_names(self) -> list[str]: ...
    @property
    def triangle_panel(self) -> npt.NDArray[np.int64]:
        """The panel of each triangle."""
    @property
    def seam_pairs(self) -> npt.NDArray[np.int64]:
        """``(K, 2)`` vertex pairs the seams join."""
    def widest_gap(self, positions: _Points | None = None) -> float:
        """The widest seam gap at ``positions`` (the placed mesh when ``None``), m."""
    def placement_warnings(self, bodies: Sequence[Body]) -> list[str]:
        """Panels placed inside a body, with the fix."""
    def sew(
        self,
        bodies: Sequence[Body],
        fabric: Fabric | Sequence[Fabric],
        *,
        settings: Mapping[str, Any] | None = None,
        self_collision: bool | Mapping[str, Any] | None = None,
        callback: _Callback | None = None,
        every: int = 1,
    ) -> SewnGarment:
        """The source's second stage: gravity off, the seams pulled closed and welded.
        ``fabric`` is one fabric for every panel (panels that name a preset get theirs) or
        one per panel. ``settings`` are a scene's ``[sewing]`` keys; ``self_collision`` as
        for :class:`Simulation`. ``callback`` sees a :class:`Snapshot` every ``every``
        steps; returning ``False`` stops the sewing (``SimulationError``). Seams that will
        not close raise ``SimulationError``."""

@final
class SewnGarment:
    """A garment whose seams are welded, at the positions where they closed."""

    @property
    def mesh(self) -> ClothMesh:
        """The welded mesh (its positions are where the seams closed)."""
    @property
    def report(self) -> dict[str, Any]:
        """Steps, seconds, CG iterations, the widest gap at welding (m), the pull (N); the
        seams that stalled and how they closed (``seam_stalls``), the layers found across
        them (``caught_layers``) and the crossings the weld made (``weld_crossings``), as a
        scene's report.json gives them."""
    def drape(
        self,
        bodies: Sequence[Body],
        *,
        settings: Mapping[str, Any] | None = None,
        self_collision: bool | Mapping[str, Any] | None = None,
        callback: _Callback | None = None,
        every: int = 1,
    ) -> Draped:
        """The source's third stage: gravity on, until at rest (``settings`` are a scene's
        ``[drape]`` keys; ``self_collision`` as for :class:`Simulation`)."""

@final
class Draped:
    """A draped garment: the simulation at rest (it can be stepped on) and how it ended."""

    @property
    def simulation(self) -> Simulation: ...
    @property
    def outcome(self) -> RestOutcome: ...
    @property
    def seconds(self) -> float: ...
    @property
    def untangling_at_rest(self) -> dict[str, Any] | None:
        """If the drape came to rest through itself, what was done: ``before`` (the
        crossings where it first rested); ``smoothed``, a list, each time the cloth was
        smoothed apart where it rested (``before``, ``left``, ``rounds``, ``most_moved``
        in m) and ``draped_on`` from there (``after``, ``body_after``, ``steps``,
        ``kept``; None if the smoothing left no fewer), again after each drape on kept
        that still crossed, at most three times; ``loose``, if it still crossed, the
        garment draped again from sewn, loose where it crossed (``after``,
        ``body_after``, ``steps``, ``kept``), or None; else None."""

@final
class StepStats:
    """Statistics of one step."""

    step: int
    time: float
    cg_iterations: int
    cg_residual: float
    cg_converged: bool
    assembly_seconds: float
    solve_seconds: float
    max_speed: float
    max_displacement: float
    kinetic_energy: float
    potential_energy: float
    contacts: int
    contact_corrections: int
    crossings: int
    feature_contacts: int
    feature_corrections: int
    contact_seconds: float
    self_contacts: int
    self_impacts: int
    self_zone_particles: int
    self_frozen: int
    self_unresolved: int
    self_collision_seconds: float
    substeps: int
    retries: int
    smallest_substep: float
    def to_dict(self) -> dict[str, Any]: ...

@final
class RestOutcome:
    """How a run to rest ended: ``reason`` is ``"at_rest"``, ``"step_limit"`` or
    ``"stopped"`` (the callback returned ``False``)."""

    reason: Literal["at_rest", "step_limit", "stopped"]
    steps: int
    last: StepStats

@final
class Snapshot:
    """What a callback sees: the stage (``"running"``, ``"sewing"``, ``"draping"``), the
    step's statistics, and copies of the positions and velocities after it."""

    stage: Literal["running", "sewing", "draping"]
    stats: StepStats
    positions: npt.NDArray[np.float64]
    velocities: npt.NDArray[np.float64]

@final
class Strain:
    """Warp and weft strain of every triangle, % (positive: stretched)."""

    warp: npt.NDArray[np.float64]
    weft: npt.NDArray[np.float64]
    max_warp: float
    max_weft: float
    p99_warp: float
    p99_weft: float

@final
class Simulation:
    """A cloth on bodies, stepped by explicit or implicit Euler.

    ``pins`` are particle numbers held where they start (or at ``pin_positions``,
    ``(K, 3)``); ``settings`` are a scene's ``[solver]`` keys (``integrator``,
    ``time_step``, ``gravity``, ``wind``, ``pcg``, ``max_speed``, ``max_halvings``, ``max_kinetic_energy``,
    ``parallel``); ``self_collision`` is ``True`` (the default), ``False``, or a scene's
    ``[self_collision]`` keys (``enabled``, ``thickness``, ``friction``, ``stiffness``).
    Stepping releases the GIL; a divergence raises :class:`SimulationError` and keeps the
    last good state.
    """

    def __init__(
        self,
        mesh: ClothMesh,
        fabric: Fabric,
        *,
        bodies: Sequence[Body] = (),
        pins: npt.ArrayLike | None = None,
        pin_positions: _Points | None = None,
        settings: Mapping[str, Any] | None = None,
        velocities: _Points | None = None,
        self_collision: bool | Mapping[str, Any] | None = None,
    ) -> None: ...
    def step(self, n: int = 1) -> StepStats:
        """Takes ``n`` steps; returns the last one's statistics."""
    def run_to_rest(
        self,
        *,
        tolerance: float = 1e-5,
        consecutive_steps: int = 10,
        max_steps: int = 10000,
        moving_fraction: float = 0.0,
        callback: _Callback | None = None,
        every: int = 1,
        max_time_step: float | None = None,
        progress: bool = False,
    ) -> RestOutcome:
        """Steps until every particle (all but ``moving_fraction`` of them) has moved
        less than ``tolerance`` m per step over a window of ``consecutive_steps`` steps
        (judged from end to end, so trembling in place is rest), or ``max_steps``.
        ``callback`` sees a
        :class:`Snapshot` every ``every`` steps; returning ``False`` stops the run
        (reason ``"stopped"``); an exception it raises stops the run and propagates.
        Ctrl-C stops it too (``KeyboardInterrupt``, the state kept). With
        ``max_time_step`` (s), each step taken whole lets the next grow by a quarter up
        to it (one that had to be cut starts again from the solver's), ``tolerance``
        growing with the step; the solver's own step is given back at the end.
        ``progress=True`` shows a tqdm bar of the steps towards ``max_steps``
        (``ImportError`` without tqdm)."""
    @property
    def positions(self) -> npt.NDArray[np.float64]:
        """``(N, 3)`` positions. Setting them moves the particles (pinned ones go back to
        their pins in the next step)."""
    @positions.setter
    def positions(self, value: _Points) -> None: ...
    @property
    def velocities(self) -> npt.NDArray[np.float64]:
        """``(N, 3)`` velocities, settable."""
    @velocities.setter
    def velocities(self, value: _Points) -> None: ...
    @property
    def masses(self) -> npt.NDArray[np.float64]:
        """``(N,)`` lumped particle masses, kg."""
    @property
    def pins(self) -> npt.NDArray[np.int64]:
        """The pinned particles."""
    @property
    def mesh(self) -> ClothMesh: ...
    @property
    def fabrics(self) -> list[Fabric]: ...
    @property
    def settings(self) -> dict[str, Any]: ...
    @property
    def time(self) -> float:
        """Simulated time, s."""
    @property
    def step_count(self) -> int: ...
    @property
    def kinetic_energy(self) -> float: ...
    @property
    def history(self) -> dict[str, Any]:
        """Every step taken through this object, as columns: ``stage`` (a list of names)
        and numpy arrays ``step``, ``time`` (s), ``cg_iterations``, ``cg_residual``,
        ``kinetic_energy``, ``potential_energy`` (J), ``max_speed`` (m/s), ``substeps``,
        ``retries``, ``contacts``, ``self_contacts``, ``step_ms`` (wall time), one entry per
        step: the columns of a run's ``history.csv``. ``pandas.DataFrame(sim.history)``
        makes a table."""
    def strain(self) -> Strain:
        """The warp and weft strain now."""
    def grid_stretch(self) -> tuple[float, float] | None:
        """The source's measure on a grid: the largest stretch between neighbouring
        particles along the warp and along the weft, %; ``None`` if not a grid."""
    def deepest_penetration(self) -> float:
        """How deep the deepest particle is inside a body, m (0 if none is)."""
    def self_intersections(self) -> int:
        """How many edge-triangle pairs of the cloth pass through each other now (pairs
        sharing or neighbouring particles, or near in the flat cloth, exempt)."""
    def body_intersections(self) -> int:
        """How many cloth edges pass through a body triangle now, counted the same way."""
    def closest_self_approach(self, within: float) -> float | None:
        """The smallest distance of a particle from a triangle of the cloth (exempt pairs
        aside), m, if one is under ``within``: how close the layers come."""

def strain(mesh: ClothMesh, positions: _Points) -> Strain:
    """Warp and weft strain of ``mesh`` at ``positions``."""

def grid_stretch(mesh: ClothMesh, positions: _Points) -> tuple[float, float] | None:
    """The largest stretch between neighbouring grid particles, warp and weft, %."""

@final
class RunResult:
    """A scene's run: the cloth where it ended, the report, and the files written."""

    @property
    def mesh(self) -> ClothMesh: ...
    @property
    def positions(self) -> npt.NDArray[np.float64]: ...
    @property
    def report(self) -> dict[str, Any]:
        """As ``report.json``."""
    @property
    def outcome(self) -> Literal["finished", "interrupted"]:
        """A failed run raises :class:`SimulationError` instead."""
    @property
    def finished(self) -> bool: ...
    @property
    def outputs(self) -> list[str]:
        """The files written."""
    @property
    def history(self) -> dict[str, Any]:
        """Every step of every stage, as columns (see :attr:`Simulation.history`): what
        ``history.csv`` holds."""
    @property
    def panel_names(self) -> list[str] | None:
        """A garment's panel names (``None`` for a sheet)."""
    @property
    def triangle_panel(self) -> npt.NDArray[np.int64] | None:
        """``(M,)`` each triangle's panel, an index into :attr:`panel_names` (``None`` for a
        sheet)."""
    def to_trimesh(self) -> Any:
        """The cloth where the run ended as a ``trimesh.Trimesh`` (z up, m; not merged or
        repaired), a garment's panel per face in ``face_attributes["panel"]`` with the names
        in ``metadata["panels"]``. Needs trimesh (``pip install cloth-drape[trimesh]``;
        ``ImportError`` without it)."""

@final
class Scene:
    """A scene file: the cloth, fabric, bodies, solver, stages and outputs of a whole run,
    as the ``cloth`` command reads it. Relative paths start at the scene's folder."""

    @staticmethod
    def load(path: _Path) -> Scene:
        """Reads a TOML scene; ``ValueError`` carries the command's message (file, line and
        column, or key)."""
    @staticmethod
    def from_toml(text: str, *, base_dir: _Path = ".", name: str = "<scene>") -> Scene: ...
    @staticmethod
    def from_dict(values: Mapping[str, Any], *, base_dir: _Path = ".", name: str = "<scene>") -> Scene:
        """From the scene's tables as a dict (what ``tomllib`` reads from a scene file)."""
    @property
    def name(self) -> str: ...
    @property
    def path(self) -> str:
        """The file (or ``name``) errors refer to."""
    @property
    def base_dir(self) -> str: ...
    def check(self) -> list[str]:
        """Reads and builds everything a run needs without simulating, as ``cloth check``;
        returns the warnings (panels placed inside a body)."""
    def run(
        self,
        out_dir: _Path,
        *,
        force: bool = False,
        callback: _Callback | None = None,
        every: int = 1,
        progress: bool = False,
    ) -> RunResult:
        """Runs as ``cloth run SCENE --out OUT_DIR`` and writes the same outputs. Bad input
        raises ``ValueError`` before anything runs; a divergence writes the last good state
        and the report, then raises :class:`SimulationError`; ``callback`` returning
        ``False`` stops the run, which is then reported and returned as interrupted; Ctrl-C
        writes the state reached and raises ``KeyboardInterrupt``. ``progress=True`` shows
        a tqdm bar of each stage's steps towards its limit (``ImportError`` without tqdm)."""


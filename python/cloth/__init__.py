"""cloth: fabric with measured properties draped on rigid bodies, and garments sewn from
flat sewing patterns onto a mannequin.

The engine is Rust (the ``cloth._cloth`` module); this package re-exports it and adds
:mod:`cloth.batch` for many runs on any ``concurrent.futures`` executor, a Dask cluster's
included. Arrays are numpy, units SI. A quick drape::

    import cloth
    sheet = cloth.ClothMesh.grid(40, 40, (1.0, 1.0), origin=(-0.5, -0.5, 0.5))
    sim = cloth.Simulation(sheet, cloth.Fabric.preset("cotton_poplin"),
                           bodies=[cloth.Body.sphere(0.3)])
    sim.run_to_rest(max_steps=500)
    print(sim.positions.shape, sim.strain().max_warp)

or a whole scene, with the same outputs as ``cloth run``::

    cloth.Scene.load("assets/scenes/dress.toml").run("target/dress-py")
"""

from ._cloth import (
    Body,
    ClothMesh,
    Draped,
    Fabric,
    Garment,
    Pattern,
    RestOutcome,
    RunResult,
    Scene,
    SewnGarment,
    Simulation,
    SimulationError,
    Snapshot,
    StepStats,
    Strain,
    __version__,
    grid_stretch,
    strain,
)

from . import batch

__all__ = [
    "Body",
    "ClothMesh",
    "Draped",
    "Fabric",
    "Garment",
    "Pattern",
    "RestOutcome",
    "RunResult",
    "Scene",
    "SewnGarment",
    "Simulation",
    "SimulationError",
    "Snapshot",
    "StepStats",
    "Strain",
    "__version__",
    "batch",
    "grid_stretch",
    "strain",
]

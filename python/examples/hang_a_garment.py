"""A garment hung by its pins with no body: the tube pattern's top edges pinned where
the sewing leaves them, the run written as `cloth run` writes it, and the cloth handed
to trimesh with its panels.

    python python/examples/hang_a_garment.py OUT_DIR
"""

import sys
from pathlib import Path

import cloth

REPO = Path(__file__).resolve().parents[2]

SCENE = """
[cloth.garment]
pattern = "tube.toml"
edge_length = 0.015
pins = [{ panel = "front", edge = "top" }, { panel = "back", edge = "top" }]
[fabric]
preset = "cotton_poplin"
[rest]
tolerance = 1e-4
consecutive_steps = 10
max_steps = 200
[output]
up_axis = "y"
"""


def main(out: Path) -> None:
    scene = cloth.Scene.from_toml(SCENE, base_dir=REPO / "assets" / "patterns", name="hung tube")
    result = scene.run(out, force=True)
    mesh = result.to_trimesh()
    stages = ", ".join(f"{s['stage']} {s['steps']} steps" for s in result.report["stages"])
    print(f"{result.outcome}: {stages}; {result.report['pinned_particles']} vertices pinned")
    print(f"panels {mesh.metadata['panels']}, {len(mesh.faces)} faces, {mesh.area * 1e4:.0f} cm2")
    print(f"height {mesh.bounds[0][2]:.3f} to {mesh.bounds[1][2]:.3f} m; outputs in {out}")


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "target/example-tube"))

"""A square of cotton poplin dropped on a sphere, stepped from Python: the run's history
as a table, the final strain, and the cloth written as OBJ.

    python python/examples/sheet_on_sphere.py OUT_DIR
"""

import sys
from pathlib import Path

import pandas

import cloth


def main(out: Path) -> None:
    out.mkdir(parents=True, exist_ok=True)
    sheet = cloth.ClothMesh.grid(24, 24, (1.0, 1.0), origin=(-0.5, -0.5, 0.4))
    sim = cloth.Simulation(sheet, cloth.Fabric.preset("cotton_poplin"), bodies=[cloth.Body.sphere(0.3)])
    outcome = sim.run_to_rest(tolerance=1e-4, max_steps=600)
    history = pandas.DataFrame(sim.history)
    strain = sim.strain()
    print(f"{outcome.reason} after {outcome.steps} steps, {sim.time:.2f} s simulated")
    print(history[["step", "cg_iterations", "kinetic_energy"]].tail(3).to_string(index=False))
    print(f"largest warp strain {strain.max_warp:.2f} %, weft {strain.max_weft:.2f} %")
    sheet.save_obj(out / "sheet.obj", positions=sim.positions)
    history.to_csv(out / "history.csv", index=False)


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "target/example-sheet"))

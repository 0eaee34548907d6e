"""Three fabrics on one scene, run as a batch on a thread pool, compared in a pandas
table: each run's folder holds the outputs of `cloth run`.

    python python/examples/fabric_sweep.py OUT_DIR
"""

import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import cloth.batch as cb

REPO = Path(__file__).resolve().parents[2]


def main(out: Path) -> None:
    # The shipped scene, coarser and shorter for an example.
    base = cb.Job.from_file(
        REPO / "assets" / "scenes" / "sheet_on_sphere.toml",
        overrides={"cloth": {"grid": {"nx": 16, "ny": 16}}, "rest": {"max_steps": 80}},
    )
    jobs = cb.sweep(base, fabrics=["cotton_poplin", "silk", "wang_black_denim"])
    with ThreadPoolExecutor(2) as pool:
        result = cb.run_batch(jobs, out, executor=pool)
    table = result.to_pandas()
    print(table[["name", "status", "seconds", "max_warp", "max_weft"]].to_string(index=False))
    print(result.summary())


if __name__ == "__main__":
    main(Path(sys.argv[1] if len(sys.argv) > 1 else "target/example-sweep"))
